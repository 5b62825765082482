#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/base/checkpoint_directory.h>
#include <sable/base/input_error.h>
#include <sable/base/write_check.h>
#include <sable/mpm/bodies/body_overlap.h>
#include <sable/mpm/postprocess/contact_node_output.h>
#include <sable/mpm/postprocess/grid_output.h>
#include <sable/mpm/postprocess/particle_output.h>
#include <sable/mpm/periodicity.h>
#include <sable/mpm/seeding.h>
#include <sable/mpm/simulator.h>
#include <sable/mpm/stress_update.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    template <int dim>
    std::string
    to_string(const Point<dim> &p)
    {
      std::ostringstream s;
      s << std::setprecision(6) << "(";
      for (unsigned int d = 0; d < dim; ++d)
        s << (d ? ", " : "") << p[d];
      s << ")";
      return s.str();
    }
  } // namespace

  template <int dim>
  Simulator<dim>::Simulator(
    parallel::distributed::Triangulation<dim> &triangulation,
    const SimulatorParameters<dim> &           parameters)
    : triangulation(triangulation)
    , parameters(parameters)
    , communicator(triangulation.get_communicator())
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator,
            pcout,
            TimerOutput::never,
            TimerOutput::wall_times)
    , parallel(Utilities::MPI::n_mpi_processes(communicator) > 1)
    , grid(triangulation, parameters.shape_functions)
    , boundary_conditions(parameters.boundaries)
    , grid_to_particle(grid, nodal_fields, body_wave_speed, velocity_gradients)
    , particle_series(parameters.output_directory, "particles", parameters.output_format)
    , contact_node_series(parameters.output_directory, "contact_nodes", parameters.output_format)
  {
    if (parameters.grid_output)
      grid_output =
        std::make_unique<GridOutput<dim>>(parameters.output_directory, parameters.output_format);
  }

  template <int dim>
  Simulator<dim>::~Simulator() = default;

  template <int dim>
  void
  Simulator<dim>::add_body(const BodyParameters<dim> &body)
  {
    AssertThrow(!seeded, ExcMessage("Bodies must be added before seed() and initialize()."));
    parameters.bodies.push_back(body);
  }

  template <int dim>
  void
  Simulator<dim>::setup_models()
  {
    check_parameters(parameters);
    const bool bodies_touch =
      parameters.contact.model != ContactParameters::Model::none && parameters.bodies.size() > 1;
    // where bodies touch, MUSL's own step makes energy at CFL numbers
    // above 0.25 and USAVG's midpoint rule does not (doc/mpm.md,
    // "Stability"); a single body keeps MUSL's cheaper step
    if (parameters.update_scheme == UpdateScheme::automatic)
      parameters.update_scheme = bodies_touch ? UpdateScheme::usavg : UpdateScheme::musl;
    // every body must lie inside the grid (a grain held by a face of it:
    // its centre; along a periodic axis: its centre, and it may not be
    // longer than the period)
    const Periodicity<dim> periodicity = Periodicity<dim>::of(triangulation);
    {
      const auto box = GridTools::compute_bounding_box(triangulation);
      for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
        {
          const auto &body     = parameters.bodies[b];
          auto        body_box = body.bounding_box();
          // the messages are made only for a body that fails (formatting
          // them for each of 10,000 grains took longer than seeding them)
          for (unsigned int d = 0; d < dim; ++d)
            if (periodicity.periodic[d] &&
                !(body_box.second[d] - body_box.first[d] <= periodicity.period(d) * (1. + 1e-12)))
              check_input(false,
                          body.label(b),
                          to_string(body_box.first) + " - " + to_string(body_box.second),
                          "a body no longer than the period " +
                            std::to_string(periodicity.period(d)) + " along the periodic axis " +
                            std::string(1, "xyz"[d]));
          const Point<dim> centre = body.centre();
          for (unsigned int d = 0; d < dim; ++d)
            if (body.clipped_by_grid || periodicity.periodic[d])
              {
                body_box.first[d]  = centre[d];
                body_box.second[d] = centre[d];
              }
          for (unsigned int d = 0; d < dim; ++d)
            if (!(body_box.first[d] >= box.get_boundary_points().first[d] - 1e-12 &&
                  body_box.second[d] <= box.get_boundary_points().second[d] + 1e-12))
              check_input(false,
                          body.label(b),
                          to_string(body_box.first) + " - " + to_string(body_box.second),
                          "a body inside the grid " + to_string(box.get_boundary_points().first) +
                            " - " + to_string(box.get_boundary_points().second));
        }
    }

    std::vector<double> lambda, shear;
    for (const auto &body : parameters.bodies)
      {
        materials.push_back(create_material(body.material));
        body_wave_speed.push_back(materials.back()->wave_speed());
        layout.n_history = std::max(layout.n_history, materials.back()->n_history());
        lambda.push_back(body.material.bulk_modulus - 2. / 3. * body.material.shear_modulus);
        shear.push_back(body.material.shear_modulus);
      }
    grid_to_particle.set_elastic_moduli(lambda, shear);
    layout.initial_position_stored = parameters.displacement_output;
    layout.affine_stored           = parameters.affine_transfers;
    // the flatter body's normal comes from its faces, not from the
    // staircase of its points' mass gradient: only boxes and meshes have
    // faces (a scene of disks stores nothing)
    const bool any_faces =
      std::any_of(parameters.bodies.begin(), parameters.bodies.end(), [](const auto &body) {
        return body.shape == BodyParameters<dim>::Shape::box ||
               body.shape == BodyParameters<dim>::Shape::mesh;
      });
    layout.surface_normal_stored =
      bodies_touch && parameters.contact.normals == ContactParameters::Normals::flatter_body &&
      any_faces;
    // the faces' positions for the contact's gap, where the face normals
    // tell which records lie under one face
    layout.to_surface_stored =
      layout.surface_normal_stored &&
      parameters.contact.detection == ContactParameters::Detection::surface_position;
    particle_to_grid.set_layout(layout);
    grid_to_particle.set_layout(layout);
    if (bodies_touch)
      {
        std::vector<unsigned int> groups;
        for (const auto &body : parameters.bodies)
          groups.push_back(body.group);
        contact = std::make_unique<MultiBodyContact<dim>>(parameters.contact, groups);
        contact->set_layout(layout);
        // contact reads the other ranks' points near it as ghost particles,
        // which deal.II 9.4 does not send across periodic faces
        check_input(!parallel || !periodicity.any(),
                    "Grid/Periodic axes",
                    periodicity.axes(),
                    "none in a scene with contact between bodies on more than one MPI "
                    "rank (run it on one rank; threads are allowed)");
      }

    // MUSL and USAVG map the points' velocities back to the grid after each
    // update: the friction heat is counted against them (MultiBodyContact)
    const bool heat_at_remap = parameters.update_scheme != UpdateScheme::usl;
    boundary_conditions.count_heat_at_remapped_velocities(heat_at_remap);
    if (contact)
      contact->count_heat_at_remapped_velocities(heat_at_remap);

    // what the contact's and the walls' corrections take from the points;
    // not beside prescribed bodies, whose work on the others is counted
    // as boundary work
    prescribed_velocities = PrescribedVelocities<dim>(parameters.bodies);
    measure_corrections = !prescribed_velocities.any() &&
                          (contact != nullptr || !parameters.boundaries.empty());
    grid_to_particle.measure_corrections(measure_corrections, &boundary_conditions);
    nodal_fields.keep_wall_corrections(measure_corrections);
    if (prescribed_velocities.any())
      {
        check_input(contact != nullptr || parameters.bodies.size() == 1,
                    "Contact/Model",
                    "none",
                    "a contact model for a scene with a body of prescribed "
                    "velocity and other bodies");
        grid_to_particle.set_prescribed_velocities(&prescribed_velocities);
        if (contact)
          contact->set_prescribed_velocities(&prescribed_velocities);
      }

    // a point reaches the nodes of its cell's neighbours, beyond the ghost
    // layer that the transfers and contact rely on
    check_input(!parallel || parameters.shape_functions == ShapeFunctions::linear,
                "Grid/Shape functions",
                "gimp",
                "linear on more than one MPI rank (run GIMP on one rank; threads "
                "are allowed)");
    if (parameters.refinement.enabled())
      mesh_refinement = std::make_unique<MeshRefinement<dim>>(parameters.refinement,
                                                              parameters.boundaries,
                                                              parameters.bodies);
  }

  template <int dim>
  void
  Simulator<dim>::create_particle_handler()
  {
    particle_cells_current = false;
    particle_handler = std::make_unique<Particles::ParticleHandler<dim>>(
      triangulation, grid.get_mapping(), layout.n_properties());
    particle_handler->signals.particle_lost.connect(
      [this](const auto &particle, const auto &) {
        ++lost_particles;
        lost_location = particle->get_location();
      });
  }

  template <int dim>
  void
  Simulator<dim>::setup_output(const bool append)
  {
    const bool write = !parameters.output_directory.empty();
    if (write)
      {
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          std::filesystem::create_directories(parameters.output_directory);
        MPI_Barrier(communicator);
      }
    std::vector<unsigned int> bodies_with_columns;
    for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
      if (parameters.bodies[b].statistics_columns)
        bodies_with_columns.push_back(b);
    statistics_file = std::make_unique<StatisticsFile<dim>>(
      parameters.output_directory + "/statistics.csv",
      bodies_with_columns,
      contact != nullptr,
      prescribed_velocities.any(),
      parameters.contact.reported_pairs,
      !grid.periodicity().any(),
      write && Utilities::MPI::this_mpi_process(communicator) == 0,
      append,
      communicator);
  }

  template <int dim>
  bool
  Simulator<dim>::finished() const
  {
    return state.time >= parameters.end_time * (1 - 1e-14) ||
           (parameters.maximum_steps > 0 && state.step_number >= parameters.maximum_steps);
  }

  template <int dim>
  void
  Simulator<dim>::seed()
  {
    if (seeded)
      return;
    TimerOutput::Scope scope(timer, "initialize");
    setup_models();
    // the levels of 'Mesh refinement' count from the coarsest cells the grid
    // starts with (make_grid() refines a small coarse mesh globally)
    unsigned int coarsest = numbers::invalid_unsigned_int;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        coarsest = std::min(coarsest, static_cast<unsigned int>(cell->level()));
    base_level = Utilities::MPI::min(coarsest, communicator);
    if (mesh_refinement)
      {
        mesh_refinement->set_base_level(base_level);
        mesh_refinement->refine_initial(triangulation, parameters.bodies);
      }
    grid.setup();
    boundary_conditions.setup(grid);
    create_particle_handler();

    seed_bodies(triangulation,
                parameters.bodies,
                materials,
                layout,
                parameters.gravity,
                *particle_handler);
    // a driver's points start with its velocity at t = 0
    if (prescribed_velocities.any())
      for (auto &particle : *particle_handler)
        {
          const auto         props = particle.get_properties();
          const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
          if (prescribed_velocities.is_prescribed(body))
            for (unsigned int d = 0; d < dim; ++d)
              props[layout.velocity + d] = prescribed_velocities.velocity(body)[d];
        }
    if (parallel && parameters.balance_particles)
      {
        connect_cell_weights();
        rebalance(); // also sizes the nodal vectors
      }
    else
      {
        if (contact && parallel)
          particle_handler->exchange_ghost_particles(true);
        allocate_nodal_data();
      }
    {
      std::vector<unsigned long long> per_body(parameters.bodies.size(), 0);
      for (const auto &particle : *particle_handler)
        ++per_body[static_cast<unsigned int>(particle.get_properties()[layout.body])];
      Utilities::MPI::sum(per_body, communicator, per_body);
      for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
        check_input(per_body[b] > 0,
                    parameters.bodies[b].label(b),
                    "(no material point)",
                    "a body large enough to hold at least one material point "
                    "on this grid");
    }
    check_bodies_apart(parameters.bodies, *particle_handler, layout, grid.periodicity(),
                       communicator);
    seeded = true;
  }

  template <int dim>
  void
  Simulator<dim>::initialize()
  {
    if (initialized)
      return;
    seed();
    TimerOutput::Scope scope(timer, "initialize");

    set_contact_body_shapes();

    // the signal speed for the first time step, and an energy scale
    double max_speed = 0, mass_wave_speed2 = 0;
    for (const auto &particle : *particle_handler)
      {
        const auto   props = particle.get_properties();
        const double c     = body_wave_speed[static_cast<unsigned int>(props[layout.body])];
        double       v2    = 0;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += props[layout.velocity + d] * props[layout.velocity + d];
        max_speed = std::max(max_speed, c + std::sqrt(v2));
        mass_wave_speed2 += props[layout.mass] * c * c;
      }
    state.max_signal_speed = Utilities::MPI::max(max_speed, communicator);
    state.energy_floor     = 1e-14 * Utilities::MPI::sum(mass_wave_speed2, communicator);
    if (parameters.settling_steps > 0)
      settle_under_gravity();

    Statistics<dim> statistics   = compute_statistics();
    state.initial_energy         = statistics.kinetic_energy + statistics.strain_energy;
    state.initial_gravity_energy = statistics.gravity_energy;
    state.resolved_energy        = std::accumulate(statistics.body_mass.begin(),
                                            statistics.body_mass.end(),
                                            0.) *
                            parameters.gravity.norm() * grid.minimum_cell_size();
    statistics.energy_drift = energy_drift(statistics);

    setup_output(false);
    statistics_file->write_row(0, 0., 0., 0., statistics);

    pcout << "sable MPM " << dim << "D: " << triangulation.n_global_active_cells()
          << " cells";
    if (mesh_refinement)
      pcout << " (levels " << parameters.refinement.minimum_level << "-"
            << triangulation.n_global_levels() - 1 - base_level << ", adapted every "
            << (parameters.refinement.interval > 0 ?
                  std::to_string(parameters.refinement.interval) + " steps)" :
                  std::string("half a fine cell of travel)"));
    pcout << ", " << particle_handler->n_global_particles()
          << " material points in " << parameters.bodies.size() << " bod"
          << (parameters.bodies.size() == 1 ? "y" : "ies") << ", "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s), "
          << MultithreadInfo::n_threads() << " thread(s) per rank, update scheme "
          << update_scheme_name(parameters.update_scheme) << ", CFL " << parameters.cfl
          << std::endl;
    if (parallel)
      print_balance();
    print_seeding_note();
    if (contact && parameters.update_scheme != UpdateScheme::usl &&
        !parameters.contact.on_strain_update)
      pcout << "note: 'Contact/Passes' leaves out the strain update: under MUSL the friction "
               "heat (contact_heat) is counted at the remapped velocities, which the contact "
               "then does not correct, so it is over-counted (doc/mpm.md, \"Passes\")"
            << std::endl;
    initialized = true;
    if (!parameters.output_directory.empty() && parameters.output_interval > 0)
      write_particles();
  }

  template <int dim>
  void
  Simulator<dim>::setup_after_mesh_change()
  {
    particle_cells_current = false;
    grid.setup();
    boundary_conditions.setup(grid);
    allocate_nodal_data();
    if (contact && parallel)
      particle_handler->exchange_ghost_particles(true);
  }

  template <int dim>
  void
  Simulator<dim>::allocate_nodal_data()
  {
    nodal_fields.reinit(grid,
                        boundary_conditions.needs_material_extent(),
                        boundary_conditions.needs_mass_moment());
    // ghost cells scatter only to the per-body fields (contact under MPI)
    particle_to_grid.reinit(grid, contact && parallel);
  }

  template <int dim>
  void
  Simulator<dim>::adapt_mesh()
  {
    state.travel_since_adaptation = 0;
    std::vector<typename MeshRefinement<dim>::CellContent> contents(
      triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &particle : particle_handler->particles_in_cell(cell))
          {
            const auto props = particle.get_properties();
            contents[cell->active_cell_index()].add(static_cast<unsigned int>(props[layout.body]),
                                                    1,
                                                    ParticleLayout<dim>::seeding_spacing(props));
          }
    // refine at once; coarsening only saves work, so it waits for a
    // refinement or for every fourth adaptation (each one rebuilds the
    // forest, the node numbering and the hanging-node tables)
    const auto flagged     = mesh_refinement->flag_cells(triangulation, contents);
    const bool coarsen_now = ++state.adaptations_without_change >= 4 && flagged.coarsen > 0;
    if (flagged.refine == 0 && !coarsen_now)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            cell->clear_coarsen_flag();
        return;
      }
    state.adaptations_without_change = 0;
    const unsigned long long before = particle_handler->n_global_particles();
    particle_handler->prepare_for_coarsening_and_refinement();
    triangulation.execute_coarsening_and_refinement();
    particle_handler->unpack_after_coarsening_and_refinement();
    particle_handler->update_cached_numbers();
    AssertThrow(particle_handler->n_global_particles() == before,
                ExcMessage("Material points were lost in a mesh adaptation."));
    setup_after_mesh_change();
  }

  template <int dim>
  void
  Simulator<dim>::step()
  {
    if (!initialized)
      initialize();
    advance();
  }

  template <int dim>
  void
  Simulator<dim>::advance()
  {
    state.time_step = compute_time_step();
    // drivers stay at rest while the bodies settle: the run, and their
    // motion, start from the settled state
    if (prescribed_velocities.any() &&
        prescribed_velocities.update(settling ? -std::numeric_limits<double>::infinity() :
                                                state.time))
      {
        // a driver that starts (or stops) changes its kinetic energy: work
        // done on it from outside, as a moving wall's
        double work = 0;
        for (const auto &particle : *particle_handler)
          {
            const auto         props = particle.get_properties();
            const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
            if (!prescribed_velocities.is_prescribed(body))
              continue;
            double v2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              v2 += props[layout.velocity + d] * props[layout.velocity + d];
            work += 0.5 * props[layout.mass] *
                    (prescribed_velocities.velocity(body).norm_square() - v2);
          }
        state.boundary_work += Utilities::MPI::sum(work, communicator);
      }
    // unless the particle container is as the last step left it
    const bool cells_rebuilt = !particle_cells_current;
    if (cells_rebuilt)
      {
        TimerOutput::Scope scope(timer, "list cells with points");
        particle_cells.rebuild(*particle_handler, grid, particle_to_grid.get_colouring());
      }
    particle_cells_current = false;
    find_contact_nodes();
    // the walls' nodes stay; the contact nodes change every step
    if (measure_corrections && (cells_rebuilt || contact))
      grid_to_particle.find_corrected_cells(particle_cells, contact.get());
    const bool usavg = parameters.update_scheme == UpdateScheme::usavg;
    if (usavg)
      update_stresses_from_initial_momenta();
    scatter_momenta_and_forces();
    update_nodal_velocities();
    if (parameters.update_scheme == UpdateScheme::usl)
      update_particles_and_strain_rates();
    else
      {
        update_particle_velocities_and_positions();
        remap_momenta_to_grid();
        update_remapped_velocities();
        // USAVG's second half; the points that took no first half take
        // the whole step
        if (usavg)
          for (double &dt : stress_time_steps)
            dt = dt == 0. ? state.time_step : 0.5 * state.time_step;
        compute_strain_rates(usavg ? 0.5 * state.time_step : state.time_step,
                             usavg && !stress_time_steps.empty() ? &stress_time_steps : nullptr);
      }
    if (usavg && !stress_time_steps.empty())
      update_stresses(0.5 * state.time_step, &stress_time_steps);
    else
      update_stresses(usavg ? 0.5 * state.time_step : state.time_step);
    sort_particles();
    advance_time();
    if (adaptation_due())
      adapt_mesh();
  }

  template <int dim>
  double
  Simulator<dim>::compute_time_step() const
  {
    double dt = parameters.cfl * grid.minimum_cell_size() / state.max_signal_speed;
    if (!settling && state.time + dt > parameters.end_time)
      dt = parameters.end_time - state.time;
    return dt;
  }

  template <int dim>
  void
  Simulator<dim>::find_contact_nodes()
  {
    if (!contact)
      return;
    TimerOutput::Scope scope(timer, "particles to grid");
    TimerOutput::Scope inner(timer, "find contact nodes (in particles to grid)");
    contact->mark_contact_nodes(particle_cells, grid, layout, boundary_conditions);
  }

  template <int dim>
  void
  Simulator<dim>::update_stresses_from_initial_momenta()
  {
    // The contact acts on the momenta at the start of the step too: each
    // body's records take the geometry the contact reads (as in the
    // momentum update, but not the forces) and the contact, decided afresh
    // on them, corrects them, so that the points at contact nodes take the
    // midpoint rule as well (uncorrected, a disk resting on a block gained
    // energy at each of its small bounces; on MUSL's whole step, two
    // unequal soft disks meeting head-on gained more at CFL 0.5,
    // doc/mpm.md, "Stability"). The points whose cells reach a friction
    // wall's node, whose decision is the momentum update's, and all points
    // near contact nodes in scenes with bodies of prescribed velocity take
    // the whole strain update from the remapped momenta. The others read
    // the single field.
    const double half_step = 0.5 * state.time_step;
    contact_in_first_half  = contact && contact->corrects_initial_velocities();
    const bool split_cells = (contact && !contact_in_first_half) ||
                             boundary_conditions.has_walls(BoundaryType::friction);
    stress_time_steps.clear();
    if (split_cells)
      {
        const std::vector<bool> &friction_nodes = boundary_conditions.friction_wall_nodes();
        stress_time_steps.resize(particle_cells.n_owned());
        for (unsigned int c = 0; c < particle_cells.n_owned(); ++c)
          {
            const auto nodes   = grid.cell_nodes(*particle_cells[c].data);
            bool       decided = contact && !contact_in_first_half && contact->touches(nodes);
            for (unsigned int k = 0; k < nodes.second && !decided; ++k)
              decided = friction_nodes[nodes.first[k]];
            stress_time_steps[c] = decided ? 0. : half_step;
          }
      }
    {
      TimerOutput::Scope scope(timer, "particles to grid");
      particle_to_grid.template scatter<GridPass::initial_momenta>(particle_cells,
                                                                   grid,
                                                                   nodal_fields,
                                                                   contact_in_first_half ?
                                                                     contact.get() :
                                                                     nullptr);
    }
    {
      TimerOutput::Scope scope(timer, "grid update and boundaries");
      nodal_fields.template compute_velocities<GridPass::initial_momenta>(boundary_conditions,
                                                                          parameters.gravity,
                                                                          state.time_step);
      if (contact_in_first_half)
        contact->correct_initial_velocities(grid,
                                            boundary_conditions,
                                            state.time_step,
                                            nodal_fields.n_owned_nodes());
    }
    {
      TimerOutput::Scope scope(timer, "grid to particles");
      process_report(grid_to_particle.compute_strain_rates(*particle_handler,
                                                           particle_cells,
                                                           contact_in_first_half ? contact.get() : nullptr,
                                                           half_step,
                                                           split_cells ? &stress_time_steps :
                                                                         nullptr,
                                                           true),
                     false);
    }
    update_stresses(half_step, split_cells ? &stress_time_steps : nullptr);
    // the contact's records at the partition read the ghost particles'
    // stresses in the momentum update
    if (contact_in_first_half && parallel)
      {
        TimerOutput::Scope scope(timer, "particles to grid");
        particle_handler->update_ghost_particles();
      }
  }

  template <int dim>
  void
  Simulator<dim>::scatter_momenta_and_forces()
  {
    TimerOutput::Scope scope(timer, "particles to grid");
    if (contact_in_first_half)
      contact->zero_records();
    particle_to_grid.template scatter<GridPass::momentum_update>(particle_cells,
                                                                 grid,
                                                                 nodal_fields,
                                                                 contact.get());
  }

  template <int dim>
  void
  Simulator<dim>::update_nodal_velocities()
  {
    TimerOutput::Scope scope(timer, "grid update and boundaries");
    const double       work =
      nodal_fields.template compute_velocities<GridPass::momentum_update>(boundary_conditions,
                                                                          parameters.gravity,
                                                                          state.time_step);
    // only moving walls do work: no reduction over ranks otherwise; every
    // rank takes part, also one without boundary nodes
    if (boundary_conditions.has_walls(BoundaryType::moving))
      state.boundary_work += Utilities::MPI::sum(work, communicator);
    if (contact)
      {
        TimerOutput::Scope scope(timer, "contact (in grid update)");
        contact->template correct_velocities<GridPass::momentum_update>(
          grid,
          boundary_conditions,
          parameters.gravity,
          state.time_step,
          nodal_fields.n_owned_nodes());
        // a driver's work enters the energy balance as a moving wall's
        if (prescribed_velocities.any())
          {
            state.boundary_work += Utilities::MPI::sum(contact->get_driver_work(), communicator);
            const Tensor<1, dim> impulse =
              Utilities::MPI::sum(contact->get_driver_impulse(), communicator);
            for (unsigned int d = 0; d < dim; ++d)
              state.driver_impulse[d] += impulse[d];
          }
      }
  }

  template <int dim>
  void
  Simulator<dim>::update_particles_and_strain_rates()
  {
    TimerOutput::Scope scope(timer, "grid to particles");
    process_report(grid_to_particle.update_particles_and_strain_rates(*particle_handler,
                                                                      particle_cells,
                                                                      contact.get(),
                                                                      state.time_step,
                                                                      parameters.pic_fraction),
                   true);
  }

  template <int dim>
  void
  Simulator<dim>::update_particle_velocities_and_positions()
  {
    TimerOutput::Scope scope(timer, "grid to particles");
    process_report(grid_to_particle.update_velocities_and_positions(*particle_handler,
                                                                    particle_cells,
                                                                    contact.get(),
                                                                    state.time_step,
                                                                    parameters.pic_fraction),
                   true);
  }

  template <int dim>
  void
  Simulator<dim>::remap_momenta_to_grid()
  {
    TimerOutput::Scope scope(timer, "particles to grid");
    if (contact)
      {
        if (parallel)
          particle_handler->update_ghost_particles();
        contact->begin_remap();
      }
    particle_to_grid.template scatter<GridPass::remapped_momenta>(particle_cells,
                                                                  grid,
                                                                  nodal_fields,
                                                                  contact.get());
  }

  template <int dim>
  void
  Simulator<dim>::update_remapped_velocities()
  {
    TimerOutput::Scope scope(timer, "grid update and boundaries");
    nodal_fields.template compute_velocities<GridPass::remapped_momenta>(boundary_conditions,
                                                                         parameters.gravity,
                                                                         state.time_step);
    if (contact)
      {
        TimerOutput::Scope scope(timer, "contact (in grid update)");
        contact->template correct_velocities<GridPass::remapped_momenta>(
          grid,
          boundary_conditions,
          parameters.gravity,
          state.time_step,
          nodal_fields.n_owned_nodes());
      }
  }

  template <int dim>
  void
  Simulator<dim>::compute_strain_rates(const double                time_step,
                                      const std::vector<double> *cell_time_steps)
  {
    TimerOutput::Scope scope(timer, "grid to particles");
    process_report(grid_to_particle.compute_strain_rates(
                     *particle_handler, particle_cells, contact.get(), time_step, cell_time_steps),
                   false);
  }

  template <int dim>
  void
  Simulator<dim>::update_stresses(const double time_step, const std::vector<double> *cell_time_steps)
  {
    TimerOutput::Scope scope(timer, "stress update");
    const StressUpdate<dim> stress_update(materials, layout);
    const auto              failure = stress_update.update(particle_cells,
                                                           velocity_gradients,
                                                           time_step,
                                                           cell_time_steps,
                                                           parameters.update_scheme ==
                                                             UpdateScheme::usavg);
    report_failure(failure.failed,
                   failure.location,
                   "a velocity or stress is not a finite number (NaN or infinity)");
  }

  template <int dim>
  void
  Simulator<dim>::process_report(const typename GridToParticle<dim>::Report &report,
                                 const bool                                  moved)
  {
    correction_loss += report.correction_loss;
    // only the pass that moves the points measures speeds (every rank
    // takes part in the reductions, also one without points)
    if (moved)
      {
        // with the fastest point's travel since the last adaptation, and
        // whether any point left its cell (then the sort is due)
        std::vector<double> maxima = {report.max_signal_speed,
                                      report.max_particle_speed,
                                      report.n_left_cell > 0 ? 1. : 0.};
        Utilities::MPI::max(maxima, communicator, maxima);
        state.max_signal_speed = maxima[0];
        if (mesh_refinement)
          state.travel_since_adaptation += maxima[1] * state.time_step;
        points_left_cells = maxima[2] > 0;
      }
    report_failure(report.not_finite,
                   report.failure_location,
                   "a velocity or stress is not a finite number (NaN or infinity)");
    report_failure(report.too_far,
                   report.failure_location,
                   "a material point moved more than one cell in one step "
                   "(reduce 'Time/CFL number')");
  }

  template <int dim>
  void
  Simulator<dim>::advance_time()
  {
    state.time += state.time_step;
    ++state.step_number;
  }

  template <int dim>
  bool
  Simulator<dim>::adaptation_due() const
  {
    const unsigned int interval = parameters.refinement.interval;
    return mesh_refinement &&
           (interval > 0 ? state.step_number % interval == 0 :
                           state.travel_since_adaptation >= 0.5 * grid.minimum_cell_size());
  }

  template <int dim>
  Statistics<dim>
  Simulator<dim>::compute_statistics() const
  {
    Statistics<dim> s = sable::mpm::compute_statistics(triangulation,
                                                       *particle_handler,
                                                       layout,
                                                       materials,
                                                       parameters.gravity,
                                                       contact ? &contact->get_model() : nullptr,
                                                       grid.periodicity(),
                                                       state.time_step);
    s.wall_heat    = Utilities::MPI::sum(boundary_conditions.frictional_heat, communicator);
    if (measure_corrections)
      s.impact_loss =
        Utilities::MPI::sum(correction_loss, communicator) - s.wall_heat - s.contact_heat;
    for (unsigned int d = 0; d < dim; ++d)
      s.driver_impulse[d] = state.driver_impulse[d];
    s.energy_drift     = energy_drift(s);
    return s;
  }

  template <int dim>
  double
  Simulator<dim>::energy_drift(const Statistics<dim> &s) const
  {
    // at the start the dissipated energies and the boundary work are zero;
    // the impacts enter only as a loss: energy the corrections create (the
    // 2000 rule's rebound) is a gain the guard must see
    const double balance = s.kinetic_energy + s.strain_energy + s.gravity_energy +
                           s.plastic_work + s.wall_heat + s.contact_heat +
                           std::max(s.impact_loss, 0.) - state.boundary_work;
    return (balance - state.initial_energy - state.initial_gravity_energy) /
           std::max(state.energy_scale(s.gravity_energy), state.resolved_energy);
  }

  template <int dim>
  Point<dim>
  Simulator<dim>::fastest_point_location() const
  {
    double     fastest = -1;
    Point<dim> where;
    for (const auto &particle : *particle_handler)
      {
        double v2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += std::pow(particle.get_properties()[layout.velocity + d], 2);
        if (v2 > fastest)
          {
            fastest = v2;
            where   = particle.get_location();
          }
      }
    const double       global_fastest = Utilities::MPI::max(fastest, communicator);
    const unsigned int rank           = Utilities::MPI::min(
      fastest == global_fastest ? Utilities::MPI::this_mpi_process(communicator) :
                                  numbers::invalid_unsigned_int,
      communicator);
    return Utilities::MPI::broadcast(communicator, where, rank);
  }

  template <int dim>
  void
  Simulator<dim>::check_energy(const Statistics<dim> &s)
  {
    const double budget = state.energy_budget(s.gravity_energy);
    const double energy = s.kinetic_energy + s.strain_energy;
    if (!(energy <= parameters.energy_growth_limit * budget))
      {
        std::ostringstream message;
        message << "the run became unstable at step " << state.step_number
                << ", time " << std::setprecision(10) << state.time
                << ": kinetic + strain energy " << energy
                << " exceeds 'Output/Energy growth limit' = "
                << parameters.energy_growth_limit << " times the energy "
                << "supplied (" << budget << ")";
        message << "; fastest material point at " << to_string(fastest_point_location());
        throw std::runtime_error(message.str());
      }
    // a gain is what an instability makes; losses (the grid's inelastic
    // impacts, material leaving the grid) only warn
    if (!(s.energy_drift <= parameters.energy_drift_limit))
      {
        std::ostringstream message;
        message << "the run became unstable at step " << state.step_number << ", time "
                << std::setprecision(10) << state.time << ": the energy balance gained "
                << s.energy_drift << " of the energy the scene can hold, beyond "
                << "'Output/Energy drift limit' = " << parameters.energy_drift_limit
                << " (statistics.csv, column energy_drift); fastest material point at "
                << to_string(fastest_point_location());
        // the gain a free body makes when it rings while it moves or
        // spins across the grid: USAVG's midpoint rule removes it, and it
        // falls steeply with the step (doc/mpm.md)
        const bool usavg = parameters.update_scheme == UpdateScheme::usavg;
        if (!usavg || parameters.cfl > 0.25)
          message << "; bodies that ring while they move or spin across the grid gain energy "
                  << "at large time steps (doc/mpm.md, \"Spinning bodies\"): ";
        if (!usavg)
          message << "'Solver/Update scheme = USAVG' (the stress updated in two halves, a "
                  << "third to a half more time per step) keeps such a body's energy";
        if (!usavg && parameters.cfl > 0.25)
          message << "; ";
        if (parameters.cfl > 0.25)
          message << "a smaller 'Time/CFL number' than " << parameters.cfl
                  << " (0.25, say) or 'Grid/Shape functions = gimp' reduces such a gain";
        // the papers' detection holds bodies together a cell before they
        // touch: a pile of disks gained half its energy in 0.3 s with it
        // under either scheme (doc/validation.md)
        if (contact &&
            parameters.contact.detection == ContactParameters::Detection::shared_nodes)
          message << "; contact at every shared node ('Contact/Detection = shared nodes') acts "
                  << "up to a cell before bodies touch and makes energy where they crowd, under "
                  << "either update scheme; 'Contact/Detection = surface position' does not";
        throw std::runtime_error(message.str());
      }
    if (std::abs(s.energy_drift) > std::min(0.01, parameters.energy_drift_limit) && !drift_warned)
      {
        drift_warned = true;
        pcout << "warning: the energy balance drifts by " << std::setprecision(3)
              << 100 * s.energy_drift << "% at step " << state.step_number << ", time "
              << state.time << " (statistics.csv, column energy_drift)" << std::setprecision(6);
        // a gain is most often MUSL's step where a body rings while it
        // moves across the grid or where bodies touch; USAVG's two halves
        // keep most of it, and MUSL's falls with the square of the step
        if (s.energy_drift > 0 && parameters.update_scheme != UpdateScheme::usavg)
          pcout << "; if bodies ring while they move or spin across the grid, or collide "
                   "or settle, 'Solver/Update scheme = USAVG' keeps their energy (doc/mpm.md, "
                   "\"Stability\"; a settling pile +0.8% against +4.8% at CFL 0.5)";
        if (s.energy_drift > 0 && s.impact_loss > 0 && parameters.cfl > 0.25)
          pcout << "; where bodies collide or settle, a smaller 'Time/CFL number' than "
                << parameters.cfl << " reduces the gain (about fourfold at half the number under "
                << "MUSL; doc/validation.md, \"Energy balance of a settling pile\")";
        pcout << std::endl;
      }
  }

  template <int dim>
  void
  Simulator<dim>::check_statistics_finite(const Statistics<dim> &s) const
  {
    const std::string column = statistics_file->first_not_finite(
      state.step_number, state.time, state.time_step, state.boundary_work, s);
    if (column.empty())
      return;
    std::ostringstream message;
    message << "the run stopped at step " << state.step_number << ", time "
            << std::setprecision(10) << state.time << ": the statistics value '" << column
            << "' is not a finite number (NaN or infinity); fastest material point at " << to_string(fastest_point_location());
    throw std::runtime_error(message.str());
  }

  template <int dim>
  void
  Simulator<dim>::write_particles()
  {
    put_particles_in_order();
    TimerOutput::Scope     scope(timer, "output");
    {
      // deal.II and MPI-IO abort on a failed write: check first (the
      // positions alone, as floats, give a lower bound of the size)
      const double bytes = double(particle_handler->n_global_particles()) * dim * sizeof(float);
      const double ranks = Utilities::MPI::n_mpi_processes(communicator);
      on_root(communicator, [&]() {
        const std::string problem = write_problem(parameters.output_directory, bytes, bytes / ranks);
        if (!problem.empty())
          throw std::runtime_error("cannot write the particle output into '" +
                                   parameters.output_directory + "': " + problem);
      });
    }
    // deal.II's output holds floats: integers are exact up to 2^24
    if (particle_handler->get_next_free_particle_index() > (1u << 24) && !id_precision_warned)
      {
        id_precision_warned = true;
        pcout << "warning: the particle output writes ids as single-precision floats, "
              << "exact only below 16777216; this run has ids up to "
              << particle_handler->get_next_free_particle_index() - 1 << std::endl;
      }
    std::vector<std::string> history_names;
    for (const auto &material : materials)
      if (material->n_history() == layout.n_history)
        history_names = material->history_names();
    ParticleOutput<dim> data_out(layout,
                                 history_names,
                                 /*tensors=*/parameters.output_format == OutputFormat::vtu,
                                 parameters.smoothed_stress_output);
    if (parameters.smoothed_stress_output)
      {
        TimerOutput::Scope scope(timer, "smoothed stress (in output)");
        if (!particle_cells_current)
          {
            particle_cells.rebuild(*particle_handler, grid, particle_to_grid.get_colouring());
            particle_cells_current = true;
          }
        StressSmoothing<dim> smoothing;
        smoothing.compute(particle_cells, grid, particle_handler->get_max_local_particle_index());
        data_out.build_patches(*particle_handler, &smoothing);
      }
    else
      data_out.build_patches(*particle_handler);
    const unsigned int counter = state.output_counter++;
    particle_series.write(data_out,
                          particle_handler->n_locally_owned_particles() > 0,
                          counter,
                          state.time,
                          communicator);
    if (contact && parameters.contact_node_output)
      {
        ContactNodeOutput<dim> contact_nodes;
        contact_nodes.build_patches(grid, contact->get_fields(), nodal_fields.n_owned_nodes());
        contact_node_series.write(
          contact_nodes, !contact_nodes.empty(), counter, state.time, communicator);
      }
    if (grid_output)
      grid_output->write(grid, *particle_handler, counter, state.time, base_level);
    state.next_output_time = state.time + parameters.output_interval;
  }

  template <int dim>
  void
  Simulator<dim>::run()
  {
    initialize();
    Timer wall;
    const bool write_output =
      !parameters.output_directory.empty() && parameters.output_interval > 0;
    const bool write_checkpoints =
      !parameters.output_directory.empty() && parameters.checkpoint_interval > 0;
    // where this run started (later than 0 after resume()), for the
    // estimate of the time left
    const double       first_time = state.time;
    const unsigned int first_step = state.step_number;
    while (!finished())
      {
        step();
        const bool last       = finished();
        const bool progress   = state.step_number % parameters.progress_interval == 0 || last;
        const bool output_due = write_output && state.time >= state.next_output_time * (1 - 1e-12);
        state.statistics_row_due = statistics_due(output_due);
        if (state.statistics_row_due || progress)
          {
            TimerOutput::Scope    scope(timer, "statistics");
            const Statistics<dim> s = compute_statistics();
            check_energy(s);
            if (state.statistics_row_due || last)
              statistics_file->write_row(
                state.step_number, state.time, state.time_step, state.boundary_work, s);
            check_statistics_finite(s);
            if (progress)
              {
                const double elapsed = wall.wall_time();
                double fraction = (state.time - first_time) / (parameters.end_time - first_time);
                if (parameters.maximum_steps > first_step)
                  fraction = std::max(fraction,
                                      double(state.step_number - first_step) /
                                        (parameters.maximum_steps - first_step));
                pcout << "step " << std::setw(7) << state.step_number << "  t = " << std::setprecision(4)
                      << std::scientific << state.time << "  dt = " << state.time_step
                      << "  E_kin = " << s.kinetic_energy << "  E_strain = " << s.strain_energy
                      << std::fixed << std::setprecision(1) << "  wall " << elapsed << " s, ~"
                      << elapsed * (1. - fraction) / std::max(fraction, 1e-12) << " s left"
                      << std::defaultfloat << std::setprecision(6) << std::endl;
              }
          }
        if (output_due)
          write_particles();
        // the checkpoint holds the state an uninterrupted run has at this
        // step: before the extra particle output of the last step
        if (write_checkpoints && (state.step_number % parameters.checkpoint_interval == 0 || last))
          save_checkpoint();
        if (write_output && last && !output_due)
          write_particles();
      }
    if (parameters.print_timings)
      {
        timer.print_summary();
        pcout << "Particle sort in " << n_sorts << " of "
              << n_sorts + n_rebins + n_sorts_skipped << " steps; only the points "
              << "that left their cells moved in " << n_rebins
              << "; no point left its cell in " << n_sorts_skipped << std::endl;
      }
    if (!parameters.output_directory.empty())
      pcout << "Output written to " << parameters.output_directory << "/ (statistics.csv"
            << (write_output ? ", " + particle_series.series_file() : "")
            << (write_output && grid_output ? ", " + grid_output->series.series_file() : "")
            << (write_checkpoints ? ", checkpoint/" : "") << ")" << std::endl;
    pcout << "Finished " << state.step_number << " steps to t = " << state.time << " in "
          << wall.wall_time() << " s wall time" << std::endl;
  }

  template <int dim>
  bool
  Simulator<dim>::statistics_due(const bool output_due) const
  {
    const unsigned int interval = parameters.statistics_interval;
    return interval > 0 ? state.step_number % interval == 0 :
                          output_due || state.step_number % parameters.progress_interval == 0;
  }

  template <int dim>
  void
  Simulator<dim>::connect_cell_weights()
  {
    // from now on p4est weighs the cells by their material points at every
    // repartition: rebalance() and adaptation
    load_balance.connect(triangulation, *particle_handler);
  }

  template <int dim>
  void
  Simulator<dim>::rebalance()
  {
    particle_handler->prepare_for_coarsening_and_refinement();
    triangulation.repartition();
    particle_handler->unpack_after_coarsening_and_refinement();
    setup_after_mesh_change();
  }

  template <int dim>
  void
  Simulator<dim>::set_contact_body_shapes()
  {
    if (!contact)
      return;
    std::vector<double> volumes(parameters.bodies.size(), 0.), masses(volumes);
    for (const auto &particle : *particle_handler)
      {
        const auto         props = particle.get_properties();
        const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
        volumes[body] += props[layout.initial_volume];
        masses[body] += props[layout.mass];
      }
    Utilities::MPI::sum(volumes, communicator, volumes);
    Utilities::MPI::sum(masses, communicator, masses);
    std::vector<double> surface_radii(parameters.bodies.size());
    for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
      surface_radii[b] = parameters.bodies[b].shape == BodyParameters<dim>::Shape::disk ?
                           parameters.bodies[b].radius :
                           std::numeric_limits<double>::infinity();
    contact->set_body_shapes(surface_radii, volumes, masses, grid.periodicity().any());
  }

  template <int dim>
  void
  Simulator<dim>::print_seeding_note() const
  {
    bool friction_walls = false;
    for (const auto &[id, boundary] : parameters.boundaries)
      friction_walls = friction_walls || boundary.type == BoundaryType::friction;
    if (!contact && !friction_walls)
      return;
    // one point per cell direction: a disk that spins turns its spin into
    // strain within a fraction of a second (doc/mpm.md, "Spinning bodies");
    // said where gravity or a spin can make disks roll
    unsigned int n_single_point_disks = 0;
    for (const auto &body : parameters.bodies)
      n_single_point_disks += body.shape == BodyParameters<dim>::Shape::disk &&
                              body.particles_per_direction == 1 &&
                              (parameters.gravity.norm() > 0 || body.angular_velocity.norm() > 0);
    if (n_single_point_disks > 0)
      pcout << "note: " << n_single_point_disks << (dim == 2 ? " disk" : " sphere")
            << (n_single_point_disks > 1 ? "s" : "")
            << " with one point per cell direction: "
            << (dim == 2 ? "a spinning or rolling disk turns its spin into strain (a free disk at "
                           "16 cells per diameter stops turning within a second and gains energy; "
                           "rolling on a plane body or a friction wall it lags the rigid disk by "
                           "30-70%)" :
                           "a spinning or rolling sphere turns its spin into strain (a free sphere "
                           "at 16 cells per diameter stops turning within a second and gains "
                           "energy)")
            << "; 'Particles per cell direction' = 2 or more keeps it (doc/mpm.md, "
               "\"Spinning bodies\")"
            << std::endl;
    unsigned int n_lattice_disks = 0;
    for (const auto &body : parameters.bodies)
      n_lattice_disks += body.shape == BodyParameters<dim>::Shape::disk &&
                         body.seeding_used() == BodyParameters<dim>::Seeding::lattice;
    if (n_lattice_disks == 0)
      return;
    const bool plural = n_lattice_disks > 1;
    pcout << "note: " << n_lattice_disks << (dim == 2 ? " disk" : " sphere") << (plural ? "s" : "")
          << " seeded on the lattice (Seeding = lattice): "
          << (dim == 2 ? "the edge is a staircase, which rolls like a polygon (16 cells per "
                         "diameter, on a plane body or a friction wall: 3-14% behind a rigid "
                         "disk) and rests like a flat punch (on a floor it sinks about half "
                         "as far as the converged disk at 12.8-25.6 cells per diameter); "
                         "Seeding = automatic or clipped (the lattice clipped to the circle) "
                         "or conforming follows the circle (rolling within 1.8%, resting within "
                         "6% at 25.6)" :
                         "the surface is a staircase, which rests like a flat punch (on a "
                         "floor it sinks about half as far as the converged sphere at 12.8 "
                         "cells per diameter); Seeding = automatic or clipped (the lattice "
                         "clipped to the sphere) or conforming (shells) follows it, which sinks about "
                         "13% further than the converged sphere and helps some rolling cases "
                         "and not others")
          << " (doc/mpm.md, \"Seeding round bodies\")" << std::endl;
  }

  template <int dim>
  void
  Simulator<dim>::print_balance() const
  {
    LoadBalance<dim>::print(pcout,
                            triangulation,
                            *particle_handler,
                            grid.n_relevant_nodes() - nodal_fields.n_owned_nodes());
  }

  template <int dim>
  std::pair<unsigned long long, unsigned long long>
  Simulator<dim>::particles_per_rank() const
  {
    return LoadBalance<dim>::particles_per_rank(*particle_handler, communicator);
  }

  template <int dim>
  void
  Simulator<dim>::report_failure(const bool         failed_here,
                                 const Point<dim> & location,
                                 const std::string &what) const
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int failed_rank = Utilities::MPI::min(
      failed_here ? rank : numbers::invalid_unsigned_int, communicator);
    if (failed_rank == numbers::invalid_unsigned_int)
      return;
    const Point<dim> where = Utilities::MPI::broadcast(communicator, location, failed_rank);
    std::ostringstream message;
    message << "the run stopped at step " << state.step_number << ", time "
            << std::setprecision(10) << state.time << ": " << what
            << ", at position " << to_string(where);
    throw std::runtime_error(message.str());
  }

  template <int dim>
  void
  Simulator<dim>::sort_particles()
  {
    TimerOutput::Scope scope(timer, "sort particles");
    lost_particles = 0;
    bool rebinned = false;
    if (points_left_cells)
      {
        // on one rank the points that left are moved on their own, unless
        // one left the grid, the moves since the last sort call for one, or
        // more left in this step than the room reserved for moves
        const auto room = static_cast<std::size_t>(
          full_sort_fraction * particle_handler->n_locally_owned_particles());
        rebinned = !parallel && rebinning.moved_since_full_sort() < room &&
                   rebinning.rebin(*particle_handler, particle_cells, grid.periodicity(), room);
        if (!rebinned)
          full_sort();
        if (contact && parallel)
          particle_handler->exchange_ghost_particles(true);
      }
    else
      {
        // no point on any rank left its cell: the sort would only set the
        // reference locations, and the ghost particles keep their cells
        particle_cells.update_reference_locations();
        if (contact && parallel)
          particle_handler->update_ghost_particles();
      }
    ++(!points_left_cells ? n_sorts_skipped : rebinned ? n_rebins : n_sorts);
    // a skipped sort leaves the owned points' container as it was (the
    // ghost update may not: rebuild then)
    particle_cells_current = !points_left_cells && !(contact && parallel);
    const unsigned long long lost = Utilities::MPI::sum(lost_particles, communicator);
    if (lost > 0)
      {
        if (!parameters.allow_outflow)
          report_failure(lost_particles > 0, lost_location,
                         std::to_string(lost) + " material point(s) left the grid "
                         "(set 'Output/Allow outflow = true' to let them go)");
        pcout << "step " << state.step_number << ": " << lost
              << " material point(s) left the grid" << std::endl;
      }
  }

  template <int dim>
  void
  Simulator<dim>::put_particles_in_order()
  {
    // the rebinning appends the cells that gained their first points to the
    // container; output and checkpoints write the points in its order, so
    // they get the order of a sort, which is also the order a resumed run
    // starts from (all points are in their cells: the sort only reorders)
    if (rebinning.moved_since_full_sort() == 0)
      return;
    TimerOutput::Scope scope(timer, "sort particles");
    full_sort();
    particle_cells_current = false;
  }

  template <int dim>
  void
  Simulator<dim>::full_sort()
  {
    // on one rank the full sort is rare, and its copy of the particle data
    // into container order sets the peak memory of a run: give back first
    // what this step no longer needs and the next rebuilds (the velocity
    // gradients and the list of cells with points, about 80 bytes a point
    // in 2D); on several ranks every step sorts
    if (!parallel)
      {
        std::vector<Tensor<2, dim>>().swap(velocity_gradients);
        particle_cells.release();
      }
    particle_handler->sort_particles_into_subdomains_and_cells();
    reset_rebinning();
  }

  template <int dim>
  void
  Simulator<dim>::reset_rebinning()
  {
    rebinning.reset();
    // the sort leaves the particle data without room to spare; the points
    // the rebinning moves are inserted before their old copies go, so make
    // room for them now rather than let the first move double the data
    if (!parallel)
      particle_handler->reserve(static_cast<std::size_t>(
        (1. + full_sort_fraction) * particle_handler->n_locally_owned_particles()));
  }

  template <int dim>
  void
  Simulator<dim>::write_output()
  {
    AssertThrow(initialized && !parameters.output_directory.empty(),
                ExcMessage("write_output() needs an initialized Simulator with an output directory."));
    write_particles();
  }

  template <int dim>
  Statistics<dim>
  Simulator<dim>::write_statistics()
  {
    AssertThrow(initialized, ExcMessage("write_statistics() needs an initialized Simulator."));
    const Statistics<dim> s = compute_statistics();
    statistics_file->write_row(
      state.step_number, state.time, state.time_step, state.boundary_work, s);
    check_statistics_finite(s);
    return s;
  }

  template class Simulator<2>;
  template class Simulator<3>;
} // namespace sable::mpm
