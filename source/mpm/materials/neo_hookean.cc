#include <sable/base/input_error.h>
#include <sable/mpm/materials/material_registry.h>
#include <sable/mpm/materials/neo_hookean.h>

#include <cmath>

namespace sable::mpm
{
  namespace
  {
    const MaterialRegistration registration({"neo-Hookean",
                                              nullptr,
                                              nullptr,
                                              nullptr,
                                              [](const MaterialParameters &p) {
                                                return std::make_unique<NeoHookean>(p);
                                              }});
  } // namespace

  void
  NeoHookean::update_stress(const Tensor<2, 3> &,
                            const Tensor<2, 3> &F,
                            const double,
                            SymmetricTensor<2, 3> &stress,
                            double *) const
  {
    const double K = parameters.bulk_modulus, G = parameters.shear_modulus;
    const double J = determinant(F);
    const SymmetricTensor<2, 3> b = symmetrize(F * transpose(F));
    stress = 0.5 * K * (J - 1. / J) * unit_symmetric_tensor<3>() +
             G * std::pow(J, -5. / 3.) * deviator(b);
  }

  double
  NeoHookean::strain_energy_density(const SymmetricTensor<2, 3> &,
                                    const Tensor<2, 3> &F) const
  {
    const double K = parameters.bulk_modulus, G = parameters.shear_modulus;
    const double J = determinant(F);
    const double trace_b = scalar_product(F, F);
    return 0.25 * K * (J * J - 1.) - 0.5 * K * std::log(J) +
           0.5 * G * (std::pow(J, -2. / 3.) * trace_b - 3.);
  }
} // namespace sable::mpm
