#ifndef sable_mpm_contact_round_body_moments_h
#define sable_mpm_contact_round_body_moments_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/particle_cells.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * 'Contact/Round body moments = kept': the part of the moment of the
   * contact's (and the walls') corrections that the transfer to the points
   * loses, given to each round body (disk, sphere) as a rigid rotation
   * about its centre of mass.
   *
   * A correction dv of a body's velocity at a node reaches its points in
   * proportion to their weights, m_p N_p dv; its moment about the body's
   * centre c is then taken at their centroid near the node, xbar = sum m_p
   * N_p x_p / m, a fraction of a cell inside the body, not at the node x:
   * the points miss (x - xbar) x m dv of what the grid received. Summed
   * over the body's contact nodes (on all ranks), this moment is given to
   * the body as a spin dw = I^-1 dL, each point's velocity changing by
   * dw x (x_p - c): momentum is kept, and a rigid rotation is a field the
   * grid resolves, so no motion below its scale is made. Not on periodic
   * grids, where a body's centre may lie across a seam.
   */
  template <int dim>
  class RoundBodyMoments
  {
  public:
    /// Each round body's centre of mass and moment of inertia from its
    /// points on all ranks (before the step's transfers; @p round per body).
    void
    update_bodies(const ParticleCells<dim> &cells,
                  const std::vector<bool> & round,
                  const MPI_Comm            communicator);

    /// Each round body's spin change from the corrections of the momentum
    /// update at the contact nodes of @p fields (Record::correction); the
    /// locally owned nodes, which come first (below @p n_owned_nodes),
    /// count on this rank.
    void
    collect(const BodyFields<dim> &          fields,
            const std::vector<Point<dim>> &  node_positions,
            const unsigned int               n_owned_nodes,
            const MPI_Comm                   communicator);

    /// The velocity change of a point of @p body at @p x (zero for bodies
    /// that are not round).
    Tensor<1, dim>
    velocity(const unsigned int body, const Point<dim> &x) const
    {
      Tensor<1, dim> v;
      if (body >= spin_changes.size())
        return v;
      const Tensor<1, 3> &w = spin_changes[body];
      const Tensor<1, dim> r = x - centres[body];
      if constexpr (dim == 2)
        {
          v[0] = -w[2] * r[1];
          v[1] = w[2] * r[0];
        }
      else
        {
          v[0] = w[1] * r[2] - w[2] * r[1];
          v[1] = w[2] * r[0] - w[0] * r[2];
          v[2] = w[0] * r[1] - w[1] * r[0];
        }
      return v;
    }

  private:
    std::vector<bool>         round;
    std::vector<Point<dim>>   centres;
    /// the inverse of each round body's moment of inertia about its centre
    /// (in 2D only [2][2], about the axis normal to the plane)
    std::vector<Tensor<2, 3>> inverse_inertia;
    std::vector<Tensor<1, 3>> spin_changes;
  };
} // namespace sable::mpm

#endif
