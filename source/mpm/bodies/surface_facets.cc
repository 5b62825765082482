#include <sable/mpm/bodies/surface_facets.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace sable::mpm
{
  namespace
  {
    /// Facets whose normals differ by more than about 2.6 degrees meet at
    /// an edge (coplanar facets of one face agree to round-off).
    constexpr double corner_cosine = 0.999;

    double
    distance_to_segment(const Point<3> &x, const Point<3> &a, const Point<3> &b)
    {
      const Tensor<1, 3> ab     = b - a;
      const double       length = ab.norm_square();
      const double       s      = length > 0 ? std::clamp((x - a) * ab / length, 0., 1.) : 0.;
      return (x - (a + s * ab)).norm();
    }

    Point<3>
    lift(const Point<2> &x)
    {
      return Point<3>(x[0], x[1], 0.);
    }

    Point<3>
    lift(const Point<3> &x)
    {
      return x;
    }

    template <int dim>
    Tensor<1, dim>
    facet_normal(const std::array<Point<dim>, dim> &v)
    {
      Tensor<1, dim> n;
      if constexpr (dim == 2)
        {
          n[0] = v[1][1] - v[0][1];
          n[1] = v[0][0] - v[1][0];
        }
      else
        n = cross_product_3d(v[1] - v[0], v[2] - v[0]);
      const double norm = n.norm();
      return norm > 0 ? Tensor<1, dim>(n / norm) : Tensor<1, dim>();
    }

    /// The faces of a cell of @p n vertices in deal.II's order, each as its
    /// vertices' indices: segments in 2D; triangles and lexicographic
    /// quadrilaterals (polygon 0-1-3-2) in 3D.
    std::vector<std::vector<unsigned int>>
    cell_faces(const int dim, const unsigned int n)
    {
      if (dim == 2)
        return n == 3 ? std::vector<std::vector<unsigned int>>{{0, 1}, {1, 2}, {2, 0}} :
                        std::vector<std::vector<unsigned int>>{{0, 1}, {1, 3}, {3, 2}, {2, 0}};
      if (n == 4)
        return {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
      return {{0, 2, 4, 6}, {1, 3, 5, 7}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}};
    }
  } // namespace

  template <int dim>
  double
  distance_to_facet(const Point<dim> &x, const std::array<Point<dim>, dim> &vertices)
  {
    if constexpr (dim == 2)
      return distance_to_segment(lift(x), lift(vertices[0]), lift(vertices[1]));
    else
      {
        // inside the triangle's prism: the distance to its plane; else to
        // the nearest edge
        const Tensor<1, 3> e1 = vertices[1] - vertices[0], e2 = vertices[2] - vertices[0];
        const Tensor<1, 3> n  = cross_product_3d(e1, e2);
        const double       n2 = n.norm_square();
        if (n2 > 0)
          {
            const Tensor<1, 3> r = x - vertices[0];
            // barycentric coordinates of the projection
            const double b1 = cross_product_3d(r, e2) * n / n2;
            const double b2 = cross_product_3d(e1, r) * n / n2;
            if (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1)
              return std::abs(r * n) / std::sqrt(n2);
          }
        return std::min({distance_to_segment(x, vertices[0], vertices[1]),
                         distance_to_segment(x, vertices[1], vertices[2]),
                         distance_to_segment(x, vertices[2], vertices[0])});
      }
  }

  template <int dim>
  void
  SurfaceFacets<dim>::set_from_cells(const std::vector<Point<dim>> &  vertices,
                                     const std::vector<unsigned int> &cell_start)
  {
    facets.clear();
    // a face by its sorted vertices; kept if one cell has it
    using Key = std::vector<std::array<double, dim>>;
    struct Face
    {
      unsigned int              cell;
      std::vector<unsigned int> local;
      unsigned int              count;
    };
    std::map<Key, Face> faces;
    for (unsigned int c = 0; c + 1 < cell_start.size(); ++c)
      {
        const unsigned int n = cell_start[c + 1] - cell_start[c];
        for (const std::vector<unsigned int> &local : cell_faces(dim, n))
          {
            Key key;
            for (const unsigned int v : local)
              {
                std::array<double, dim> coordinates;
                for (unsigned int d = 0; d < dim; ++d)
                  coordinates[d] = vertices[cell_start[c] + v][d];
                key.push_back(coordinates);
              }
            std::sort(key.begin(), key.end());
            auto [it, inserted] = faces.try_emplace(key, Face{c, local, 0});
            ++it->second.count;
          }
      }
    for (const auto &[key, face] : faces)
      {
        if (face.count != 1)
          continue;
        const Point<dim> *v = &vertices[cell_start[face.cell]];
        const unsigned int n = cell_start[face.cell + 1] - cell_start[face.cell];
        Point<dim>         cell_centre;
        for (unsigned int i = 0; i < n; ++i)
          cell_centre += v[i] / double(n);
        // a quadrilateral face (polygon 0-1-3-2) as two triangles
        std::vector<std::array<unsigned int, dim>> pieces;
        if (face.local.size() == dim)
          {
            std::array<unsigned int, dim> piece;
            std::copy(face.local.begin(), face.local.end(), piece.begin());
            pieces.push_back(piece);
          }
        else if constexpr (dim == 3)
          {
            const auto &q = face.local;
            pieces.push_back({{q[0], q[1], q[3]}});
            pieces.push_back({{q[0], q[3], q[2]}});
          }
        for (const auto &piece : pieces)
          {
            Facet facet;
            Point<dim> facet_centre;
            for (unsigned int i = 0; i < dim; ++i)
              {
                facet.vertices[i] = v[piece[i]];
                facet_centre += v[piece[i]] / double(dim);
              }
            facet.normal = facet_normal<dim>(facet.vertices);
            if (facet.normal * (facet_centre - cell_centre) < 0)
              facet.normal = -facet.normal;
            if (facet.normal.norm_square() > 0)
              facets.push_back(facet);
          }
      }
  }

  template <int dim>
  void
  SurfaceFacets<dim>::set_from_triangles(const std::vector<std::array<Point<dim>, dim>> &triangles)
  {
    facets.clear();
    double signed_volume = 0;
    for (const auto &t : triangles)
      {
        Facet facet;
        facet.vertices = t;
        facet.normal   = facet_normal<dim>(t);
        if constexpr (dim == 3)
          signed_volume +=
            Tensor<1, 3>(t[0]) * cross_product_3d(Tensor<1, 3>(t[1]), Tensor<1, 3>(t[2]));
        if (facet.normal.norm_square() > 0)
          facets.push_back(facet);
      }
    // a surface listed inside out
    if (signed_volume < 0)
      for (Facet &facet : facets)
        facet.normal = -facet.normal;
  }

  template <int dim>
  FaceBelow<dim>
  SurfaceFacets<dim>::nearest_face(const Point<dim> &x,
                                     const double      depth_limit,
                                     const double      edge_margin) const
  {
    double       nearest = std::numeric_limits<double>::max();
    const Facet *best    = nullptr;
    for (const Facet &facet : facets)
      {
        // the facet's bounding box first: most facets are far
        double outside = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            double low = facet.vertices[0][d], high = low;
            for (unsigned int i = 1; i < dim; ++i)
              {
                low  = std::min(low, facet.vertices[i][d]);
                high = std::max(high, facet.vertices[i][d]);
              }
            outside = std::max({outside, low - x[d], x[d] - high});
          }
        if (outside >= nearest || outside > depth_limit)
          continue;
        const double distance = distance_to_facet<dim>(x, facet.vertices);
        if (distance < nearest)
          {
            nearest = distance;
            best    = &facet;
          }
      }
    if (best == nullptr || nearest > depth_limit)
      return {};
    // near an edge or a corner, where a facet of another direction is
    // within the margin, the face is ambiguous
    for (const Facet &facet : facets)
      if (facet.normal * best->normal < corner_cosine &&
          distance_to_facet<dim>(x, facet.vertices) <= edge_margin)
        return {};
    return {best->normal, (best->vertices[0] - x) * best->normal};
  }

  template class SurfaceFacets<2>;
  template class SurfaceFacets<3>;
  template double distance_to_facet<2>(const Point<2> &, const std::array<Point<2>, 2> &);
  template double distance_to_facet<3>(const Point<3> &, const std::array<Point<3>, 3> &);
} // namespace sable::mpm
