#include <sable/mpm/particle_layout.h>
#include <sable/mpm/postprocess/stress_smoothing.h>

#include <algorithm>

namespace sable::mpm
{
  template <int dim>
  typename StressSmoothing<dim>::Sums &
  StressSmoothing<dim>::sums(const unsigned int node, const unsigned int body)
  {
    unsigned int &first = first_body[node];
    if (first == numbers::invalid_unsigned_int)
      first = body;
    if (first == body)
      return first_sums[node];
    // a second body at this node (a contact)
    return others[(static_cast<unsigned long long>(node) << 32) | body];
  }

  template <int dim>
  void
  StressSmoothing<dim>::compute(const ParticleCells<dim> &cells,
                                const Grid<dim> &         grid,
                                const unsigned int        n_local_indices)
  {
    using Layout = ParticleLayout<dim>;
    first_body.assign(grid.n_relevant_nodes(), numbers::invalid_unsigned_int);
    first_sums.assign(grid.n_relevant_nodes(), Sums());
    others.clear();
    typename Grid<dim>::Shape shape;
    // the projection: owned and ghost cells, so that the nodes of the
    // owned cells see every point in their support
    for (unsigned int c = 0; c < cells.size(); ++c)
      for (const auto &particle : cells[c].particles)
        {
          const auto         props  = particle.get_properties();
          const unsigned int body   = static_cast<unsigned int>(props[Layout::body]);
          const double       volume =
            determinant(Layout::deformation_gradient(props)) * props[Layout::initial_volume];
          const SymmetricTensor<2, 3> sigma = Layout::stress_tensor(props);
          grid.evaluate(*cells[c].data,
                        particle.get_reference_location(),
                        props[Layout::initial_volume],
                        shape);
          for (unsigned int v = 0; v < shape.n_nodes; ++v)
            if (shape.values[v] != 0.)
              {
                Sums &s = sums(shape.nodes[v], body);
                s.volume += shape.values[v] * volume;
                s.volume_stress += (shape.values[v] * volume) * sigma;
              }
        }
    // the interpolation back to the owned points
    smoothed.assign(n_local_indices, SymmetricTensor<2, 3>());
    for (unsigned int c = 0; c < cells.n_owned(); ++c)
      for (const auto &particle : cells[c].particles)
        {
          const auto         props = particle.get_properties();
          const unsigned int body  = static_cast<unsigned int>(props[Layout::body]);
          grid.evaluate(*cells[c].data,
                        particle.get_reference_location(),
                        props[Layout::initial_volume],
                        shape);
          SymmetricTensor<2, 3> sigma;
          double                weight = 0;
          for (unsigned int v = 0; v < shape.n_nodes; ++v)
            if (shape.values[v] != 0.)
              {
                const Sums &s = sums(shape.nodes[v], body);
                if (s.volume > 0)
                  {
                    sigma += (shape.values[v] / s.volume) * s.volume_stress;
                    weight += shape.values[v];
                  }
              }
          // the shape values of a point's cell add up to one; the division
          // only matters for a point of zero volume
          smoothed[particle.get_local_index()] = weight > 0 ? sigma / weight : sigma;
        }
  }

  template class StressSmoothing<2>;
  template class StressSmoothing<3>;
} // namespace sable::mpm
