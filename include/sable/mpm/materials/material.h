#ifndef sable_mpm_materials_material_h
#define sable_mpm_materials_material_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/materials/material_parameters.h>

#include <memory>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// A dim x dim tensor as 3 x 3 (plane strain in 2D: zeros off the plane,
  /// @p diagonal_fill in the zz entry: 0 for L, 1 for F).
  template <int dim>
  inline Tensor<2, 3>
  embed_in_3d(const Tensor<2, dim> &a, const double diagonal_fill)
  {
    Tensor<2, 3> result;
    for (unsigned int i = 0; i < 3; ++i)
      result[i][i] = diagonal_fill;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        result[i][j] = a[i][j];
    return result;
  }

  /// The points of one body in one cell, as update_stresses() takes them:
  /// velocity and deformation gradients (3D, see Material), and where each
  /// point's stress and history are.
  struct MaterialPointBatch
  {
    std::vector<Tensor<2, 3>>            L;
    std::vector<Tensor<2, 3>>            F;
    std::vector<SymmetricTensor<2, 3> *> stress;
    std::vector<double *>                history;

    unsigned int
    size() const
    {
      return L.size();
    }

    void
    clear()
    {
      L.clear();
      F.clear();
      stress.clear();
      history.clear();
    }
  };

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

    /**
     * update_stress() for a batch of points of one body (the points of one
     * cell): one virtual call per batch, the model's own update inlined in
     * the loop (BatchedMaterial).
     */
    virtual void
    update_stresses(const MaterialPointBatch &batch, const double dt) const = 0;

    /// Stored elastic energy per unit reference volume.
    virtual double
    strain_energy_density(const SymmetricTensor<2, 3> &stress,
                          const Tensor<2, 3> &         F) const = 0;

    /// Work dissipated by plastic flow so far per unit reference volume,
    /// from a point's history (zero for elastic models).
    virtual double
    plastic_work_density(const double * /*history*/) const
    {
      return 0.;
    }

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

  /// Implements Material::update_stresses() for a final model class
  /// @p Model by calling its update_stress() directly (no virtual call per
  /// point).
  template <typename Model>
  class BatchedMaterial : public Material
  {
  public:
    using Material::Material;

    void
    update_stresses(const MaterialPointBatch &batch, const double dt) const final
    {
      const Model &model = static_cast<const Model &>(*this);
      for (unsigned int p = 0; p < batch.size(); ++p)
        model.Model::update_stress(batch.L[p], batch.F[p], dt, *batch.stress[p], batch.history[p]);
    }
  };

  /// Create the model named in @p parameters.model.
  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters);
} // namespace sable::mpm

#endif
