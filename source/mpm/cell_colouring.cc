#include <deal.II/base/graph_coloring.h>

#include <sable/mpm/cell_colouring.h>

#include <algorithm>

namespace sable::mpm
{
  template <int dim>
  void
  CellColouring<dim>::reinit(const Grid<dim> &grid, const bool with_ghost_cells)
  {
    colours.clear();
    std::vector<CellIterator> cells;
    for (const auto &cell : grid.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() || (with_ghost_cells && cell->is_ghost()))
        cells.push_back(cell);
    if (cells.empty())
      return;

    // blocks: their first cell's index; a block ends where the next starts
    std::vector<unsigned int> blocks;
    for (unsigned int c = 0; c < cells.size(); c += block_size)
      blocks.push_back(c);
    const auto block_end = [&](const unsigned int first) {
      return std::min<std::size_t>(first + block_size, cells.size());
    };

    // conflict = a shared unconstrained node (local node indices)
    using Block           = std::vector<unsigned int>::const_iterator;
    const auto conflicts = [&](const Block &block) {
      std::vector<types::global_dof_index> nodes;
      for (unsigned int c = *block; c < block_end(*block); ++c)
        {
          const auto [cell_nodes, n_nodes] = grid.cell_nodes(grid.cell_data(cells[c]));
          nodes.insert(nodes.end(), cell_nodes, cell_nodes + n_nodes);
        }
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      return nodes;
    };
    const std::vector<std::vector<Block>> coloured =
      GraphColoring::make_graph_coloring<Block>(blocks.cbegin(), blocks.cend(), conflicts);

    // each colour's blocks in the mesh's order
    colours.resize(coloured.size());
    for (unsigned int k = 0; k < coloured.size(); ++k)
      {
        std::vector<unsigned int> firsts;
        for (const Block &block : coloured[k])
          firsts.push_back(*block);
        std::sort(firsts.begin(), firsts.end());
        Colour &colour = colours[k];
        for (const unsigned int first : firsts)
          {
            colour.block_start.push_back(colour.cells.size());
            colour.cells.insert(colour.cells.end(),
                                cells.begin() + first,
                                cells.begin() + block_end(first));
            for (unsigned int c = first; c < block_end(first); ++c)
              colour.cell_indices.push_back(cells[c]->active_cell_index());
          }
        colour.block_start.push_back(colour.cells.size());
      }
  }

  template class CellColouring<2>;
  template class CellColouring<3>;
} // namespace sable::mpm
