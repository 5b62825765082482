// sable::mpm::ParticleRebinning against deal.II's particle sort: two
// ParticleHandlers get the same random points (three per cell) and the
// same random moves of up to 0.9 of the smallest cell per direction, 25
// times; one is sorted by ParticleHandler::sort_particles_into_subdomains_
// and_cells(), the other rebinned. After every move every cell must hold
// the same points in the same order in both, with bit-identical
// reference locations, locations and properties (the rebinning claims to
// reproduce the sort's container, so that every pass adds up in the same
// order). Cases, 2D and 3D: a uniform grid; a grid periodic along x whose
// points cross the seam; a grid refined once on one half and twice in a
// corner (points moving between coarse and finer cells). A point moved out
// of the grid, or more points leaving than the room for moves, makes
// rebin() report that a sort is needed, with no point moved.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_rebinning.h>
#include <sable/mpm/periodicity.h>
#include <sable/mpm/run_scene.h>

#include <random>
#include <string>
#include <vector>

#include "test_support.h"

using namespace dealii;
using sable_tests::check;

namespace
{
  template <int dim>
  using Handler = Particles::ParticleHandler<dim>;

  /// Whether every cell holds the same points in the same order in the two
  /// containers (the order of the cells in the container may differ: deal.II
  /// keeps the cells that gain their first point in index order, which the
  /// rebinning cannot; no pass of a step depends on it).
  template <int dim>
  bool
  identical(const Triangulation<dim> &triangulation,
            const Handler<dim> &      a,
            const Handler<dim> &      b,
            std::string &             difference)
  {
    if (a.n_locally_owned_particles() != b.n_locally_owned_particles())
      {
        difference = "different numbers of points";
        return false;
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const auto in_a = a.particles_in_cell(cell), in_b = b.particles_in_cell(cell);
        if (a.n_particles_in_cell(cell) != b.n_particles_in_cell(cell))
          {
            difference = "cell " + std::to_string(cell->active_cell_index()) +
                         ": different numbers of points";
            return false;
          }
        auto q = in_b.begin();
        for (auto p = in_a.begin(); p != in_a.end(); ++p, ++q)
          {
            const auto pa = p->get_properties(), pb = q->get_properties();
            bool same = p->get_id() == q->get_id() && p->get_location() == q->get_location() &&
                        p->get_reference_location() == q->get_reference_location() &&
                        pa.size() == pb.size();
            for (unsigned int k = 0; same && k < pa.size(); ++k)
              same = pa[k] == pb[k];
            if (!same)
              {
                difference = "cell " + std::to_string(cell->active_cell_index()) + ": point " +
                             std::to_string(p->get_id()) + " against point " +
                             std::to_string(q->get_id());
                return false;
              }
          }
      }
    return true;
  }

  template <int dim>
  void
  run_case(const std::string &name, const bool periodic_x, const bool refined)
  {
    using namespace sable::mpm;
    const std::string label = std::to_string(dim) + "D " + name;
    GridParameters<dim> parameters;
    for (unsigned int d = 0; d < dim; ++d)
      parameters.upper_corner[d] = 1.;
    parameters.subdivisions.assign(dim, dim == 2 ? 8 : 6);
    for (unsigned int f = 0; f < 2 * dim; ++f)
      parameters.face_ids.push_back(f);
    parameters.periodic[0] = periodic_x;
    parallel::distributed::Triangulation<dim> triangulation(MPI_COMM_WORLD);
    make_grid(parameters, triangulation, true);
    if (refined)
      for (unsigned int round = 0; round < 2; ++round)
        {
          for (const auto &cell : triangulation.active_cell_iterators())
            if (cell->center()[0] < 0.5 && (round == 0 || cell->center()[1] < 0.25))
              cell->set_refine_flag();
          triangulation.execute_coarsening_and_refinement();
        }
    Grid<dim> grid(triangulation);
    grid.setup();
    CellColouring<dim> colouring;
    colouring.reinit(grid, false);
    const Periodicity<dim> periodicity = Periodicity<dim>::of(triangulation);
    double                 smallest    = 1.;
    for (const auto &cell : triangulation.active_cell_iterators())
      smallest = std::min(smallest, cell->extent_in_direction(0));

    // three random points per cell, with three properties each
    Handler<dim>     sorted(triangulation, grid.get_mapping(), 3);
    Handler<dim>     rebinned(triangulation, grid.get_mapping(), 3);
    std::mt19937     random(17);
    std::uniform_real_distribution<double> unit(0., 1.);
    unsigned int     id = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (unsigned int k = 0; k < 3; ++k, ++id)
        {
          Point<dim> reference, x = cell->vertex(0);
          for (unsigned int d = 0; d < dim; ++d)
            {
              reference[d] = unit(random);
              x[d] += reference[d] * cell->extent_in_direction(d);
            }
          const std::vector<double> properties = {1. * id, unit(random), unit(random)};
          for (Handler<dim> *h : {&sorted, &rebinned})
            h->insert_particle(x, reference, id, cell, make_array_view(properties));
        }
    for (Handler<dim> *h : {&sorted, &rebinned})
      h->update_cached_numbers();

    ParticleRebinning<dim> rebinning;
    ParticleCells<dim>     cells;
    bool                   all_rebinned = true, all_identical = true;
    unsigned int           seam_crossings = 0;
    std::string            difference;
    for (unsigned int step = 0; step < 25; ++step)
      {
        // the same move for a point in both containers: drawn from its id
        for (Handler<dim> *h : {&sorted, &rebinned})
          for (auto &particle : *h)
            {
              std::mt19937 draw(1000 * particle.get_id() + step);
              Point<dim>   x = particle.get_location();
              for (unsigned int d = 0; d < dim; ++d)
                {
                  x[d] += 0.9 * smallest * (2. * unit(draw) - 1.);
                  if (!periodicity.periodic[d])
                    x[d] = std::clamp(x[d], 0., 1.);
                }
              if (periodicity.wrap(x) && h == &sorted)
                ++seam_crossings;
              particle.set_location(x);
            }
        sorted.sort_particles_into_subdomains_and_cells();
        cells.rebuild(rebinned, grid, colouring);
        all_rebinned = rebinning.rebin(rebinned, cells, periodicity) && all_rebinned;
        if (all_identical && !identical<dim>(triangulation, sorted, rebinned, difference))
          {
            all_identical = false;
            std::cout << label << ", step " << step << ": " << difference << std::endl;
          }
      }
    std::cout << label << ": " << id << " points, " << rebinning.moved_since_full_sort()
              << " moved between cells in 25 steps, " << seam_crossings
              << " across the periodic seam" << std::endl;
    check(label + ": every step rebinned", all_rebinned);
    check(label + ": container identical to the sorted one after every step", all_identical);
    // the test has to move points: about half the points leave their cell
    // per step on the finest cells
    check(label + ": points moved between cells", rebinning.moved_since_full_sort() > 5 * id);
    if (periodic_x)
      check(label + ": points crossed the periodic seam", seam_crossings > id / 10);

    // more points leaving in one step than the room for moves: left to the
    // sort, with no point moved (each move is inserted before its old copy
    // goes; beyond the room reserved the particle data would double)
    for (auto &particle : rebinned)
      {
        Point<dim> y = particle.get_location();
        y[0]         = std::clamp(y[0] + 0.9 * smallest, 0., 1.);
        periodicity.wrap(y);
        particle.set_location(y);
      }
    cells.rebuild(rebinned, grid, colouring);
    const unsigned long long moved_before = rebinning.moved_since_full_sort();
    std::vector<unsigned int> cell_before;
    for (const auto &particle : rebinned)
      cell_before.push_back(particle.get_surrounding_cell()->active_cell_index());
    const bool refused = !rebinning.rebin(rebinned, cells, periodicity, 1);
    bool       unmoved = rebinning.moved_since_full_sort() == moved_before &&
                   rebinned.n_locally_owned_particles() == cell_before.size();
    unsigned int k = 0;
    for (const auto &particle : rebinned)
      unmoved = unmoved && k < cell_before.size() &&
                particle.get_surrounding_cell()->active_cell_index() == cell_before[k++];
    check(label + ": more points leaving than the room for moves are left to the sort, none moved",
          refused && unmoved);
    rebinned.sort_particles_into_subdomains_and_cells();

    // a point outside the grid (across a face that is not periodic): the
    // rebinning leaves it to the sort
    auto       outside = rebinned.begin();
    Point<dim> x       = outside->get_location();
    x[dim - 1]         = -0.5 * smallest;
    outside->set_location(x);
    cells.rebuild(rebinned, grid, colouring);
    check(label + ": a point that left the grid is left to the sort",
          !rebinning.rebin(rebinned, cells, periodicity));
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const bool periodic : {false, true})
    for (const bool refined : {false, true})
      {
        const std::string name = std::string(periodic ? "periodic in x" : "box") +
                                 (refined ? ", refined" : ", uniform");
        run_case<2>(name, periodic, refined);
        run_case<3>(name, periodic, refined);
      }
  return sable_tests::exit_code();
}
