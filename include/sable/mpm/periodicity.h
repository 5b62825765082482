#ifndef sable_mpm_periodicity_h
#define sable_mpm_periodicity_h

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The axes along which the box-shaped grid is periodic (the grid's faces
   * were matched with Triangulation::add_periodicity() before refinement)
   * and the box: wraps positions into it and gives the image shift between
   * two positions. Read off the triangulation, so that a program embedding
   * sable only has to make its box periodic.
   */
  template <int dim>
  struct Periodicity
  {
    std::array<bool, dim> periodic{};
    Point<dim>            lower;
    Point<dim>            upper;

    /// From @p triangulation's periodic face pairs (a face x- matched to
    /// x+ makes x periodic) and its bounding box.
    static Periodicity
    of(const parallel::distributed::Triangulation<dim> &triangulation);

    bool
    any() const
    {
      for (const bool p : periodic)
        if (p)
          return true;
      return false;
    }

    double
    period(const unsigned int d) const
    {
      return upper[d] - lower[d];
    }

    /// @p x moved by whole periods into [lower, upper) along periodic axes.
    /// Returns whether it moved.
    bool
    wrap(Point<dim> &x) const
    {
      bool moved = false;
      for (unsigned int d = 0; d < dim; ++d)
        if (periodic[d] && (x[d] < lower[d] || x[d] >= upper[d]))
          {
            x[d] -= std::floor((x[d] - lower[d]) / period(d)) * period(d);
            // floor of a tiny negative offset can land exactly on upper
            if (x[d] >= upper[d])
              x[d] = lower[d];
            moved = true;
          }
      return moved;
    }

    /// The whole periods to add to @p from to come nearest to @p to.
    Tensor<1, dim>
    image_shift(const Point<dim> &from, const Point<dim> &to) const
    {
      Tensor<1, dim> shift;
      for (unsigned int d = 0; d < dim; ++d)
        if (periodic[d])
          shift[d] = std::round((to[d] - from[d]) / period(d)) * period(d);
      return shift;
    }

    /// The whole-period shifts of a position's images: zero first, then
    /// -P and +P along each periodic axis in turn, combined with the
    /// shifts before (3^k in all for k periodic axes).
    std::vector<Tensor<1, dim>>
    image_shifts() const
    {
      std::vector<Tensor<1, dim>> shifts(1);
      for (unsigned int d = 0; d < dim; ++d)
        if (periodic[d])
          {
            const std::size_t n = shifts.size();
            for (const double sign : {-1., 1.})
              for (std::size_t i = 0; i < n; ++i)
                {
                  Tensor<1, dim> shift = shifts[i];
                  shift[d]             = sign * period(d);
                  shifts.push_back(shift);
                }
          }
      return shifts;
    }

    /// The periodic axes as "x, y", or "none".
    std::string
    axes() const
    {
      std::string s;
      for (unsigned int d = 0; d < dim; ++d)
        if (periodic[d])
          s += (s.empty() ? "" : ", ") + std::string(1, "xyz"[d]);
      return s.empty() ? "none" : s;
    }
  };
} // namespace sable::mpm

#endif
