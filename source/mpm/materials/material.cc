#include <sable/base/input_error.h>
#include <sable/mpm/materials/hypoelastic.h>
#include <sable/mpm/materials/material.h>
#include <sable/mpm/materials/neo_hookean.h>
#include <sable/mpm/materials/von_mises.h>

#include <cmath>
#include <functional>
#include <map>

namespace sable::mpm
{
  Material::Material(const MaterialParameters &parameters)
    : parameters(parameters)
  {}

  double
  Material::wave_speed() const
  {
    return std::sqrt(
      (parameters.bulk_modulus + 4. / 3. * parameters.shear_modulus) /
      parameters.density);
  }

  double
  Material::complementary_energy(const SymmetricTensor<2, 3> &stress) const
  {
    const double pressure = trace(stress) / 3.;
    const auto   s        = deviator(stress);
    return 0.5 * pressure * pressure / parameters.bulk_modulus +
           0.25 * (s * s) / parameters.shear_modulus;
  }

  SymmetricTensor<2, 3>
  Material::jaumann_elastic_update(const Tensor<2, 3> &          L,
                                   const double                  dt,
                                   const SymmetricTensor<2, 3> &stress) const
  {
    const double K = parameters.bulk_modulus, G = parameters.shear_modulus;
    const SymmetricTensor<2, 3> D = symmetrize(L);
    const Tensor<2, 3>          W = 0.5 * (L - transpose(L));
    const Tensor<2, 3>          s(stress);
    // W sigma - sigma W is symmetric for symmetric sigma and skew W
    const SymmetricTensor<2, 3> rotation = symmetrize(W * s - s * W);
    return stress + dt * (rotation + (K - 2. / 3. * G) * trace(D) *
                                       unit_symmetric_tensor<3>() +
                          2. * G * D);
  }

  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters)
  {
    static const std::map<
      std::string,
      std::function<std::unique_ptr<Material>(const MaterialParameters &)>>
      registry = {{"linear elastic",
                   [](const auto &p) { return std::make_unique<Hypoelastic>(p); }},
                  {"neo-Hookean",
                   [](const auto &p) { return std::make_unique<NeoHookean>(p); }},
                  {"von Mises",
                   [](const auto &p) { return std::make_unique<VonMises>(p); }}};
    const auto it = registry.find(parameters.model);
    check_input(it != registry.end(),
                "Material",
                parameters.model,
                "linear elastic | neo-Hookean | von Mises");
    return it->second(parameters);
  }
} // namespace sable::mpm
