#ifndef sable_mpm_particle_rebinning_h
#define sable_mpm_particle_rebinning_h

#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/particle_cells.h>
#include <sable/mpm/periodicity.h>

#include <limits>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Moves the material points that left their cells into their new cells,
   * on one MPI rank, in place of the ParticleHandler's sort.
   *
   * deal.II 9.4's sort_particles_into_subdomains_and_cells() checks every
   * point on one thread, which makes it the part of the step that does not
   * scale with threads. Here the points that stayed in their cells only
   * get their reference locations, in parallel; the few that left are
   * moved one after the other, as the sort moves them: in the order of
   * their old cells' indices, each is inserted at the end of its new cell's
   * points, and then the old copies are removed, a cell's last first (a
   * removal moves the cell's last point into the gap). Every cell then
   * holds the same points in the same order as after the sort, so every
   * pass of the next step adds them up in the same order (the order of
   * the cells within the container may differ; no pass depends on it).
   * What the sort does on top, putting the cells in index order and the
   * points' data in memory in the order of the container, is left to the
   * full sort the caller runs from time to time (see
   * moved_since_full_sort()): without it, the scattered data of the moved
   * points slows the transfers down (by half after a thousand steps of the
   * throughput benchmark).
   *
   * A point's new cell is found by walking from its old cell through the
   * faces it crossed (a point moves less than one cell per step), across a
   * periodic seam to the periodic neighbour, and down to the active child
   * of a finer neighbour. A point that left the grid is not moved: then
   * rebin() reports that the full sort is needed (it removes such points
   * and reports them as lost).
   */
  template <int dim>
  class ParticleRebinning
  {
  public:
    /**
     * Set the reference locations of the locally owned points of @p cells
     * (which must describe @p particle_handler as it is) and move the
     * points that left their cells. Returns false, with nothing changed
     * but reference locations, if a point could not be placed (it left the
     * grid) or more than @p max_moves points left: the caller then sorts.
     * Each move is inserted before its old copy goes, so a step's moves
     * need as many free slots in the particle data: beyond the room the
     * caller reserved, the data would double.
     */
    bool
    rebin(Particles::ParticleHandler<dim> &particle_handler,
          const ParticleCells<dim> &       cells,
          const Periodicity<dim> &         periodicity,
          const std::size_t                max_moves = std::numeric_limits<std::size_t>::max());

    /// Points moved by rebin() since reset(), summed over the calls.
    unsigned long long
    moved_since_full_sort() const
    {
      return n_moved;
    }

    /// A full sort has put the particle container in order again.
    void
    reset()
    {
      n_moved = 0;
    }

  private:
    using CellIterator     = typename Triangulation<dim>::active_cell_iterator;
    using ParticleIterator = typename Particles::ParticleHandler<dim>::particle_iterator;

    /// The active cell that holds @p x, found from @p old_cell, or an
    /// invalid iterator if @p x is not within reach (it left the grid).
    static CellIterator
    find_cell(const CellIterator &old_cell, const Point<dim> &x, const Periodicity<dim> &periodicity);

    unsigned long long n_moved = 0;

    /// a point that left its cell, with that cell's active index
    using Leaving = std::pair<unsigned int, ParticleIterator>;
    /// the points that left their cells, by old cell index and, within a
    /// cell, in the container's order
    std::vector<Leaving> leaving;
    /// per leaving point: its new cell
    std::vector<CellIterator> destination;
    /// one point's properties (a copy: inserting may move the pool)
    std::vector<double> properties;
  };
} // namespace sable::mpm

#endif
