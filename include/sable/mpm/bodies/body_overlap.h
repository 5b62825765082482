#ifndef sable_mpm_bodies_body_overlap_h
#define sable_mpm_bodies_body_overlap_h

#include <deal.II/base/mpi.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/bodies/body_parameters.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/periodicity.h>

#include <vector>

namespace sable::mpm
{
  /**
   * Refuse bodies seeded into each other. A material point of one body
   * that lies inside another body's shape (a disk or sphere, box or mesh;
   * bodies of points have none) by more than a quarter of its own spacing
   * puts mass there twice, and a contact would start from surfaces that
   * have already passed through each other. Bodies may touch: points lie
   * inside their own body, so touching shapes put none of them into the
   * other. Periodic images count. Throws the same InputError on every
   * rank, naming both bodies, the deepest such point and its depth.
   * Collective over @p communicator.
   */
  template <int dim>
  void
  check_bodies_apart(const std::vector<BodyParameters<dim>> &bodies,
                     const Particles::ParticleHandler<dim> & particle_handler,
                     const ParticleLayout<dim> &             layout,
                     const Periodicity<dim> &                periodicity,
                     const MPI_Comm                          communicator);
} // namespace sable::mpm

#endif
