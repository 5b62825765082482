#ifndef sable_mpm_parameters_h
#define sable_mpm_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <sable/base/parameter_settings.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// Constitutive model and constants of one body.
  struct MaterialParameters
  {
    /// "linear elastic" (hypoelastic, Jaumann rate), "neo-Hookean" or
    /// "von Mises" (J2 plasticity with linear isotropic hardening).
    std::string model         = "linear elastic";
    double      density       = 1000.;
    double      bulk_modulus  = 0.;
    double      shear_modulus = 0.;
    /// Initial yield stress and hardening modulus (von Mises only).
    double yield_stress      = 0.;
    double hardening_modulus = 0.;

    /// Set both moduli from Young's modulus and Poisson's ratio.
    void
    set_young_poisson(const double young, const double poisson);
  };

  template <int dim>
  struct BodyParameters
  {
    enum class Shape
    {
      disk, ///< a disk in 2D, a sphere in 3D
      box
    };
    Shape        shape  = Shape::disk;
    Point<dim>   center = {};
    double       radius = 0.;
    Point<dim>   lower_corner = {};
    Point<dim>   upper_corner = {};
    unsigned int particles_per_direction = 2;

    MaterialParameters material;

    Tensor<1, dim> velocity = {};
    /// Rigid rotation about the body centre (2D uses only the z component).
    Tensor<1, 3> angular_velocity = {};
    /// Initialise σ = −p I with ∇p = ρ g, p = 0 at the body's top.
    bool lithostatic_stress = false;
    /// Contact group: friction coefficients are set per pair of groups.
    unsigned int group = 0;
    /// Refine around this body's surface (Mesh refinement criterion
    /// 'body surface').
    bool refine_surface = true;

    /// Axis-aligned bounding box of the shape.
    std::pair<Point<dim>, Point<dim>>
    bounding_box() const;
    bool
    contains(const Point<dim> &x) const;
    /// The point of the shape lowest in the potential −g·x (where p = 0).
    Point<dim>
    top_point(const Tensor<1, dim> &gravity) const;
  };

  enum class BoundaryType
  {
    free,
    fixed,
    slip,
    friction,
    moving
  };

  template <int dim>
  struct BoundaryParameters
  {
    BoundaryType   type     = BoundaryType::free;
    double         friction = 0.;
    Tensor<1, dim> velocity = {};
    /// Friction walls only: act only where the material points reach the wall
    /// within the step (Boundary conditions/Friction wall contact =
    /// material), not wherever a node with mass approaches it.
    bool material_contact = true;
  };

  template <int dim>
  struct GridParameters
  {
    Point<dim>                      lower_corner;
    Point<dim>                      upper_corner;
    std::vector<unsigned int>       subdivisions;
    /// Boundary ids of the faces x−, x+, y−, y+ (z−, z+).
    std::vector<types::boundary_id> face_ids;
  };

  /// Multi-body contact (SPEC Part A steps 3-7).
  struct ContactParameters
  {
    enum class Model
    {
      none,             ///< one velocity field: no-slip, no separation
      bardenhagen_2000, ///< act while bodies approach
      bardenhagen_2001  ///< ... or while the normal traction is compressive
    };
    Model model = Model::none;
    /// How a node's body normals are made collinear: from the bodies'
    /// mass-gradient directions weighted by their nodal masses (the
    /// default), or with equal weights, n = (n1 - n2)/|n1 - n2| (papers).
    bool mass_weighted_normals = true;
    /// Coulomb coefficient for pairs of groups not listed below;
    /// infinity means sticking contact.
    double                                                 friction = 0.;
    std::map<std::pair<unsigned int, unsigned int>, double> group_friction;
    /// Impulse scaling factor gamma in [0.5, 1]; 0 switches scaling off.
    double impulse_scaling = 0.5;
    /// Apply contact to the velocities after the momentum update, and to
    /// the velocities the strain update uses (MUSL's remapped velocities).
    bool on_momentum_update = true;
    bool on_strain_update   = true;
    /// Pairs of bodies whose contact force goes to statistics.csv.
    std::vector<std::pair<unsigned int, unsigned int>> reported_pairs;

    double
    friction_between(const unsigned int group_a, const unsigned int group_b) const
    {
      const auto it = group_friction.find({std::min(group_a, group_b),
                                           std::max(group_a, group_b)});
      return it == group_friction.end() ? friction : it->second;
    }
  };

  /**
   * Local refinement of the background grid between steps (Mesh
   * refinement subsection). Levels count from the grid the scene (or the
   * embedding program) starts with.
   */
  template <int dim>
  struct MeshRefinementParameters
  {
    enum class Criterion
    {
      body_surface,   ///< cells at a body's surface or between bodies
      contact,        ///< cells where bodies meet each other or a friction wall
      particle_count, ///< cells holding more than a number of points
      region          ///< cells inside a box
    };
    /// Empty: the grid never changes.
    std::vector<Criterion> criteria;
    /// Finest level a criterion refines to.
    unsigned int maximum_level = 0;
    /// Coarsest level anywhere: the starting grid is refined to it.
    unsigned int minimum_level = 0;
    /// Steps between mesh adaptations; 0: whenever a point may have moved
    /// half of the smallest cell since the last one.
    unsigned int interval = 0;
    /// particle count criterion
    unsigned int maximum_particles_per_cell = 16;
    /// region criterion
    Point<dim> region_lower_corner = {};
    Point<dim> region_upper_corner = {};

    bool
    enabled() const
    {
      return !criteria.empty();
    }

    bool
    uses(const Criterion criterion) const
    {
      return std::find(criteria.begin(), criteria.end(), criterion) != criteria.end();
    }
  };

  enum class UpdateScheme
  {
    usl,
    musl
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

    UpdateScheme update_scheme = UpdateScheme::musl;
    /// Fraction of PIC in the particle velocity update (0 = pure FLIP).
    double pic_fraction = 0.;
    /// With two or more MPI ranks: after seeding, repartition the grid so
    /// that every rank holds about the same work, a cell costing
    /// Simulator::cell_cost plus Simulator::particle_cost per material
    /// point (Solver/Balance particles across ranks, true by default in a
    /// scene file). Off by default here: it repartitions the caller's
    /// triangulation, which invalidates data other objects keep on it.
    bool balance_particles = false;

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
    unsigned int statistics_interval = 1;  ///< steps between CSV rows
    unsigned int progress_interval   = 100;
    bool         print_timings       = true;
    /// Steps between checkpoints (and one at the end of the run);
    /// 0 = no checkpoints.
    unsigned int checkpoint_interval = 0;

    /// Stop when kinetic + strain energy exceeds this factor times the
    /// largest energy the scene could hold (see doc/user_guide.md).
    double energy_growth_limit = 10.;
    /// Allow particles to leave the grid (they are removed and counted).
    bool allow_outflow = false;

    std::vector<BodyParameters<dim>> bodies;
  };

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
   * Check parameters that do not depend on the grid; throws InputError.
   * Called by read_scene() and by the Simulator for embedded use.
   */
  template <int dim>
  void
  check_parameters(const SimulatorParameters<dim> &parameters);

  /// Check one body's parameters; @p name prefixes the entries in messages.
  template <int dim>
  void
  check_body(const BodyParameters<dim> &body, const std::string &name);
} // namespace sable::mpm

#endif
