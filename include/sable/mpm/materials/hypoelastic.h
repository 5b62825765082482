#ifndef sable_mpm_materials_hypoelastic_h
#define sable_mpm_materials_hypoelastic_h

#include <sable/mpm/materials/material.h>

namespace sable::mpm
{
  /// Linear hypoelasticity with the Jaumann stress rate; no history.
  class Hypoelastic final : public BatchedMaterial<Hypoelastic>
  {
  public:
    using BatchedMaterial<Hypoelastic>::BatchedMaterial;

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
  };
} // namespace sable::mpm

#endif
