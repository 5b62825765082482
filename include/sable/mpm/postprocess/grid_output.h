#ifndef sable_mpm_postprocess_grid_output_h
#define sable_mpm_postprocess_grid_output_h

#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/grid.h>
#include <sable/mpm/postprocess/output_series.h>

#include <string>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Output of the background grid (Output/Grid output): the locally owned
   * active cells of every rank, with
   *
   * - vertex fields `mass` (kg) and `velocity` (m/s): the material points'
   *   mass and momentum as they are at the output time, scattered to the
   *   nodes with the shape functions of the transfers (Grid::evaluate, so
   *   hanging nodes get nothing). Hanging nodes then take the mass and
   *   momentum their constraints give (AffineConstraints::distribute), so
   *   that the fields are continuous; velocity = momentum / mass (0 where
   *   the mass is 0);
   * - cell fields `material_points` (number of points in the cell),
   *   `level` (refinement level, counted as in 'Mesh refinement': 0 for
   *   the Grid/Subdivisions cells) and `rank` (owning MPI rank).
   *
   * The nodal fields are computed here from the material points rather
   * than taken from the simulator's nodal vectors: those hold the state at
   * the start of the last step, on the mesh before any adaptation at its
   * end, while the points and the mesh written belong to the output time.
   */
  template <int dim>
  class GridOutput
  {
  public:
    GridOutput(const std::string &directory, const OutputFormat format);

    /// Write output number @p counter at @p time (collective); cell
    /// levels count from @p base_level (that of the Subdivisions cells).
    void
    write(const Grid<dim> &                      grid,
          const Particles::ParticleHandler<dim> &particles,
          const unsigned int                     counter,
          const double                           time,
          const unsigned int                     base_level);

    /// grid_NNNNN.pvtu and grid.pvd, or grid_NNNNN.h5 and grid.xdmf
    OutputSeries series;
  };
} // namespace sable::mpm

#endif
