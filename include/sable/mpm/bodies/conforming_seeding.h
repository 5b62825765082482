#ifndef sable_mpm_bodies_conforming_seeding_h
#define sable_mpm_bodies_conforming_seeding_h

#include <deal.II/base/point.h>

#include <sable/mpm/bodies/point_file.h>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Material points filling a disk (2D) or sphere (3D) in layers parallel
   * to its surface: n = round(R / s) layers of equal thickness R / n, each
   * carrying points at its mid radius about s apart (in 2D rings of the
   * multiple of four nearest 2 pi r / s points, half a step off the axes
   * through the centre; shells of round(4 pi r^2 / s^2) points on a
   * Fibonacci spiral in 3D), each point the layer's volume over its
   * points. The outermost points lie half a layer inside the surface, as a
   * lattice's do below a flat face, but at every point of the surface: a
   * rolling body meets the plane with the same surface all round instead
   * of the lattice's staircase. In 2D the disk is its own mirror image
   * across both axes and no point lies on them: a disk centred on a grid
   * line puts no point on a cell face, where the gradients of the linear
   * functions jump, and a disk resting on a floor pushes it evenly left
   * and right of its centre.
   */
  template <int dim>
  PointCloud<dim>
  conforming_ball_points(const Point<dim> &centre, const double radius, const double spacing);
} // namespace sable::mpm

#endif
