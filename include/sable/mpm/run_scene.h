#ifndef sable_mpm_run_scene_h
#define sable_mpm_run_scene_h

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <sable/mpm/parameters.h>

#include <string>

namespace sable::mpm
{
  /// Build the box grid a scene describes, with its boundary ids.
  template <int dim>
  void
  make_grid(const GridParameters<dim> &                 parameters,
            parallel::distributed::Triangulation<dim> &triangulation);

  /// Read, check and run the MPM scene in @p filename; with @p resume,
  /// continue it from the last checkpoint in its output directory.
  template <int dim>
  void
  run_scene(const std::string &filename, MPI_Comm communicator, const bool resume = false);
} // namespace sable::mpm

#endif
