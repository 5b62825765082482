// The smoothed stress of the particle output (sable::mpm::StressSmoothing),
// 2D and 3D, on a box body of 2^dim points per cell beside a second box
// body that shares grid nodes with it:
//  - a uniform stress comes back exactly (round-off, 1e-12 relative) at
//    every point of the body, also at its surface and next to the other
//    body, whose very different stress is not averaged in (each body has
//    its own nodal values);
//  - a linear stress comes back exactly at the interior points (every
//    node of their cell surrounded by the body's points one cell wide):
//    there the projection weights sum_p N_i V_p are symmetric about the
//    node and average a linear field to its nodal value, which the Q1
//    interpolation returns;
//  - a checkerboard of +-C on the point lattice (the speckle the point
//    stresses show) added to the linear field: at an interior node the
//    weights 1/4, 3/4, 3/4, 1/4 per direction of the four points a cell
//    row holds cancel it exactly, so the interior points get the linear
//    field to round-off, and over the whole body (surface points included)
//    the rms deviation from the linear field falls below C/2.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/postprocess/stress_smoothing.h>
#include <sable/mpm/run_scene.h>
#include <sable/mpm/simulator.h>

#include <cmath>
#include <sstream>
#include <string>

#include "test_support.h"

using namespace dealii;
using sable_tests::check;

namespace
{
  std::string
  scientific(const double x)
  {
    std::ostringstream s;
    s.precision(2);
    s << std::scientific << x;
    return s.str();
  }

  template <int dim>
  void
  run_case()
  {
    using namespace sable::mpm;
    using Layout                  = ParticleLayout<dim>;
    const unsigned int n_cells    = dim == 2 ? 16 : 12;
    const double       h          = 1. / n_cells;
    GridParameters<dim> grid_parameters;
    for (unsigned int d = 0; d < dim; ++d)
      grid_parameters.upper_corner[d] = 1.;
    grid_parameters.subdivisions.assign(dim, n_cells);
    for (unsigned int f = 0; f < 2 * dim; ++f)
      grid_parameters.face_ids.push_back(f);
    parallel::distributed::Triangulation<dim> triangulation(MPI_COMM_WORLD);
    make_grid(grid_parameters, triangulation);

    SimulatorParameters<dim> parameters;
    parameters.output_directory = "";
    parameters.print_timings    = false;
    BodyParameters<dim> body, neighbour;
    body.shape = neighbour.shape = BodyParameters<dim>::Shape::box;
    for (unsigned int d = 0; d < dim; ++d)
      {
        body.lower_corner[d]      = 2 * h;
        body.upper_corner[d]      = 1. - 2 * h;
        neighbour.lower_corner[d] = 2 * h;
        neighbour.upper_corner[d] = 1. - 2 * h;
      }
    // the neighbour fills the last cells of the first axis, touching
    body.upper_corner[0]      = 1. - 4 * h;
    neighbour.lower_corner[0] = 1. - 4 * h;
    for (auto *b : {&body, &neighbour})
      {
        b->particles_per_direction = 2;
        b->material.model          = "linear elastic";
        b->material.density        = 1000.;
        b->material.set_young_poisson(1e6, 0.3);
      }
    neighbour.group   = 1;
    parameters.bodies = {body, neighbour};
    Simulator<dim> simulator(triangulation, parameters);
    simulator.initialize();
    // the test writes the stresses itself
    auto &particles = const_cast<Particles::ParticleHandler<dim> &>(simulator.get_particle_handler());
    const Grid<dim> &grid = simulator.get_grid();
    CellColouring<dim> colouring;
    colouring.reinit(grid, false);
    ParticleCells<dim> cells;
    cells.rebuild(particles, grid, colouring);

    // a stress with all six components
    SymmetricTensor<2, 3> A, B[3], D;
    for (unsigned int c = 0; c < 6; ++c)
      {
        A.access_raw_entry(c) = 1e6 * (1. + 0.3 * c);
        D.access_raw_entry(c) = -7e6 * (1. + 0.1 * c);
        for (unsigned int d = 0; d < 3; ++d)
          B[d].access_raw_entry(c) = 2e6 * (0.5 + c - 0.7 * d);
      }
    const auto linear = [&](const Point<dim> &x) {
      SymmetricTensor<2, 3> s = A;
      for (unsigned int d = 0; d < dim; ++d)
        s += (x[d] - 0.5) * B[d];
      return s;
    };
    const auto parity = [&](const Point<dim> &x) {
      int sum = 0;
      for (unsigned int d = 0; d < dim; ++d)
        sum += static_cast<int>(std::floor(x[d] / (h / 2)));
      return sum % 2 == 0 ? 1. : -1.;
    };
    // interior: each node of the point's cell has the body's points a whole
    // cell around it
    const auto interior = [&](const Point<dim> &x) {
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double lower_node = std::floor(x[d] / h) * h;
          if (lower_node - h < body.lower_corner[d] - 1e-12 ||
              lower_node + 2 * h > body.upper_corner[d] + 1e-12)
            return false;
        }
      return true;
    };
    const double C = 3e6;

    enum class Field
    {
      uniform,
      linear,
      checkerboard
    };
    for (const Field field : {Field::uniform, Field::linear, Field::checkerboard})
      {
        for (auto &particle : particles)
          {
            auto                  props = particle.get_properties();
            const Point<dim>      x     = particle.get_location();
            SymmetricTensor<2, 3> s;
            if (props[Layout::body] != 0)
              s = D;
            else if (field == Field::uniform)
              s = A;
            else
              s = linear(x) + (field == Field::checkerboard ? C * parity(x) : 0.) * A / A.norm();
            for (unsigned int c = 0; c < 6; ++c)
              props[Layout::stress + c] = s.access_raw_entry(c);
          }
        StressSmoothing<dim> smoothing;
        smoothing.compute(cells, grid, particles.get_max_local_particle_index());
        double       worst_all = 0, worst_interior = 0, squares = 0;
        unsigned int n_body = 0, n_interior = 0;
        for (const auto &particle : particles)
          {
            if (particle.get_properties()[Layout::body] != 0)
              continue;
            const Point<dim>            x = particle.get_location();
            const SymmetricTensor<2, 3> expected = field == Field::uniform ? A : linear(x);
            const double error = (smoothing[particle.get_local_index()] - expected).norm();
            worst_all          = std::max(worst_all, error);
            squares += error * error;
            ++n_body;
            if (interior(x))
              {
                worst_interior = std::max(worst_interior, error);
                ++n_interior;
              }
          }
        const std::string name = std::to_string(dim) + "D ";
        const double      scale = A.norm();
        if (field == Field::uniform)
          check(name + "uniform stress exact at all " + std::to_string(n_body) +
                  " points, next to another body's stress (largest error " +
                  scientific(worst_all / scale) + " of |sigma|)",
                worst_all <= 1e-12 * scale);
        else
          check(name + (field == Field::linear ? "linear" : "linear + checkerboard") +
                  " stress exact at the " + std::to_string(n_interior) +
                  " interior points (largest error " + scientific(worst_interior / scale) +
                  " of |sigma|)",
                n_interior > 0 && worst_interior <= 1e-12 * scale);
        if (field == Field::checkerboard)
          {
            const double rms = std::sqrt(squares / n_body);
            check(name + "checkerboard +-C over the whole body: rms deviation " +
                    scientific(rms / C) + " C < C/2",
                  rms < 0.5 * C);
          }
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run_case<2>();
  run_case<3>();
  return sable_tests::exit_code();
}
