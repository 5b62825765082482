#ifndef sable_mpm_run_scene_h
#define sable_mpm_run_scene_h

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <sable/base/output_directory.h>
#include <sable/mpm/parameters.h>

#include <string>

namespace sable::mpm
{
  /**
   * Build the box grid a scene describes, with its boundary ids: a coarse
   * mesh of as few cells as possible, Subdivisions / 2^k in each direction
   * with 2^k the largest power of two that divides every subdivision, then
   * (with @p refine) k global refinements. p4est thus stores only each
   * rank's own and ghost cells, not every cell of the grid on every rank.
   * Returns k: the level of the Subdivisions cells, from which the levels
   * of 'Mesh refinement' count (Simulator::initialize() finds it as the
   * coarsest active level). Resuming from a checkpoint needs the coarse
   * mesh alone (@p refine = false).
   */
  template <int dim>
  unsigned int
  make_grid(const GridParameters<dim> &                 parameters,
            parallel::distributed::Triangulation<dim> &triangulation,
            bool                                       refine = true);

  /// Read, check and run the MPM scene in @p filename, with the entries of
  /// @p settings (`--set`) changed. @p mode says what happens to an earlier
  /// run's results in the output directory (see OutputDirectory):
  /// OutputMode::resume continues that run from its last checkpoint.
  template <int dim>
  void
  run_scene(const std::string &                  filename,
            MPI_Comm                             communicator,
            OutputMode                           mode     = OutputMode::fresh,
            const std::vector<ParameterSetting> &settings = {});
} // namespace sable::mpm

#endif
