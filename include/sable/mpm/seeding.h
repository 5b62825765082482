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
  /// The gradient of a body's spin velocity omega x (x - c) in the plane
  /// (2D) or space (3D): the skew tensor a point of the affine transfers
  /// starts with.
  template <int dim>
  inline Tensor<2, dim>
  spin_velocity_gradient(const Tensor<1, 3> &omega)
  {
    // d(omega x r)_i / dr_k = eps_ijk omega_j, eps_ijk = (i-j)(j-k)(k-i)/2
    Tensor<2, dim> gradient;
    for (int i = 0; i < dim; ++i)
      for (int k = 0; k < dim; ++k)
        for (int j = 0; j < 3; ++j)
          gradient[i][k] += 0.5 * (i - j) * (j - k) * (k - i) * omega[j];
    return gradient;
  }

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
