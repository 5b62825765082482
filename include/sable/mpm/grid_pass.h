#ifndef sable_mpm_grid_pass_h
#define sable_mpm_grid_pass_h

namespace sable::mpm
{
  /**
   * The two kinds of particle-to-grid pass of a step. Every step has the
   * momentum update (mass, momentum and internal force: new nodal
   * velocities, whose change moves the particles); MUSL adds a second pass
   * that remaps the updated particle momenta to the grid for the strain
   * update (mass and momentum only).
   */
  enum class GridPass
  {
    momentum_update,
    remapped_momenta
  };
} // namespace sable::mpm

#endif
