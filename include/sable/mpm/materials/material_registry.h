#ifndef sable_mpm_materials_material_registry_h
#define sable_mpm_materials_material_registry_h

#include <deal.II/base/parameter_handler.h>

#include <sable/mpm/materials/material_parameters.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sable::mpm
{
  class Material;

  /**
   * The material models by name (ASPECT's plugin pattern): each model's
   * file registers its name, its own entries (in a subsection named after
   * it), their parsing and checks, and a factory. A new model is one new
   * file with a MaterialRegistration in it.
   */
  struct MaterialModelEntry
  {
    std::string name;
    /// Declare the model's own entries in the current subsection (which is
    /// the model's subsection); may be empty.
    std::function<void(ParameterHandler &)> declare_parameters;
    /// Read them into the parameters (in the model's subsection).
    std::function<void(const ParameterHandler &, MaterialParameters &)> parse_parameters;
    /// Throw InputError for invalid values; @p path prefixes the entries.
    std::function<void(const MaterialParameters &, const std::string &path)> check;
    std::function<std::unique_ptr<Material>(const MaterialParameters &)> create;
  };

  /// The registered models, sorted by name.
  const std::vector<MaterialModelEntry> &
  material_models();

  /// The model named @p name; throws InputError naming @p entry otherwise.
  const MaterialModelEntry &
  find_material_model(const std::string &name, const std::string &entry);

  /// "name|name|...", for the Material entry's pattern.
  std::string
  material_model_names();

  /// Registers a model when the library is loaded (a static object in the
  /// model's file).
  struct MaterialRegistration
  {
    explicit MaterialRegistration(MaterialModelEntry entry);
  };
} // namespace sable::mpm

#endif
