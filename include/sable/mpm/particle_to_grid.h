#ifndef sable_mpm_particle_to_grid_h
#define sable_mpm_particle_to_grid_h

#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/contact/multi_body_contact.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/grid_pass.h>
#include <sable/mpm/nodal_fields.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_layout.h>

namespace sable::mpm
{
  /**
   * The particle-to-grid transfer (SPEC Part A step 1) as a loop over the
   * cells with material points (ParticleCells): for each of them, evaluate the shape functions at
   * every point once, then let the assemblers add the points' shares into
   * nodal storage: the single field (mass, momentum, internal force
   * -V sigma grad N, and the material extent friction walls read) and, in
   * cells at contact nodes, the per-body fields of MultiBodyContact.
   *
   * The loop runs over the blocks of a deterministic cell colouring: blocks
   * of one colour share no node, so they scatter concurrently without
   * locks, and every node adds up its contributions in an order fixed by
   * the mesh alone (cell_colouring.h): results do not depend on the number
   * of threads. Under MPI with contact, ghost cells are visited too, for
   * the per-body fields only (their points complete the contact nodes of
   * locally owned cells).
   */
  template <int dim>
  class ParticleToGrid
  {
  public:
    /// Colour the cells of @p grid's mesh (after every mesh change).
    void
    reinit(const Grid<dim> &grid, const bool with_ghost_cells)
    {
      colouring.reinit(grid, with_ghost_cells);
    }

    /// Whether (and where) the points carry the velocity gradient C of the
    /// affine transfers: then a point's velocity at node i is
    /// v_p + C (x_i - x_p), so that an affine velocity field, a rigid spin
    /// included, reaches the nodes exactly.
    void
    set_layout(const ParticleLayout<dim> &particle_layout)
    {
      layout = particle_layout;
    }

    /// Scatter every point into @p fields (and @p contact, if not null):
    /// mass and momentum, and in the momentum-update pass internal forces,
    /// mass gradients, stresses and the material extent.
    template <GridPass pass>
    void
    scatter(const ParticleCells<dim> &cells,
            const Grid<dim> &         grid,
            NodalFields<dim> &        fields,
            MultiBodyContact<dim> *   contact) const;

    const CellColouring<dim> &
    get_colouring() const
    {
      return colouring;
    }

  private:
    CellColouring<dim>  colouring;
    ParticleLayout<dim> layout;
  };
} // namespace sable::mpm

#endif
