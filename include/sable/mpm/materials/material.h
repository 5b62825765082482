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

  /// The stress of a point in plane strain (2D): the in-plane components
  /// and sigma_zz. sigma_xz = sigma_yz = 0: they are seeded zero, and a
  /// velocity gradient in the plane keeps them zero.
  struct PlaneStrainStress
  {
    double xx, yy, zz, xy;
  };

  /// The points of one body in one cell, as update_stresses() takes them:
  /// velocity gradient over the step and deformation gradient at its end
  /// (dim x dim), and where each point's stress (the six components
  /// xx yy zz xy xz yz, updated in place) and history are.
  template <int dim>
  struct MaterialPointBatch
  {
    std::vector<Tensor<2, dim>> L;
    std::vector<Tensor<2, dim>> F;
    std::vector<double *>       stress;
    std::vector<double *>       history;

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
   * A constitutive model. Kinematics are three-dimensional: in 2D (plane
   * strain) the velocity gradient has a zero third row and column and
   * F_33 = 1, so sigma_zz is carried and plasticity sees it. The batched
   * update of 2D points computes this on the 2D data (PlaneStrainStress).
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
     * the loop (BatchedMaterial); in 2D the model's plane-strain update.
     */
    virtual void
    update_stresses(const MaterialPointBatch<2> &batch, const double dt) const = 0;

    virtual void
    update_stresses(const MaterialPointBatch<3> &batch, const double dt) const = 0;

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

    /// The same in plane strain, on the 2D data.
    PlaneStrainStress
    jaumann_elastic_update(const Tensor<2, 2> &     L,
                           const double             dt,
                           const PlaneStrainStress &stress) const;
  };

  inline PlaneStrainStress
  Material::jaumann_elastic_update(const Tensor<2, 2> &     L,
                                   const double             dt,
                                   const PlaneStrainStress &stress) const
  {
    // the 3 x 3 update without its zero terms (W_12 = w, W_21 = -w), in
    // the same order of operations: the same bits
    const double K = parameters.bulk_modulus, G = parameters.shear_modulus;
    const double lambda_trace = (K - 2. / 3. * G) * (L[0][0] + L[1][1]);
    const double w            = 0.5 * (L[0][1] - L[1][0]);
    PlaneStrainStress result;
    result.xx = stress.xx + dt * (2. * (w * stress.xy + G * L[0][0]) + lambda_trace);
    result.yy = stress.yy + dt * (2. * (-w * stress.xy + G * L[1][1]) + lambda_trace);
    result.zz = stress.zz + dt * lambda_trace;
    result.xy = stress.xy + dt * (w * stress.yy - w * stress.xx + G * (L[0][1] + L[1][0]));
    return result;
  }

  /**
   * Implements Material::update_stresses() for a final model class
   * @p Model by calling its update_stress() directly (no virtual call per
   * point), and in 2D its update_plane_strain_stress(): the model's own
   * plane-strain kernel if it has one, else the one below through its 3D
   * update.
   */
  template <typename Model>
  class BatchedMaterial : public Material
  {
  public:
    using Material::Material;

    void
    update_stresses(const MaterialPointBatch<2> &batch, const double dt) const final
    {
      const Model &model = static_cast<const Model &>(*this);
      for (unsigned int p = 0; p < batch.size(); ++p)
        {
          double *const     s = batch.stress[p];
          PlaneStrainStress stress{s[0], s[1], s[2], s[3]};
          model.Model::update_plane_strain_stress(batch.L[p], batch.F[p], dt, stress, batch.history[p]);
          s[0] = stress.xx;
          s[1] = stress.yy;
          s[2] = stress.zz;
          s[3] = stress.xy;
        }
    }

    void
    update_stresses(const MaterialPointBatch<3> &batch, const double dt) const final
    {
      const Model &model = static_cast<const Model &>(*this);
      for (unsigned int p = 0; p < batch.size(); ++p)
        {
          double *const         s = batch.stress[p];
          SymmetricTensor<2, 3> stress;
          for (unsigned int c = 0; c < 6; ++c)
            stress.access_raw_entry(c) = s[c];
          model.Model::update_stress(batch.L[p], batch.F[p], dt, stress, batch.history[p]);
          for (unsigned int c = 0; c < 6; ++c)
            s[c] = stress.access_raw_entry(c);
        }
    }

    /// The plane-strain update through the 3D one (L and F embedded).
    void
    update_plane_strain_stress(const Tensor<2, 2> &L,
                               const Tensor<2, 2> &F,
                               const double        dt,
                               PlaneStrainStress & stress,
                               double *            history) const
    {
      SymmetricTensor<2, 3> s;
      s[0][0] = stress.xx;
      s[1][1] = stress.yy;
      s[2][2] = stress.zz;
      s[0][1] = stress.xy;
      static_cast<const Model &>(*this).Model::update_stress(
        embed_in_3d<2>(L, 0.), embed_in_3d<2>(F, 1.), dt, s, history);
      stress = {s[0][0], s[1][1], s[2][2], s[0][1]};
    }
  };

  /// Create the model named in @p parameters.model.
  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters);
} // namespace sable::mpm

#endif
