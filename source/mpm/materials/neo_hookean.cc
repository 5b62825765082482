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

  void
  NeoHookean::update_plane_strain_stress(const Tensor<2, 2> &,
                                         const Tensor<2, 2> &F,
                                         const double,
                                         PlaneStrainStress &stress,
                                         double *) const
  {
    const double K = parameters.bulk_modulus, G = parameters.shear_modulus;
    const double J = determinant(F);
    // b = F F^T with b_zz = 1, b_xz = b_yz = 0
    const double b_xx   = F[0][0] * F[0][0] + F[0][1] * F[0][1];
    const double b_yy   = F[1][0] * F[1][0] + F[1][1] * F[1][1];
    const double b_xy   = F[0][0] * F[1][0] + F[0][1] * F[1][1];
    const double mean   = (b_xx + b_yy + 1.) / 3.;
    const double volume = 0.5 * K * (J - 1. / J);
    const double shear  = G * std::pow(J, -5. / 3.);
    stress = {volume + shear * (b_xx - mean),
              volume + shear * (b_yy - mean),
              volume + shear * (1. - mean),
              shear * b_xy};
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
