#ifndef sable_mpm_parameters_h
#define sable_mpm_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <sable/base/parameter_settings.h>
#include <sable/mpm/bodies/body_parameters.h>
#include <sable/mpm/boundaries/boundary_parameters.h>
#include <sable/mpm/contact/contact_parameters.h>
#include <sable/mpm/gimp_shape.h>
#include <sable/mpm/materials/material_parameters.h>
#include <sable/mpm/mesh_refinement_parameters.h>

#include <map>
#include <string>
#include <array>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  template <int dim>
  struct GridParameters
  {
    Point<dim>                      lower_corner;
    Point<dim>                      upper_corner;
    std::vector<unsigned int>       subdivisions;
    /// Boundary ids of the faces x−, x+, y−, y+ (z−, z+).
    std::vector<types::boundary_id> face_ids;
    /// Axes along which the grid is periodic (its two faces matched).
    std::array<bool, dim> periodic{};
  };

  enum class UpdateScheme
  {
    usl,
    musl,
    usavg,
    /// USAVG where bodies can touch one another (contact on, two or more
    /// bodies), MUSL otherwise; resolved when the simulator sets up its models
    automatic
  };

  /// File format of the particle (and grid) output.
  enum class OutputFormat
  {
    vtu, ///< particles_NNNNN.vtu/.pvtu and particles.pvd
    hdf5 ///< particles_NNNNN.h5 and particles.xdmf
  };

  template <int dim>
  struct SimulatorParameters
  {
    double       end_time      = 1.;
    unsigned int maximum_steps = 0; ///< 0: no limit
    double       cfl           = 0.5;

    UpdateScheme update_scheme = UpdateScheme::automatic;
    /// Fraction of PIC in the particle velocity update (0 = pure FLIP).
    double pic_fraction = 0.;
    /// Solver/Affine transfers: each point carries its velocity gradient C
    /// into the particle-to-grid transfers, v_p + C (x_i - x_p) at node i
    /// (APIC's affine velocity; with FLIP, affine FLIP), so that rigid
    /// rotations reach the grid exactly.
    bool affine_transfers = false;
    /// With two or more MPI ranks: after seeding, repartition the grid so
    /// that every rank holds about the same work, a cell costing
    /// Simulator::cell_cost plus Simulator::particle_cost per material
    /// point (Solver/Balance particles across ranks, true by default in a
    /// scene file). Off by default here: it repartitions the caller's
    /// triangulation, which invalidates data other objects keep on it.
    bool balance_particles = false;
    /// Before the run, let the bodies settle under gravity at rest (kinetic
    /// damping) for at most this many steps, then give them their initial
    /// velocities; 0 = start as seeded (Solver/Settling steps).
    unsigned int settling_steps = 0;
    /// Settled when a peak of the kinetic energy is below this fraction of
    /// the strain energy (Solver/Settling tolerance).
    double settling_tolerance = 1e-8;
    /// The gravity while settling: the scene's unless given (Solver/Settling
    /// gravity), e.g. its part normal to a slope a body would slide down.
    Tensor<1, dim> settling_gravity = {};
    /// Whether contacts between bodies and friction walls stick while the
    /// bodies settle (Solver/Settling friction = stick), so that a body
    /// that slides or rolls under the scene's gravity settles under it.
    bool settling_stick = false;

    /// Grid/Shape functions: linear, or GIMP on a uniform grid on one rank.
    ShapeFunctions shape_functions = ShapeFunctions::linear;

    Tensor<1, dim> gravity = {};

    std::map<types::boundary_id, BoundaryParameters<dim>> boundaries;

    ContactParameters contact;

    MeshRefinementParameters<dim> refinement;

    /// Directory of all output; empty: write nothing.
    std::string  output_directory    = "";
    double       output_interval     = 0.; ///< particle files; 0 = off
    OutputFormat output_format       = OutputFormat::vtu;
    /// with the particle output, also the contact nodes (VTU)
    bool         contact_node_output = false;
    /// with the particle output, also the background grid with nodal mass
    /// and velocity and per-cell fields (GridOutput), in output_format
    bool         grid_output         = false;
    /// keep each point's initial position and write the displacement with
    /// the particle output (dim more properties per point)
    bool         displacement_output = false;
    /// particle output also of the stress smoothed over the grid
    /// (StressSmoothing), its pressure, von Mises and in-plane principal
    /// stress difference
    bool smoothed_stress_output = false;
    /// steps between CSV rows; 0 = with every particle output and
    /// progress line (Simulator::statistics_due())
    unsigned int statistics_interval = 0;
    unsigned int progress_interval   = 100;
    bool         print_timings       = true;
    /// Steps between checkpoints (and one at the end of the run);
    /// 0 = no checkpoints.
    unsigned int checkpoint_interval = 0;

    /// Stop when kinetic + strain energy exceeds this factor times the
    /// largest energy the scene could hold (see doc/mpm.md, RunState::energy_budget()).
    double energy_growth_limit = 10.;
    /// Stop when the energy balance gains more than this fraction of that
    /// energy (Statistics::energy_drift).
    double energy_drift_limit = 0.5;
    /// Allow particles to leave the grid (they are removed and counted).
    bool allow_outflow = false;

    std::vector<BodyParameters<dim>> bodies;

    /// The scene's entries as ("Subsection/Entry", value) (read_scene()
    /// fills them from the parameter file): a checkpoint keeps them, and
    /// Simulator::resume() refuses a scene whose entries differ in more
    /// than may_change_on_resume() allows. Empty: not compared.
    std::vector<std::pair<std::string, std::string>> scene_entries;
  };

  /// Whether the entry @p name ("Subsection/Entry") may have another value
  /// when a run is resumed: the time limits and CFL number, the output
  /// (besides its format and whether the displacement is written: both
  /// shape the checkpoint), threads and load balancing. Materials, bodies,
  /// the grid, boundaries, contact, refinement, gravity and the update
  /// scheme may not.
  bool
  may_change_on_resume(const std::string &name);

  /// The name of @p scheme as the parameter file writes it ("MUSL", ...).
  std::string
  update_scheme_name(const UpdateScheme scheme);

  /// Declare every MPM entry (besides the common ones) for @p n_bodies bodies.
  template <int dim>
  void
  declare_parameters(ParameterHandler &prm, const unsigned int n_bodies);

  /// Everything an MPM parameter file describes.
  template <int dim>
  struct Scene
  {
    GridParameters<dim>      grid;
    SimulatorParameters<dim> simulator;
  };

  /**
   * Read and check the MPM scene in @p filename, with the entries of
   * @p settings (the command line's `--set`) changed after the file is read.
   * Throws InputError naming the entry, value and allowed range for
   * anything invalid.
   */
  template <int dim>
  Scene<dim>
  read_scene(const std::string &                  filename,
             const std::vector<ParameterSetting> &settings = {});

  /**
   * Check parameters that do not depend on the grid, each component with
   * its own check(); throws InputError. Called by read_scene() and by the
   * Simulator for embedded use.
   */
  template <int dim>
  void
  check_parameters(const SimulatorParameters<dim> &parameters);
} // namespace sable::mpm

#endif
