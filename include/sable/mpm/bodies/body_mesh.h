#ifndef sable_mpm_bodies_body_mesh_h
#define sable_mpm_bodies_body_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/bodies/surface_facets.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  class ClosedSurface;

  /**
   * The region of a body given as a volume mesh (Shape = mesh): the union of
   * its cells, triangles and quadrilaterals in 2D, tetrahedra and hexahedra
   * in 3D. A quadrilateral is the polygon of its four straight edges, a
   * hexahedron the trilinear image of the unit cube (as in deal.II's
   * MappingQ1). Cells are binned on a uniform grid over the bounding box so
   * that contains() tests only the few cells near a point. In 3D the
   * region may instead be the inside of a closed surface (an STL file).
   */
  template <int dim>
  class BodyMesh
  {
  public:
    /// Whether @p x lies in a cell (closed cells: points on faces count).
    bool
    contains(const Point<dim> &x) const;

    unsigned int
    n_cells() const
    {
      return cell_start.size() - 1;
    }
    /// Area (2D) or volume (3D) of the region, m^dim.
    double
    measure() const
    {
      return total_measure;
    }
    /// Centroid of the region.
    Point<dim>
    centroid() const
    {
      return region_centroid;
    }
    /// Axis-aligned bounding box of the vertices.
    std::pair<Point<dim>, Point<dim>>
    bounding_box() const
    {
      return box;
    }
    /// The vertex highest against @p gravity.
    Point<dim>
    top_point(const Tensor<1, dim> &gravity) const;

    /**
     * Add a cell of @p vertices in deal.II's order (lexicographic for
     * quadrilaterals and hexahedra): 3 or 4 in 2D, 4 or 8 in 3D.
     */
    void
    add_cell(const std::vector<Point<dim>> &vertices);

    /// Compute the bins, measure and centroid after the last add_cell().
    void
    finish();

    /// Make the region the inside of @p surface (3D only), instead of cells.
    void
    set_surface(const ClosedSurface &surface);

    /// The boundary facet nearest @p x (the cells' faces no other cell
    /// shares, or the closed surface's triangles), as
    /// SurfaceFacets::nearest_face() gives it.
    FaceBelow<dim>
    face_below(const Point<dim> &x, const double depth_limit, const double edge_margin) const
    {
      return facets.nearest_face(x, depth_limit, edge_margin);
    }

  private:
    /// cell c's vertices are vertices[cell_start[c] .. cell_start[c + 1])
    std::vector<Point<dim>>   vertices;
    std::vector<unsigned int> cell_start = {0};

    std::pair<Point<dim>, Point<dim>> box;
    double                            total_measure = 0;
    Point<dim>                        region_centroid;

    /// bins per direction, their size, and the cells overlapping each bin
    std::array<unsigned int, dim>          n_bins = {};
    Tensor<1, dim>                         bin_size;
    std::vector<std::vector<unsigned int>> bins;

    /// the closed surface, if the region is given by one
    std::shared_ptr<const ClosedSurface> surface;
    SurfaceFacets<dim>                   facets;

    bool
    cell_contains(const unsigned int c, const Point<dim> &x) const;
  };

  /**
   * Read the volume mesh in @p filename with deal.II's GridIn (the format
   * from the file's suffix: .msh Gmsh, .vtk legacy VTK, .inp or .ucd UCD),
   * or in 3D the closed surface of an STL file (.stl, read_stl()), and map
   * each vertex x to @p scale x + @p translation. A file that
   * cannot be opened, an unknown suffix, a file GridIn cannot read, a mesh
   * without cells of dimension @p dim and cells other than those BodyMesh
   * knows throw an InputError whose message is what is allowed instead
   * (the caller names the entry and value).
   */
  template <int dim>
  BodyMesh<dim>
  read_body_mesh(const std::string &   filename,
                 const double          scale,
                 const Tensor<1, dim> &translation);
} // namespace sable::mpm

#endif
