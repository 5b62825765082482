#ifndef sable_mpm_contact_multi_body_contact_h
#define sable_mpm_contact_multi_body_contact_h

#include <deal.II/base/array_view.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/bodies/prescribed_velocities.h>
#include <sable/mpm/boundaries/boundary_conditions.h>
#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/contact/bardenhagen_contact.h>
#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/contact/round_body_moments.h>
#include <sable/mpm/contact/separating_plane.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/grid_pass.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_layout.h>

#include <limits>
#include <vector>

namespace sable::mpm
{
  /**
   * The multi-velocity-field contact of a scene with two or more bodies, as
   * an assembler over the cells of the particle-to-grid and grid-to-particle
   * loops (DESIGN.md, "Assemblers over cells"). It owns the per-body nodal
   * fields (BodyFields: records only at contact nodes) and the contact
   * kernel, and plugs into the transfers through four calls:
   *
   * - mark_contact_nodes(): once per step, before the first scatter, the
   *   nodes whose cells hold points of two or more bodies;
   * - touches() and scatter(): a particle's share of its body's field at
   *   the contact nodes of its cell (its mass, momentum and, in the
   *   momentum-update pass, internal force, mass gradient and stress);
   * - correct_velocities(): per pass, the bodies' nodal velocities, the
   *   contact correction and the walls' conditions on them;
   * - velocities(): what a particle reads back from its body's field.
   */
  template <int dim>
  class MultiBodyContact
  {
  public:
    using Record = typename BodyFields<dim>::Record;

    MultiBodyContact(const ContactParameters &        parameters,
                     const std::vector<unsigned int> &body_groups);

    /// Find this step's contact nodes (bodies per node) and create their
    /// zeroed records; threaded over the coloured cells with points.
    /// @p boundary_conditions: the walls, whose nodes keep the single
    /// field (replaces_single_field()).
    void
    mark_contact_nodes(const ParticleCells<dim> &       cells,
                       const Grid<dim> &                grid,
                       const ParticleLayout<dim> &      layout,
                       const BoundaryConditions<dim> &  boundary_conditions);

    /// Zero the records' mass, momentum and force for a second scatter
    /// (MUSL's remapped momenta) on the same contact nodes.
    void
    begin_remap()
    {
      fields.zero_momenta();
    }

    /// Whether a cell with nodes @p nodes has a contact node.
    bool
    touches(const std::pair<const unsigned int *, unsigned int> &nodes) const
    {
      for (unsigned int k = 0; k < nodes.second; ++k)
        if (fields.is_contact_node(nodes.first[k]))
          return true;
      return false;
    }

    /// Whether nothing reads the single field at any of @p nodes: each is
    /// a contact node, where every point reads its body's record, and no
    /// wall acts there. A cell all of whose nodes are such need not
    /// scatter into the single field (in a dense pack of small grains,
    /// most cells).
    bool
    replaces_single_field(const std::pair<const unsigned int *, unsigned int> &nodes) const
    {
      for (unsigned int k = 0; k < nodes.second; ++k)
        if (!fields.is_contact_node(nodes.first[k]) || (*wall_nodes)[nodes.first[k]])
          return false;
      return true;
    }

    /// Scatter one particle's share into its body's records at the contact
    /// nodes of @p shape, component d of its velocity as node v sees it
    /// being velocity_at(v, d) (ParticleToGrid). Cells of one colour may
    /// call this concurrently.
    template <GridPass pass, typename VelocityAt>
    void
    scatter(const ArrayView<const double> &   properties,
            const Point<dim> &                location,
            const typename Grid<dim>::Shape &shape,
            const VelocityAt &                velocity_at,
            const Tensor<2, dim> &            volume_stress)
    {
      const unsigned int body = static_cast<unsigned int>(properties[ParticleLayout<dim>::body]);
      const double       mass = properties[ParticleLayout<dim>::mass];
      // the passes whose contact decides afresh sum the geometry it reads
      // (USAVG's first half: all of it but the forces)
      constexpr bool geometry = pass != GridPass::remapped_momenta;
      // one root per point, only where the detection reads it
      const double spacing = geometry && with_position ?
                               ParticleLayout<dim>::seeding_spacing(properties) :
                               0.;
      // the normal of the face the point lies under (unit length, turned
      // with its body), if it carries one
      Tensor<1, dim> surface_normal;
      if (geometry && any_body_with_normals && bodies_with_normals[body])
        surface_normal = layout.reference_surface_normal(properties);
      const bool carries_normal = surface_normal.norm_square() > 0;
      if (carries_normal)
        surface_normal = body_rotations[body] * surface_normal;
      // the vector to the body's surface, carried by the material's
      // deformation (F turns and stretches it with the point)
      const bool     surface_vectors =
        geometry && with_position && layout.to_surface_stored;
      Tensor<1, dim> to_surface;
      if (surface_vectors)
        to_surface = ParticleLayout<dim>::deformation_gradient(properties) *
                     layout.reference_to_surface(properties);
      // a point on its face carries the zero vector
      const bool carries_surface =
        surface_vectors && (carries_normal || to_surface.norm_square() > 0);
      for (unsigned int v = 0; v < shape.n_nodes; ++v)
        {
          if (!fields.is_contact_node(shape.nodes[v]))
            continue;
          Record &     record = fields.record(shape.nodes[v], body);
          const double weight = mass * shape.values[v];
          record.mass += weight;
          for (unsigned int d = 0; d < dim; ++d)
            record.momentum[d] += weight * velocity_at(v, d);
          if constexpr (geometry)
            {
              if constexpr (pass == GridPass::momentum_update)
                record.force -= volume_stress * shape.gradients[v];
              record.mass_gradient += mass * shape.gradients[v];
              if (with_position)
                {
                  record.mass_position += weight * shape.image_for_node(location, v);
                  record.mass_spacing += weight * spacing;
                }
              if (carries_normal)
                {
                  record.mass_surface_normal += weight * surface_normal;
                  record.mass_surface += weight;
                }
              if (with_position && carries_surface)
                {
                  record.mass_surface_point +=
                    weight * (shape.image_for_node(location, v) + to_surface);
                  record.mass_on_surface += weight;
                }
              if (with_regression && !planes_fitted)
                samples[fields.index_of(record)].push_back(
                  {shape.image_for_node(location, v), weight});
              if (with_traction)
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int j = i; j < dim; ++j)
                    record.mass_stress[i][j] +=
                      weight * properties[ParticleLayout<dim>::stress +
                                          ParticleLayout<dim>::stress_component(i, j)];
            }
        }
    }

    /// Zero the records before a second momentum-update scatter (after
    /// correct_initial_velocities()).
    void
    zero_records()
    {
      fields.zero_records();
    }

    /// Whether USAVG's first half can take the contact on the velocities
    /// at the start of the step (not with bodies of prescribed velocity,
    /// whose records the passes scale).
    bool
    corrects_initial_velocities() const
    {
      return !(prescribed != nullptr && prescribed->any());
    }

    /**
     * USAVG's first half: the bodies' velocities at every contact node
     * from the momenta at the start of the step (scattered as in the
     * momentum update, with the geometry the contact reads), corrected by
     * the contact decided afresh on them, and by the fixed and slip walls.
     * Nothing is recorded: forces, heat and the pairs' carried pull are
     * those of the momentum update that follows.
     */
    void
    correct_initial_velocities(const Grid<dim> &              grid,
                               const BoundaryConditions<dim> &boundary_conditions,
                               const double                   time_step,
                               const unsigned int             n_owned_nodes);

    /**
     * The bodies' velocities at every contact node from their momenta
     * (and, in the momentum-update pass, forces and @p gravity over
     * @p time_step), then the contact correction if the scene applies it
     * in this pass, then the walls' conditions. @p n_owned_nodes: the
     * locally owned nodes come first; only they count in the sums.
     */
    template <GridPass pass>
    void
    correct_velocities(const Grid<dim> &              grid,
                       BoundaryConditions<dim> &      boundary_conditions,
                       const Tensor<1, dim> &         gravity,
                       const double                   time_step,
                       const unsigned int             n_owned_nodes);

    /// With 'Round body moments = kept', each round body's rotation that
    /// carries the moment the transfer to its points loses (for the
    /// grid-to-particle transfer after the momentum update); else nullptr.
    const RoundBodyMoments<dim> *
    kept_moments() const
    {
      return keep_moments ? &moments : nullptr;
    }

    /// The record of @p body at @p node if @p node is a contact node, else
    /// nullptr: a particle then reads the single field.
    const Record *
    velocities(const unsigned int node, const unsigned int body) const
    {
      return fields.is_contact_node(node) ? &fields.record(node, body) : nullptr;
    }

    /// Where the points keep their properties; with surface normals stored
    /// (ParticleLayout::surface_normal_stored) the records sum them.
    void
    set_layout(const ParticleLayout<dim> &particle_layout)
    {
      layout = particle_layout;
    }

    /// Per body, the radius of curvature of its surface (infinite for
    /// bodies with faces), its volume and its mass, for 'Normals = flatter
    /// body' and the overlap test (BardenhagenContact::set_body_shapes()).
    /// With 'flatter body', nodes where only round bodies meet take the
    /// fitted plane's normal (fit_separating_planes()), or with 'Round
    /// pair normals = line of centres' the line between the bodies'
    /// centres (update_body_centres()), except on a @p periodic_grid,
    /// where a body's centre may lie across a seam.
    void
    set_body_shapes(const std::vector<double> &surface_radii,
                    const std::vector<double> &volumes,
                    const std::vector<double> &masses,
                    const bool                 periodic_grid = false);

    /// The bodies of prescribed velocity (kept by the caller), whose
    /// records correct_velocities() sets to their velocity: the kernel
    /// sees them with their masses times driver_mass_factor, so that the
    /// other bodies take their velocity as from a rigid driver.
    void
    set_prescribed_velocities(const PrescribedVelocities<dim> *drivers)
    {
      prescribed = drivers;
      std::vector<double> mass_factors(drivers != nullptr ? drivers->n_bodies() : 0, 1.);
      for (unsigned int body = 0; body < mass_factors.size(); ++body)
        if (drivers->is_prescribed(body))
          mass_factors[body] = driver_mass_factor;
      model.set_body_mass_factors(mass_factors);
    }

    /// Work the drivers did on the other bodies in the last
    /// momentum-update pass (their impulses times their velocity; this
    /// rank's nodes).
    double
    get_driver_work() const
    {
      return driver_work;
    }

    /// Impulse the drivers gave the other bodies in the last
    /// momentum-update pass (this rank's nodes).
    const Tensor<1, dim> &
    get_driver_impulse() const
    {
      return driver_impulse;
    }

    const BodyFields<dim> &
    get_fields() const
    {
      return fields;
    }

    /**
     * With @p remapped (MUSL), the friction heat of the contact and of the
     * friction walls at contact nodes is counted in the remapped-momenta
     * pass, as each record's friction impulse of the momentum update
     * times the velocity its body's points show after it, mapped back to
     * the grid: -dt F_t . v, summed over a node's bodies the impulse times
     * their relative slip, at least zero per node; F_t only where the
     * correction slips (static friction does no work). The nodal
     * velocities after the correction are
     * not the points' (a record of little mass carries f dt / m of its
     * force, which the points see only in part), and heat counted from
     * them grows with that noise. Without, the heat is counted at the
     * nodes (USL).
     */
    void
    count_heat_at_remapped_velocities(const bool remapped)
    {
      heat_at_remap = remapped;
      model.count_heat_at_nodes(!remapped);
    }

    /// The contact kernel, with its running sums (heat, pair forces).
    BardenhagenContact<dim> &
    get_model()
    {
      return model;
    }

    const BardenhagenContact<dim> &
    get_model() const
    {
      return model;
    }

  private:
    /// Relative to the other bodies' nodal masses, the drivers' masses
    /// differ from unbounded in the kernel's centre-of-mass velocity by
    /// 1e-9 of the velocity difference.
    static constexpr double driver_mass_factor = 1e9;

    /// Before the kernel (@p before): the drivers' records take their
    /// velocity and the scaled mass; after it: their mass back, their
    /// velocity again, and (with @p record_work) the work they did.
    void
    hold_drivers(const bool before, const bool record_work, const unsigned int n_owned_nodes);

    /// Every record's velocity from its momentum (@p with_forces: plus
    /// its force and @p gravity over @p time_step, keeping the velocity
    /// before them as old_velocity), and the correction's starting value.
    void
    compute_velocities(const bool            with_forces,
                       const Tensor<1, dim> &gravity,
                       const double          time_step);

    /// Each record's correction: its velocity after the contact and the
    /// walls less the one correct_velocities() started from (which the
    /// field holds until then); zero at a moving wall's node.
    void
    keep_corrections(const BoundaryConditions<dim> &boundary_conditions);

    /// In the remapped pass, before any correction: add each owned record's
    /// -dt F_t . v to the contact's heat (F_t: the friction part of its
    /// contact force) and -m dv_t . v to the walls' (dv_t: the friction
    /// walls' tangential change in the momentum update), v the remapped
    /// velocity; summed chunk by chunk, the same for any number of threads.
    void
    count_heat_on_remapped(BoundaryConditions<dim> &boundary_conditions,
                           const double             time_step,
                           const unsigned int       n_owned_nodes);

    /// With 'Normals = logistic regression': each record's fitted normal
    /// from the points sampled at its node (threaded over the contact
    /// nodes; each node is fitted on its own); with 'fitted at edges' only
    /// at nodes where two bodies meet at an edge, with 'flatter body' only
    /// at nodes where only round bodies meet; zero elsewhere.
    void
    fit_separating_planes(const Grid<dim> &grid);

    /// Gather the bodies of each cell's points into cell_bodies, threaded
    /// over fixed blocks of cells (the same list for any number of
    /// threads).
    void
    gather_cell_bodies(const ParticleCells<dim> &cells, const ParticleLayout<dim> &layout);

    /// Each body's rotation, that of the polar decomposition of its points'
    /// mean deformation gradient (weighted by their initial volumes): the
    /// rotation its points' surface normals are turned by. The points' own
    /// F would tilt them by the strain near a contact (a slipping sphere's
    /// spin lost 7% of the friction's moment to a plane body's normals
    /// turned so).
    void
    update_body_rotations(const ParticleCells<dim> &cells, const MPI_Comm communicator);

    /// The centre of mass of each round body, over its points on all
    /// ranks, to the kernel (BardenhagenContact::set_body_centres()).
    void
    update_body_centres(const ParticleCells<dim> &cells, const MPI_Comm communicator);

    bool heat_at_remap = false;

    const PrescribedVelocities<dim> *prescribed  = nullptr;
    double                           driver_work = 0;
    Tensor<1, dim>                   driver_impulse;

    const ContactParameters parameters;
    ParticleLayout<dim>     layout;
    const bool              with_traction;
    const bool              with_position;
    bool                    with_regression;
    /// 'flatter body' in a scene of two or more round bodies: they meet
    /// along their line of centres ('Round pair normals'), or the planes
    /// are fitted at the nodes where only round bodies meet
    bool                    centre_lines    = false;
    /// 'Round body moments = kept' in a scene with a round body (not on a
    /// periodic grid)
    bool                    keep_moments = false;
    RoundBodyMoments<dim>   moments;
    bool                    fit_round_pairs = false;
    std::vector<bool>       round_body;
    BodyFields<dim>         fields;
    /// per relevant node, whether a wall acts there (from
    /// mark_contact_nodes())
    const std::vector<unsigned char> *wall_nodes = nullptr;
    /// with_regression: per record, its body's points around the node
    /// (their storage kept from step to step), and the normal out of its
    /// body of the plane fitted between them and the other bodies' points
    std::vector<std::vector<NodeSample<dim>>> samples;
    std::vector<Tensor<1, dim>>               fitted_normals;
    /// whether fitted_normals hold this step's planes (from USAVG's first
    /// half; reset by mark_contact_nodes())
    bool                    planes_fitted = false;
    BardenhagenContact<dim> model;

    /// the bodies some of whose points carry a face normal (found at the
    /// first step), and each body's rotation (update_body_rotations())
    const unsigned int          n_bodies;
    std::vector<bool>           bodies_with_normals;
    bool                        any_body_with_normals = false;
    std::vector<Tensor<2, dim>> body_rotations;
    /// at most this many face directions per body (more: a curved mesh,
    /// none kept)
    static constexpr unsigned int max_face_directions = 32;

    /// The distinct reference normals of each body's points on all ranks,
    /// to the kernel (BardenhagenContact::set_face_directions(); once).
    void
    find_face_directions(const ParticleCells<dim> &cells, const MPI_Comm communicator);

    /// The bodies of each cell's points (linear shape functions), in the
    /// order of the ParticleCells list: cell i's are
    /// [cell_bodies_start[i], cell_bodies_start[i + 1]); valid while the
    /// list's version is cell_bodies_version (points do not change body,
    /// and only a rebuilt list has points change cells).
    std::vector<unsigned int> cell_bodies;
    std::vector<unsigned int> cell_bodies_start;
    unsigned long long        cell_bodies_version = std::numeric_limits<unsigned long long>::max();
  };
} // namespace sable::mpm

#endif
