#ifndef sable_mpm_particle_cells_h
#define sable_mpm_particle_cells_h

#include <deal.II/base/parallel.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/grid.h>

#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// The box of an axis-aligned cell: vertex 0, and per direction d the
  /// coordinate d of vertex 2^d.
  template <int dim, typename CellIterator>
  std::pair<Point<dim>, Point<dim>>
  cell_box(const CellIterator &cell)
  {
    Point<dim> lower = cell->vertex(0), upper;
    for (unsigned int d = 0; d < dim; ++d)
      upper[d] = cell->vertex(1u << d)[d];
    return {lower, upper};
  }

  /// The reference coordinates of @p x in the box [@p lower, @p upper],
  /// (x - lower) / (upper - lower) per direction: the operations of
  /// deal.II's MappingCartesian, so the same bits as its sort.
  template <int dim>
  Point<dim>
  reference_location_in_box(const Point<dim> &x, const Point<dim> &lower, const Point<dim> &upper)
  {
    Point<dim> reference = x;
    reference -= lower;
    for (unsigned int d = 0; d < dim; ++d)
      reference[d] /= upper[d] - lower[d];
    return reference;
  }

  /**
   * The cells that hold material points, as a flat list of the cell, its
   * grid data and its range of particles: the passes of a step visit only
   * these, instead of walking every cell of the mesh and looking up its
   * particles (most cells of a scene are often empty).
   *
   * Built from the ParticleHandler's own list of non-empty cells (a cost
   * per non-empty cell, not per cell) after every change of the particle
   * container: a sort, a ghost exchange, a mesh change. The locally owned
   * cells come first, in the handler's order, then the ghost cells with
   * ghost particles. For the threaded scatter the list is also arranged
   * like the CellColouring, colour by colour and block by block with the
   * empty cells left out, so a scatter adds up every node's contributions
   * in the same order as a walk over all coloured cells.
   */
  template <int dim>
  class ParticleCells
  {
  public:
    using ParticleRange = typename Particles::ParticleHandler<dim>::particle_iterator_range;

    struct Cell
    {
      typename Triangulation<dim>::active_cell_iterator cell;
      unsigned int                                      active_cell_index;
      const typename Grid<dim>::CellData *              data;
      ParticleRange                                     particles;
      bool                                              owned;
      /// vertex 0, and per direction d the coordinate d of vertex 2^d
      Point<dim> lower, upper;

      /// Whether @p x is in the cell (faces included).
      bool
      contains(const Point<dim> &x) const
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (x[d] < lower[d] || x[d] > upper[d])
            return false;
        return true;
      }

      /// The reference coordinates of @p x in the cell.
      Point<dim>
      reference_location(const Point<dim> &x) const
      {
        return reference_location_in_box(x, lower, upper);
      }
    };

    /// Collect the cells with points of @p particle_handler (owned, and
    /// ghost cells if @p colouring holds them) and arrange them by colour.
    void
    rebuild(const Particles::ParticleHandler<dim> &particle_handler,
            const Grid<dim> &                      grid,
            const CellColouring<dim> &             colouring);

    /**
     * Set every locally owned point's reference location from its position
     * in its cell, as the ParticleHandler's sort does (MappingCartesian:
     * (x - v_0) / (v_{2^d} - v_0) per direction d, the same operations, so
     * the same bits): instead of a sort when no point left its cell.
     */
    void
    update_reference_locations() const;

    /// Give the list's memory back (rebuild() before the next use): the
    /// full sort copies the particle data, and the list is stale after it.
    void
    release()
    {
      std::vector<Cell>().swap(cells);
      std::vector<Colour>().swap(colours);
      std::vector<unsigned int>().swap(slot);
      n_owned_cells = 0;
      ++n_versions;
    }

    /// How many times the list was rebuilt or released: what others keep
    /// per cell of the list (the bodies of its points) stays valid while
    /// this does not change.
    unsigned long long
    version() const
    {
      return n_versions;
    }

    /// Locally owned cells with points: [0, n_owned()).
    unsigned int
    n_owned() const
    {
      return n_owned_cells;
    }

    /// All cells with points, the ghost cells after the owned ones.
    unsigned int
    size() const
    {
      return cells.size();
    }

    const Cell &
    operator[](const unsigned int i) const
    {
      return cells[i];
    }

    /**
     * Call @p f(begin, end) on ranges of indices into this list
     * (const unsigned int *), colour by colour; the ranges of one colour
     * run in parallel, each a whole number of blocks (see CellColouring).
     */
    template <typename Function>
    void
    for_each_coloured_range(const Function &f) const
    {
      for (const Colour &colour : colours)
        parallel::apply_to_subranges(
          0u,
          static_cast<unsigned int>(colour.block_start.size() - 1),
          [&](const unsigned int first_block, const unsigned int end_block) {
            f(colour.cells.data() + colour.block_start[first_block],
              colour.cells.data() + colour.block_start[end_block]);
          },
          1);
    }

  private:
    std::vector<Cell>  cells;
    unsigned int       n_owned_cells = 0;
    unsigned long long n_versions    = 0;

    struct Colour
    {
      /// indices into cells, block after block (blocks without points left out)
      std::vector<unsigned int> cells;
      /// where each block starts in cells, and cells.size() at the end
      std::vector<unsigned int> block_start;
    };
    std::vector<Colour> colours;

    /// per active cell: its index in cells, or numbers::invalid_unsigned_int
    std::vector<unsigned int> slot;
  };
} // namespace sable::mpm

#endif
