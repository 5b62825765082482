#ifndef sable_mpm_nodal_fields_h
#define sable_mpm_nodal_fields_h

#include <deal.II/lac/la_parallel_vector.h>

#include <sable/mpm/boundaries/boundary_conditions.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/grid_pass.h>

#include <vector>

namespace sable::mpm
{
  /**
   * The single velocity field on the grid nodes (SPEC Part A steps 1-2 and
   * 8): what the particle-to-grid pass scatters (mass, momentum, internal
   * force, stored node by node with ghost entries under MPI), and the nodal
   * velocities computed from it before (old) and after (new) the momentum
   * update, with the walls' conditions applied.
   */
  template <int dim>
  class NodalFields
  {
  public:
    using NodalVector = LinearAlgebra::distributed::Vector<double>;

    /// values per node in scattered(): mass, momentum (dim), force (dim)
    static constexpr unsigned int n_components = 1 + 2 * dim;

    /// Size every field for @p grid's nodes; with @p with_material_extent
    /// also the material extent a friction wall with material contact
    /// reads (BoundaryConditions::set_material_extent()), with
    /// @p with_mass_moment the mass moments sum_p N_i m_p x_p and the
    /// mass-weighted point spacings sum_p N_i m_p s_p a friction wall with
    /// surface-position contact reads.
    void
    reinit(const Grid<dim> &grid, const bool with_material_extent, const bool with_mass_moment);

    /// Zero what a particle-to-grid pass adds to (the extent: to +max).
    template <GridPass pass>
    void
    zero();

    /// Add the ghost nodes' contributions to their owners and send the
    /// sums back (collective).
    template <GridPass pass>
    void
    compress();

    /**
     * The nodal velocities: in the momentum-update pass v_old = p/m and
     * v_new = v_old + dt (f/m + g), then the walls' conditions (returns the
     * work the moving walls did, summed over ranks); in the remap pass
     * v_new = p/m with the conditions the walls imposed in the update.
     */
    template <GridPass pass>
    double
    compute_velocities(BoundaryConditions<dim> &boundary_conditions,
                       const Tensor<1, dim> &   gravity,
                       const double             time_step);

    /// Locally owned nodes (they come before the ghost nodes).
    unsigned int
    n_owned_nodes() const
    {
      return scattered.get_partitioner()->locally_owned_size() / n_components;
    }

    /// Locally owned plus ghost nodes.
    unsigned int
    n_relevant_nodes() const
    {
      return mass.size();
    }

    /// n_components values per relevant node.
    double *
    scattered_values()
    {
      return scattered.get_values();
    }

    /// 2 dim values per relevant node, or nullptr without friction walls
    /// that check for material.
    double *
    material_extent_values()
    {
      return material_extent.size() > 0 ? material_extent.get_values() : nullptr;
    }

    /// dim values per relevant node, sum_p N_i(x_p) m_p x_p, or nullptr
    /// without friction walls that check the surface position.
    double *
    mass_moment_values()
    {
      return mass_moment.size() > 0 ? mass_moment.get_values() : nullptr;
    }

    const std::vector<double> &
    get_mass() const
    {
      return mass;
    }
    const std::vector<double> &
    get_old_velocity() const
    {
      return old_velocity;
    }
    const std::vector<double> &
    get_new_velocity() const
    {
      return new_velocity;
    }

    /// Keep what the walls' conditions change in each pass's velocities
    /// (get_wall_correction()), for the loss of their impacts
    /// (GridToParticle::measure_corrections()). Before reinit().
    void
    keep_wall_corrections(const bool keep)
    {
      keep_wall_correction = keep;
      if (!keep)
        wall_correction = std::vector<double>();
    }

    /// What the walls' conditions changed in the last pass's velocities,
    /// dim values per node: zero where no wall acts and at a moving wall's
    /// nodes (its work is boundary work); empty unless kept.
    const std::vector<double> &
    get_wall_correction() const
    {
      return wall_correction;
    }

  private:
    NodalVector         scattered;
    NodalVector         material_extent;
    NodalVector         mass_moment;
    std::vector<double> mass;
    std::vector<double> old_velocity;
    std::vector<double> new_velocity;
    bool                keep_wall_correction = false;
    std::vector<double> wall_correction;
  };
} // namespace sable::mpm

#endif
