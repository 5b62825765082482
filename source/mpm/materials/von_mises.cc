#include <sable/mpm/materials/von_mises.h>

#include <cmath>

namespace sable::mpm
{
  void
  VonMises::update_stress(const Tensor<2, 3> &L,
                          const Tensor<2, 3> &,
                          const double           dt,
                          SymmetricTensor<2, 3> &stress,
                          double *               history) const
  {
    const double G = parameters.shear_modulus, H = parameters.hardening_modulus;
    const SymmetricTensor<2, 3> trial = jaumann_elastic_update(L, dt, stress);
    const SymmetricTensor<2, 3> s     = deviator(trial);
    const double q = std::sqrt(1.5 * (s * s));
    double &     plastic_strain = history[0];
    const double yield_stress = parameters.yield_stress + H * plastic_strain;
    if (q <= yield_stress)
      {
        stress = trial;
        return;
      }
    // radial return: exact for linear hardening
    const double increment = (q - yield_stress) / (3. * G + H);
    plastic_strain += increment;
    stress = trial - (3. * G * increment / q) * s;
  }

  double
  VonMises::strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                  const Tensor<2, 3> &         F) const
  {
    return complementary_energy(stress) * determinant(F);
  }
} // namespace sable::mpm
