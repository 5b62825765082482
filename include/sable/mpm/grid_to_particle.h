#ifndef sable_mpm_grid_to_particle_h
#define sable_mpm_grid_to_particle_h

#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/bodies/prescribed_velocities.h>
#include <sable/mpm/contact/multi_body_contact.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/nodal_fields.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_layout.h>

#include <vector>

namespace sable::mpm
{
  /**
   * The grid-to-particle transfer (SPEC Part A steps 9-10) as a threaded
   * loop over the locally owned cells with material points (ParticleCells): each point reads the nodal
   * velocities of its body (its body's record at a contact node, the single
   * field elsewhere) and updates its velocity (FLIP with a PIC fraction)
   * and position, or stores its velocity gradient L = sum v_i grad N_i for
   * the stress update, or both in one pass (USL). Each point changes only
   * its own data, so threads change nothing. With the affine transfers a
   * node without mass of the point's body (the point on its cell's face:
   * N = 0, grad N != 0) enters L as if it moved with the point, so that a
   * uniform motion has no gradient: L becomes the point's C, which the
   * next transfer applies with full weight.
   */
  template <int dim>
  class GridToParticle
  {
  public:
    /// What a pass found: the largest signal and point speeds (this rank),
    /// and the lowest-id point that failed (not finite, or moved more than
    /// a cell).
    struct Report
    {
      double                max_signal_speed   = 0;
      double                max_particle_speed = 0;
      /// points whose new position is outside their cell (this rank)
      unsigned int          n_left_cell        = 0;
      /// the kinetic and strain energy the contact's and the walls'
      /// corrections took from this rank's points in this pass
      /// (measure_corrections())
      double                correction_loss    = 0;
      bool                  not_finite         = false;
      bool                  too_far            = false;
      types::particle_index failed_id          = numbers::invalid_unsigned_int;
      Point<dim>            failure_location;

      void
      fail(const bool distance, const types::particle_index id, const Point<dim> &x);
      void
      merge(const Report &other);
    };

    GridToParticle(const Grid<dim> &                 grid,
                   const NodalFields<dim> &          fields,
                   const std::vector<double> &       body_wave_speed,
                   std::vector<Tensor<2, dim>> &     velocity_gradients)
      : grid(grid)
      , fields(fields)
      , body_wave_speed(body_wave_speed)
      , velocity_gradients(velocity_gradients)
    {}

    /// Points of prescribed-velocity bodies (kept by the caller) move with
    /// their body's velocity and have no strain rate.
    void
    set_prescribed_velocities(const PrescribedVelocities<dim> *drivers)
    {
      prescribed = drivers;
    }

    /**
     * Count what the corrections of the nodal velocities by the contact
     * and by the walls that do no work (fixed, slip, friction) take from
     * the points (Report::correction_loss): the records' corrections
     * (BodyFields::Record::correction) and the walls' on the single field
     * (NodalFields::get_wall_correction()). Where a node's velocity v was
     * changed by dv, the points' velocities change by dv_p = sum N dv,
     * and the loss is -m_p dv_p . (v_p before + v_p after)/2 in the
     * momentum update; in the pass whose velocities drive the stress
     * update, the strain energy the correction kept from being stored,
     * -dt V_p (sigma_p + dt C : (L_p - G_p / 2)) : G_p with G_p = sum dv
     * grad N and C the body's elastic tangent (set_elastic_moduli()): the
     * difference of the strain energies the corrected and the uncorrected
     * velocity gradient L_p and L_p - G_p store over the step, exact for a
     * linear elastic increment. In the first of USAVG's two halves the
     * tangent's term is dt C : G/2 instead: the stress that half leaves
     * drives the momentum update's internal force, which works on the
     * uncorrected velocities (the exact balance of USAVG's step for a
     * linear elastic body). Moving walls are left out (their
     * work is boundary work), and so are scenes with prescribed-velocity
     * bodies (their work on the others is already counted).
     */
    void
    measure_corrections(const bool measure, const BoundaryConditions<dim> *walls)
    {
      measuring = measure;
      boundary  = walls;
    }

    /// Per body, the Lame constants lambda = K - 2 G / 3 and G of its
    /// elastic tangent, for the strain part of the correction loss.
    void
    set_elastic_moduli(const std::vector<double> &lambda, const std::vector<double> &shear)
    {
      body_lambda = lambda;
      body_shear  = shear;
    }

    /// With measure_corrections(): mark the owned cells with points whose
    /// shape functions reach a node that the contact or a wall may
    /// correct in this step (a contact node of @p contact, a wall's node),
    /// where the transfers count the loss. After the contact nodes are
    /// found, and whenever the cells change.
    void
    find_corrected_cells(const ParticleCells<dim> &cells, const MultiBodyContact<dim> *contact);

    /// With the affine transfers (@p layout stores C), computing the
    /// strain rates also stores each point's C = L, the velocity gradient
    /// of its stress update.
    void
    set_layout(const ParticleLayout<dim> &particle_layout)
    {
      layout = particle_layout;
    }

    /// New velocities v = (1 - alpha)(v + sum N (v_new - v_old)) +
    /// alpha sum N v_new and positions x += dt sum N v_new.
    Report
    update_velocities_and_positions(Particles::ParticleHandler<dim> &particle_handler,
                                    const ParticleCells<dim> &       cells,
                                    const MultiBodyContact<dim> *    contact,
                                    const double                     time_step,
                                    const double                     pic_fraction) const
    {
      return transfer<true, false, false>(
        particle_handler, cells, contact, time_step, pic_fraction);
    }

    /// The velocity gradients of the strain update (by local index); with
    /// @p cell_time_steps only for the points of the owned cells c where
    /// (*cell_time_steps)[c] is not 0 (those that update their stress).
    /// @p first_half: the first of USAVG's two halves, whose stress the
    /// momentum update's internal force then reads (measure_corrections()).
    Report
    compute_strain_rates(Particles::ParticleHandler<dim> &particle_handler,
                         const ParticleCells<dim> &       cells,
                         const MultiBodyContact<dim> *    contact,
                         const double                     strain_time_step,
                         const std::vector<double> *      cell_time_steps = nullptr,
                         const bool                       first_half      = false) const
    {
      return layout.affine_stored ?
               transfer<false, true, true>(particle_handler,
                                           cells,
                                           contact,
                                           strain_time_step,
                                           0.,
                                           cell_time_steps,
                                           first_half) :
               transfer<false, true, false>(particle_handler,
                                            cells,
                                            contact,
                                            strain_time_step,
                                            0.,
                                            cell_time_steps,
                                            first_half);
    }

    /// Both in one pass, from the same nodal velocities (USL).
    Report
    update_particles_and_strain_rates(Particles::ParticleHandler<dim> &particle_handler,
                                      const ParticleCells<dim> &       cells,
                                      const MultiBodyContact<dim> *    contact,
                                      const double                     time_step,
                                      const double                     pic_fraction) const
    {
      return layout.affine_stored ?
               transfer<true, true, true>(
                 particle_handler, cells, contact, time_step, pic_fraction) :
               transfer<true, true, false>(
                 particle_handler, cells, contact, time_step, pic_fraction);
    }

  private:
    /// The part of a point's velocity gradient (of @p body, with @p shape)
    /// from the nodes without mass of its body, as if they moved with the
    /// point (they added nothing to sum v_i grad N_i, their velocity being
    /// 0).
    Tensor<2, dim>
    massless_gradient_part(const typename Grid<dim>::Shape &shape,
                           const unsigned int               body,
                           const MultiBodyContact<dim> *    contact) const;

    /// What every cell of one pass reads.
    struct PassInput
    {
      const MultiBodyContact<dim> *    contact;
      /// the round bodies' rotations that carry the moments the transfer
      /// loses (update_positions only; nullptr if none)
      const RoundBodyMoments<dim> *    moments;
      const PrescribedVelocities<dim> *drivers;
      const Periodicity<dim> *         periodicity;
      const double *                   new_velocity;
      const double *                   old_velocity;
      /// NodalFields::get_wall_correction(), nullptr if empty
      const double *wall_correction;
      double        time_step;
      double        alpha;
      /// the first of USAVG's two halves (compute_strain_rates())
      bool first_half;
    };

    /// One cell's points in a pass of transfer(); with @p measure, returns
    /// the loss the corrections caused there (measure_corrections()), its
    /// strain part over @p strain_time_step.
    template <bool update_positions, bool update_strain_rates, bool affine, bool measure>
    double
    transfer_cell(const PassInput &                         input,
                  const typename ParticleCells<dim>::Cell &cell,
                  const double                              strain_time_step,
                  typename Grid<dim>::Shape &               shape,
                  Report &                                  local) const;

    /// @p affine: store each point's C = L (the affine transfers).
    template <bool update_positions, bool update_strain_rates, bool affine>
    Report
    transfer(Particles::ParticleHandler<dim> &particle_handler,
             const ParticleCells<dim> &       cells,
             const MultiBodyContact<dim> *    contact,
             const double                     time_step,
             const double                     pic_fraction,
             const std::vector<double> *      cell_time_steps = nullptr,
             const bool                       first_half      = false) const;

    const Grid<dim> &            grid;
    const NodalFields<dim> &     fields;
    const std::vector<double> &  body_wave_speed;
    std::vector<double>          body_lambda, body_shear;
    std::vector<Tensor<2, dim>> &velocity_gradients;
    const PrescribedVelocities<dim> *prescribed = nullptr;
    ParticleLayout<dim>              layout;
    bool                             measuring = false;
    const BoundaryConditions<dim> *  boundary = nullptr;
    /// per owned cell of the last pass: its points' correction loss, summed
    /// in cell order so that threads do not change the total
    mutable std::vector<double> cell_correction_loss;
    /// per owned cell with points: whether the transfers count the loss
    /// there (find_corrected_cells())
    std::vector<unsigned char> corrected_cells;
  };
} // namespace sable::mpm

#endif
