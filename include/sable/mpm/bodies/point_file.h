#ifndef sable_mpm_bodies_point_file_h
#define sable_mpm_bodies_point_file_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// The material points of a body read from a file (Shape = points).
  template <int dim>
  struct PointCloud
  {
    std::vector<Point<dim>> positions;
    /// initial volume of each point, m^3 (m^2 in 2D)
    std::vector<double> volumes;
    /// initial velocity of each point; empty if the file gives none
    std::vector<Tensor<1, dim>> velocities;
  };

  /**
   * Read a CSV file of material points: a header line naming the columns
   * in any order, `x`, `y` (and `z` in 3D), `volume`, and optionally the
   * velocity `vx`, `vy` (, `vz`), all of its components or none; then one
   * line per point. Blank lines and lines starting with '#' are skipped.
   * An unknown or repeated column name, a missing column, a line with
   * another number of fields, a field that is not a number or a volume
   * <= 0 is an InputError naming the file and line.
   */
  template <int dim>
  PointCloud<dim>
  read_point_file(const std::string &filename);
} // namespace sable::mpm

#endif
