#ifndef sable_mpm_materials_material_parameters_h
#define sable_mpm_materials_material_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Constitutive model and constants of one body. The entries common to
   * every model (density and the elastic constants) sit in the body's
   * subsection; a model's own entries in a subsection named after the
   * model, declared by the model (MaterialRegistry), e.g.
   *
   *   subsection Body 0
   *     set Material        = von Mises
   *     set Young's modulus = 1e6
   *     subsection von Mises
   *       set Yield stress = 2e4
   *     end
   *   end
   */
  struct MaterialParameters
  {
    /// A name in the MaterialRegistry: "linear elastic" (hypoelastic,
    /// Jaumann rate), "neo-Hookean" or "von Mises" (J2 plasticity with
    /// linear isotropic hardening).
    std::string model         = "linear elastic";
    double      density       = 1000.;
    double      bulk_modulus  = 0.;
    double      shear_modulus = 0.;
    /// Initial yield stress and hardening modulus (von Mises only).
    double yield_stress      = 0.;
    double hardening_modulus = 0.;

    /// Set both moduli from Young's modulus and Poisson's ratio.
    void
    set_young_poisson(const double young, const double poisson);

    /// Declare the entries of every model in the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read the current subsection; @p path (e.g. "Body 0/") prefixes the
    /// entries in messages.
    void
    parse_parameters(ParameterHandler &prm, const std::string &path);

    /// Throw InputError (naming path + entry) for invalid values: the one
    /// check of a material, for scene files and embedding programs alike.
    void
    check(const std::string &path) const;
  };
} // namespace sable::mpm

#endif
