#include <deal.II/base/numbers.h>

#include <sable/mpm/bodies/conforming_seeding.h>

#include <algorithm>
#include <cmath>

namespace sable::mpm
{
  template <int dim>
  PointCloud<dim>
  conforming_ball_points(const Point<dim> &centre, const double radius, const double spacing)
  {
    PointCloud<dim>    cloud;
    const unsigned int n_layers  = std::max(1u, static_cast<unsigned int>(std::lround(radius / spacing)));
    const double       thickness = radius / n_layers;
    const double       pi        = numbers::PI;
    for (unsigned int j = 0; j < n_layers; ++j)
      {
        const double outer = radius - j * thickness;
        const double inner = outer - thickness;
        const double r     = 0.5 * (outer + inner);
        if (dim == 2)
          {
            // a multiple of four points, half a step off the axes: the
            // ring is its own mirror image across both axes through the
            // centre and no point lies on them, so a disk centred on a
            // grid line puts no point on a cell face, where the gradients
            // of the linear functions jump and take the side of whichever
            // cell holds the point (two equal disks meeting head-on on a
            // grid line spun and drifted sideways)
            const unsigned int n =
              4 * std::max(1u, static_cast<unsigned int>(std::lround(pi * r / (2 * thickness))));
            const double volume = pi * (outer * outer - inner * inner) / n;
            for (unsigned int i = 0; i < n; ++i)
              {
                const double phi = 2 * pi * (i + 0.5) / n;
                Point<dim>   x   = centre;
                x[0] += r * std::cos(phi);
                x[1] += r * std::sin(phi);
                cloud.positions.push_back(x);
                cloud.volumes.push_back(volume);
              }
          }
        else
          {
            const unsigned int n = std::max(
              1u, static_cast<unsigned int>(std::lround(4 * pi * r * r / (thickness * thickness))));
            const double volume = 4. / 3. * pi * (std::pow(outer, 3) - std::pow(inner, 3)) / n;
            // a Fibonacci spiral: equal areas per point on the sphere
            const double golden = pi * (3 - std::sqrt(5.));
            for (unsigned int i = 0; i < n; ++i)
              {
                const double z   = 1 - (2 * i + 1.) / n;
                const double rho = std::sqrt(std::max(0., 1 - z * z));
                const double phi = golden * i + pi * (j % 2);
                Point<dim>   x   = centre;
                x[0] += r * rho * std::cos(phi);
                x[1] += r * rho * std::sin(phi);
                x[dim - 1] += r * z;
                cloud.positions.push_back(x);
                cloud.volumes.push_back(volume);
              }
          }
      }
    return cloud;
  }

  template PointCloud<2>
  conforming_ball_points<2>(const Point<2> &, const double, const double);
  template PointCloud<3>
  conforming_ball_points<3>(const Point<3> &, const double, const double);
} // namespace sable::mpm
