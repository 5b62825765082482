#include <sable/base/input_error.h>
#include <sable/mpm/materials/material_registry.h>
#include <sable/mpm/materials/hypoelastic.h>

namespace sable::mpm
{
  namespace
  {
    const MaterialRegistration registration({"linear elastic",
                                              nullptr,
                                              nullptr,
                                              nullptr,
                                              [](const MaterialParameters &p) {
                                                return std::make_unique<Hypoelastic>(p);
                                              }});
  } // namespace

  void
  Hypoelastic::update_stress(const Tensor<2, 3> &L,
                             const Tensor<2, 3> &,
                             const double           dt,
                             SymmetricTensor<2, 3> &stress,
                             double *) const
  {
    stress = jaumann_elastic_update(L, dt, stress);
  }

  void
  Hypoelastic::update_plane_strain_stress(const Tensor<2, 2> &L,
                                          const Tensor<2, 2> &,
                                          const double        dt,
                                          PlaneStrainStress & stress,
                                          double *) const
  {
    stress = jaumann_elastic_update(L, dt, stress);
  }

  double
  Hypoelastic::strain_energy_density(const SymmetricTensor<2, 3> &stress,
                                     const Tensor<2, 3> &         F) const
  {
    // the complementary energy is per current volume
    return complementary_energy(stress) * determinant(F);
  }
} // namespace sable::mpm
