#ifndef sable_mpm_bodies_clipped_seeding_h
#define sable_mpm_bodies_clipped_seeding_h

#include <deal.II/base/point.h>

namespace sable::mpm
{
  using namespace dealii;

  /// The part of a box inside a ball: its volume (area in 2D) and centroid.
  template <int dim>
  struct BallPart
  {
    double     volume = 0;
    Point<dim> centroid;
  };

  /**
   * The part of the box [@p lower, @p upper] inside the ball of @p centre
   * and @p radius, for seeding a disk or sphere clipped to its surface
   * (`Seeding = clipped`): a sub-cell the surface cuts carries one point at
   * the centroid of its part inside, with that part's volume. The box is
   * halved along every direction down to 2^-8 of its size in 2D (2^-5 in
   * 3D) where the surface crosses it; the boxes of the last level count by
   * their centres. The volume is then within about 2^-8 (2^-5) of the box
   * times the surface's share of it, and a box wholly inside or outside is
   * exact.
   */
  template <int dim>
  BallPart<dim>
  ball_part_in_box(const Point<dim> &centre,
                   const double      radius,
                   const Point<dim> &lower,
                   const Point<dim> &upper);
} // namespace sable::mpm

#endif
