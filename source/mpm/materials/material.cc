#include <sable/base/input_error.h>
#include <sable/mpm/materials/material.h>
#include <sable/mpm/materials/material_registry.h>

#include <cmath>
#include <algorithm>

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

  namespace
  {
    /// function-local, so that registrations from any file's static
    /// objects find it constructed
    std::vector<MaterialModelEntry> &
    registry()
    {
      static std::vector<MaterialModelEntry> models;
      return models;
    }
  } // namespace

  MaterialRegistration::MaterialRegistration(MaterialModelEntry entry)
  {
    auto &models = registry();
    const auto position =
      std::find_if(models.begin(), models.end(), [&](const MaterialModelEntry &m) {
        return m.name > entry.name;
      });
    models.insert(position, std::move(entry));
  }

  const std::vector<MaterialModelEntry> &
  material_models()
  {
    return registry();
  }

  std::string
  material_model_names()
  {
    std::string names;
    for (const MaterialModelEntry &model : registry())
      names += (names.empty() ? "" : "|") + model.name;
    return names;
  }

  const MaterialModelEntry &
  find_material_model(const std::string &name, const std::string &entry)
  {
    for (const MaterialModelEntry &model : registry())
      if (model.name == name)
        return model;
    std::string names = material_model_names();
    for (auto &c : names)
      if (c == '|')
        c = ',';
    throw InputError("invalid input: '" + entry + " = " + name + "'; allowed: one of: " + names);
  }

  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters)
  {
    return find_material_model(parameters.model, "Material").create(parameters);
  }
} // namespace sable::mpm
