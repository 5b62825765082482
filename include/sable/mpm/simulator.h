#ifndef sable_mpm_simulator_h
#define sable_mpm_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/boundaries/boundary_conditions.h>
#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/contact/bardenhagen_contact.h>
#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/materials/material.h>
#include <sable/mpm/mesh_refinement.h>
#include <sable/mpm/owned_cell_strip.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/postprocess/output_series.h>
#include <sable/mpm/postprocess/statistics.h>

#include <memory>
#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  template <int dim>
  class GridOutput;

  /**
   * Explicit material point method on a deal.II background grid
   * (SPEC Part A). The triangulation belongs to the caller: a scene file
   * builds a box (run_scene), an embedding program hands in its own mesh of
   * axis-aligned cells. Typical use:
   *
   *   Simulator<2> simulator(triangulation, parameters);
   *   simulator.add_body(body);        // or parameters.bodies
   *   simulator.run();                 // or initialize() + step() ...
   *
   * One step, with only what the scene enabled:
   * particles_to_grid -> momentum update (+ gravity) -> boundary conditions
   * -> grid_to_particles (FLIP/PIC velocity, position) -> stress update
   * (USL; MUSL remaps momenta first) -> sort particles -> statistics/output.
   */
  template <int dim>
  class Simulator
  {
  public:
    Simulator(parallel::distributed::Triangulation<dim> &triangulation,
              const SimulatorParameters<dim> &           parameters);
    ~Simulator();

    /// Add a body before initialize(); checked against the grid.
    void
    add_body(const BodyParameters<dim> &body);

    /// Check the input, refine the grid where the scene's refinement
    /// criteria ask (this changes the caller's triangulation), seed the
    /// particles, set up grid and output.
    void
    initialize();

    /// Advance one time step.
    void
    step();

    /// initialize() if needed, then step to the end time or step limit,
    /// with progress lines, statistics, output and checkpoints.
    void
    run();

    /**
     * Write a checkpoint of the run into @p directory (collective): the
     * mesh and the material points with all their properties through
     * Triangulation::save(), and the simulator's own state (time, step,
     * energy bookkeeping, output series, contact heat, ...) in a side file.
     * The checkpoint is first written to @p directory.tmp and then renamed
     * into place, the previous one kept as @p directory.old until then, so
     * an interrupted write never leaves no usable checkpoint
     * (source/mpm/checkpoint.cc). Empty: <output directory>/checkpoint.
     */
    void
    save_checkpoint(const std::string &directory = "");

    /**
     * Instead of initialize(): continue the run saved in the checkpoint
     * @p directory (see find_checkpoint() in sable/mpm/checkpoint.h). The
     * triangulation must be the unrefined coarse mesh the saved run started
     * from and the parameters those of that run (times, step limits and
     * output settings may differ). statistics.csv keeps the rows up to the
     * checkpoint's step and is continued.
     */
    void
    resume(const std::string &directory);

    double
    get_time() const
    {
      return time;
    }

    unsigned int
    get_step_number() const
    {
      return step_number;
    }

    /// Length of the last step.
    double
    get_time_step() const
    {
      return time_step;
    }

    const Particles::ParticleHandler<dim> &
    get_particle_handler() const
    {
      return *particle_handler;
    }

    /// The background grid's caches (nodes, hanging-node folding).
    const Grid<dim> &
    get_grid() const
    {
      return grid;
    }

    const ParticleLayout<dim> &
    get_particle_layout() const
    {
      return layout;
    }

    /// Energies, momentum and per-body centre of mass over all ranks.
    Statistics<dim>
    compute_statistics() const;

    /// The contact kernel (nullptr without multi-body contact).
    const BardenhagenContact<dim> *
    get_contact() const
    {
      return contact.get();
    }

    /// Total work done by moving walls so far.
    double
    get_boundary_work() const
    {
      return boundary_work;
    }

    /**
     * Repartition the grid over the MPI ranks by the cell weights
     * (cell_cost + particle_cost per material point; the weight signal is
     * connected when Solver/Balance particles across ranks is set), move
     * the particles with their cells, and rebuild what depends on the
     * partition: the grid caches, boundary nodes, nodal vectors and ghost
     * particles. initialize() calls it once after seeding; after a mesh
     * change, call it instead of repeating those steps.
     */
    void
    rebalance();

    /// Weigh cells by cell_weight() in every repartition from now on.
    void
    connect_cell_weights();

    /// Material points per rank after the last rebalance(): min, max.
    std::pair<unsigned long long, unsigned long long>
    particles_per_rank() const;

    /**
     * Partition weights (p4est cell weights, integers): a cell costs
     * cell_cost, each material point in it particle_cost more. From the
     * 2D step time on one core (doc/benchmarks.md, eight measurements on
     * a shared machine: 0.03-0.24 us per cell, 0.24-0.68 us per material
     * point per step, ratio 1.6-26, median 6.5): 100 : 600.
     */
    static constexpr unsigned int cell_cost     = 100;
    static constexpr unsigned int particle_cost = 600;

  private:
    using NodalVector = LinearAlgebra::distributed::Vector<double>;

    /// The bodies' materials, the contact model and the refinement
    /// criteria (initialize() and resume()).
    void
    setup_models();
    /// An empty particle handler on the current mesh.
    void
    create_particle_handler();
    /// The output directory and statistics.csv (continued with @p append).
    void
    setup_output(const bool append);
    /// Whether the end time or the step limit is reached.
    bool
    finished() const;
    void
    seed_body(const unsigned int         body_index,
              const OwnedCellStrip<dim> &owned_cells,
              types::particle_index &    next_id);
    /// Size the nodal vectors and colour the cells for the current grid.
    void
    allocate_nodal_data();
    /// Rebuild the grid caches, boundary nodes and nodal vectors after
    /// the triangulation changed (refinement, repartitioning).
    void
    setup_after_mesh_change();
    /// Refine and coarsen the grid by the scene's criteria; particles
    /// follow through the ParticleHandler, the grid caches are rebuilt.
    void
    adapt_mesh();
    /// Find the contact nodes of this step (bodies per node), threaded
    /// over the coloured cells as particles_to_grid().
    void
    find_contact_nodes();
    /// Per-body velocities at contact nodes, contact, boundary conditions.
    void
    update_body_velocities(const bool with_forces);
    double
    compute_time_step() const;
    /// Scatter mass, momentum and (if @p with_forces) internal forces;
    /// threaded over the blocks of each colour of scatter_colouring.
    void
    particles_to_grid(const bool with_forces);
    /// Nodal velocities before (old) and after (new) the momentum update.
    void
    update_grid_velocities(const bool with_forces);
    /// USL: velocity, position, and stress in one pass over the particles.
    void
    grid_to_particles(const bool update_positions, const bool update_stresses);
    /// The locally owned cells holding material points.
    std::vector<typename Triangulation<dim>::active_cell_iterator>
    cells_with_particles() const;
    /// F and stress of every locally owned particle in @p cells from the
    /// velocity gradients grid_to_particles() stored; threaded over cells.
    void
    update_particle_stresses(
      const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells);
    /// Console line: material points, cells and work per rank (min .. max).
    void
    print_balance() const;
    unsigned int
    cell_weight(const typename Triangulation<dim>::cell_iterator &cell,
                const typename Triangulation<dim>::CellStatus     status) const;
    void
    sort_particles();
    /// Particle output, with the contact nodes and the grid if asked for.
    void
    write_particles();
    void
    write_contact_nodes(const unsigned int counter);
    void
    check_energy(const Statistics<dim> &statistics);
    /// Stop all ranks if any flagged a problem at @p location.
    void
    report_failure(const bool         failed_here,
                   const Point<dim> & location,
                   const std::string &what) const;

    parallel::distributed::Triangulation<dim> &triangulation;
    SimulatorParameters<dim>                   parameters;
    MPI_Comm                                   communicator;
    ConditionalOStream                         pcout;
    mutable TimerOutput                        timer;

    Grid<dim>                                        grid;
    BoundaryConditions<dim>                          boundary_conditions;
    std::vector<std::unique_ptr<Material>>           materials;
    std::vector<double>                              body_wave_speed;
    ParticleLayout<dim>                              layout;
    std::unique_ptr<Particles::ParticleHandler<dim>> particle_handler;

    /// the cells particles_to_grid() visits, in blocks coloured so that no
    /// two blocks of a colour share a node; rebuilt with the grid caches
    CellColouring<dim> scatter_colouring;
    /// mass, momentum (dim), force (dim) per node, node by node
    NodalVector         nodal_data;
    /// extent of the material around each node, 2 dim values per node
    /// (BoundaryConditions::set_material_extent()); only with friction
    /// walls that check for material
    NodalVector         material_extent;
    std::vector<double> nodal_mass;
    std::vector<double> old_velocity;
    std::vector<double> new_velocity;
    /// per locally owned particle (by local index): L = grad v of the
    /// strain update, from grid_to_particles() to update_particle_stresses()
    std::vector<Tensor<2, dim>> velocity_gradients;
    bool                has_gravity = false;
    boost::signals2::connection weight_connection;
    /// level of the coarsest cells at the start (see make_grid())
    unsigned int base_level = 0;

    /// multi-body contact: only with a contact model and two or more bodies
    bool                                     use_contact = false;
    BodyFields<dim>                          body_fields;
    std::unique_ptr<BardenhagenContact<dim>> contact;
    bool                                     parallel = false;

    /// only with refinement criteria
    std::unique_ptr<MeshRefinement<dim>> mesh_refinement;
    unsigned int                         adaptations_without_change = 0;
    double                               travel_since_adaptation    = 0;

    bool         initialized = false;
    double       time        = 0;
    double       time_step   = 0;
    unsigned int step_number = 0;
    double       max_signal_speed = 0;
    double       boundary_work    = 0;
    double       initial_energy   = 0;
    double       initial_gravity_energy = 0;
    double       energy_floor           = 0;
    double       largest_gravity_release = 0;

    unsigned long long lost_particles = 0;
    Point<dim>         lost_location;

    std::unique_ptr<StatisticsFile<dim>>              statistics_file;
    OutputSeries                                      particle_series;
    std::vector<std::pair<double, std::string>>       contact_node_files;
    /// only with Output/Grid output
    std::unique_ptr<GridOutput<dim>>                  grid_output;
    double                                            next_output_time = 0;
    unsigned int                                      output_counter   = 0;
  };
} // namespace sable::mpm

#endif
