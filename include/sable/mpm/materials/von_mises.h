#ifndef sable_mpm_materials_von_mises_h
#define sable_mpm_materials_von_mises_h

#include <sable/mpm/materials/material.h>

namespace sable::mpm
{
  /**
   * J2 (von Mises) plasticity with linear isotropic hardening, paper 000:
   * hypoelastic Jaumann trial stress, then radial return to the yield
   * surface sqrt(3/2 s:s) = sigma_y0 + H eps_p. The one history variable is
   * the equivalent plastic strain eps_p.
   */
  class VonMises final : public BatchedMaterial<VonMises>
  {
  public:
    using BatchedMaterial<VonMises>::BatchedMaterial;

    unsigned int
    n_history() const override
    {
      return 1;
    }

    std::vector<std::string>
    history_names() const override
    {
      return {"equivalent_plastic_strain"};
    }

    void
    update_stress(const Tensor<2, 3> &   L,
                  const Tensor<2, 3> &   F,
                  const double           dt,
                  SymmetricTensor<2, 3> &stress,
                  double *               history) const override;

    /// update_stress() in plane strain, on the 2D data.
    void
    update_plane_strain_stress(const Tensor<2, 2> &L,
                               const Tensor<2, 2> &F,
                               const double        dt,
                               PlaneStrainStress & stress,
                               double *            history) const;

    double
    strain_energy_density(const SymmetricTensor<2, 3> &stress,
                          const Tensor<2, 3> &         F) const override;

    double
    plastic_work_density(const double *history) const override;
  };
} // namespace sable::mpm

#endif
