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

    /**
     * Apply the conditions to velocities remapped from the particles (MUSL's
     * second grid pass). A friction wall holds the normal velocity of
     * exactly the nodes it held in apply(), without new friction, so that
     * the strain rate sees the motion the particles were given.
     */
    void
    apply_to_remapped(std::vector<double> &velocity,
                      const std::vector<double> &mass) const;

    /// Apply the conditions to every body's velocity at contact nodes,
    /// after apply() (@p remapped: as apply_to_remapped()).
    void
    apply_to_bodies(BodyFields<dim> &fields, const bool remapped) const;

    bool
    empty() const
    {
      return constraints.empty();
    }

  private:
    struct NodeConstraint
    {
      unsigned int  node;
      unsigned int  direction; ///< axis of the wall normal
      double        sign;      ///< +1: normal along +axis, -1: along -axis
      types::boundary_id id;
    };

    /// Apply constraint @p c to the velocity @p v; @p held: whether a
    /// friction wall held this node in the momentum update (for remapped
    /// velocities). Returns whether a friction wall acted.
    bool
    apply_one(const NodeConstraint &c,
              double *              v,
              const bool            remapped,
              const bool            held) const;

    std::map<types::boundary_id, BoundaryParameters<dim>> parameters;
    std::vector<NodeConstraint>                            constraints;
    /// per constraint: did the friction wall act in the last apply()?
    std::vector<bool> in_contact;
  };
} // namespace sable::mpm

#endif
