#ifndef sable_mpm_surface_offset_h
#define sable_mpm_surface_offset_h

namespace sable::mpm
{
  /**
   * How far, in cells, the mass centroid of a node on a flat body surface
   * lies inside the body: k points per cell direction at (j + 1/2)/k of the
   * cell below the surface node, weighted by the hat function 1 − y, have
   * their centroid at sum w y / sum w (1/2 for k = 1, 0.352 for k = 3, 1/3
   * for k → ∞). Contact between bodies and friction walls with surface-
   * position contact take a body's surface to lie this far outside the
   * centroid.
   */
  inline double
  surface_centroid_offset(const unsigned int points_per_cell_direction)
  {
    const unsigned int k        = points_per_cell_direction;
    double             weighted = 0, weights = 0;
    for (unsigned int j = 0; j < k; ++j)
      {
        const double y = (j + 0.5) / k;
        weighted += (1 - y) * y;
        weights += 1 - y;
      }
    return weighted / weights;
  }
} // namespace sable::mpm

#endif
