#ifndef sable_mpm_bodies_grain_file_h
#define sable_mpm_bodies_grain_file_h

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// One disk (2D) or sphere (3D) of a grain file, and the file line that
  /// gave it (for messages).
  template <int dim>
  struct Grain
  {
    Point<dim>   centre;
    double       radius = 0;
    unsigned int line   = 0;
  };

  /**
   * Read a CSV file of grains (as contrib/packs/disk_pack.py writes): a
   * header line naming the columns in any order, `x`, `y` (and `z` in 3D)
   * and `radius`, then one line per grain. Blank lines and lines starting
   * with '#' are skipped. A file that cannot be opened, an unknown or
   * repeated column name, a missing column, a line with another number of
   * fields, a field that is not a number, a radius <= 0 or a file without
   * grains is an InputError naming the file, line and column.
   */
  template <int dim>
  std::vector<Grain<dim>>
  read_grain_file(const std::string &filename);
} // namespace sable::mpm

#endif
