#include <sable/base/input_error.h>
#include <sable/qusgm/load_path.h>

namespace sable::qusgm
{
  LoadPath::Type
  LoadPath::parse_type(const std::string &name)
  {
    if (name == "isotropic")
      return Type::isotropic;
    if (name == "uniaxial strain")
      return Type::uniaxial_strain;
    if (name == "triaxial")
      return Type::triaxial;
    throw InputError("invalid input: 'Load path/Type = " + name +
                     "'; allowed: isotropic | uniaxial strain | triaxial");
  }

  std::array<double, 3>
  LoadPath::strain_increments() const
  {
    std::array<double, 3> d{};
    switch (type)
      {
        case Type::isotropic:
          d.fill(strain_increment);
          break;
        case Type::uniaxial_strain:
          d[axis] = strain_increment;
          break;
        case Type::triaxial:
          d.fill(lateral_ratio * strain_increment);
          d[axis] = strain_increment;
          break;
      }
    return d;
  }

  std::array<double, 6>
  LoadPath::wall_moves(const std::array<double, 3> &d_strain,
                       const std::array<double, 3> &lengths)
  {
    std::array<double, 6> move{};
    for (unsigned int a = 0; a < 3; ++a)
      {
        // Compression positive: both walls move inwards by half.
        move[a]     = 0.5 * d_strain[a] * lengths[a];
        move[a + 3] = -move[a];
      }
    return move;
  }
} // namespace sable::qusgm
