#ifndef sable_mpm_gimp_shape_h
#define sable_mpm_gimp_shape_h

#include <deal.II/base/config.h>

#include <algorithm>
#include <cmath>

namespace sable::mpm
{
  /// The functions that carry the points' data to the grid's nodes and back.
  enum class ShapeFunctions
  {
    /// the cell's tensor-product linear functions (plain MPM)
    linear,
    /// uniform GIMP (gimp_weights_1d()): each point averages the linear
    /// functions over its domain of one seeding spacing; uniform grids on
    /// one MPI rank
    gimp
  };

  /**
   * One direction of the uniform generalized interpolation material point
   * (uGIMP) weights of Bardenhagen & Kober (2004): a point of half-length
   * l (its seeding spacing over two, in cell units) averages each node's
   * linear hat function over its domain [a, b] = [xi - l, xi + l],
   *
   *   S_j(xi) = 1/(b - a) int_a^b hat_j(x) dx,
   *
   * with the domain shrunk where it would leave the grid: its half-length
   * is min(l, xi - lower, upper - xi), so that the weights keep the
   * partition of unity (and their derivatives sum to zero) and become the
   * linear ones at a face of the grid. There the face's nodes, on which
   * walls act, carry the points' whole velocity normal to the face, as with
   * the linear functions (a domain merely clipped at the face would keep a
   * share of the interior nodes' velocity and let points pass a wall). The
   * weights and their first derivatives are continuous as the point
   * crosses a cell face, where those of the linear (l = 0) functions jump:
   * that jump is the cell-crossing noise of plain MPM.
   *
   * Coordinates are in units of the cell extent, relative to the lower
   * vertex of the point's cell (0 <= xi <= 1). With l <= 1/2 at most three
   * nodes reach the point: those at first, first + 1, first + 2, with
   * first = -1 for xi < 1/2 and 0 otherwise (first_gimp_node()).
   */
  struct GimpWeights1D
  {
    double value[3];
    /// d value / d xi (in cell units: divide by the cell extent)
    double derivative[3];
  };

  /// The lowest of the three nodes (relative to the cell's lower vertex)
  /// that may reach a point at @p xi.
  inline int
  first_gimp_node(const double xi)
  {
    return xi < 0.5 ? -1 : 0;
  }

  namespace internal
  {
    /// The hat function centred at 0, of support (-1, 1).
    inline double
    hat(const double x)
    {
      return std::max(0., 1. - std::abs(x));
    }

    /// int_{-inf}^x hat.
    inline double
    hat_integral(const double x)
    {
      if (x <= -1.)
        return 0.;
      if (x <= 0.)
        return 0.5 * (x + 1.) * (x + 1.);
      if (x < 1.)
        return 1. - 0.5 * (1. - x) * (1. - x);
      return 1.;
    }
  } // namespace internal

  /**
   * The three weights at @p xi of a point of half-length @p l, on a line
   * of nodes whose extreme ones lie at @p lower and @p upper (cell units
   * relative to the cell's lower vertex; pass -infinity and +infinity on a
   * periodic axis). Nodes beyond lower or upper get weight 0.
   */
  DEAL_II_ALWAYS_INLINE inline GimpWeights1D
  gimp_weights_1d(const double xi, const double l, const double lower, const double upper)
  {
    GimpWeights1D w;
    const int     first = first_gimp_node(xi);
    // the half-length, and how the domain's ends move with the point:
    // together, or one end fixed where the domain meets a face
    double half = l, da = 1., db = 1.;
    if (xi - lower < half)
      half = xi - lower, da = 0., db = 2.;
    if (upper - xi < half)
      half = upper - xi, da = 2., db = 0.;
    const double a = xi - half, b = xi + half, width = 2. * half;
    // no node strictly inside the domain: every hat is linear over it, and
    // its mean is its value at the centre (also the limit of a vanishing
    // domain, without the round-off of a difference divided by the width)
    const double kink = std::ceil(a + 1e-12);
    if (!(kink < b - 1e-12))
      {
        for (int k = 0; k < 3; ++k)
          {
            const double x = xi - (first + k);
            w.value[k]      = internal::hat(x);
            w.derivative[k] = std::abs(x) < 1. ? (x > 0 ? -1. : 1.) : 0.;
          }
        return w;
      }
    for (int k = 0; k < 3; ++k)
      {
        const double node = first + k;
        w.value[k] =
          (internal::hat_integral(b - node) - internal::hat_integral(a - node)) / width;
        w.derivative[k] = (internal::hat(b - node) * db - internal::hat(a - node) * da -
                           w.value[k] * (db - da)) /
                          width;
      }
    return w;
  }
} // namespace sable::mpm

#endif
