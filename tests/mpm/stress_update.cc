// StressUpdate, the batched strain and stress update, on the points of a
// 2D scene: two bodies of different materials (linear elastic, von Mises)
// that overlap in a column of cells, so that cells hold batches of both,
// with random velocity gradients (large enough that some von Mises points
// yield).
// (a) Every point's F, stress and plastic strain equal F <- (I + dt L) F and
//     its material's 3D update_stress() with L and F embedded, point by
//     point: the batching by cell and body and the plane-strain kernels
//     change nothing, so equality is exact.
// (b) The finiteness test folded into one per batch: with finite velocity
//     gradients no failure; with a NaN gradient at one point and an
//     infinite one at a point of lower id in the other body, the update
//     reports the latter, with its location.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/run_scene.h>
#include <sable/mpm/simulator.h>
#include <sable/mpm/stress_update.h>

#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <random>
#include <string>

#include "test_support.h"

using namespace dealii;
using namespace sable::mpm;
using sable_tests::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using Layout = ParticleLayout<2>;

  GridParameters<2> grid_parameters;
  grid_parameters.upper_corner = Point<2>(1, 1);
  grid_parameters.subdivisions = {16, 16};
  grid_parameters.face_ids     = {0, 1, 2, 3};
  parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  make_grid(grid_parameters, triangulation);

  SimulatorParameters<2> parameters;
  parameters.end_time         = 1e3;
  parameters.output_directory = "";
  parameters.print_timings    = false;
  // x = 0.53 is inside a column of cells (h = 1/16): those cells hold
  // points of both bodies
  for (const double x : {0.2, 0.53})
    {
      BodyParameters<2> box;
      box.shape        = BodyParameters<2>::Shape::box;
      box.lower_corner = Point<2>(x, 0.2);
      box.upper_corner = Point<2>(x + 0.33 - 1e-12, 0.6);
      box.material.set_young_poisson(1e9, 0.3);
      box.material.density = 1000;
      parameters.bodies.push_back(box);
    }
  parameters.bodies[1].material.model        = "von Mises";
  parameters.bodies[1].material.yield_stress = 1e5;
  Simulator<2> simulator(triangulation, parameters);
  simulator.initialize();

  const auto &particle_handler = simulator.get_particle_handler();
  const auto &grid             = simulator.get_grid();
  const auto &layout           = simulator.get_particle_layout();
  std::vector<std::unique_ptr<Material>> materials;
  for (const auto &body : parameters.bodies)
    materials.push_back(create_material(body.material));
  CellColouring<2> colouring;
  colouring.reinit(grid, false);
  ParticleCells<2> cells;
  cells.rebuild(particle_handler, grid, colouring);
  unsigned int n_mixed = 0;
  for (unsigned int c = 0; c < cells.n_owned(); ++c)
    {
      std::set<double> bodies;
      for (const auto &particle : cells[c].particles)
        bodies.insert(particle.get_properties()[Layout::body]);
      n_mixed += bodies.size() > 1;
    }
  check(std::to_string(n_mixed) + " cells hold points of both bodies", n_mixed >= 4);

  // (a) random L per point, and the expected state point by point
  const double                dt = 1e-3;
  std::vector<Tensor<2, 2>>   velocity_gradients(particle_handler.get_max_local_particle_index());
  std::map<types::particle_index, std::tuple<Tensor<2, 2>, SymmetricTensor<2, 3>, double>> expected;
  std::uniform_real_distribution<double> u(-1., 1.);
  for (const auto &particle : particle_handler)
    {
      std::mt19937  rng(particle.get_id());
      Tensor<2, 2> &L = velocity_gradients[particle.get_local_index()];
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          L[i][j] = u(rng);
      const auto   props = particle.get_properties();
      const auto   body  = static_cast<unsigned int>(props[Layout::body]);
      Tensor<2, 2> F     = Layout::deformation_gradient(props);
      F                  = (Tensor<2, 2>(unit_symmetric_tensor<2>()) + dt * L) * F;
      SymmetricTensor<2, 3> stress  = Layout::stress_tensor(props);
      double                plastic = layout.n_history > 0 ? props[layout.history] : 0.;
      materials[body]->update_stress(
        embed_in_3d<2>(L, 0.), embed_in_3d<2>(F, 1.), dt, stress, body == 1 ? &plastic : nullptr);
      expected[particle.get_id()] = {F, stress, plastic};
    }
  const StressUpdate<2> stress_update(materials, layout);
  const auto            no_failure = stress_update.update(cells, velocity_gradients, dt);
  check("finite velocity gradients: no failure reported", !no_failure.failed);
  unsigned int n_equal = 0, n_yielded = 0;
  for (const auto &particle : particle_handler)
    {
      const auto &[F, stress, plastic] = expected.at(particle.get_id());
      const auto props                 = particle.get_properties();
      bool       equal = Layout::deformation_gradient(props) == F && Layout::stress_tensor(props) == stress;
      if (layout.n_history > 0)
        equal = equal && props[layout.history] == plastic;
      n_equal += equal;
      n_yielded += plastic > 0;
    }
  check(std::to_string(n_equal) + " of " + std::to_string(expected.size()) +
          " points: F, stress and plastic strain exactly as the 3D update point by point",
        n_equal == expected.size() && n_equal > 100);
  check(std::to_string(n_yielded) + " von Mises points yielded", n_yielded > 10);

  // (b) a NaN gradient at the first point of body 1 and an infinite one at
  // the last point of body 0 (a lower id: bodies are seeded in turn)
  types::particle_index nan_id = std::numeric_limits<types::particle_index>::max(), inf_id = 0;
  Point<2>              inf_location;
  for (const auto &particle : particle_handler)
    if (particle.get_properties()[Layout::body] == 1.)
      nan_id = std::min(nan_id, particle.get_id());
    else if (particle.get_id() >= inf_id)
      {
        inf_id       = particle.get_id();
        inf_location = particle.get_location();
      }
  for (const auto &particle : particle_handler)
    if (particle.get_id() == nan_id)
      velocity_gradients[particle.get_local_index()][0][1] = std::numeric_limits<double>::quiet_NaN();
    else if (particle.get_id() == inf_id)
      velocity_gradients[particle.get_local_index()][1][1] = std::numeric_limits<double>::infinity();
  const auto failure = stress_update.update(cells, velocity_gradients, dt);
  check("NaN at point " + std::to_string(nan_id) + ", infinity at point " + std::to_string(inf_id) +
          ": failure reported at point " + std::to_string(failure.id),
        failure.failed && failure.id == inf_id && inf_id < nan_id);
  check("failure location is that point's", failure.location.distance(inf_location) == 0.);
  return sable_tests::exit_code();
}
