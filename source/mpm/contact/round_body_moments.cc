#include <sable/mpm/contact/per_body_sums.h>
#include <sable/mpm/contact/round_body_moments.h>

namespace sable::mpm
{
  namespace
  {
    /// a x b, with 2D vectors in the plane z = 0
    template <int dim>
    Tensor<1, 3>
    cross(const Tensor<1, dim> &a, const Tensor<1, dim> &b)
    {
      Tensor<1, 3> a3, b3;
      for (unsigned int d = 0; d < dim; ++d)
        {
          a3[d] = a[d];
          b3[d] = b[d];
        }
      return cross_product_3d(a3, b3);
    }
  } // namespace

  template <int dim>
  void
  RoundBodyMoments<dim>::update_bodies(const ParticleCells<dim> &cells,
                                       const std::vector<bool> & round_bodies,
                                       const MPI_Comm            communicator)
  {
    round                = round_bodies;
    const unsigned int n = round.size();
    // the centres first, then the second moments about them: about the
    // origin the moments of a small grain far from it would cancel
    centres = centres_of_mass(cells, round, communicator);
    const auto add_second_moment = [&](const auto &props, const auto &x, double *sum) {
      const double         mass = props[ParticleLayout<dim>::mass];
      const unsigned int   body = static_cast<unsigned int>(props[ParticleLayout<dim>::body]);
      const Tensor<1, dim> r    = x - centres[body];
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          sum[i * dim + j] += mass * r[i] * r[j];
    };
    const std::vector<double> second_moments =
      sum_per_body<dim>(cells, round, dim * dim, communicator, add_second_moment);
    inverse_inertia.assign(n, Tensor<2, 3>());
    for (unsigned int b = 0; b < n; ++b)
      {
        const double *const S     = &second_moments[b * dim * dim];
        double              trace = 0;
        for (unsigned int d = 0; d < dim; ++d)
          trace += S[d * dim + d];
        if (!round[b] || !(trace > 0))
          continue;
        if constexpr (dim == 2)
          inverse_inertia[b][2][2] = 1. / trace;
        else
          {
            Tensor<2, 3> inertia;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                inertia[i][j] = (i == j ? trace : 0.) - S[i * dim + j];
            inverse_inertia[b] = invert(inertia);
          }
      }
  }

  template <int dim>
  void
  RoundBodyMoments<dim>::collect(const BodyFields<dim> &          fields,
                                 const std::vector<Point<dim>> &  node_positions,
                                 const unsigned int               n_owned_nodes,
                                 const MPI_Comm                   communicator)
  {
    const unsigned int n = round.size();
    std::vector<double> sums(3 * n, 0.);
    for (const unsigned int node : fields.get_contact_nodes())
      {
        if (node >= n_owned_nodes)
          continue;
        const auto [begin, end] = fields.node_records(node);
        for (const auto *r = begin; r != end; ++r)
          if (r->body < n && round[r->body] && r->mass > 0)
            {
              // the moment of m dv at the node less that at the points'
              // centroid, which is what the points take
              const Tensor<1, dim> arm    = node_positions[node] - r->mass_position / r->mass;
              const Tensor<1, 3>   moment = cross<dim>(arm, r->mass * r->correction);
              for (unsigned int d = 0; d < 3; ++d)
                sums[3 * r->body + d] += moment[d];
            }
      }
    Utilities::MPI::sum(sums, communicator, sums);
    spin_changes.assign(n, Tensor<1, 3>());
    for (unsigned int b = 0; b < n; ++b)
      {
        Tensor<1, 3> moment;
        for (unsigned int d = 0; d < 3; ++d)
          moment[d] = sums[3 * b + d];
        spin_changes[b] = inverse_inertia[b] * moment;
      }
  }

  template class RoundBodyMoments<2>;
  template class RoundBodyMoments<3>;
} // namespace sable::mpm
