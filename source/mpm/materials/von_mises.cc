#include <sable/base/input_error.h>
#include <sable/mpm/materials/material_registry.h>
#include <sable/mpm/materials/von_mises.h>

#include <cmath>

namespace sable::mpm
{
  namespace
  {
    void
    declare_von_mises_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Yield stress", "0", Patterns::Double(), "Initial yield stress, Pa, > 0.");
      prm.declare_entry("Hardening modulus",
                        "0",
                        Patterns::Double(),
                        "Linear isotropic hardening modulus H, Pa, >= 0: "
                        "sigma_y = sigma_y0 + H * equivalent plastic strain.");
    }

    void
    parse_von_mises_parameters(const ParameterHandler &prm, MaterialParameters &parameters)
    {
      parameters.yield_stress      = prm.get_double("Yield stress");
      parameters.hardening_modulus = prm.get_double("Hardening modulus");
    }

    void
    check_von_mises_parameters(const MaterialParameters &parameters, const std::string &path)
    {
      check_input(parameters.yield_stress > 0,
                  path + "Yield stress",
                  parameters.yield_stress,
                  "a number > 0 (Pa) for the von Mises material");
      check_input(parameters.hardening_modulus >= 0,
                  path + "Hardening modulus",
                  parameters.hardening_modulus,
                  "a number >= 0 (Pa)");
    }

    const MaterialRegistration registration({"von Mises",
                                              &declare_von_mises_parameters,
                                              &parse_von_mises_parameters,
                                              &check_von_mises_parameters,
                                              [](const MaterialParameters &p) {
                                                return std::make_unique<VonMises>(p);
                                              }});
  } // namespace

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

  void
  VonMises::update_plane_strain_stress(const Tensor<2, 2> &L,
                                       const Tensor<2, 2> &,
                                       const double        dt,
                                       PlaneStrainStress & stress,
                                       double *            history) const
  {
    // update_stress() on the 2D data: s_xz = s_yz = 0
    const double            G = parameters.shear_modulus, H = parameters.hardening_modulus;
    const PlaneStrainStress trial = jaumann_elastic_update(L, dt, stress);
    const double            mean  = (trial.xx + trial.yy + trial.zz) / 3.;
    const PlaneStrainStress s = {trial.xx - mean, trial.yy - mean, trial.zz - mean, trial.xy};
    const double q = std::sqrt(1.5 * (2. * (s.xy * s.xy) + s.xx * s.xx + s.yy * s.yy + s.zz * s.zz));
    double &     plastic_strain = history[0];
    const double yield_stress   = parameters.yield_stress + H * plastic_strain;
    if (q <= yield_stress)
      {
        stress = trial;
        return;
      }
    const double increment = (q - yield_stress) / (3. * G + H);
    plastic_strain += increment;
    const double factor = 3. * G * increment / q;
    stress = {trial.xx - factor * s.xx,
              trial.yy - factor * s.yy,
              trial.zz - factor * s.zz,
              trial.xy - factor * s.xy};
  }

  double
  VonMises::strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                  const Tensor<2, 3> &         F) const
  {
    return complementary_energy(stress) * determinant(F);
  }

  double
  VonMises::plastic_work_density(const double *history) const
  {
    // integral of the yield stress over the equivalent plastic strain (the
    // flow is isochoric, so per reference or current volume alike up to the
    // elastic volume change)
    const double plastic_strain = history[0];
    return (parameters.yield_stress + 0.5 * parameters.hardening_modulus * plastic_strain) *
           plastic_strain;
  }
} // namespace sable::mpm
