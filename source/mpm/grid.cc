#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/affine_constraints.h>

#include <sable/mpm/grid.h>

#include <limits>

namespace sable::mpm
{
  template <int dim>
  Grid<dim>::Grid(const parallel::distributed::Triangulation<dim> &triangulation)
    : triangulation(triangulation)
    , fe(1)
    , dof_handler(triangulation)
  {}

  template <int dim>
  void
  Grid<dim>::setup()
  {
    dof_handler.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    node_partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      dof_handler.locally_owned_dofs(),
      relevant,
      triangulation.get_communicator());

    // hanging nodes: each constrained vertex is a weighted sum of
    // unconstrained nodes (close() resolves chains of constraints)
    AffineConstraints<double> constraints;
    constraints.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    constraints.close();

    cells.assign(triangulation.n_active_cells(), CellData());
    hanging_cells.clear();
    double h_min = std::numeric_limits<double>::max();
    Tensor<1, dim> huge;
    for (unsigned int d = 0; d < dim; ++d)
      huge[d] = std::numeric_limits<double>::max();
    spacing.assign(n_relevant_nodes(), huge);
    positions.assign(n_relevant_nodes(), Point<dim>());
    std::vector<types::global_dof_index> dofs(nodes_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          CellData &data = cells[cell->active_cell_index()];
          cell->get_dof_indices(dofs);
          bool hanging = false;
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              data.nodes[v]             = node_partitioner->global_to_local(dofs[v]);
              positions[data.nodes[v]] = cell->vertex(v);
              hanging = hanging || constraints.is_constrained(dofs[v]);
            }
          if (hanging)
            {
              data.hanging = hanging_cells.size();
              hanging_cells.push_back(fold_hanging_vertices(dofs, constraints));
            }
          const auto [nodes, n_nodes] = cell_nodes(data);
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double h = cell->extent_in_direction(d);
              data.inverse_h[d] = 1. / h;
              if (cell->is_locally_owned())
                h_min = std::min(h_min, h);
              for (unsigned int k = 0; k < n_nodes; ++k)
                spacing[nodes[k]][d] = std::min(spacing[nodes[k]][d], h);
            }
        }
    min_cell_size = Utilities::MPI::min(h_min, triangulation.get_communicator());
  }

  template <int dim>
  typename Grid<dim>::HangingCell
  Grid<dim>::fold_hanging_vertices(const std::vector<types::global_dof_index> &dofs,
                                   const AffineConstraints<double> &constraints) const
  {
    HangingCell folded;
    for (auto &row : folded.weights)
      row.fill(0.);
    const auto slot = [&](const types::global_dof_index dof) {
      const unsigned int node = node_partitioner->global_to_local(dof);
      for (unsigned int k = 0; k < folded.n_nodes; ++k)
        if (folded.nodes[k] == node)
          return k;
      AssertThrow(folded.n_nodes < max_nodes_per_cell,
                  ExcMessage("A cell's hanging vertices reach more nodes than a "
                             "2:1 balanced mesh allows."));
      folded.nodes[folded.n_nodes] = node;
      return folded.n_nodes++;
    };
    const auto relevant = [&](const types::global_dof_index dof) {
      return node_partitioner->in_local_range(dof) || node_partitioner->is_ghost_entry(dof);
    };
    for (unsigned int v = 0; v < nodes_per_cell; ++v)
      {
        const auto *entries = constraints.get_constraint_entries(dofs[v]);
        if (entries == nullptr)
          folded.weights[v][slot(dofs[v])] += 1.;
        else
          for (const auto &[master, weight] : *entries)
            // a ghost cell's master may lie beyond this rank's nodes; no
            // local particle reads it, so its share is not needed here
            if (relevant(master))
              folded.weights[v][slot(master)] += weight;
      }
    return folded;
  }

  template <int dim>
  std::shared_ptr<const Utilities::MPI::Partitioner>
  Grid<dim>::make_partitioner(const unsigned int n_components) const
  {
    const auto expand = [n_components](const IndexSet &set) {
      IndexSet expanded(set.size() * n_components);
      for (const auto index : set)
        expanded.add_range(index * n_components, (index + 1) * n_components);
      expanded.compress();
      return expanded;
    };
    return std::make_shared<Utilities::MPI::Partitioner>(
      expand(node_partitioner->locally_owned_range()),
      expand(node_partitioner->ghost_indices()),
      triangulation.get_communicator());
  }

  template class Grid<2>;
  template class Grid<3>;
} // namespace sable::mpm
