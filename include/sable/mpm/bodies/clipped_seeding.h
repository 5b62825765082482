#ifndef sable_mpm_bodies_clipped_seeding_h
#define sable_mpm_bodies_clipped_seeding_h

#include <deal.II/base/point.h>

#include <sable/mpm/bodies/point_file.h>

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
   * and @p radius. The box is halved along every direction down to 2^-8 of
   * its size in 2D (2^-5 in 3D) where the surface crosses it; the boxes of
   * the last level count by their centres. A box wholly inside or outside
   * is exact; a cut one is within a random error near 1e-6 of its volume.
   */
  template <int dim>
  BallPart<dim>
  ball_part_in_box(const Point<dim> &centre,
                   const double      radius,
                   const Point<dim> &lower,
                   const Point<dim> &upper);

  /**
   * Material points filling a disk (2D) or sphere (3D) on the lattice of a
   * grid of cells @p cell (per direction) through @p origin, k^dim points
   * per cell (`Seeding = clipped`). A sub-cell wholly inside keeps the
   * lattice's point at its centre; one the surface cuts carries the part
   * inside, at that part's centroid: the mass and its first moment follow
   * the surface instead of the lattice's staircase. Two rules keep such
   * points safe. No point lies less than a quarter spacing (of the
   * sub-cell's smallest edge) inside the surface: a part whose centroid
   * lies shallower joins the deepest part of its cell, and where that one
   * is still shallower (a cell the surface barely enters) its point moves
   * in along the radius to that depth. No point holds less than a quarter
   * of a sub-cell: a smaller one joins the nearest larger point of its
   * cell or the cells beside it, at their common centroid. The mass is
   * kept (up to the quadrature's 1e-6); the first moment changes only by
   * the points moved in.
   */
  template <int dim>
  PointCloud<dim>
  clipped_ball_points(const Point<dim> &    centre,
                      const double          radius,
                      const Point<dim> &    origin,
                      const Tensor<1, dim> &cell,
                      const unsigned int    k);
} // namespace sable::mpm

#endif
