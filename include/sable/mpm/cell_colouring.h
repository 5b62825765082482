#ifndef sable_mpm_cell_colouring_h
#define sable_mpm_cell_colouring_h

#include <sable/mpm/grid.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The cells a particle-to-grid scatter visits (the locally owned cells,
   * and with @p with_ghost_cells the ghost cells too), split into colours:
   * two cells of one colour share no node their shape functions reach
   * (Grid::cell_nodes(), hanging-node folding included). The cells of a
   * colour can therefore scatter concurrently without locks, and every node
   * receives the cells' contributions colour by colour, in an order fixed by
   * the mesh alone: the sums do not depend on the number of threads.
   *
   * Computed with deal.II's GraphColoring::make_graph_coloring() (itself
   * deterministic), once per mesh change; within a colour the cells keep
   * the mesh's order, for memory locality.
   */
  template <int dim>
  std::vector<std::vector<typename Triangulation<dim>::active_cell_iterator>>
  colour_cells_by_nodes(const Grid<dim> &grid, const bool with_ghost_cells);
} // namespace sable::mpm

#endif
