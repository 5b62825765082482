#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/mpm/checkpoint.h>
#include <sable/mpm/memory_estimate.h>
#include <sable/mpm/run_scene.h>
#include <sable/mpm/simulator.h>

#include <algorithm>
#include <optional>

namespace sable::mpm
{
  template <int dim>
  unsigned int
  make_grid(const GridParameters<dim> &                 parameters,
            parallel::distributed::Triangulation<dim> &triangulation,
            const bool                                 refine)
  {
    unsigned int              k = 0;
    std::vector<unsigned int> coarse = parameters.subdivisions;
    // a periodic axis keeps 3 coarse cells (a cell's nodes must not meet
    // across the seam)
    const auto halves = [&](const unsigned int d) {
      return coarse[d] > 0 && coarse[d] % 2 == 0 && (!parameters.periodic[d] || coarse[d] >= 6);
    };
    while (true)
      {
        bool all = true;
        for (unsigned int d = 0; d < dim; ++d)
          all = all && halves(d);
        if (!all)
          break;
        for (unsigned int &n : coarse)
          n /= 2;
        ++k;
      }
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              coarse,
                                              parameters.lower_corner,
                                              parameters.upper_corner,
                                              /*colorize=*/true);
    // colorize numbers the faces x-, x+, y-, ... as 0, 1, 2, ...; the
    // periodic pairs are matched by these ids, before the user's ids
    std::vector<GridTools::PeriodicFacePair<
      typename parallel::distributed::Triangulation<dim>::cell_iterator>>
      periodic_faces;
    for (unsigned int d = 0; d < dim; ++d)
      if (parameters.periodic[d])
        GridTools::collect_periodic_faces(triangulation, 2 * d, 2 * d + 1, d, periodic_faces);
    // children inherit the ids
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          face->set_boundary_id(parameters.face_ids[face->boundary_id()]);
    if (!periodic_faces.empty())
      triangulation.add_periodicity(periodic_faces);
    if (refine)
      triangulation.refine_global(k);
    return k;
  }

  template <int dim>
  void
  run_scene(const std::string &                  filename,
            MPI_Comm                             communicator,
            const OutputMode                     mode,
            const std::vector<ParameterSetting> &settings)
  {
    const bool       resume = mode == OutputMode::resume;
    const Scene<dim> scene  = read_scene<dim>(filename, settings);
    check_memory(scene, communicator);
    parallel::distributed::Triangulation<dim> triangulation(communicator);
    make_grid(scene.grid, triangulation, /*refine=*/!resume);
    std::optional<Simulator<dim>> simulator;
    simulator.emplace(triangulation, scene.simulator);
    try
      {
        // a new run's bodies are seeded and checked before the output
        // directory is touched: --overwrite removes nothing for a scene
        // that is refused
        if (!resume)
          simulator->seed();
        // the output directory (locked for the run) and the checkpoint to
        // resume from
        const OutputDirectory output_directory(scene.simulator.output_directory,
                                               mode,
                                               communicator,
                                               std::cout);
        if (resume)
          simulator->resume(
            find_checkpoint(scene.simulator.output_directory, communicator, std::cout));
        simulator->run();
      }
    catch (...)
      {
        // destroy the simulator while no exception is in flight, so its
        // timers finish normally, then pass the error on
        simulator.reset();
        throw;
      }
  }

  template unsigned int
  make_grid<2>(const GridParameters<2> &, parallel::distributed::Triangulation<2> &, bool);
  template unsigned int
  make_grid<3>(const GridParameters<3> &, parallel::distributed::Triangulation<3> &, bool);
  template void
  run_scene<2>(const std::string &, MPI_Comm, OutputMode, const std::vector<ParameterSetting> &);
  template void
  run_scene<3>(const std::string &, MPI_Comm, OutputMode, const std::vector<ParameterSetting> &);
} // namespace sable::mpm
