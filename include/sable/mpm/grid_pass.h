#ifndef sable_mpm_grid_pass_h
#define sable_mpm_grid_pass_h

namespace sable::mpm
{
  /**
   * The kinds of particle-to-grid pass of a step. Every step has the
   * momentum update (mass, momentum and internal force: new nodal
   * velocities, whose change moves the particles); MUSL and USAVG add a
   * pass that remaps the updated particle momenta to the grid for the
   * strain update (mass and momentum only); USAVG also maps the momenta at
   * the start of the step, for the first half of its strain update (mass
   * and momentum only, no heat counted; with contact, the bodies' records
   * also take the geometry the contact reads, not the forces, see
   * MultiBodyContact::correct_initial_velocities()).
   */
  enum class GridPass
  {
    momentum_update,
    remapped_momenta,
    initial_momenta
  };
} // namespace sable::mpm

#endif
