#ifndef sable_mpm_stress_update_h
#define sable_mpm_stress_update_h

#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/materials/material.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_layout.h>

#include <memory>
#include <vector>

namespace sable::mpm
{
  /**
   * The strain and stress update (SPEC Part A step 11): F <- (I + dt L) F
   * and the material's stress update, from the velocity gradients the
   * grid-to-particle pass stored. Threaded over the locally owned cells
   * with points (ParticleCells);
   * within a cell the points of one body go to their material as one batch
   * (Material::update_stresses(), in 2D on the 2D data), with one
   * finiteness test per batch. Each point depends only on its own
   * data, so threads change nothing.
   */
  template <int dim>
  class StressUpdate
  {
  public:
    /// Where a point's stress stopped being finite (lowest id).
    struct Failure
    {
      bool                  failed = false;
      types::particle_index id     = numbers::invalid_unsigned_int;
      Point<dim>            location;
    };

    StressUpdate(const std::vector<std::unique_ptr<Material>> &materials,
                 const ParticleLayout<dim> &                   layout)
      : materials(materials)
      , layout(layout)
    {}

    /// With @p cell_time_steps, the points of owned cell c take
    /// (*cell_time_steps)[c] instead of @p time_step (0: left as they are).
    /// With @p midpoint_deformation, F <- (I - dt/2 L)^-1 (I + dt/2 L) F,
    /// which keeps det F and turns F exactly under a spin (USAVG), instead
    /// of F <- (I + dt L) F.
    Failure
    update(const ParticleCells<dim> &         cells,
           const std::vector<Tensor<2, dim>> &velocity_gradients,
           const double                       time_step,
           const std::vector<double> *        cell_time_steps      = nullptr,
           const bool                         midpoint_deformation = false) const;

  private:
    const std::vector<std::unique_ptr<Material>> &materials;
    const ParticleLayout<dim> &                   layout;
  };
} // namespace sable::mpm

#endif
