#ifndef sable_mpm_bodies_closed_surface_h
#define sable_mpm_bodies_closed_surface_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The solid inside a closed triangulated surface in 3D (an STL file).
   * contains() casts a ray from the point along +x and counts the triangles
   * it crosses; a ray through an edge or a vertex is counted once by the
   * rasterisation (top-left) rule on the triangles' projections onto the
   * y-z plane, with each edge's test computed the same way from both of
   * its triangles, so the parity is right whatever the triangulation.
   * Triangles are binned on a uniform grid in the y-z plane.
   */
  class ClosedSurface
  {
  public:
    /// Whether @p x lies inside (a point on the surface may count either way).
    bool
    contains(const Point<3> &x) const;

    unsigned int
    n_triangles() const
    {
      return triangles.size();
    }
    /// Volume enclosed, m^3.
    double
    volume() const
    {
      return enclosed_volume;
    }
    Point<3>
    centroid() const
    {
      return solid_centroid;
    }
    std::pair<Point<3>, Point<3>>
    bounding_box() const
    {
      return box;
    }
    /// The vertex highest against @p gravity.
    Point<3>
    top_point(const Tensor<1, 3> &gravity) const;

    const std::vector<std::array<Point<3>, 3>> &
    get_triangles() const
    {
      return triangles;
    }

    /**
     * Set the triangles, compute volume, centroid and bins. Throws an
     * InputError (its message what is allowed instead) unless every edge
     * belongs to exactly two triangles and the enclosed volume is > 0.
     */
    void
    set_triangles(const std::vector<std::array<Point<3>, 3>> &triangles);

  private:
    std::vector<std::array<Point<3>, 3>> triangles;
    std::pair<Point<3>, Point<3>>        box;
    double                               enclosed_volume = 0;
    Point<3>                             solid_centroid;

    /// bins in y and z, their size, the triangles overlapping each
    std::array<unsigned int, 2>            n_bins = {};
    std::array<double, 2>                  bin_size = {};
    std::vector<std::vector<unsigned int>> bins;
  };

  /**
   * Read an STL file, ASCII or binary, mapping each vertex x to @p scale x
   * + @p translation. A file that cannot be opened or parsed, or a surface
   * that is not closed, throws an InputError whose message is what is
   * allowed instead.
   */
  ClosedSurface
  read_stl(const std::string &filename, const double scale, const Tensor<1, 3> &translation);
} // namespace sable::mpm

#endif
