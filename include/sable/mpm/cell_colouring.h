#ifndef sable_mpm_cell_colouring_h
#define sable_mpm_cell_colouring_h

#include <deal.II/base/parallel.h>

#include <sable/mpm/grid.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The cells a particle-to-grid scatter visits (the locally owned cells,
   * and optionally the ghost cells too), arranged for a threaded scatter
   * whose sums do not depend on the number of threads.
   *
   * The cells, in the mesh's order, are cut into blocks of block_size
   * consecutive cells (compact patches: deal.II orders the coarse cells of
   * a distributed mesh hierarchically), and the blocks are coloured with
   * deal.II's GraphColoring::make_graph_coloring() (deterministic) so that
   * two blocks of one colour share no node their cells' shape functions
   * reach (Grid::cell_nodes(), hanging-node folding included). One thread
   * scatters a whole block, cell after cell, so the blocks of a colour run
   * concurrently without locks, and every node adds up its contributions
   * colour by colour, block by block, cell by cell: an order fixed by the
   * mesh alone, also with one thread. Colouring blocks rather than single
   * cells keeps the serial loop's memory locality (single-cell colours
   * stride through the particle and node data, one pass per colour).
   *
   * Built once per mesh change; nothing is rebuilt when particles change
   * cells (ParticleCells keeps, per colour and block, the cells that hold
   * points).
   */
  template <int dim>
  class CellColouring
  {
  public:
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    /// Consecutive cells per block.
    static constexpr unsigned int block_size = 64;

    /// Colour the locally owned cells (and with @p with_ghost_cells the
    /// ghost cells) of @p grid's mesh.
    void
    reinit(const Grid<dim> &grid, const bool with_ghost_cells);

    /**
     * Call @p f(begin, end) on ranges [begin, end) of cells (iterators into
     * a std::vector<CellIterator>), colour by colour; the ranges of one
     * colour run in parallel, each a whole number of blocks.
     */
    template <typename Function>
    void
    for_each_cell_range(const Function &f) const
    {
      for (const Colour &colour : colours)
        parallel::apply_to_subranges(
          0u,
          static_cast<unsigned int>(colour.block_start.size() - 1),
          [&](const unsigned int first_block, const unsigned int end_block) {
            f(colour.cells.cbegin() + colour.block_start[first_block],
              colour.cells.cbegin() + colour.block_start[end_block]);
          },
          1);
    }

    unsigned int
    n_colours() const
    {
      return colours.size();
    }

    struct Colour
    {
      /// the cells of the colour's blocks, block after block
      std::vector<CellIterator> cells;
      /// their active cell indices
      std::vector<unsigned int> cell_indices;
      /// where each block starts in cells, and cells.size() at the end
      std::vector<unsigned int> block_start;
    };

    const std::vector<Colour> &
    get_colours() const
    {
      return colours;
    }

  private:
    std::vector<Colour> colours;
  };
} // namespace sable::mpm

#endif
