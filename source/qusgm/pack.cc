#include <sable/base/input_error.h>
#include <sable/qusgm/pack.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace sable::qusgm
{
  void
  Pack::add_grain(const Point<3> &x,
                  const double    r,
                  const double    e,
                  const double    nu,
                  const double    rho,
                  const std::uint64_t grain_id)
  {
    id.push_back(grain_id == std::uint64_t(-1) ? centre.size() : grain_id);
    centre.push_back(x);
    radius.push_back(r);
    youngs_modulus.push_back(e);
    poisson_ratio.push_back(nu);
    shear_modulus.push_back(e / (2. * (1. + nu)));
    density.push_back(rho);
  }

  std::string
  Pack::name(const unsigned int i) const
  {
    std::string text = "grain " + std::to_string(i);
    if (i < id.size() && id[i] != i)
      text += " (id " + std::to_string(id[i]) + ")";
    return text;
  }

  double
  Pack::mass(const unsigned int i) const
  {
    return 4. / 3. * M_PI * std::pow(radius[i], 3) * density[i];
  }

  double
  Pack::mean_radius() const
  {
    return size() ? std::accumulate(radius.begin(), radius.end(), 0.) / size() :
                    0.;
  }

  double
  Pack::max_radius() const
  {
    return size() ? *std::max_element(radius.begin(), radius.end()) : 0.;
  }

  double
  Pack::mean_youngs_modulus() const
  {
    return size() ? std::accumulate(youngs_modulus.begin(),
                                    youngs_modulus.end(),
                                    0.) /
                      size() :
                    0.;
  }

  void
  Pack::permute(const std::vector<unsigned int> &permutation)
  {
    const Pack old = *this;
    for (unsigned int k = 0; k < permutation.size(); ++k)
      {
        const unsigned int i = permutation[k];
        centre[k]            = old.centre[i];
        radius[k]            = old.radius[i];
        youngs_modulus[k]    = old.youngs_modulus[i];
        poisson_ratio[k]     = old.poisson_ratio[i];
        shear_modulus[k]     = old.shear_modulus[i];
        density[k]           = old.density[i];
        id[k]                = old.id[i];
      }
  }

  void
  Pack::sort_spatially()
  {
    permute(spatial_order());
  }

  std::vector<unsigned int>
  Pack::spatial_order() const
  {
    std::vector<unsigned int> permutation(size());
    if (size() < 2)
      {
        std::iota(permutation.begin(), permutation.end(), 0u);
        return permutation;
      }
    Point<3> lo = centre[0], hi = centre[0];
    for (const Point<3> &x : centre)
      for (unsigned int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], x[a]);
          hi[a] = std::max(hi[a], x[a]);
        }
    const double cell = 2. * max_radius();
    // Spread the low 10 bits of v to every third bit.
    auto spread = [](std::uint64_t v) {
      std::uint64_t r = 0;
      for (unsigned int b = 0; b < 10; ++b)
        r |= ((v >> b) & 1u) << (3 * b);
      return r;
    };
    std::vector<std::pair<std::uint64_t, unsigned int>> keys(size());
    for (unsigned int i = 0; i < size(); ++i)
      {
        std::uint64_t code = 0;
        for (unsigned int a = 0; a < 3; ++a)
          {
            const auto c = static_cast<std::uint64_t>(
              std::min(1023., (centre[i][a] - lo[a]) / cell));
            code |= spread(c) << a;
          }
        keys[i] = {code, i};
      }
    std::sort(keys.begin(), keys.end());
    for (unsigned int k = 0; k < size(); ++k)
      permutation[k] = keys[k].second;
    return permutation;
  }

  void
  Pack::check(const std::string &source) const
  {
    check_input(size() > 1,
                source + ": number of grains",
                size(),
                "at least two grains (a pack)");
    check_input(id.size() == size(), source + ": number of ids", id.size(), "one per grain");
    for (unsigned int i = 0; i < size(); ++i)
      {
        const std::string grain = source + ": " + name(i);
        check_input(std::isfinite(centre[i].norm()),
                    grain + " centre",
                    centre[i],
                    "finite coordinates");
        check_input(radius[i] > 0 && std::isfinite(radius[i]),
                    grain + " radius",
                    radius[i],
                    "radius > 0");
        check_input(youngs_modulus[i] > 0 && std::isfinite(youngs_modulus[i]),
                    grain + " Young's modulus",
                    youngs_modulus[i],
                    "E > 0");
        check_input(poisson_ratio[i] > -1 && poisson_ratio[i] < 0.5,
                    grain + " Poisson's ratio",
                    poisson_ratio[i],
                    "-1 < nu < 0.5");
        check_input(density[i] > 0 && std::isfinite(density[i]),
                    grain + " density",
                    density[i],
                    "rho > 0");
      }
    std::vector<std::uint64_t> sorted = id;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    check_input(twice == sorted.end(),
                source + ": grain id",
                twice == sorted.end() ? 0 : *twice,
                "each id once");
  }

  void
  check_overlaps(const Pack        &pack,
                 const Walls       &walls,
                 const double       max_overlap,
                 const std::string &source)
  {
    const unsigned int n = pack.size();
    if (n == 0)
      return;
    // Cell list of cells of one largest diameter over the centres' box.
    Point<3> lo = pack.centre[0], hi = pack.centre[0];
    for (const Point<3> &x : pack.centre)
      for (unsigned int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], x[a]);
          hi[a] = std::max(hi[a], x[a]);
        }
    const double cell = 2. * pack.max_radius();
    std::array<unsigned int, 3> n_cells;
    for (unsigned int a = 0; a < 3; ++a)
      n_cells[a] = static_cast<unsigned int>(
        std::min(std::max(1., (hi[a] - lo[a]) / cell), std::cbrt(8. * n + 27.)));
    auto cell_of = [&](const Point<3> &x, const unsigned int a) {
      const double s = (x[a] - lo[a]) / std::max(hi[a] - lo[a], cell) * n_cells[a];
      return std::min(n_cells[a] - 1, static_cast<unsigned int>(std::max(0., s)));
    };
    const std::size_t total_cells = std::size_t(n_cells[0]) * n_cells[1] * n_cells[2];
    std::vector<std::vector<unsigned int>> cells(total_cells);
    for (unsigned int i = 0; i < n; ++i)
      cells[cell_of(pack.centre[i], 0) +
            n_cells[0] * (cell_of(pack.centre[i], 1) + n_cells[1] * cell_of(pack.centre[i], 2))]
        .push_back(i);
    for (unsigned int i = 0; i < n; ++i)
      {
        const Point<3> &x = pack.centre[i];
        const int       cx = cell_of(x, 0), cy = cell_of(x, 1), cz = cell_of(x, 2);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              {
                const int ix = cx + dx, iy = cy + dy, iz = cz + dz;
                if (ix < 0 || iy < 0 || iz < 0 || ix >= int(n_cells[0]) ||
                    iy >= int(n_cells[1]) || iz >= int(n_cells[2]))
                  continue;
                for (const unsigned int j : cells[ix + n_cells[0] * (iy + n_cells[1] * iz)])
                  {
                    if (j <= i)
                      continue;
                    const double d       = (x - pack.centre[j]).norm();
                    const double overlap = pack.radius[i] + pack.radius[j] - d;
                    const double smaller = std::min(pack.radius[i], pack.radius[j]);
                    if (d > 0 && overlap <= max_overlap * smaller)
                      continue;
                    const std::string pair = pack.name(i) + " and " + pack.name(j);
                    check_input(d > 0,
                                source + ": centres of " + pair,
                                x,
                                "distinct centres (the grains coincide)");
                    std::ostringstream allowed;
                    allowed << "at most Pack/Maximum initial overlap = " << max_overlap
                            << " times the smaller radius (" << max_overlap * smaller
                            << " m)";
                    check_input(false, source + ": overlap of " + pair, overlap, allowed.str());
                  }
              }
        for (unsigned int w = 0; w < 6; ++w)
          {
            const double overlap = walls.overlap(w, x, pack.radius[i]);
            if (overlap <= max_overlap * pack.radius[i])
              continue;
            std::ostringstream allowed;
            allowed << "at most Pack/Maximum initial overlap = " << max_overlap
                    << " times the radius (" << max_overlap * pack.radius[i] << " m)";
            check_input(overlap <= max_overlap * pack.radius[i],
                        source + ": overlap of " + pack.name(i) + " and wall " +
                          Walls::name(w),
                        overlap,
                        allowed.str());
          }
      }
  }

  Point<3>
  Walls::centre() const
  {
    return Point<3>(0.5 * (position[0] + position[3]),
                    0.5 * (position[1] + position[4]),
                    0.5 * (position[2] + position[5]));
  }

  void
  Walls::check() const
  {
    static const char *names[] = {"x", "y", "z"};
    for (unsigned int a = 0; a < 3; ++a)
      check_input(length(a) > 0,
                  std::string("Walls: upper minus lower ") + names[a] +
                    " wall position",
                  length(a),
                  "> 0 (walls must not overlap or cross)");
    check_input(youngs_modulus > 0,
                "Walls/Young's modulus",
                youngs_modulus,
                "> 0");
    check_input(poisson_ratio > -1 && poisson_ratio < 0.5,
                "Walls/Poisson's ratio",
                poisson_ratio,
                "-1 < nu < 0.5");
  }

  const char *
  Walls::name(const unsigned int w)
  {
    static const char *names[] = {"x_min", "y_min", "z_min", "x_max", "y_max", "z_max"};
    return w < 6 ? names[w] : "(no wall)";
  }

  Walls
  bounding_walls(const Pack &pack)
  {
    Walls walls;
    for (unsigned int a = 0; a < 3; ++a)
      {
        walls.position[a]     = std::numeric_limits<double>::max();
        walls.position[a + 3] = -std::numeric_limits<double>::max();
      }
    for (unsigned int i = 0; i < pack.size(); ++i)
      for (unsigned int a = 0; a < 3; ++a)
        {
          walls.position[a] =
            std::min(walls.position[a], pack.centre[i][a] - pack.radius[i]);
          walls.position[a + 3] =
            std::max(walls.position[a + 3], pack.centre[i][a] + pack.radius[i]);
        }
    return walls;
  }
} // namespace sable::qusgm
