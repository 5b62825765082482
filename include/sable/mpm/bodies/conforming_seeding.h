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
   * carrying points at its mid radius about s apart: in 2D a ring of the
   * multiple of four nearest 2 pi r / s points, each the layer's area over
   * their number; in 3D an even number (nearest pi r / s) of latitude
   * bands, each of the multiple of four nearest 2 pi r sin(theta) / s
   * points, each point its band's share of the shell's volume. Points sit
   * half a step off the planes through the centre along the axes. The
   * outermost points lie half a layer inside the surface, as a lattice's
   * do below a flat face, but at every point of the surface: a rolling
   * body meets the plane with the same surface all round instead of the
   * lattice's staircase. The body is its own mirror image across those
   * planes and no point lies on them: a body centred on a grid line puts
   * no point on a cell face, where the gradients of the linear functions
   * jump, and one resting on a floor pushes it evenly on both sides.
   */
  template <int dim>
  PointCloud<dim>
  conforming_ball_points(const Point<dim> &centre, const double radius, const double spacing);
} // namespace sable::mpm

#endif
