#include <deal.II/dofs/dof_tools.h>

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

    cells.assign(triangulation.n_active_cells(), CellData());
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
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              data.nodes[v]             = node_partitioner->global_to_local(dofs[v]);
              positions[data.nodes[v]] = cell->vertex(v);
            }
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double h = cell->extent_in_direction(d);
              data.inverse_h[d] = 1. / h;
              if (cell->is_locally_owned())
                h_min = std::min(h_min, h);
              for (unsigned int v = 0; v < nodes_per_cell; ++v)
                spacing[data.nodes[v]][d] = std::min(spacing[data.nodes[v]][d], h);
            }
        }
    min_cell_size = Utilities::MPI::min(h_min, triangulation.get_communicator());
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
