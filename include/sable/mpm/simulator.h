#ifndef sable_mpm_simulator_h
#define sable_mpm_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/boundaries/boundary_conditions.h>
#include <sable/mpm/contact/multi_body_contact.h>
#include <sable/mpm/grid.h>
#include <sable/mpm/grid_to_particle.h>
#include <sable/mpm/load_balance.h>
#include <sable/mpm/materials/material.h>
#include <sable/mpm/mesh_refinement.h>
#include <sable/mpm/nodal_fields.h>
#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_rebinning.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/particle_to_grid.h>
#include <sable/mpm/postprocess/output_series.h>
#include <sable/mpm/postprocess/statistics.h>
#include <sable/mpm/run_state.h>

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
   * step() sequences the phases of one step (doc/architecture.md), each
   * an object of its own file: the particle-to-grid and grid-to-particle
   * transfers (cell loops), the nodal fields, the multi-body contact (an
   * assembler in those loops), the stress update, the sort, adaptation.
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

    /// The first part of initialize(), which calls it if needed: refine
    /// the grid where the scene's refinement criteria ask (this changes
    /// the caller's triangulation) and seed the bodies, refusing
    /// (InputError) a body without a material point and bodies seeded into
    /// each other. Writes nothing, so that a program can have the scene
    /// checked before it prepares an output directory.
    void
    seed();

    /// seed() if needed, settle the bodies if asked, and set up the
    /// statistics and output (the first row and particle files).
    void
    initialize();

    /// Advance one time step.
    void
    step();

    /// initialize() if needed, then step to the end time or step limit,
    /// with progress lines, statistics, output and checkpoints.
    void
    run();

    /// For a program's own step() loop (collective; after initialize()):
    /// write the particle files of the current state, with the contact
    /// nodes and the grid if the parameters ask for them, into the output
    /// directory, as run() does every output interval.
    void
    write_output();

    /// For a program's own step() loop (collective; after initialize()):
    /// append the current statistics as a row of
    /// <output directory>/statistics.csv, as run() does; returns them.
    Statistics<dim>
    write_statistics();

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
      return state.time;
    }

    unsigned int
    get_step_number() const
    {
      return state.step_number;
    }

    /// Length of the last step.
    double
    get_time_step() const
    {
      return state.time_step;
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
      return contact ? &contact->get_model() : nullptr;
    }

    /// The wall time of each phase of the steps so far (the sections
    /// run() prints when Output/Print timings is set); reset() it to time
    /// only the steps that follow.
    TimerOutput &
    get_timer()
    {
      return timer;
    }

    /// Total work done by moving walls so far.
    double
    get_boundary_work() const
    {
      return state.boundary_work;
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

    /// Partition weights: see LoadBalance.
    static constexpr unsigned int cell_cost     = LoadBalance<dim>::cell_cost;
    static constexpr unsigned int particle_cost = LoadBalance<dim>::particle_cost;

  private:
    /// The phases of one step, in order (step() after initialize()).
    void
    advance();

    /// Solver/Settling steps: settle the bodies at rest under gravity
    /// (kinetic damping), then give them their seeded velocities and
    /// restart the clock and the energy bookkeeping (settling.cc).
    void
    settle_under_gravity();

    // --- the phases of step(), in order ---
    double
    compute_time_step() const;
    /// This step's contact nodes (bodies per node), before the first
    /// scatter.
    void
    find_contact_nodes();
    /// USAVG: the points' momenta at the start of the step to the grid,
    /// their velocities there with the walls' conditions, and the first
    /// half of the strain update from them.
    void
    update_stresses_from_initial_momenta();
    /// Scatter mass, momentum and internal forces to the single field and
    /// the bodies' fields.
    void
    scatter_momenta_and_forces();
    /// Old and new nodal velocities, walls, contact.
    void
    update_nodal_velocities();
    /// USL: velocities, positions and velocity gradients in one pass.
    void
    update_particles_and_strain_rates();
    /// MUSL: velocities and positions from the updated nodal velocities ...
    void
    update_particle_velocities_and_positions();
    /// ... the updated particle momenta back to the grid ...
    void
    remap_momenta_to_grid();
    /// ... with the walls' and the contact's conditions ...
    void
    update_remapped_velocities();
    /// ... and the velocity gradients from them, for a stress update over
    /// @p time_step (or per owned cell with points over @p cell_time_steps).
    void
    compute_strain_rates(const double time_step, const std::vector<double> *cell_time_steps);
    /// F and stress of every point from its velocity gradient, over
    /// @p time_step (USAVG: half the step, twice), or per owned cell with
    /// points over @p cell_time_steps.
    void
    update_stresses(const double time_step, const std::vector<double> *cell_time_steps = nullptr);
    void
    sort_particles();
    /// The particle container in the order a sort leaves it (cells by
    /// index), for output and checkpoints: see the definition.
    void
    put_particles_in_order();
    /// deal.II's sort of all points into their cells, and
    /// reset_rebinning().
    void
    full_sort();
    /// After a full sort: the rebinning starts counting again.
    void
    reset_rebinning();
    void
    advance_time();
    /// Every 'Refinement interval' steps, or (interval 0) when a point may
    /// have moved half of the smallest cell since the last adaptation.
    bool
    adaptation_due() const;
    /// Refine and coarsen the grid by the scene's criteria; particles
    /// follow through the ParticleHandler, the grid caches are rebuilt.
    void
    adapt_mesh();

    // --- set-up ---
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
    /// Whether 'Output/Statistics interval' asks for a row at this step
    /// (interval 0: with particle output, @p output_due, and progress lines).
    bool
    statistics_due(const bool output_due) const;
    /// Size the nodal fields and colour the cells for the current grid.
    void
    allocate_nodal_data();
    /// Rebuild the grid caches, boundary nodes and nodal fields after
    /// the triangulation changed (refinement, repartitioning).
    void
    setup_after_mesh_change();

    // --- reports and output ---
    /// The speeds and failures a grid-to-particle pass found; @p moved:
    /// the pass moved the points (their speeds set the next time step).
    void
    process_report(const typename GridToParticle<dim>::Report &report, const bool moved);
    /// Console line: material points, cells and work per rank (min .. max).
    void
    print_balance() const;
    /// Each body's surface radius (a disk's or sphere's radius, infinite
    /// for other shapes) and volume (the sum of its points' initial
    /// volumes over all ranks) to the contact, for 'Contact/Normals =
    /// flatter body'.
    void
    set_contact_body_shapes();
    /// Console notes where disks (spheres) meet contact: seeded on the
    /// lattice, their staircase surface rolls like a polygon; with one
    /// point per cell direction, their spin turns into strain.
    void
    print_seeding_note() const;
    /// Particle output, with the contact nodes and the grid if asked for.
    void
    write_particles();
    /// Stop if kinetic + strain energy exceed the energy guard's limit or
    /// the energy balance drifts beyond its limit; warn once when the
    /// balance drifts by more than 1%.
    void
    check_energy(const Statistics<dim> &statistics);
    /// Stop the run, naming the step, time and column, if a value of the
    /// statistics row is not a finite number.
    void
    check_statistics_finite(const Statistics<dim> &statistics) const;
    /// Statistics::energy_drift of @p statistics.
    double
    energy_drift(const Statistics<dim> &statistics) const;
    /// Where the fastest material point is, on every rank (for messages).
    Point<dim>
    fastest_point_location() const;
    /// Whether the drift warning was printed.
    bool drift_warned = false;
    /// whether the console was told that ids beyond 2^24 are not exact in
    /// the (single-precision) particle output
    bool id_precision_warned = false;
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
    bool                                       parallel = false;
    bool                                       seeded      = false;
    bool                                       initialized = false;

    Grid<dim>                                        grid;
    BoundaryConditions<dim>                          boundary_conditions;
    std::vector<std::unique_ptr<Material>>           materials;
    std::vector<double>                              body_wave_speed;
    ParticleLayout<dim>                              layout;
    std::unique_ptr<Particles::ParticleHandler<dim>> particle_handler;
    LoadBalance<dim>                                 load_balance;
    /// level of the coarsest cells at the start (see make_grid())
    unsigned int base_level = 0;

    // the step's phases and their data
    NodalFields<dim>    nodal_fields;
    ParticleToGrid<dim> particle_to_grid;
    /// per locally owned particle (by local index): L = grad v of the
    /// strain update, from the grid-to-particle pass to the stress update
    std::vector<Tensor<2, dim>> velocity_gradients;
    /// USAVG with contact or friction walls: per owned cell with points,
    /// the time step of its points' stress update in the current half of
    /// the step (0 in the first half where they take MUSL's whole step).
    std::vector<double> stress_time_steps;
    GridToParticle<dim>         grid_to_particle;
    /// the cells with material points, rebuilt at the start of a step
    /// unless particle_cells_current
    ParticleCells<dim> particle_cells;
    /// whether particle_cells still describes the particle container: only
    /// after a step whose sort was skipped (no ghost particles), until the
    /// next step or mesh change
    bool particle_cells_current = false;
    /// whether a point left its cell in this step's move (sort_particles()
    /// sorts only then)
    bool points_left_cells = true;
    /// whether the transfers count what the contact's and the walls'
    /// corrections take from the points (correction_loss)
    bool measure_corrections = false;
    /// the kinetic and strain energy those corrections took from this
    /// rank's points so far (GridToParticle::measure_corrections()); summed
    /// over the ranks for the statistics, and kept on rank 0 by a restart
    double correction_loss = 0;
    /// USAVG's first half took the contact on this step's initial velocities
    bool contact_in_first_half = false;
    /// on one rank: moves the points that left their cells in place of a
    /// sort; a full sort still runs once the moved points add up to
    /// full_sort_fraction of the points (it orders their data in memory)
    ParticleRebinning<dim> rebinning;
    static constexpr double full_sort_fraction = 0.1;
    /// steps that sorted the particles, that moved only the points that
    /// left their cells, and that did not need to do either
    unsigned int n_sorts = 0, n_rebins = 0, n_sorts_skipped = 0;
    /// multi-body contact: only with a contact model and two or more bodies
    std::unique_ptr<MultiBodyContact<dim>> contact;
    /// the bodies of prescribed velocity, with this step's velocities
    PrescribedVelocities<dim> prescribed_velocities;
    /// only with refinement criteria
    std::unique_ptr<MeshRefinement<dim>> mesh_refinement;

    RunState state;
    /// while settle_under_gravity() runs: its clock is not the run's, so
    /// its steps are not cut at the end time
    bool settling = false;

    unsigned long long lost_particles = 0;
    Point<dim>         lost_location;

    std::unique_ptr<StatisticsFile<dim>>        statistics_file;
    OutputSeries                                particle_series;
    /// only with Output/Contact node output
    OutputSeries                                contact_node_series;
    /// only with Output/Grid output
    std::unique_ptr<GridOutput<dim>> grid_output;
  };
} // namespace sable::mpm

#endif
