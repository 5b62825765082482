#include <deal.II/base/graph_coloring.h>

#include <sable/mpm/cell_colouring.h>

#include <algorithm>

namespace sable::mpm
{
  template <int dim>
  std::vector<std::vector<typename Triangulation<dim>::active_cell_iterator>>
  colour_cells_by_nodes(const Grid<dim> &grid, const bool with_ghost_cells)
  {
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;
    std::vector<CellIterator> cells;
    for (const auto &cell : grid.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() || (with_ghost_cells && cell->is_ghost()))
        cells.push_back(cell);
    if (cells.empty())
      return {};

    // conflict = a shared unconstrained node (local node indices)
    using Position = typename std::vector<CellIterator>::const_iterator;
    const auto conflicts = [&grid](const Position &cell) {
      const auto [nodes, n_nodes] = grid.cell_nodes(grid.cell_data(*cell));
      return std::vector<types::global_dof_index>(nodes, nodes + n_nodes);
    };
    const std::vector<std::vector<Position>> coloured =
      GraphColoring::make_graph_coloring<Position>(cells.cbegin(), cells.cend(), conflicts);

    std::vector<std::vector<CellIterator>> colours(coloured.size());
    for (unsigned int c = 0; c < coloured.size(); ++c)
      {
        std::vector<Position> positions = coloured[c];
        std::sort(positions.begin(), positions.end());
        colours[c].reserve(positions.size());
        for (const Position &position : positions)
          colours[c].push_back(*position);
      }
    return colours;
  }

  template std::vector<std::vector<Triangulation<2>::active_cell_iterator>>
  colour_cells_by_nodes<2>(const Grid<2> &, const bool);
  template std::vector<std::vector<Triangulation<3>::active_cell_iterator>>
  colour_cells_by_nodes<3>(const Grid<3> &, const bool);
} // namespace sable::mpm
