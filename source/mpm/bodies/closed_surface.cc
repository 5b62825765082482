#include <sable/base/input_error.h>
#include <sable/mpm/bodies/closed_surface.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    using Point2 = std::array<double, 2>;

    /// (v - u) x (p - u), computed from the edge's lexicographically
    /// smaller end, so that both triangles of an edge get exactly opposite
    /// values
    double
    edge_function(const Point2 &u, const Point2 &v, const Point2 &p)
    {
      const auto cross = [](const Point2 &a, const Point2 &b, const Point2 &q) {
        return (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
      };
      return u < v ? cross(u, v, p) : -cross(v, u, p);
    }

    /// Whether a point on the directed edge u -> v of a counter-clockwise
    /// triangle counts as inside: as if it were moved by (1, -eta) times an
    /// infinitesimal, i.e. edges going down, or horizontal going left.
    bool
    top_left(const Point2 &u, const Point2 &v)
    {
      return v[1] < u[1] || (v[1] == u[1] && v[0] < u[0]);
    }

    Point2
    project(const Point<3> &x)
    {
      return {{x[1], x[2]}};
    }
  } // namespace

  void
  ClosedSurface::set_triangles(const std::vector<std::array<Point<3>, 3>> &new_triangles)
  {
    triangles = new_triangles;
    if (triangles.empty())
      throw InputError("a closed triangulated surface; the file has no triangles");

    // closed: every edge in exactly two triangles
    using Key = std::array<double, 3>;
    std::map<std::pair<Key, Key>, unsigned int> edges;
    for (const auto &t : triangles)
      for (unsigned int e = 0; e < 3; ++e)
        {
          const Point<3> &a = t[e], &b = t[(e + 1) % 3];
          Key             ka{{a[0], a[1], a[2]}}, kb{{b[0], b[1], b[2]}};
          if (kb < ka)
            std::swap(ka, kb);
          ++edges[{ka, kb}];
        }
    unsigned int open = 0;
    for (const auto &edge : edges)
      open += edge.second != 2;
    if (open > 0)
      throw InputError("a closed surface (each edge in two triangles); " + std::to_string(open) + " of its " +
                       std::to_string(edges.size()) + " edges are not");

    box = {triangles[0][0], triangles[0][0]};
    double         signed_volume = 0;
    Tensor<1, 3>   moment;
    for (const auto &t : triangles)
      {
        for (const Point<3> &v : t)
          for (unsigned int d = 0; d < 3; ++d)
            {
              box.first[d]  = std::min(box.first[d], v[d]);
              box.second[d] = std::max(box.second[d], v[d]);
            }
        // the tetrahedron of the origin and the triangle
        const double v = Tensor<1, 3>(t[0]) * cross_product_3d(Tensor<1, 3>(t[1]), Tensor<1, 3>(t[2])) / 6.;
        signed_volume += v;
        moment += v * (Tensor<1, 3>(t[0]) + Tensor<1, 3>(t[1]) + Tensor<1, 3>(t[2])) / 4.;
      }
    enclosed_volume = std::abs(signed_volume);
    if (!(enclosed_volume > 0))
      throw InputError("a closed surface around a volume > 0");
    solid_centroid = Point<3>(moment / signed_volume);

    // bins in the y-z plane, about one triangle per bin
    const unsigned int per_direction =
      std::max(1u, static_cast<unsigned int>(std::ceil(std::sqrt(double(triangles.size())))));
    for (unsigned int d = 0; d < 2; ++d)
      {
        n_bins[d]   = per_direction;
        bin_size[d] = std::max(box.second[d + 1] - box.first[d + 1], 1e-300) / per_direction;
      }
    bins.assign(per_direction * per_direction, {});
    const auto bin = [&](const unsigned int d, const double y) {
      const double b = std::floor((y - box.first[d + 1]) / bin_size[d]);
      return static_cast<unsigned int>(std::clamp(b, 0., double(n_bins[d] - 1)));
    };
    for (unsigned int i = 0; i < triangles.size(); ++i)
      {
        std::array<unsigned int, 2> lo, hi;
        for (unsigned int d = 0; d < 2; ++d)
          {
            double low = triangles[i][0][d + 1], high = low;
            for (const Point<3> &v : triangles[i])
              {
                low  = std::min(low, v[d + 1]);
                high = std::max(high, v[d + 1]);
              }
            // a point on a bin border looks in the bin above it: widen
            lo[d] = bin(d, low - 1e-10 * bin_size[d]);
            hi[d] = bin(d, high + 1e-10 * bin_size[d]);
          }
        for (unsigned int a = lo[0]; a <= hi[0]; ++a)
          for (unsigned int b = lo[1]; b <= hi[1]; ++b)
            bins[a + n_bins[0] * b].push_back(i);
      }
  }

  bool
  ClosedSurface::contains(const Point<3> &x) const
  {
    for (unsigned int d = 0; d < 3; ++d)
      if (x[d] < box.first[d] || x[d] > box.second[d])
        return false;
    std::array<unsigned int, 2> b;
    for (unsigned int d = 0; d < 2; ++d)
      b[d] = static_cast<unsigned int>(
        std::clamp(std::floor((x[d + 1] - box.first[d + 1]) / bin_size[d]), 0., double(n_bins[d] - 1)));
    const Point2 p         = project(x);
    unsigned int crossings = 0;
    for (const unsigned int i : bins[b[0] + n_bins[0] * b[1]])
      {
        const auto &t = triangles[i];
        Point2      q[3] = {project(t[0]), project(t[1]), project(t[2])};
        unsigned int order[3] = {0, 1, 2};
        const double area     = edge_function(q[0], q[1], q[2]);
        if (area == 0)
          continue; // parallel to the ray: a perturbed ray misses it
        if (area < 0)
          std::swap(order[1], order[2]);
        double weight[3]; // of the vertex opposite each edge
        bool   inside = true;
        for (unsigned int e = 0; e < 3 && inside; ++e)
          {
            const Point2 &u = q[order[e]], &v = q[order[(e + 1) % 3]];
            const double  w = edge_function(u, v, p);
            inside          = w > 0 || (w == 0 && top_left(u, v));
            weight[order[(e + 2) % 3]] = w;
          }
        if (!inside)
          continue;
        const double sum = weight[0] + weight[1] + weight[2];
        const double hit = (weight[0] * t[0][0] + weight[1] * t[1][0] + weight[2] * t[2][0]) / sum;
        crossings += hit > x[0];
      }
    return crossings % 2 == 1;
  }

  Point<3>
  ClosedSurface::top_point(const Tensor<1, 3> &gravity) const
  {
    Point<3> top = triangles.empty() ? Point<3>() : triangles[0][0];
    for (const auto &t : triangles)
      for (const Point<3> &v : t)
        if (gravity * (v - top) < 0)
          top = v;
    return top;
  }

  ClosedSurface
  read_stl(const std::string &filename, const double scale, const Tensor<1, 3> &translation)
  {
    std::ifstream in(filename, std::ios::binary);
    if (!in)
      throw InputError("a readable STL file (cannot open " + filename + ")");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto        map = [&](const double x, const double y, const double z) {
      return Point<3>(scale * x + translation[0], scale * y + translation[1], scale * z + translation[2]);
    };

    std::vector<std::array<Point<3>, 3>> triangles;
    std::uint32_t                        count = 0;
    if (bytes.size() >= 84)
      std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() >= 84 && bytes.size() == 84 + 50 * std::uint64_t(count))
      {
        // binary: 80 bytes header, count, per triangle normal, 3 vertices
        // (little-endian float32) and 2 attribute bytes
        for (std::uint32_t i = 0; i < count; ++i)
          {
            float values[12];
            std::memcpy(values, bytes.data() + 84 + 50 * std::size_t(i), sizeof(values));
            std::array<Point<3>, 3> t;
            for (unsigned int v = 0; v < 3; ++v)
              t[v] = map(values[3 + 3 * v], values[4 + 3 * v], values[5 + 3 * v]);
            triangles.push_back(t);
          }
      }
    else
      {
        std::istringstream text(bytes);
        std::string        word;
        if (!(text >> word) || word != "solid")
          throw InputError("an ASCII STL file (starting with 'solid') or a binary one (84 + 50 bytes per "
                           "triangle)");
        std::vector<Point<3>> vertices;
        while (text >> word)
          if (word == "vertex")
            {
              double x, y, z;
              if (!(text >> x >> y >> z))
                throw InputError("an ASCII STL file; vertex " + std::to_string(vertices.size() + 1) +
                                 " is not three numbers");
              vertices.push_back(map(x, y, z));
            }
          else if (word == "endloop")
            {
              if (vertices.size() != 3)
                throw InputError("an STL file of triangles; facet " + std::to_string(triangles.size() + 1) +
                                 " has " + std::to_string(vertices.size()) + " vertices");
              triangles.push_back({{vertices[0], vertices[1], vertices[2]}});
              vertices.clear();
            }
      }
    ClosedSurface surface;
    surface.set_triangles(triangles);
    return surface;
  }
} // namespace sable::mpm
