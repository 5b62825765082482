#ifndef sable_mpm_boundaries_boundary_conditions_h
#define sable_mpm_boundaries_boundary_conditions_h

#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/parameters.h>

#include <map>
#include <vector>

namespace sable::mpm
{
  /**
   * Grid boundary conditions applied to nodal velocities (SPEC Part A step 8):
   * fixed, slip, Coulomb friction wall and prescribed-velocity wall, per
   * boundary id. Walls are the grid's axis-aligned boundary faces; each
   * condition is applied at the nodes of those faces with the face's
   * outward normal. Free boundaries cost nothing.
   */
  template <int dim>
  class BoundaryConditions
  {
  public:
    BoundaryConditions(
      const std::map<types::boundary_id, BoundaryParameters<dim>> &parameters);

    /// Collect the constrained nodes of @p grid (after every grid setup).
    void
    setup(const Grid<dim> &grid);

    /**
     * Apply all conditions to the velocities (dim values per relevant node,
     * node by node) at nodes with mass, after the momentum update. Friction
     * walls remember which nodes they held. Returns the work the moving
     * walls did in this step, sum m_i (v_wall - v_i) . v_wall over locally
     * owned nodes.
     */
    double
    apply(std::vector<double> &      velocity,
          const std::vector<double> &mass,
          const unsigned int         n_owned_nodes);

    /// True if a friction wall acts only where material reaches it
    /// ('Friction wall contact = material'); apply() then needs
    /// set_material_extent() first.
    bool
    needs_material_extent() const;

    /**
     * The extent of the material around every relevant node: 2 dim values
     * per node, for each axis d the lowest coordinate min_p (x_p,d − l_p/2)
     * and minus the highest, −max_p (x_p,d + l_p/2), over the material points
     * p in the cells around the node (l_p: edge of the point's volume). A
     * friction wall with material contact acts at a node only if
     * gap − Δt · approach ≤ 0, the material reaching the wall in the step.
     * The pointer must stay valid until apply().
     */
    void
    set_material_extent(const double *extent, const double time_step);

    bool
    needs_mass_moment() const;

    /**
     * The mass moments sum_p N_i(x_p) m_p x_p and mass-weighted point
     * spacings sum_p N_i(x_p) m_p s_p (dim + 1 values per relevant node). A
     * friction wall with surface-position contact acts at a node only where
     * the body's surface, taken surface_centroid_offset() cells
     * outside the node's mass centroid, is within a hundredth of a cell of
     * the wall after the step's approach. The pointer must stay valid until
     * apply().
     */
    void
    set_mass_moment(const double *moment, const double time_step);

    /**
     * Apply the conditions to velocities remapped from the particles (MUSL's
     * second grid pass). A friction wall acts exactly at the nodes it
     * acted on in apply(), removing the normal velocity and any tangential
     * speed beyond the slip it left there (a node it held stays held), so
     * that the strain rate sees the contact state the particles were given
     * without taking their friction a second time.
     */
    void
    apply_to_remapped(std::vector<double> &velocity,
                      const std::vector<double> &mass) const;

    /// Apply the conditions to every body's velocity at contact nodes,
    /// after apply() (@p remapped: as apply_to_remapped()). After the
    /// momentum update, the bodies' velocities, which reach the particles,
    /// replace the single field's in frictional_heat at these nodes.
    void
    apply_to_bodies(BodyFields<dim> &  fields,
                    const bool         remapped,
                    const unsigned int n_owned_nodes);

    /// Friction heat of the walls so far (this rank's owned nodes): the
    /// work of their forces against the nodes' velocities relative to them
    /// after the correction, -sum m (v' - v) . (v' - v_wall) over the
    /// momentum updates; or, with count_heat_at_remapped_velocities(), the
    /// friction walls' tangential impulses against the remapped velocities
    /// (count_heat_on_remapped()).
    double frictional_heat = 0;

    /// While @p stick, friction walls hold the tangential velocity
    /// (infinite friction): bodies settling on a slope (Solver/Settling
    /// friction).
    void
    stick_everywhere(const bool stick)
    {
      sticking = stick;
    }

    /// While @p rest, moving walls hold the nodes at rest like fixed
    /// walls: bodies settling before the run (Solver/Settling steps),
    /// whose walls start moving with the run.
    void
    hold_moving_walls(const bool rest)
    {
      moving_walls_at_rest = rest;
    }

    /// Count the friction walls' heat in MUSL's remapped pass
    /// (count_heat_on_remapped()) instead of at the corrected velocities;
    /// see MultiBodyContact::count_heat_at_remapped_velocities(). Without
    /// friction walls there is nothing to count (the other walls make no
    /// heat) and nothing is kept.
    void
    count_heat_at_remapped_velocities(const bool remapped)
    {
      heat_at_remap = false;
      for (const auto &[id, wall] : parameters)
        heat_at_remap = heat_at_remap || (remapped && wall.type == BoundaryType::friction);
    }

    /// With count_heat_at_remapped_velocities(): before apply_to_remapped(),
    /// add -m dv_t . v to frictional_heat at the owned nodes without
    /// contact, for each friction wall's tangential change dv_t in the last
    /// apply() and the remapped velocity v.
    void
    count_heat_on_remapped(const std::vector<double> &velocity,
                           const std::vector<double> &mass,
                           const unsigned int         n_owned_nodes);

    /// Whether some wall is of @p type.
    bool
    has_walls(const BoundaryType type) const
    {
      for (const auto &[id, wall] : parameters)
        if (wall.type == type)
          return true;
      return false;
    }

    bool
    empty() const
    {
      return constraints.empty();
    }

    /// Per relevant node: 1 where a wall's condition acts (setup()), one
    /// byte per node so that many nodes are tested at once without
    /// branches. At those nodes the walls read the single field even where
    /// contact keeps per-body records (a moving wall's work, a friction
    /// wall's reach).
    const std::vector<unsigned char> &
    constrained_nodes() const
    {
      return constrained;
    }

    /// Per relevant node: whether a friction wall acts there (setup()).
    const std::vector<bool> &
    friction_wall_nodes() const
    {
      return friction_constrained;
    }

    /// The relevant nodes where a wall's condition acts, in order, once each
    /// (setup()).
    const std::vector<unsigned int> &
    constrained_node_list() const
    {
      return constrained_list;
    }

    /// Per relevant node: whether a moving wall acts there (setup()). Its
    /// work is counted as boundary work, not as a loss of the impacts.
    const std::vector<bool> &
    moving_wall_nodes() const
    {
      return moving_constrained;
    }

    /**
     * Apply the conditions to the velocities of USAVG's momenta at the
     * start of a step: those of the fixed, slip and moving walls. A
     * friction wall's condition depends on its decision in the momentum
     * update, which comes later: the points near its nodes take their
     * whole strain update from the remapped momenta instead.
     */
    void
    apply_to_initial(std::vector<double> &velocity, const std::vector<double> &mass) const;

    /// The same on the bodies' records at the contact nodes.
    void
    apply_to_initial_bodies(BodyFields<dim> &fields) const;

  private:
    struct NodeConstraint
    {
      unsigned int  node;
      unsigned int  direction; ///< axis of the wall normal
      double        sign;      ///< +1: normal along +axis, -1: along -axis
      types::boundary_id id;
      double             position; ///< wall coordinate along the normal axis
      double             cell_size; ///< the wall cells' extent along the normal
    };

    /// Whether the material around the node stays clear of a friction wall
    /// in this step, by the wall's contact criterion.
    bool
    out_of_reach_of(const NodeConstraint &c, const double *v, const double mass) const;

    /// Apply constraint @p c to the velocity @p v after a momentum update.
    /// For friction walls, returns the fraction of the tangential velocity
    /// removed (1: stick), or -1 if the wall did not act.
    double
    apply_one(const NodeConstraint &c, double *v) const;

    /// Apply constraint @p c to the remapped velocity @p v (MUSL). A
    /// friction wall acts only where it acted in the momentum update
    /// (@p slip >= 0, the tangential speed it left there: zero where it
    /// held the node), removing the normal velocity and any tangential
    /// speed beyond @p slip; the other walls act as after the momentum
    /// update.
    void
    apply_one_remapped(const NodeConstraint &c, double *v, const double slip) const;

    /// The speed of @p v along the wall of @p c.
    static double
    tangential_speed(const NodeConstraint &c, const double *v);

    /// apply_one() after a momentum update, returning the energy it
    /// dissipated at a node of mass @p mass in @p dissipation.
    double
    apply_one_counting(const NodeConstraint &c,
                       double *              v,
                       const double          mass,
                       double &              dissipation) const;

    /// A moving wall's velocity now (zero while hold_moving_walls()).
    Tensor<1, dim>
    velocity_of(const BoundaryParameters<dim> &wall) const
    {
      return moving_walls_at_rest ? Tensor<1, dim>() : wall.velocity;
    }

    std::map<types::boundary_id, BoundaryParameters<dim>> parameters;
    bool                                                  sticking = false;
    /// hold_moving_walls()
    bool                                                  moving_walls_at_rest = false;
    std::vector<NodeConstraint>                            constraints;
    /// per relevant node: whether some constraint acts there
    std::vector<unsigned char> constrained;
    /// per relevant node: whether a friction wall's constraint acts there
    std::vector<bool> friction_constrained;
    /// per relevant node: whether a moving wall's constraint acts there
    std::vector<bool> moving_constrained;
    /// the nodes of constrained, in order
    std::vector<unsigned int> constrained_list;
    /// per constraint: the tangential speed a friction wall left in the
    /// last apply(), -1 where it did not act
    std::vector<double> slip_left;
    /// per constraint: excluded by the material check in the last apply()
    std::vector<bool> out_of_reach;
    /// per constraint: what it added to frictional_heat in the last apply()
    std::vector<double> last_heat;
    bool heat_at_remap = false;
    /// per constraint, with heat_at_remap: a friction wall's tangential
    /// velocity change in the last apply() (dim values; zero at contact
    /// nodes, whose records keep their own)
    std::vector<double> tangential_change;

    /// The tangential part of the change a friction wall @p c made, from
    /// @p before to @p after, if the node slips (@p held, the fraction of
    /// the tangential velocity removed, below 1); zero for a node it holds
    /// or did not touch and for the other walls.
    Tensor<1, dim>
    friction_change(const NodeConstraint &c,
                    const Tensor<1, dim> &before,
                    const double *        after,
                    const double          held) const;
    const double *    material_extent = nullptr;
    const double *    mass_moment      = nullptr;
    double            extent_time_step = 0.;
    /// surfaces closer to a wall than this, in cells, touch it (as between
    /// bodies, BardenhagenContact::touching_tolerance)
    static constexpr double touching_tolerance = 0.01;
  };
} // namespace sable::mpm

#endif
