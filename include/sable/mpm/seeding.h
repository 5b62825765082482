#ifndef sable_mpm_seeding_h
#define sable_mpm_seeding_h

#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/materials/material.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/particle_layout.h>

#include <memory>
#include <vector>

namespace sable::mpm
{
  /**
   * Fill every body with material points (SPEC Part A, initial state):
   * k^dim points per cell at the seeding_point() positions of each locally
   * owned cell the body covers, with mass, volume, velocity v0 + omega x
   * (x - c), F = I and, if asked, a lithostatic stress; a body of
   * Shape = points gets one material point per point of its file, in the
   * owned cell holding it (cells half open, closed at the grid's upper
   * bounds, so that a point on a face is seeded once over all ranks). Point ids are
   * unique over all ranks: numbered body by body and cell by cell on each
   * rank, then offset by the points of the lower ranks.
   */
  template <int dim>
  void
  seed_bodies(const parallel::distributed::Triangulation<dim> &triangulation,
              const std::vector<BodyParameters<dim>> &         bodies,
              const std::vector<std::unique_ptr<Material>> &   materials,
              const ParticleLayout<dim> &                      layout,
              const Tensor<1, dim> &                           gravity,
              Particles::ParticleHandler<dim> &                particle_handler);
} // namespace sable::mpm

#endif
