#ifndef sable_mpm_surface_offset_h
#define sable_mpm_surface_offset_h

namespace sable::mpm
{
  /**
   * How far, in cells, the mass centroid of a node on a flat body surface
   * lies inside the body when the points sit at spacing @p spacing (in
   * cells) from the surface, at (j + 1/2) spacing: weighted by the hat
   * function 1 − y over the cell below the surface node, their centroid is
   * at sum w y / sum w (1/2 for a spacing of one cell, 0.375 for half a
   * cell, 0.352 for a third, 1/3 as the spacing goes to zero). A spacing of
   * two cells or more leaves one point per node's reach, half a spacing
   * inside the surface. Contact between bodies and friction walls with
   * surface-position contact take a body's surface to lie this far outside
   * the centroid.
   */
  inline double
  surface_centroid_offset(const double spacing)
  {
    if (spacing >= 2.)
      return 0.5 * spacing;
    if (spacing < 1e-2) // the limit of a continuum, within 1e-4
      return 1. / 3.;
    double weighted = 0, weights = 0;
    for (unsigned int j = 0; (j + 0.5) * spacing < 1.; ++j)
      {
        const double y = (j + 0.5) * spacing;
        weighted += (1 - y) * y;
        weights += 1 - y;
      }
    return weighted / weights;
  }
} // namespace sable::mpm

#endif
