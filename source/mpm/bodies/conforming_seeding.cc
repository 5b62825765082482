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
    PointCloud<dim> cloud;
    // a count: x rounded, at least one
    const auto count = [](const double x) {
      return std::max(1u, static_cast<unsigned int>(std::lround(x)));
    };
    const unsigned int n_layers  = count(radius / spacing);
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
            const unsigned int n      = 4 * count(pi * r / (2 * thickness));
            const double       volume = pi * (outer * outer - inner * inner) / n;
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
            // latitude bands, an even number of them so that none lies on
            // the equator, each with a multiple of four points half a step
            // off the meridian planes through the axes: the sphere is its own
            // mirror image across the three planes through its centre
            // along the axes, and no point lies on them (a Fibonacci
            // spiral, the layout before, is the mirror image of nothing:
            // two spheres meeting head-on along a grid line spun at 0.7%
            // of the impact speed). Each point carries its band's share
            // of the shell's volume, so the rounding of the counts does
            // not change the density.
            const double       shell_volume = 4. / 3. * pi * (std::pow(outer, 3) - std::pow(inner, 3));
            const unsigned int n_bands      = 2 * count(pi * r / (2 * thickness));
            for (unsigned int k = 0; k < n_bands; ++k)
              {
                const double theta = pi * (k + 0.5) / n_bands;
                const double band_area_fraction =
                  0.5 * (std::cos(pi * k / n_bands) - std::cos(pi * (k + 1) / n_bands));
                const unsigned int n = 4 * count(pi * r * std::sin(theta) / (2 * thickness));
                const double volume = shell_volume * band_area_fraction / n;
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const double phi = 2 * pi * (i + 0.5) / n;
                    Point<dim>   x   = centre;
                    x[0] += r * std::sin(theta) * std::cos(phi);
                    x[1] += r * std::sin(theta) * std::sin(phi);
                    x[dim - 1] += r * std::cos(theta);
                    cloud.positions.push_back(x);
                    cloud.volumes.push_back(volume);
                  }
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
