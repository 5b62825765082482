#include <sable/mpm/particle_to_grid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace sable::mpm
{
  template <int dim>
  template <GridPass pass>
  void
  ParticleToGrid<dim>::scatter(const ParticleCells<dim> &cells,
                               const Grid<dim> &         grid,
                               NodalFields<dim> &        fields,
                               MultiBodyContact<dim> *   contact) const
  {
    using Layout                           = ParticleLayout<dim>;
    constexpr bool         momentum_update = pass == GridPass::momentum_update;
    constexpr unsigned int n_components    = NodalFields<dim>::n_components;
    fields.template zero<pass>();
    double *const grid_values = fields.scattered_values();
    double *const extent      = momentum_update ? fields.material_extent_values() : nullptr;
    double *const moment      = momentum_update ? fields.mass_moment_values() : nullptr;

    // the single-field assembler: one point's share of mass, momentum,
    // internal force -V sigma . grad N and material extent
    const auto add_to_single_field = [&](const auto &                     particle,
                                         const ArrayView<const double> &  props,
                                         const typename Grid<dim>::Shape &shape,
                                         const auto &                     velocity_at,
                                         const Tensor<2, dim> &           volume_stress) {
      const double mass = props[Layout::mass];
      if (extent != nullptr)
        {
          const Tensor<2, dim> F = Layout::deformation_gradient(props);
          // half the edge of the point's current volume
          const double half =
            0.5 * std::pow(determinant(F) * props[Layout::initial_volume], 1. / dim);
          for (unsigned int v = 0; v < shape.n_nodes; ++v)
            {
              const Point<dim> x = shape.image_for_node(particle.get_location(), v);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  double *const e = extent + shape.nodes[v] * 2 * dim + 2 * d;
                  e[0]            = std::min(e[0], x[d] - half);
                  e[1]            = std::min(e[1], -(x[d] + half));
                }
            }
        }
      if (moment != nullptr)
        {
          const double     spacing = Layout::seeding_spacing(props);
          for (unsigned int v = 0; v < shape.n_nodes; ++v)
            {
              const Point<dim> x = shape.image_for_node(particle.get_location(), v);
              double *const m      = moment + shape.nodes[v] * (dim + 1);
              const double  weight = mass * shape.values[v];
              for (unsigned int d = 0; d < dim; ++d)
                m[d] += weight * x[d];
              m[dim] += weight * spacing;
            }
        }
      for (unsigned int v = 0; v < shape.n_nodes; ++v)
        {
          double *const node   = grid_values + shape.nodes[v] * n_components;
          const double  weight = mass * shape.values[v];
          node[0] += weight;
          for (unsigned int d = 0; d < dim; ++d)
            node[1 + d] += weight * velocity_at(v, d);
          if constexpr (momentum_update)
            {
              const Tensor<1, dim> force = -(volume_stress * shape.gradients[v]);
              for (unsigned int d = 0; d < dim; ++d)
                node[1 + dim + d] += force[d];
            }
        }
    };

    // the cell worker; with the affine transfers (@p affine true) a point's
    // velocity at node i is v_p + C (x_i - x_p), kept in @p velocities
    const std::vector<Point<dim>> &node_positions = grid.node_positions();
    const auto scatter_cell = [&](const typename ParticleCells<dim>::Cell &cell,
                                  typename Grid<dim>::Shape &              shape,
                                  Tensor<1, dim> *                         velocities,
                                  const auto                               affine) {
      const auto nodes        = grid.cell_nodes(*cell.data);
      const bool near_contact = contact != nullptr && contact->touches(nodes);
      // where the contact's records replace the single field at every node
      // of the cell, nothing would read what the cell added to it
      const bool single_field =
        cell.owned && !(near_contact && contact->replaces_single_field(nodes));
      if (!single_field && !near_contact)
        return;
      for (const auto &particle : cell.particles)
        {
          const ArrayView<const double> props = particle.get_properties();
          grid.evaluate(*cell.data,
                        particle.get_reference_location(),
                        props[Layout::initial_volume],
                        shape);
          const Tensor<2, dim>          volume_stress =
            momentum_update ? Layout::volume_stress(props) : Tensor<2, dim>();
          const auto scatter_point = [&](const auto &velocity_at) {
            if (near_contact)
              contact->template scatter<pass>(
                props, particle.get_location(), shape, velocity_at, volume_stress);
            if (single_field)
              add_to_single_field(particle, props, shape, velocity_at, volume_stress);
          };
          if constexpr (decltype(affine)::value)
            {
              const Tensor<2, dim> C = layout.affine_gradient(props);
              for (unsigned int v = 0; v < shape.n_nodes; ++v)
                {
                  const Tensor<1, dim> offset = node_positions[shape.nodes[v]] -
                                                shape.image_for_node(particle.get_location(), v);
                  for (unsigned int d = 0; d < dim; ++d)
                    velocities[v][d] = props[Layout::velocity + d] + C[d] * offset;
                }
              scatter_point([velocities](const unsigned int v, const unsigned int d) {
                return velocities[v][d];
              });
            }
          else
            scatter_point([&props](const unsigned int, const unsigned int d) {
              return props[Layout::velocity + d];
            });
        }
    };

    cells.for_each_coloured_range([&](const unsigned int *begin, const unsigned int *end) {
      // the worker's scratch: the shape functions at one point and the
      // point's velocity as each of their nodes sees it
      typename Grid<dim>::Shape                                  shape;
      std::array<Tensor<1, dim>, Grid<dim>::max_nodes_per_cell> velocities;
      if (layout.affine_stored)
        for (const unsigned int *c = begin; c != end; ++c)
          scatter_cell(cells[*c], shape, velocities.data(), std::true_type());
      else
        for (const unsigned int *c = begin; c != end; ++c)
          scatter_cell(cells[*c], shape, velocities.data(), std::false_type());
    });
    fields.template compress<pass>();
  }

  template class ParticleToGrid<2>;
  template class ParticleToGrid<3>;
#define SABLE_INSTANTIATE(dim, pass)                                                    \
  template void ParticleToGrid<dim>::scatter<pass>(const ParticleCells<dim> &,              \
                                                   const Grid<dim> &,                   \
                                                   NodalFields<dim> &,                  \
                                                   MultiBodyContact<dim> *) const;
  SABLE_INSTANTIATE(2, GridPass::momentum_update)
  SABLE_INSTANTIATE(2, GridPass::remapped_momenta)
  SABLE_INSTANTIATE(2, GridPass::initial_momenta)
  SABLE_INSTANTIATE(3, GridPass::momentum_update)
  SABLE_INSTANTIATE(3, GridPass::remapped_momenta)
  SABLE_INSTANTIATE(3, GridPass::initial_momenta)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
