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
    const double lambda_trace = (K - 2. / 3. * G) * trace(L);
    // by components (per point, the step's largest single cost): with
    // W = (L - L^T) / 2 and A = W sigma, the rotation W sigma - sigma W is
    // A + A^T for symmetric sigma and skew W
    double s[3][3], W[3][3], A[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          s[i][j] = stress[i][j];
          W[i][j] = 0.5 * (L[i][j] - L[j][i]);
        }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        A[i][j] = W[i][0] * s[0][j] + W[i][1] * s[1][j] + W[i][2] * s[2][j];
    SymmetricTensor<2, 3> result;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        result[i][j] = s[i][j] + dt * (A[i][j] + A[j][i] + G * (L[i][j] + L[j][i]) +
                                       (i == j ? lambda_trace : 0.));
    return result;
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
