// separating_normal(): the plane between two bodies' points near a node,
// fitted by logistic regression, on point clouds whose answer is known:
// - two faces ending flush at the node (the front ends of stacked blocks),
//   in 2D and 3D: the data are mirror images of each other across the
//   interface, so the normal is the interface's to round-off;
// - swapping the clouds reverses the normal to round-off;
// - a straight interface at angles 0..75 degrees, each body seeded on its
//   own lattice aligned with the interface, the node at several offsets
//   from it: the plane of widest gap is the interface, and the fit (whose
//   penalty stops short of that limit) is within 3 degrees of it; in 2D,
//   with cells of 1 x 0.5 (the fit works in cell units) and in 3D;
// - a block's corner on a plane, the corner at or beyond the node, and the
//   block moved 0.1 and 0.2 cells into the plane: within 3.5 degrees of the
//   plane's normal (the limit of the fit's penalty, see separating_plane.cc;
//   the direction between the two clouds' centroids, printed alongside,
//   tilts 8-33 degrees).
#include <sable/mpm/contact/separating_plane.h>

#include <test_support.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace sable::mpm;
using sable_tests::check;

namespace
{
  constexpr double degree = M_PI / 180.;

  template <int dim>
  Tensor<1, dim>
  unit_cells()
  {
    Tensor<1, dim> size;
    for (unsigned int d = 0; d < dim; ++d)
      size[d] = 1;
    return size;
  }

  /// Points on a lattice of spacing 1/2 in the frame (t, n) rotated by
  /// @p angle, moved by @p shift, kept where @p inside says so and the
  /// node's Q1 weight on cells of @p cell_size is positive; weight = that
  /// Q1 shape value (unit masses).
  template <int dim>
  std::vector<NodeSample<dim>>
  cloud(const std::function<bool(const Point<dim> &)> &inside,
        const Point<dim> &                              node,
        const double                                    angle     = 0,
        const Tensor<1, dim> &                          shift     = Tensor<1, dim>(),
        const Tensor<1, dim> &                          cell_size = unit_cells<dim>())
  {
    std::vector<NodeSample<dim>> samples;
    const double                 s = 0.5;
    const int                    m = 12;
    for (int i = -m; i < m; ++i)
      for (int j = -m; j < m; ++j)
        for (int k = (dim == 3 ? -m : 0); k < (dim == 3 ? m : 1); ++k)
          {
            // lattice coordinates in the rotated frame, then real ones
            const double a = (i + 0.5) * s, b = (j + 0.5) * s, c = (k + 0.5) * s;
            Point<dim>   x;
            x[0] = std::cos(angle) * a - std::sin(angle) * b;
            x[1] = std::sin(angle) * a + std::cos(angle) * b;
            if (dim == 3)
              x[dim - 1] = c;
            if (!inside(x))
              continue;
            x += shift;
            double weight = 1;
            for (unsigned int d = 0; d < dim; ++d)
              weight *= std::max(0., 1. - std::abs(x[d] - node[d]) / cell_size[d]);
            if (weight > 0)
              samples.push_back({x, weight});
          }
    return samples;
  }

  /// The angle between @p a and @p b, in degrees.
  template <int dim>
  double
  angle_between(const Tensor<1, dim> &a, const Tensor<1, dim> &b)
  {
    return std::acos(std::min(1., std::max(-1., a * b / (a.norm() * b.norm())))) / degree;
  }

  void
  flush_faces()
  {
    // 2D: top block y in (0, 1), lower block y in (-1, 0), both ending at
    // x = xe near the node at the origin
    for (const double xe : {0., 0.3, 0.5, 0.8})
      {
        const Point<2> node;
        const auto     top   = cloud<2>([&](const Point<2> &x) { return x[0] < xe && x[1] > 0; }, node);
        const auto     lower = cloud<2>([&](const Point<2> &x) { return x[0] < xe && x[1] < 0; }, node);
        const Tensor<1, 2> n = separating_normal(top, lower, node, unit_cells<2>());
        check("2D flush ends at x = " + std::to_string(xe) + ": normal (" + std::to_string(n[0]) +
                ", " + std::to_string(n[1]) + ") is -y to round-off",
              std::abs(n[0]) < 1e-12 && std::abs(n[1] + 1) < 1e-12);
        const Tensor<1, 2> m = separating_normal(lower, top, node, unit_cells<2>());
        check("2D flush ends: swapping the clouds reverses the normal",
              (m + n).norm() < 1e-12);
      }
    // 3D: a corner of both boxes at the node, interface z = 0
    const Point<3> node;
    const auto     top =
      cloud<3>([](const Point<3> &x) { return x[0] < 0.3 && x[1] < 0.6 && x[2] > 0; }, node);
    const auto lower =
      cloud<3>([](const Point<3> &x) { return x[0] < 0.3 && x[1] < 0.6 && x[2] < 0; }, node);
    const Tensor<1, 3> n = separating_normal(top, lower, node, unit_cells<3>());
    check("3D flush corners: normal (" + std::to_string(n[0]) + ", " + std::to_string(n[1]) +
            ", " + std::to_string(n[2]) + ") is -z to round-off",
          std::abs(n[0]) < 1e-12 && std::abs(n[1]) < 1e-12 && std::abs(n[2] + 1) < 1e-12);
  }

  /// A straight interface through the x-y plane at 0..75 degrees (in 3D a
  /// plane containing z), each side seeded on a lattice aligned with it,
  /// the node up to 0.45 cells off it; cells of @p cell_size.
  template <int dim>
  void
  tilted_interface(const Tensor<1, dim> &cell_size, const std::string &what)
  {
    double worst = 0;
    for (const double angle : {0., 10., 17., 30., 45., 60., 75.})
      for (const double offset : {0., 0.2, 0.45})
        {
          const double   a = angle * degree;
          Tensor<1, dim> normal;
          normal[0] = -std::sin(a);
          normal[1] = std::cos(a);
          // the node off the interface by offset cells along its normal
          double cells_along_normal = 0;
          for (unsigned int d = 0; d < dim; ++d)
            cells_along_normal += std::pow(normal[d] * cell_size[d], 2);
          const Point<dim> node(-offset * std::sqrt(cells_along_normal) * normal);
          const auto       upper = cloud<dim>(
            [&](const Point<dim> &x) { return x * normal > 0; }, node, a, Tensor<1, dim>(), cell_size);
          const auto lower = cloud<dim>(
            [&](const Point<dim> &x) { return x * normal < 0; }, node, a, Tensor<1, dim>(), cell_size);
          const Tensor<1, dim> n = separating_normal(upper, lower, node, cell_size);
          worst                  = std::max(worst, angle_between(n, Tensor<1, dim>(-normal)));
        }
    check(what + ": straight interface at 0..75 degrees, node up to 0.45 cells off it: the "
                 "fitted normal is within 3 degrees (worst " +
            std::to_string(worst) + ")",
          worst < 3);
  }

  void
  corner_on_plane()
  {
    for (const double penetration : {0., 0.1, 0.2})
      for (const double xe : {0., 0.25, 0.5, 0.75})
        {
          const Point<2> node;
          // the block's points moved into the plane: its surface, half a
          // spacing below its lowest points, overlaps the plane's
          const auto block = cloud<2>([&](const Point<2> &x) { return x[0] < xe && x[1] > 0; },
                                      node,
                                      0,
                                      Tensor<1, 2>({0., -penetration}));
          const auto plane = cloud<2>([](const Point<2> &x) { return x[1] < 0; }, node);
          const Tensor<1, 2> n    = separating_normal(block, plane, node, unit_cells<2>());
          const double       tilt = angle_between(n, Tensor<1, 2>({0., -1.}));
          // for comparison: the direction between the clouds' centroids
          const auto centroid = [](const std::vector<NodeSample<2>> &samples) {
            Tensor<1, 2> sum;
            double       weight = 0;
            for (const NodeSample<2> &s : samples)
              {
                sum += s.weight * s.location;
                weight += s.weight;
              }
            return Tensor<1, 2>(sum / weight);
          };
          const double centroid_tilt =
            angle_between(centroid(plane) - centroid(block), Tensor<1, 2>({0., -1.}));
          check("block corner at x = " + std::to_string(xe) + " on a plane, overlapping by " +
                  std::to_string(penetration) + " cells: the normal tilts " +
                  std::to_string(tilt) + " degrees (at most 3.5; the centroids' direction " +
                  std::to_string(centroid_tilt) + ")",
                tilt < 3.5);
        }
  }

  void
  empty_cloud()
  {
    const Point<2> node;
    const auto     some = cloud<2>([](const Point<2> &x) { return x[1] > 0; }, node);
    check("no points on one side: no normal",
          separating_normal<2>(some, {}, node, unit_cells<2>()).norm() == 0);
  }
} // namespace

int
main()
{
  flush_faces();
  tilted_interface<2>(unit_cells<2>(), "2D");
  // the fit works in cell units: the normal must come back in real space
  tilted_interface<2>(Tensor<1, 2>({1., 0.5}), "2D, cells of 1 x 0.5");
  tilted_interface<3>(unit_cells<3>(), "3D");
  corner_on_plane();
  empty_cloud();
  return sable_tests::exit_code();
}
