// Strain-controlled load paths: isotropic, uniaxial strain, triaxial.
#ifndef sable_qusgm_load_path_h
#define sable_qusgm_load_path_h

#include <sable/qusgm/pack.h>

#include <array>
#include <string>

namespace sable::qusgm
{
  /**
   * Strain increments per axis (compression positive) for each load
   * increment. Isotropic: the same increment on all axes. Uniaxial strain:
   * only the axial one, lateral walls fixed. Triaxial: axial increment and
   * two equal lateral increments, lateral = ratio * axial.
   */
  struct LoadPath
  {
    enum class Type
    {
      isotropic,
      uniaxial_strain,
      triaxial
    };
    Type         type             = Type::uniaxial_strain;
    unsigned int axis             = 2;
    double       strain_increment = 1e-4;
    unsigned int n_increments     = 10;
    double       lateral_ratio    = 0.5;

    static Type
    parse_type(const std::string &name);

    std::array<double, 3>
    strain_increments() const;

    /**
     * Wall moves for strain increments @p d_strain applied symmetrically
     * to the current walls, each relative to the reference lengths
     * @p lengths (the undeformed box).
     */
    static std::array<double, 6>
    wall_moves(const std::array<double, 3> &d_strain,
               const std::array<double, 3> &lengths);
  };
} // namespace sable::qusgm

#endif
