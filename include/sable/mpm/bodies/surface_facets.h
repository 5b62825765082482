#ifndef sable_mpm_bodies_surface_facets_h
#define sable_mpm_bodies_surface_facets_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The boundary of a body given by a mesh, as flat facets (segments in 2D,
   * triangles in 3D) with their outward unit normals, for the surface
   * normals its material points carry (the contact's `flatter body`
   * normals): a face inclined to the grid is a staircase of points, whose
   * mass gradient at a node tilts from node to node; the face's own normal
   * does not.
   */
  /**
   * The face of a body that a point lies under: its outward unit normal
   * and the point's depth below the face's plane, so that x + depth normal
   * lies on the face. A zero normal where the point lies under none.
   */
  template <int dim>
  struct FaceBelow
  {
    Tensor<1, dim> normal;
    double         depth = 0;
  };

  template <int dim>
  class SurfaceFacets
  {
  public:
    /// A segment (2D) or triangle (3D) and its outward unit normal.
    struct Facet
    {
      std::array<Point<dim>, dim> vertices;
      Tensor<1, dim>              normal;
    };

    /// The faces of the cells (vertices in deal.II's order, as
    /// BodyMesh::add_cell() takes them: triangles and quadrilaterals in
    /// 2D, tetrahedra and hexahedra in 3D) that no other cell shares,
    /// oriented away from their cell; a quadrilateral face is split into
    /// two triangles.
    void
    set_from_cells(const std::vector<Point<dim>> &  vertices,
                   const std::vector<unsigned int> &cell_start);

    /// The triangles of a closed surface (3D), oriented so that the
    /// enclosed volume is positive.
    void
    set_from_triangles(const std::vector<std::array<Point<dim>, dim>> &triangles);

    /// The outward normal of the facet nearest @p x and the depth of @p x
    /// below the facet's plane; a zero normal if that facet is farther than
    /// @p depth_limit (or there are none), or if a facet of another
    /// direction is within @p edge_margin (@p x near an edge or a corner,
    /// where the face is ambiguous). O(facets).
    FaceBelow<dim>
    nearest_face(const Point<dim> &x, const double depth_limit, const double edge_margin) const;

    unsigned int
    n_facets() const
    {
      return facets.size();
    }

  private:
    std::vector<Facet> facets;
  };

  /// Distance from @p x to the segment (2D) or triangle (3D) @p vertices.
  template <int dim>
  double
  distance_to_facet(const Point<dim> &x, const std::array<Point<dim>, dim> &vertices);
} // namespace sable::mpm

#endif
