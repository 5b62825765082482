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
                  const double    rho)
  {
    centre.push_back(x);
    radius.push_back(r);
    youngs_modulus.push_back(e);
    poisson_ratio.push_back(nu);
    shear_modulus.push_back(e / (2. * (1. + nu)));
    density.push_back(rho);
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
    check_input(size() > 0,
                source + ": number of grains",
                size(),
                "at least one grain");
    for (unsigned int i = 0; i < size(); ++i)
      {
        const std::string grain = source + ": grain " + std::to_string(i);
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
        check_input(density[i] >= 0 && std::isfinite(density[i]),
                    grain + " density",
                    density[i],
                    "rho >= 0");
      }
  }

  Pack
  read_pack(const std::string &filename,
            const double       default_youngs_modulus,
            const double       default_poisson_ratio,
            const double       default_density)
  {
    std::ifstream in(filename);
    check_input(static_cast<bool>(in),
                "Pack file",
                filename,
                "an existing, readable CSV file with columns x y z r [E nu rho]");
    Pack         pack;
    std::string  line;
    unsigned int line_number = 0;
    while (std::getline(in, line))
      {
        ++line_number;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::replace(line.begin(), line.end(), ';', ' ');
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
          continue;
        // A header line of column names.
        if (pack.size() == 0 && std::isalpha(line[first]))
          continue;
        std::istringstream  fields(line);
        std::vector<double> values;
        std::string         token;
        bool                numeric = true;
        while (fields >> token)
          {
            char        *end   = nullptr;
            const double value = std::strtod(token.c_str(), &end);
            if (end == token.c_str() || *end != '\0')
              numeric = false;
            values.push_back(value);
          }
        const std::string where =
          "Pack file " + filename + ", line " + std::to_string(line_number);
        check_input(numeric && values.size() >= 4 && values.size() <= 7,
                    where,
                    line,
                    "4 to 7 numbers: x y z r [E nu rho]");
        pack.add_grain(Point<3>(values[0], values[1], values[2]),
                       values[3],
                       values.size() > 4 ? values[4] : default_youngs_modulus,
                       values.size() > 5 ? values[5] : default_poisson_ratio,
                       values.size() > 6 ? values[6] : default_density);
      }
    pack.check("Pack file " + filename);
    return pack;
  }

  void
  write_pack(const Pack &pack, const std::string &filename)
  {
    std::ofstream out(filename);
    out << "x,y,z,r,E,nu,rho\n" << std::setprecision(17);
    for (unsigned int i = 0; i < pack.size(); ++i)
      out << pack.centre[i][0] << ',' << pack.centre[i][1] << ','
          << pack.centre[i][2] << ',' << pack.radius[i] << ','
          << pack.youngs_modulus[i] << ',' << pack.poisson_ratio[i] << ','
          << pack.density[i] << '\n';
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
