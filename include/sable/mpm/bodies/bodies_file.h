#ifndef sable_mpm_bodies_bodies_file_h
#define sable_mpm_bodies_bodies_file_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/bodies/body_parameters.h>

#include <string>
#include <array>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Many disk (2D) or sphere (3D) bodies from a grain file (subsection
   * 'Bodies file'): one body per row of 'File' (read_grain_file()), all
   * with the template's seeding, material, initial motion and contact
   * group. They come after the bodies of the 'Body k' subsections and have
   * no columns of their own in statistics.csv.
   *
   * Grains held by a face of the grid: with '<Lower|Upper> <x|y|z> wall
   * velocity' set, a grain that reaches beyond that face (centre inside
   * the grid) becomes a body of prescribed velocity moving with that
   * velocity from 'Wall velocity start time' on, seeded only inside the
   * grid; without it, such a grain is an error.
   */
  template <int dim>
  struct BodiesFile
  {
    /// the file as given; empty: no bodies from a file
    std::string         file;
    BodyParameters<dim> body_template;
    /// per face x-, x+, y-, y+ (, z-, z+): whether it holds the grains
    /// crossing it, and their velocity
    std::vector<bool>           holds;
    std::vector<Tensor<1, dim>> wall_velocities;
    double                      wall_start_time = 0;

    /// Declare the entries in the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read the current subsection ("Bodies file").
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Read the file (a relative path from @p folder, that of the parameter
     * file) and make its bodies, in the order of its rows, for a grid
     * [@p lower, @p upper]. A grain whose centre lies outside the grid, or
     * that reaches beyond a face that does not hold grains (or beyond two
     * faces that do), is an InputError naming the file and line.
     */
    std::vector<BodyParameters<dim>>
    create_bodies(const std::string &          folder,
                  const Point<dim> &           lower,
                  const Point<dim> &           upper,
                  const std::array<bool, dim> &periodic) const;
  };
} // namespace sable::mpm

#endif
