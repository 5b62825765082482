#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <sable/base/input_error.h>
#include <sable/mpm/bodies/body_mesh.h>
#include <sable/mpm/bodies/closed_surface.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace sable::mpm
{
  namespace
  {
    // inclusive tests: a point on a face shared by two cells, or on the
    // mesh's boundary, is inside (as the built-in shapes' boundaries are)
    constexpr double tolerance = 1e-10;

    /// Barycentric test of a triangle (2D) or tetrahedron (3D), either
    /// orientation.
    template <int dim>
    bool
    simplex_contains(const Point<dim> *v, const Point<dim> &x)
    {
      Tensor<2, dim> edges;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          edges[d][i] = v[i + 1][d] - v[0][d];
      const double det = determinant(edges);
      if (det == 0)
        return false;
      const Tensor<1, dim> lambda = invert(edges) * (x - v[0]);
      double               sum    = 0;
      for (unsigned int i = 0; i < dim; ++i)
        {
          if (lambda[i] < -tolerance)
            return false;
          sum += lambda[i];
        }
      return sum <= 1 + tolerance;
    }

    template <int dim>
    double
    simplex_measure(const Point<dim> *v)
    {
      Tensor<2, dim> edges;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          edges[d][i] = v[i + 1][d] - v[0][d];
      return std::abs(determinant(edges)) / (dim == 2 ? 2. : 6.);
    }

    /// The two triangles of a quadrilateral (lexicographic vertices 0, 1,
    /// 2, 3; its polygon is 0-1-3-2), cut along the diagonal that lies
    /// inside it: 0-3 unless that gives triangles of opposite orientation.
    std::array<std::array<unsigned int, 3>, 2>
    quad_triangles(const Point<2> *v)
    {
      const auto orientation = [&](unsigned int a, unsigned int b, unsigned int c) {
        return (v[b][0] - v[a][0]) * (v[c][1] - v[a][1]) - (v[b][1] - v[a][1]) * (v[c][0] - v[a][0]);
      };
      if (orientation(0, 1, 3) * orientation(0, 3, 2) > 0)
        return {{{{0, 1, 3}}, {{0, 3, 2}}}};
      return {{{{0, 1, 2}}, {{1, 3, 2}}}};
    }

    /// Trilinear map of a hexahedron (lexicographic vertices) at @p xi and its Jacobian.
    std::pair<Point<3>, Tensor<2, 3>>
    trilinear(const Point<3> *v, const Point<3> &xi)
    {
      Point<3>     x;
      Tensor<2, 3> jacobian;
      for (unsigned int i = 0; i < 8; ++i)
        {
          double         shape = 1;
          Tensor<1, 3>   gradient;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const bool   upper = (i >> d) & 1;
              const double value = upper ? xi[d] : 1 - xi[d];
              shape *= value;
            }
          for (unsigned int d = 0; d < 3; ++d)
            {
              double derivative = 1;
              for (unsigned int e = 0; e < 3; ++e)
                {
                  const bool upper = (i >> e) & 1;
                  derivative *= e == d ? (upper ? 1. : -1.) : (upper ? xi[e] : 1 - xi[e]);
                }
              gradient[d] = derivative;
            }
          x += shape * Tensor<1, 3>(v[i]);
          jacobian += outer_product(Tensor<1, 3>(v[i]), gradient);
        }
      return {x, jacobian};
    }

    /// Whether x is the image of a point of the closed unit cube (Newton
    /// from the centre; no convergence counts as outside, as in deal.II's
    /// MappingQ1::transform_real_to_unit_cell()).
    bool
    hex_contains(const Point<3> *v, const Point<3> &x)
    {
      Point<3> xi(0.5, 0.5, 0.5);
      for (unsigned int iteration = 0; iteration < 30; ++iteration)
        {
          const auto [y, jacobian] = trilinear(v, xi);
          const double det         = determinant(jacobian);
          if (det == 0)
            return false;
          const Tensor<1, 3> step = invert(jacobian) * (x - y);
          xi += step;
          if (xi.norm() > 10)
            return false;
          if (step.norm() < 1e-13)
            break;
        }
      const Point<3> y = trilinear(v, xi).first;
      if ((y - x).norm() > 1e-10 * (v[7] - v[0]).norm())
        return false;
      for (unsigned int d = 0; d < 3; ++d)
        if (xi[d] < -tolerance || xi[d] > 1 + tolerance)
          return false;
      return true;
    }

    /// Measure and first moment of a cell: simplices exactly, quadrilaterals
    /// as two triangles, hexahedra by 2-point Gauss quadrature per
    /// direction (exact: det J x is at most cubic in each coordinate).
    template <int dim>
    std::pair<double, Tensor<1, dim>>
    cell_moments(const Point<dim> *v, const unsigned int n_vertices)
    {
      if (n_vertices == dim + 1)
        {
          Tensor<1, dim> centroid;
          for (unsigned int i = 0; i <= dim; ++i)
            centroid += Tensor<1, dim>(v[i]) / (dim + 1.);
          const double measure = simplex_measure(v);
          return {measure, measure * centroid};
        }
      double         measure = 0;
      Tensor<1, dim> moment;
      if constexpr (dim == 2)
        for (const auto &t : quad_triangles(v))
          {
            const Point<2> triangle[3] = {v[t[0]], v[t[1]], v[t[2]]};
            const auto [m, first]      = cell_moments<2>(triangle, 3);
            measure += m;
            moment += first;
          }
      else
        {
          const double g[2] = {0.5 - 0.5 / std::sqrt(3.), 0.5 + 0.5 / std::sqrt(3.)};
          for (unsigned int q = 0; q < 8; ++q)
            {
              const auto [x, jacobian] = trilinear(v, Point<3>(g[q & 1], g[(q >> 1) & 1], g[q >> 2]));
              const double weight      = std::abs(determinant(jacobian)) / 8.;
              measure += weight;
              moment += weight * Tensor<1, 3>(x);
            }
        }
      return {measure, moment};
    }

    /// The "Additional information" of a deal.II exception, on one line.
    std::string
    short_message(const std::exception &error)
    {
      std::string       text   = error.what();
      const std::string marker = "Additional information:";
      const auto        start  = text.find(marker);
      if (start != std::string::npos)
        {
          text          = text.substr(start + marker.size());
          const auto end = text.find("Stacktrace");
          text           = text.substr(0, end);
        }
      std::string result;
      for (const char c : text)
        if (!std::isspace(static_cast<unsigned char>(c)))
          result += c;
        else if (!result.empty() && result.back() != ' ')
          result += ' ';
      while (!result.empty() && (result.back() == ' ' || result.back() == '-'))
        result.pop_back();
      return result;
    }

    /// Whether GridIn reads @p filename as a mesh of dimension @p other_dim
    /// with cells: to tell a mesh of the other dimension from a bad file.
    template <int other_dim>
    bool
    is_mesh_of_dimension(const std::string &filename, const typename GridIn<other_dim>::Format format)
    {
      try
        {
          std::ifstream           in(filename);
          Triangulation<other_dim> triangulation;
          GridIn<other_dim>        grid_in(triangulation);
          grid_in.read(in, format);
          return triangulation.n_active_cells() > 0;
        }
      catch (const std::exception &)
        {
          return false;
        }
    }
  } // namespace

  template <int dim>
  void
  BodyMesh<dim>::add_cell(const std::vector<Point<dim>> &cell_vertices)
  {
    vertices.insert(vertices.end(), cell_vertices.begin(), cell_vertices.end());
    cell_start.push_back(vertices.size());
  }

  template <int dim>
  void
  BodyMesh<dim>::finish()
  {
    box = {vertices.empty() ? Point<dim>() : vertices[0], vertices.empty() ? Point<dim>() : vertices[0]};
    for (const Point<dim> &v : vertices)
      for (unsigned int d = 0; d < dim; ++d)
        {
          box.first[d]  = std::min(box.first[d], v[d]);
          box.second[d] = std::max(box.second[d], v[d]);
        }

    total_measure = 0;
    Tensor<1, dim> moment;
    for (unsigned int c = 0; c < n_cells(); ++c)
      {
        const auto [m, first] = cell_moments<dim>(&vertices[cell_start[c]], cell_start[c + 1] - cell_start[c]);
        total_measure += m;
        moment += first;
      }
    region_centroid = Point<dim>(total_measure > 0 ? moment / total_measure : moment);
    facets.set_from_cells(vertices, cell_start);

    // about one cell per bin
    const unsigned int per_direction =
      std::max(1u, static_cast<unsigned int>(std::ceil(std::pow(double(n_cells()), 1. / dim))));
    unsigned int n_total = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        n_bins[d]   = per_direction;
        bin_size[d] = std::max(box.second[d] - box.first[d], 1e-300) / per_direction;
        n_total *= per_direction;
      }
    bins.assign(n_total, {});
    for (unsigned int c = 0; c < n_cells(); ++c)
      {
        std::array<unsigned int, dim> lo, hi;
        for (unsigned int d = 0; d < dim; ++d)
          {
            double low = vertices[cell_start[c]][d], high = low;
            for (unsigned int v = cell_start[c]; v < cell_start[c + 1]; ++v)
              {
                low  = std::min(low, vertices[v][d]);
                high = std::max(high, vertices[v][d]);
              }
            const auto bin = [&](const double y) {
              const double b = std::floor((y - box.first[d]) / bin_size[d]);
              return static_cast<unsigned int>(std::clamp(b, 0., double(n_bins[d] - 1)));
            };
            // widened by the tolerance of the tests: a point on a bin's
            // border finds the cells of both bins
            lo[d] = bin(low - tolerance * bin_size[d]);
            hi[d] = bin(high + tolerance * bin_size[d]);
          }
        std::array<unsigned int, dim> i = lo;
        while (true)
          {
            unsigned int index = 0;
            for (int d = dim - 1; d >= 0; --d)
              index = index * n_bins[d] + i[d];
            bins[index].push_back(c);
            unsigned int d = 0;
            for (; d < dim; ++d)
              if (i[d] < hi[d])
                {
                  ++i[d];
                  break;
                }
              else
                i[d] = lo[d];
            if (d == dim)
              break;
          }
      }
  }

  template <int dim>
  void
  BodyMesh<dim>::set_surface(const ClosedSurface &closed_surface)
  {
    if constexpr (dim == 3)
      {
        surface         = std::make_shared<const ClosedSurface>(closed_surface);
        box             = surface->bounding_box();
        total_measure   = surface->volume();
        region_centroid = surface->centroid();
        facets.set_from_triangles(surface->get_triangles());
      }
    else
      throw InputError("a 2D volume mesh; an STL file is a 3D surface");
  }

  template <int dim>
  bool
  BodyMesh<dim>::cell_contains(const unsigned int c, const Point<dim> &x) const
  {
    const Point<dim> * v          = &vertices[cell_start[c]];
    const unsigned int n_vertices = cell_start[c + 1] - cell_start[c];
    if (n_vertices == dim + 1)
      return simplex_contains(v, x);
    if constexpr (dim == 2)
      {
        for (const auto &t : quad_triangles(v))
          {
            const Point<2> triangle[3] = {v[t[0]], v[t[1]], v[t[2]]};
            if (simplex_contains<2>(triangle, x))
              return true;
          }
        return false;
      }
    else
      return hex_contains(v, x);
  }

  template <int dim>
  bool
  BodyMesh<dim>::contains(const Point<dim> &x) const
  {
    if constexpr (dim == 3)
      if (surface)
        return surface->contains(x);
    unsigned int index = 0;
    for (int d = dim - 1; d >= 0; --d)
      {
        const double margin = tolerance * bin_size[d];
        if (x[d] < box.first[d] - margin || x[d] > box.second[d] + margin)
          return false;
        const double b = std::floor((x[d] - box.first[d]) / bin_size[d]);
        index          = index * n_bins[d] + static_cast<unsigned int>(std::clamp(b, 0., double(n_bins[d] - 1)));
      }
    for (const unsigned int c : bins[index])
      if (cell_contains(c, x))
        return true;
    return false;
  }

  template <int dim>
  Point<dim>
  BodyMesh<dim>::top_point(const Tensor<1, dim> &gravity) const
  {
    if constexpr (dim == 3)
      if (surface)
        return surface->top_point(gravity);
    Point<dim> top = vertices.empty() ? Point<dim>() : vertices[0];
    for (const Point<dim> &v : vertices)
      if (gravity * (v - top) < 0)
        top = v;
    return top;
  }

  template <int dim>
  BodyMesh<dim>
  read_body_mesh(const std::string &filename, const double scale, const Tensor<1, dim> &translation)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("a readable mesh file (cannot open " + filename + ")");

    const std::string suffix = filename.substr(std::min(filename.size(), filename.rfind('.') + 1));
    // the same enumerator in GridIn<2> and GridIn<3>
    typename GridIn<dim>::Format format;
    std::string                  format_name;
    if (suffix == "msh")
      format = GridIn<dim>::msh, format_name = "Gmsh";
    else if (suffix == "vtk")
      format = GridIn<dim>::vtk, format_name = "VTK";
    else if (suffix == "inp" || suffix == "ucd")
      format = GridIn<dim>::ucd, format_name = "UCD";
    else if (suffix == "stl" && dim == 3)
      {
        BodyMesh<dim> mesh;
        Tensor<1, 3>  shift;
        for (unsigned int d = 0; d < dim; ++d)
          shift[d] = translation[d];
        mesh.set_surface(read_stl(filename, scale, shift));
        return mesh;
      }
    else if (suffix == "stl")
      throw InputError("a 2D volume mesh (*.msh, *.vtk, *.inp, *.ucd); an STL file is a 3D surface");
    else
      throw InputError(std::string("a file named *.msh (Gmsh), *.vtk (legacy VTK), *.inp, *.ucd (UCD)") +
                       (dim == 3 ? " or *.stl (a closed surface)" : ""));

    const std::string cells = dim == 2 ? "triangles or quadrilaterals" : "tetrahedra or hexahedra";
    const std::string what  = "a " + format_name + " file of a " + std::to_string(dim) +
                             "D volume mesh (" + cells + ")";
    Triangulation<dim> triangulation;
    try
      {
        GridIn<dim> grid_in(triangulation);
        grid_in.read(in, format);
      }
    catch (const std::exception &error)
      {
        constexpr int other_dim = 5 - dim;
        if (is_mesh_of_dimension<other_dim>(
              filename, static_cast<typename GridIn<other_dim>::Format>(static_cast<int>(format))))
          throw InputError(what + "; this is a " + std::to_string(other_dim) + "D mesh");
        throw InputError(what + "; deal.II's GridIn cannot read it: " + short_message(error));
      }
    if (triangulation.n_active_cells() == 0)
      throw InputError(what + "; it has no " + std::to_string(dim) + "D cells");

    BodyMesh<dim>           mesh;
    std::vector<Point<dim>> cell_vertices;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const ReferenceCell type = cell->reference_cell();
        if (type != (dim == 2 ? ReferenceCells::Triangle : ReferenceCells::Tetrahedron) &&
            type != ReferenceCells::get_hypercube<dim>())
          throw InputError(what + "; it has a cell of type " + type.to_string());
        cell_vertices.clear();
        for (const unsigned int v : cell->vertex_indices())
          cell_vertices.push_back(Point<dim>(scale * Tensor<1, dim>(cell->vertex(v)) + translation));
        mesh.add_cell(cell_vertices);
      }
    mesh.finish();
    return mesh;
  }

  template class BodyMesh<2>;
  template class BodyMesh<3>;
  template BodyMesh<2>
  read_body_mesh<2>(const std::string &, double, const Tensor<1, 2> &);
  template BodyMesh<3>
  read_body_mesh<3>(const std::string &, double, const Tensor<1, 3> &);
} // namespace sable::mpm
