// A lower bound of the memory a scene needs, checked against the machine's
// before anything is allocated.
#ifndef sable_mpm_memory_estimate_h
#define sable_mpm_memory_estimate_h

#include <deal.II/base/mpi.h>

#include <sable/mpm/parameters.h>

namespace sable::mpm
{
  /// The bytes a scene needs at least, and the entry that asks for most.
  struct MemoryEstimate
  {
    double      cells           = 0; ///< of the grid as given
    double      material_points = 0; ///< seeded in all bodies
    double      bytes           = 0;
    std::string entry;               ///< "Grid/Subdivisions" or a body's seeding
    std::string value;
  };

  /**
   * Bytes per cell and per material point in 2D and 3D, half of what
   * short runs with deal.II 9.4 measured (peak resident memory beyond that
   * of a tiny scene; doc/mpm.md, "Output directory and run safety"): the
   * estimate is a lower bound, so only scenes that cannot fit are refused.
   */
  inline constexpr double bytes_per_cell[2]           = {450., 450.};
  inline constexpr double bytes_per_material_point[2] = {200., 300.};

  template <int dim>
  MemoryEstimate
  estimate_memory(const Scene<dim> &scene);

  /// The memory available to new programs on the hosts of @p communicator
  /// (MemAvailable of /proc/meminfo, else free pages, summed over hosts).
  double
  available_memory(MPI_Comm communicator);

  /**
   * Throw an InputError naming the entry, the estimated need and the
   * available memory if the scene cannot fit into @p communicator's hosts.
   * Collective; costs no allocation proportional to the scene.
   */
  template <int dim>
  void
  check_memory(const Scene<dim> &scene, MPI_Comm communicator);
} // namespace sable::mpm

#endif
