#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <sable/mpm/nodal_fields.h>

#include <algorithm>
#include <limits>

namespace sable::mpm
{
  template <int dim>
  void
  NodalFields<dim>::reinit(const Grid<dim> &grid,
                           const bool       with_material_extent,
                           const bool       with_mass_moment)
  {
    scattered.reinit(grid.make_partitioner(n_components));
    if (with_material_extent)
      material_extent.reinit(grid.make_partitioner(2 * dim));
    else
      material_extent.reinit(0);
    if (with_mass_moment)
      mass_moment.reinit(grid.make_partitioner(dim + 1));
    else
      mass_moment.reinit(0);
    mass.assign(grid.n_relevant_nodes(), 0.);
    old_velocity.assign(grid.n_relevant_nodes() * dim, 0.);
    new_velocity.assign(grid.n_relevant_nodes() * dim, 0.);
    // nonzero only at the walls' nodes, which change only with the grid
    if (keep_wall_correction)
      wall_correction.assign(grid.n_relevant_nodes() * dim, 0.);
  }

  template <int dim>
  template <GridPass pass>
  void
  NodalFields<dim>::zero()
  {
    scattered = 0.;
    scattered.zero_out_ghost_values();
    // the material extent around each node for friction walls that act
    // only where material reaches them (lowest coordinate, minus highest)
    if (pass == GridPass::momentum_update && material_extent.size() > 0)
      {
        material_extent.zero_out_ghost_values();
        const auto &partitioner = *material_extent.get_partitioner();
        std::fill(material_extent.get_values(),
                  material_extent.get_values() + partitioner.locally_owned_size() +
                    partitioner.n_ghost_indices(),
                  std::numeric_limits<double>::max());
      }
    if (pass == GridPass::momentum_update && mass_moment.size() > 0)
      {
        mass_moment = 0.;
        mass_moment.zero_out_ghost_values();
      }
  }

  template <int dim>
  template <GridPass pass>
  void
  NodalFields<dim>::compress()
  {
    scattered.compress(VectorOperation::add);
    scattered.update_ghost_values();
    if (pass == GridPass::momentum_update && material_extent.size() > 0)
      {
        material_extent.compress(VectorOperation::min);
        material_extent.update_ghost_values();
      }
    if (pass == GridPass::momentum_update && mass_moment.size() > 0)
      {
        mass_moment.compress(VectorOperation::add);
        mass_moment.update_ghost_values();
      }
  }

  template <int dim>
  template <GridPass pass>
  double
  NodalFields<dim>::compute_velocities(BoundaryConditions<dim> &boundary_conditions,
                                       const Tensor<1, dim> &   gravity,
                                       const double             time_step)
  {
    constexpr bool      momentum_update = pass == GridPass::momentum_update;
    const double *const values          = scattered.get_values();
    // node by node: threads change nothing
    parallel::apply_to_subranges(
      0u,
      n_relevant_nodes(),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int i = begin; i < end; ++i)
          {
            const double *const node = values + i * n_components;
            const double        m    = node[0];
            mass[i]                  = m;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double v = m > 0. ? node[1 + d] / m : 0.;
                if constexpr (momentum_update)
                  {
                    old_velocity[i * dim + d] = v;
                    new_velocity[i * dim + d] =
                      m > 0. ? v + time_step * (node[1 + dim + d] / m + gravity[d]) : 0.;
                  }
                else
                  new_velocity[i * dim + d] = v;
              }
          }
      },
      4096);
    if (boundary_conditions.empty())
      return 0.;
    // the walls' nodes' velocities before the conditions; every other
    // entry of wall_correction stays zero (reinit())
    const std::vector<unsigned int> &wall_nodes = boundary_conditions.constrained_node_list();
    if (keep_wall_correction)
      {
        if (wall_correction.size() != new_velocity.size())
          wall_correction.assign(new_velocity.size(), 0.);
        for (const unsigned int i : wall_nodes)
          for (unsigned int d = 0; d < dim; ++d)
            wall_correction[i * dim + d] = new_velocity[i * dim + d];
      }
    double work = 0.;
    if constexpr (!momentum_update)
      {
        if constexpr (pass == GridPass::initial_momenta)
          boundary_conditions.apply_to_initial(new_velocity, mass);
        else
          {
            boundary_conditions.count_heat_on_remapped(new_velocity, mass, n_owned_nodes());
            boundary_conditions.apply_to_remapped(new_velocity, mass);
          }
      }
    else
      {
        if (material_extent.size() > 0)
          boundary_conditions.set_material_extent(material_extent.get_values(), time_step);
        if (mass_moment.size() > 0)
          boundary_conditions.set_mass_moment(mass_moment.get_values(), time_step);
        work = boundary_conditions.apply(new_velocity, mass, n_owned_nodes());
      }
    if (keep_wall_correction)
      {
        const std::vector<bool> &moving = boundary_conditions.moving_wall_nodes();
        for (const unsigned int i : wall_nodes)
          for (unsigned int d = 0; d < dim; ++d)
            wall_correction[i * dim + d] =
              moving[i] ? 0. : new_velocity[i * dim + d] - wall_correction[i * dim + d];
      }
    return work;
  }

  template class NodalFields<2>;
  template class NodalFields<3>;
#define SABLE_INSTANTIATE(dim, pass)                                                    \
  template void   NodalFields<dim>::zero<pass>();                                       \
  template void   NodalFields<dim>::compress<pass>();                                   \
  template double NodalFields<dim>::compute_velocities<pass>(BoundaryConditions<dim> &, \
                                                             const Tensor<1, dim> &,    \
                                                             const double);
  SABLE_INSTANTIATE(2, GridPass::momentum_update)
  SABLE_INSTANTIATE(2, GridPass::remapped_momenta)
  SABLE_INSTANTIATE(2, GridPass::initial_momenta)
  SABLE_INSTANTIATE(3, GridPass::momentum_update)
  SABLE_INSTANTIATE(3, GridPass::remapped_momenta)
  SABLE_INSTANTIATE(3, GridPass::initial_momenta)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
