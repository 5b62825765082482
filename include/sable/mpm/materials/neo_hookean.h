#ifndef sable_mpm_materials_neo_hookean_h
#define sable_mpm_materials_neo_hookean_h

#include <sable/mpm/materials/material.h>

namespace sable::mpm
{
  /**
   * Compressible neo-Hookean solid (paper 002):
   * sigma = (K/2)(J - 1/J) I + G J^(-5/3) dev(F F^T), with stored energy
   * W = (K/4)(J^2 - 1) - (K/2) ln J + (G/2)(J^(-2/3) tr(F F^T) - 3).
   * The stress follows from F alone: no history.
   */
  class NeoHookean final : public BatchedMaterial<NeoHookean>
  {
  public:
    using BatchedMaterial<NeoHookean>::BatchedMaterial;

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
