#include <sable/base/input_error.h>
#include <sable/mpm/materials/material_parameters.h>
#include <sable/mpm/materials/material_registry.h>

namespace sable::mpm
{
  void
  MaterialParameters::set_young_poisson(const double young, const double poisson)
  {
    bulk_modulus  = young / (3. * (1. - 2. * poisson));
    shear_modulus = young / (2. * (1. + poisson));
  }

  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Material",
                      "linear elastic",
                      Patterns::Selection(material_model_names()),
                      "Constitutive model: linear elastic (hypoelastic, "
                      "Jaumann rate), neo-Hookean (compressible) or von "
                      "Mises (J2 plasticity, linear isotropic hardening). "
                      "A model's own entries are in the subsection named "
                      "after it.");
    prm.declare_entry("Density", "1000", Patterns::Double(), "kg/m^3, > 0.");
    prm.declare_entry("Young's modulus",
                      "0",
                      Patterns::Double(),
                      "Pa. Give either Young's modulus and Poisson's ratio "
                      "or Bulk modulus and Shear modulus.");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Double(),
                      "In (-1, 0.5); used with Young's modulus.");
    prm.declare_entry("Bulk modulus", "0", Patterns::Double(), "Pa.");
    prm.declare_entry("Shear modulus", "0", Patterns::Double(), "Pa.");
    for (const MaterialModelEntry &model : material_models())
      if (model.declare_parameters)
        {
          prm.enter_subsection(model.name);
          model.declare_parameters(prm);
          prm.leave_subsection();
        }
  }

  void
  MaterialParameters::parse_parameters(ParameterHandler &prm, const std::string &path)
  {
    model                = prm.get("Material");
    density              = prm.get_double("Density");
    const double young   = prm.get_double("Young's modulus");
    const double poisson = prm.get_double("Poisson's ratio");
    const double bulk    = prm.get_double("Bulk modulus");
    const double shear   = prm.get_double("Shear modulus");
    // the two ways of giving the elastic constants exclude each other
    if (bulk != 0. || shear != 0.)
      {
        check_input(young == 0.,
                    path + "Young's modulus",
                    young,
                    "0 (unset) when Bulk and Shear modulus are given");
        bulk_modulus  = bulk;
        shear_modulus = shear;
      }
    else
      {
        check_input(young > 0,
                    path + "Young's modulus",
                    young,
                    "a number > 0 (Pa), or give Bulk and Shear modulus");
        check_input(poisson > -1. && poisson < 0.5,
                    path + "Poisson's ratio",
                    poisson,
                    "the open interval (-1, 0.5)");
        set_young_poisson(young, poisson);
      }
    const MaterialModelEntry &entry = find_material_model(model, path + "Material");
    if (entry.parse_parameters)
      {
        prm.enter_subsection(model);
        entry.parse_parameters(prm, *this);
        prm.leave_subsection();
      }
  }

  void
  MaterialParameters::check(const std::string &path) const
  {
    const MaterialModelEntry &entry = find_material_model(model, path + "Material");
    check_input(density > 0, path + "Density", density, "a number > 0 (kg/m^3)");
    check_input(bulk_modulus > 0, path + "Bulk modulus", bulk_modulus, "a number > 0 (Pa)");
    check_input(shear_modulus > 0, path + "Shear modulus", shear_modulus, "a number > 0 (Pa)");
    if (entry.check)
      entry.check(*this, path + model + "/");
  }
} // namespace sable::mpm
