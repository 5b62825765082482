#ifndef sable_mpm_materials_material_h
#define sable_mpm_materials_material_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/parameters.h>

#include <memory>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * A constitutive model. Kinematics are always three-dimensional: in 2D
   * (plane strain) the velocity gradient has a zero third row and column
   * and F_33 = 1, so sigma_zz is carried and plasticity sees it.
   * Each model stores only the history it needs (n_history() doubles per
   * material point).
   */
  class Material
  {
  public:
    explicit Material(const MaterialParameters &parameters);
    virtual ~Material() = default;

    /// Number of history variables stored per material point.
    virtual unsigned int
    n_history() const
    {
      return 0;
    }

    /// Names of the history variables (for output).
    virtual std::vector<std::string>
    history_names() const
    {
      return {};
    }

    /**
     * Advance the Cauchy stress over one step of length @p dt with velocity
     * gradient @p L; @p F is the deformation gradient at the end of the step.
     */
    virtual void
    update_stress(const Tensor<2, 3> &    L,
                  const Tensor<2, 3> &    F,
                  const double            dt,
                  SymmetricTensor<2, 3> & stress,
                  double *                history) const = 0;

    /// Stored elastic energy per unit reference volume.
    virtual double
    strain_energy_density(const SymmetricTensor<2, 3> &stress,
                          const Tensor<2, 3> &         F) const = 0;

    double
    density() const
    {
      return parameters.density;
    }

    /// Elastic P-wave speed sqrt((K + 4G/3)/rho), for the CFL condition.
    double
    wave_speed() const;

    const MaterialParameters parameters;

  protected:
    /// sigma : C^{-1} : sigma / 2 for isotropic linear elasticity.
    double
    complementary_energy(const SymmetricTensor<2, 3> &stress) const;

    /// The hypoelastic (Jaumann-rate) trial stress after one step.
    SymmetricTensor<2, 3>
    jaumann_elastic_update(const Tensor<2, 3> &          L,
                           const double                  dt,
                           const SymmetricTensor<2, 3> &stress) const;
  };

  /// Create the model named in @p parameters.model.
  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters);
} // namespace sable::mpm

#endif
