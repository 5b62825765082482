#include <sable/mpm/materials/hypoelastic.h>

namespace sable::mpm
{
  void
  Hypoelastic::update_stress(const Tensor<2, 3> &L,
                             const Tensor<2, 3> &,
                             const double           dt,
                             SymmetricTensor<2, 3> &stress,
                             double *) const
  {
    stress = jaumann_elastic_update(L, dt, stress);
  }

  double
  Hypoelastic::strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                     const Tensor<2, 3> &         F) const
  {
    // the complementary energy is per current volume
    return complementary_energy(stress) * determinant(F);
  }
} // namespace sable::mpm
