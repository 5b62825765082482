#ifndef sable_mpm_owned_cell_strip_h
#define sable_mpm_owned_cell_strip_h

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The locally owned active cells sorted by their lowest x, so that a body
   * visits only the strip of cells its bounding box spans (seeding, and
   * refinement by the seeding points) instead of every cell of the grid.
   */
  template <int dim>
  class OwnedCellStrip
  {
  public:
    struct Cell
    {
      typename Triangulation<dim>::active_cell_iterator cell;
      Point<dim>                                        lower;
      Point<dim>                                        upper;
    };

    explicit OwnedCellStrip(const Triangulation<dim> &triangulation)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto corners = cell->bounding_box().get_boundary_points();
            cells.push_back({cell, corners.first, corners.second});
            widest = std::max(widest, corners.second[0] - corners.first[0]);
          }
      std::sort(cells.begin(), cells.end(), [](const Cell &a, const Cell &b) {
        return a.lower[0] < b.lower[0];
      });
    }

    /// Call @p f(cell) for every owned cell whose box meets @p box.
    template <typename Function>
    void
    for_each_overlapping(const std::pair<Point<dim>, Point<dim>> &box, const Function &f) const
    {
      const auto first =
        std::lower_bound(cells.begin(), cells.end(), box.first[0] - widest, [](const Cell &c, const double x) {
          return c.lower[0] < x;
        });
      for (auto it = first; it != cells.end() && it->lower[0] <= box.second[0]; ++it)
        {
          bool overlaps = true;
          for (unsigned int d = 0; d < dim; ++d)
            overlaps = overlaps && it->upper[d] >= box.first[d] && it->lower[d] <= box.second[d];
          if (overlaps)
            f(*it);
        }
    }

  private:
    std::vector<Cell> cells;
    double            widest = 0;
  };

  /// Reference coordinates of seeding point @p i of the k^dim points of a
  /// cell: the centres of a k x k (x k) subdivision.
  template <int dim>
  inline Point<dim>
  seeding_point(const unsigned int i, const unsigned int k)
  {
    Point<dim> reference;
    for (unsigned int d = 0, rest = i; d < dim; ++d, rest /= k)
      reference[d] = ((rest % k) + 0.5) / k;
    return reference;
  }
} // namespace sable::mpm

#endif
