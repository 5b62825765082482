#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/particles/data_out.h>

#include <sable/base/input_error.h>
#include <sable/mpm/cell_colouring.h>
#include <sable/mpm/postprocess/grid_output.h>
#include <sable/mpm/q1_shape.h>
#include <sable/mpm/simulator.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <mutex>
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

    /// Embed a dim x dim tensor into 3 x 3 (plane strain: zeros elsewhere).
    template <int dim>
    Tensor<2, 3>
    embed(const Tensor<2, dim> &a, const double diagonal_fill)
    {
      Tensor<2, 3> result;
      for (unsigned int i = 0; i < 3; ++i)
        result[i][i] = diagonal_fill;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          result[i][j] = a[i][j];
      return result;
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
    , grid(triangulation)
    , boundary_conditions(parameters.boundaries)
    , particle_series(parameters.output_directory, "particles", parameters.output_format)
  {
    if (parameters.grid_output)
      grid_output =
        std::make_unique<GridOutput<dim>>(parameters.output_directory, parameters.output_format);
  }

  template <int dim>
  Simulator<dim>::~Simulator()
  {
    weight_connection.disconnect();
  }

  template <int dim>
  void
  Simulator<dim>::add_body(const BodyParameters<dim> &body)
  {
    AssertThrow(!initialized,
                ExcMessage("Bodies must be added before initialize()."));
    parameters.bodies.push_back(body);
  }

  template <int dim>
  void
  Simulator<dim>::setup_models()
  {
    check_parameters(parameters);
    // every body must lie inside the grid
    {
      const auto box = GridTools::compute_bounding_box(triangulation);
      for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
        {
          const auto body_box = parameters.bodies[b].bounding_box();
          for (unsigned int d = 0; d < dim; ++d)
            check_input(body_box.first[d] >= box.get_boundary_points().first[d] - 1e-12 &&
                          body_box.second[d] <= box.get_boundary_points().second[d] + 1e-12,
                        "Body " + std::to_string(b),
                        to_string(body_box.first) + " - " + to_string(body_box.second),
                        "a body inside the grid " + to_string(box.get_boundary_points().first) +
                          " - " + to_string(box.get_boundary_points().second));
        }
    }

    for (const auto &body : parameters.bodies)
      {
        materials.push_back(create_material(body.material));
        body_wave_speed.push_back(materials.back()->wave_speed());
        layout.n_history = std::max(layout.n_history, materials.back()->n_history());
      }
    has_gravity = parameters.gravity.norm() > 0.;
    parallel    = Utilities::MPI::n_mpi_processes(communicator) > 1;

    use_contact = parameters.contact.model != ContactParameters::Model::none &&
                  parameters.bodies.size() > 1;
    if (use_contact)
      {
        std::vector<unsigned int> groups;
        for (const auto &body : parameters.bodies)
          groups.push_back(body.group);
        contact = std::make_unique<BardenhagenContact<dim>>(parameters.contact, groups);
      }

    if (parameters.refinement.enabled())
      mesh_refinement = std::make_unique<MeshRefinement<dim>>(parameters.refinement,
                                                              parameters.boundaries,
                                                              parameters.bodies);
  }

  template <int dim>
  void
  Simulator<dim>::create_particle_handler()
  {
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
    statistics_file = std::make_unique<StatisticsFile<dim>>(
      parameters.output_directory + "/statistics.csv",
      parameters.bodies.size(),
      use_contact,
      parameters.contact.reported_pairs,
      write && Utilities::MPI::this_mpi_process(communicator) == 0,
      append);
  }

  template <int dim>
  bool
  Simulator<dim>::finished() const
  {
    return time >= parameters.end_time * (1 - 1e-14) ||
           (parameters.maximum_steps > 0 && step_number >= parameters.maximum_steps);
  }

  template <int dim>
  void
  Simulator<dim>::initialize()
  {
    if (initialized)
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

    // seed every body; ids are unique over all ranks
    const OwnedCellStrip<dim> owned_cells(triangulation);
    types::particle_index     next_id = 0;
    for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
      seed_body(b, owned_cells, next_id);
    {
      types::particle_index offset = 0;
      const types::particle_index local = particle_handler->n_locally_owned_particles();
      MPI_Exscan(&local, &offset, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, communicator);
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        offset = 0;
      for (auto &particle : *particle_handler)
        particle.set_id(particle.get_id() + offset);
    }
    particle_handler->update_cached_numbers();
    if (parallel && parameters.balance_particles)
      {
        connect_cell_weights();
        rebalance(); // also sizes the nodal vectors
      }
    else
      {
        if (use_contact && parallel)
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
                    "Body " + std::to_string(b),
                    "(no material point)",
                    "a body large enough to hold at least one material point "
                    "on this grid");
    }

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
    max_signal_speed = Utilities::MPI::max(max_speed, communicator);
    energy_floor     = 1e-14 * Utilities::MPI::sum(mass_wave_speed2, communicator);

    const Statistics<dim> statistics = compute_statistics();
    initial_energy         = statistics.kinetic_energy + statistics.strain_energy;
    initial_gravity_energy = statistics.gravity_energy;

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
          << MultithreadInfo::n_threads() << " thread(s) per rank" << std::endl;
    if (parallel)
      print_balance();
    initialized = true;
    if (!parameters.output_directory.empty() && parameters.output_interval > 0)
      write_particles();
  }

  template <int dim>
  void
  Simulator<dim>::setup_after_mesh_change()
  {
    grid.setup();
    boundary_conditions.setup(grid);
    allocate_nodal_data();
    if (use_contact && parallel)
      particle_handler->exchange_ghost_particles(true);
  }

  template <int dim>
  void
  Simulator<dim>::allocate_nodal_data()
  {
    const unsigned int n_components = 1 + 2 * dim;
    nodal_data.reinit(grid.make_partitioner(n_components));
    if (boundary_conditions.needs_material_extent())
      material_extent.reinit(grid.make_partitioner(2 * dim));
    nodal_mass.assign(grid.n_relevant_nodes(), 0.);
    old_velocity.assign(grid.n_relevant_nodes() * dim, 0.);
    new_velocity.assign(grid.n_relevant_nodes() * dim, 0.);
    // ghost cells scatter only to the per-body fields (contact under MPI)
    scatter_colouring.reinit(grid, use_contact && parallel);
  }

  template <int dim>
  void
  Simulator<dim>::adapt_mesh()
  {
    travel_since_adaptation = 0;
    std::vector<typename MeshRefinement<dim>::CellContent> contents(
      triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &particle : particle_handler->particles_in_cell(cell))
          contents[cell->active_cell_index()].add(
            static_cast<unsigned int>(particle.get_properties()[layout.body]));
    // refine at once; coarsening only saves work, so it waits for a
    // refinement or for every fourth adaptation (each one rebuilds the
    // forest, the node numbering and the hanging-node tables)
    const auto flagged     = mesh_refinement->flag_cells(triangulation, contents);
    const bool coarsen_now = ++adaptations_without_change >= 4 && flagged.coarsen > 0;
    if (flagged.refine == 0 && !coarsen_now)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            cell->clear_coarsen_flag();
        return;
      }
    adaptations_without_change = 0;
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
  Simulator<dim>::seed_body(const unsigned int         b,
                            const OwnedCellStrip<dim> &owned_cells,
                            types::particle_index &    next_id)
  {
    const BodyParameters<dim> &body     = parameters.bodies[b];
    const Material &           material = *materials[b];
    const unsigned int         k        = body.particles_per_direction;
    const auto                 box      = body.bounding_box();
    const Point<dim>           top      = body.top_point(parameters.gravity);
    const Point<dim>           centre =
      body.shape == BodyParameters<dim>::Shape::disk ?
        body.center :
        Point<dim>((Tensor<1, dim>(body.lower_corner) + Tensor<1, dim>(body.upper_corner)) / 2.);

    std::vector<double> properties(layout.n_properties(), 0.);
    unsigned int        n_sub = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_sub *= k;

    owned_cells.for_each_overlapping(box, [&](const auto &strip_cell) {
        const auto &     cell  = strip_cell.cell;
        const Point<dim> lower = strip_cell.lower;
        const Point<dim> upper = strip_cell.upper;
        const double sub_volume = cell->measure() / n_sub;
        for (unsigned int i = 0; i < n_sub; ++i)
          {
            const Point<dim> reference = seeding_point<dim>(i, k);
            Point<dim>       x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = lower[d] + reference[d] * (upper[d] - lower[d]);
            if (!body.contains(x))
              continue;
            std::fill(properties.begin(), properties.end(), 0.);
            properties[layout.mass]           = material.density() * sub_volume;
            properties[layout.initial_volume] = sub_volume;
            properties[layout.body]           = b;
            // v = v0 + omega x (x - c)
            Tensor<1, 3> r, omega_cross_r;
            for (unsigned int d = 0; d < dim; ++d)
              r[d] = x[d] - centre[d];
            omega_cross_r = cross_product_3d(body.angular_velocity, r);
            for (unsigned int d = 0; d < dim; ++d)
              properties[layout.velocity + d] = body.velocity[d] + omega_cross_r[d];
            for (unsigned int d = 0; d < dim; ++d)
              properties[layout.deformation + d * dim + d] = 1.;
            if (body.lithostatic_stress)
              {
                // p = rho g . (x - x_top) >= 0, sigma = -p I
                const double pressure =
                  material.density() * (parameters.gravity * (x - top));
                for (unsigned int d = 0; d < 3; ++d)
                  properties[layout.stress + d] = -pressure;
              }
            particle_handler->insert_particle(x, reference, next_id++, cell,
                                              make_array_view(properties));
          }
      });
  }

  template <int dim>
  double
  Simulator<dim>::compute_time_step() const
  {
    double dt = parameters.cfl * grid.minimum_cell_size() / max_signal_speed;
    if (time + dt > parameters.end_time)
      dt = parameters.end_time - time;
    return dt;
  }

  template <int dim>
  void
  Simulator<dim>::find_contact_nodes()
  {
    TimerOutput::Scope scope(timer, "find contact nodes (in particles to grid)");
    body_fields.clear(grid.n_relevant_nodes());
    // blocks of one colour share no node, so their threads mark different
    // nodes; the extra (node, body) pairs are collected per range of cells
    // and sorted by allocate(), so the table does not depend on the threads
    std::mutex mutex;
    scatter_colouring.for_each_cell_range([&](const auto begin, const auto end) {
      std::vector<unsigned int>                          bodies;
      std::vector<std::pair<unsigned int, unsigned int>> extra;
      for (auto cell = begin; cell != end; ++cell)
        {
          const auto particles = particle_handler->particles_in_cell(*cell);
          if (particles.begin() == particles.end())
            continue;
          bodies.clear();
          for (const auto &particle : particles)
            {
              const unsigned int body =
                static_cast<unsigned int>(particle.get_properties()[layout.body]);
              if (std::find(bodies.begin(), bodies.end(), body) == bodies.end())
                bodies.push_back(body);
            }
          const auto [nodes, n_nodes] = grid.cell_nodes(grid.cell_data(*cell));
          for (unsigned int k = 0; k < n_nodes; ++k)
            for (const unsigned int body : bodies)
              body_fields.add(nodes[k], body, extra);
        }
      if (!extra.empty())
        {
          std::lock_guard<std::mutex> lock(mutex);
          body_fields.add_extra_bodies(extra);
        }
    });
    body_fields.allocate();
  }

  template <int dim>
  void
  Simulator<dim>::particles_to_grid(const bool with_forces)
  {
    constexpr unsigned int n_components = 1 + 2 * dim;
    if (use_contact)
      {
        if (with_forces)
          find_contact_nodes();
        else
          body_fields.zero_momenta();
      }
    const bool with_traction =
      parameters.contact.model == ContactParameters::Model::bardenhagen_2001;

    // the share of one particle in the per-body fields of the contact
    // nodes of its cell (owned and, under MPI, ghost particles)
    const auto scatter_to_bodies = [&](const auto &                   particle,
                                       const typename Grid<dim>::Shape &shape,
                                       const Tensor<2, dim> &         volume_stress) {
      const auto         props = particle.get_properties();
      const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
      const double       mass  = props[layout.mass];
      for (unsigned int v = 0; v < shape.n_nodes; ++v)
        {
          if (!body_fields.is_contact_node(shape.nodes[v]))
            continue;
          auto &       record = body_fields.record(shape.nodes[v], body);
          const double weight = mass * shape.values[v];
          record.mass += weight;
          for (unsigned int d = 0; d < dim; ++d)
            record.momentum[d] += weight * props[layout.velocity + d];
          if (!with_forces)
            continue;
          record.force -= volume_stress * shape.gradients[v];
          record.mass_gradient += mass * shape.gradients[v];
          if (with_traction)
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                record.mass_stress[i][j] +=
                  weight * props[layout.stress + ParticleLayout<dim>::stress_component(i, j)];
        }
    };
    const auto cell_touches_contact = [&](const typename Grid<dim>::CellData &data) {
      const auto [nodes, n_nodes] = grid.cell_nodes(data);
      for (unsigned int k = 0; k < n_nodes; ++k)
        if (body_fields.is_contact_node(nodes[k]))
          return true;
      return false;
    };
    nodal_data = 0.;
    nodal_data.zero_out_ghost_values();
    double *const grid_values = nodal_data.get_values();

    // the material extent around each node for friction walls that act
    // only where material reaches them (lowest coordinate, minus highest)
    const bool    with_extent = with_forces && material_extent.size() > 0;
    double *const extent      = with_extent ? material_extent.get_values() : nullptr;
    if (with_extent)
      std::fill(extent,
                extent + material_extent.get_partitioner()->locally_owned_size() +
                  material_extent.get_partitioner()->n_ghost_indices(),
                std::numeric_limits<double>::max());

    // one cell's particles: everything for a locally owned cell, only the
    // per-body fields for a ghost cell (its particles complete the contact
    // nodes of locally owned cells)
    const auto scatter_cell = [&](const typename Triangulation<dim>::active_cell_iterator &cell,
                                  typename Grid<dim>::Shape &                             shape) {
      const auto particles = particle_handler->particles_in_cell(cell);
      if (particles.begin() == particles.end())
        return;
      const typename Grid<dim>::CellData &data = grid.cell_data(cell);
      const bool near_contact = use_contact && cell_touches_contact(data);
      if (!cell->is_locally_owned())
        {
          if (near_contact)
            for (const auto &particle : particles)
              {
                const auto props = particle.get_properties();
                grid.evaluate(data, particle.get_reference_location(), shape);
                scatter_to_bodies(particle,
                                  shape,
                                  with_forces ? ParticleLayout<dim>::volume_stress(props) :
                                                Tensor<2, dim>());
              }
          return;
        }
      for (const auto &particle : particles)
        {
          const auto props = particle.get_properties();
          grid.evaluate(data, particle.get_reference_location(), shape);
          const double mass = props[layout.mass];
          if (with_extent)
            {
              const Tensor<2, dim> F = ParticleLayout<dim>::deformation_gradient(props);
              // half the edge of the point's current volume
              const double half =
                0.5 * std::pow(determinant(F) * props[layout.initial_volume], 1. / dim);
              const Point<dim> x = particle.get_location();
              for (unsigned int v = 0; v < shape.n_nodes; ++v)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    double *const e = extent + shape.nodes[v] * 2 * dim + 2 * d;
                    e[0]            = std::min(e[0], x[d] - half);
                    e[1]            = std::min(e[1], -(x[d] + half));
                  }
            }
          // internal force -V sigma . grad N
          const Tensor<2, dim> volume_stress =
            with_forces ? ParticleLayout<dim>::volume_stress(props) : Tensor<2, dim>();
          if (near_contact)
            scatter_to_bodies(particle, shape, volume_stress);
          for (unsigned int v = 0; v < shape.n_nodes; ++v)
            {
              double *const node   = grid_values + shape.nodes[v] * n_components;
              const double  weight = mass * shape.values[v];
              node[0] += weight;
              for (unsigned int d = 0; d < dim; ++d)
                node[1 + d] += weight * props[layout.velocity + d];
              if (with_forces)
                {
                  const Tensor<1, dim> force = -(volume_stress * shape.gradients[v]);
                  for (unsigned int d = 0; d < dim; ++d)
                    node[1 + dim + d] += force[d];
                }
            }
        }
    };
    // Blocks of cells of one colour share no node: they scatter
    // concurrently without locks, and each node adds up its contributions
    // in an order that does not depend on the number of threads (one
    // thread runs the same order; cell_colouring.h).
    scatter_colouring.for_each_cell_range([&](const auto begin, const auto end) {
      typename Grid<dim>::Shape shape;
      for (auto cell = begin; cell != end; ++cell)
        scatter_cell(*cell, shape);
    });
    nodal_data.compress(VectorOperation::add);
    nodal_data.update_ghost_values();
    if (with_extent)
      {
        material_extent.compress(VectorOperation::min);
        material_extent.update_ghost_values();
      }
  }

  template <int dim>
  void
  Simulator<dim>::update_grid_velocities(const bool with_forces)
  {
    constexpr unsigned int n_components = 1 + 2 * dim;
    const double *const    grid_values  = nodal_data.get_values();
    // node by node: threads change nothing
    parallel::apply_to_subranges(
      0u,
      grid.n_relevant_nodes(),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int i = begin; i < end; ++i)
          {
            const double *const node = grid_values + i * n_components;
            const double        mass = node[0];
            nodal_mass[i]            = mass;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double v = mass > 0. ? node[1 + d] / mass : 0.;
                if (with_forces)
                  {
                    old_velocity[i * dim + d] = v;
                    new_velocity[i * dim + d] =
                      mass > 0. ? v + time_step * (node[1 + dim + d] / mass +
                                                   parameters.gravity[d]) :
                                  0.;
                  }
                else
                  new_velocity[i * dim + d] = v;
              }
          }
      },
      4096);
    double work = 0;
    if (!boundary_conditions.empty())
      {
        if (with_forces && material_extent.size() > 0)
          boundary_conditions.set_material_extent(material_extent.get_values(), time_step);
        if (with_forces)
          work = boundary_conditions.apply(new_velocity,
                                           nodal_mass,
                                           nodal_data.get_partitioner()->locally_owned_size() /
                                             n_components);
        else
          boundary_conditions.apply_to_remapped(new_velocity, nodal_mass);
      }
    // only moving walls do work: no reduction over ranks otherwise; every
    // rank takes part, also one without boundary nodes
    if (with_forces && boundary_conditions.has_moving_walls())
      boundary_work += Utilities::MPI::sum(work, communicator);
    if (use_contact)
      update_body_velocities(with_forces);
  }

  template <int dim>
  void
  Simulator<dim>::update_body_velocities(const bool with_forces)
  {
    TimerOutput::Scope scope(timer, "contact (in grid update)");
    // node by node: threads change nothing
    const std::vector<unsigned int> &contact_nodes = body_fields.get_contact_nodes();
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(contact_nodes.size()),
      [&](const unsigned int first, const unsigned int last) {
        for (unsigned int i = first; i < last; ++i)
          {
            const auto [begin, end] = body_fields.node_records(contact_nodes[i]);
            for (auto *r = begin; r != end; ++r)
              {
                if (r->mass <= 0.)
                  continue;
                const Tensor<1, dim> velocity = r->momentum / r->mass;
                if (with_forces)
                  {
                    r->old_velocity = velocity;
                    r->new_velocity =
                      velocity + time_step * (r->force / r->mass + parameters.gravity);
                  }
                else
                  r->new_velocity = velocity;
              }
          }
      },
      256);
    const unsigned int n_owned_nodes =
      nodal_data.get_partitioner()->locally_owned_size() / (1 + 2 * dim);
    if (with_forces ? parameters.contact.on_momentum_update :
                      parameters.contact.on_strain_update)
      contact->apply(body_fields, grid.node_spacing(), time_step, n_owned_nodes, with_forces);
    if (!boundary_conditions.empty())
      boundary_conditions.apply_to_bodies(body_fields, !with_forces);
  }

  template <int dim>
  void
  Simulator<dim>::grid_to_particles(const bool update_positions,
                                    const bool update_stresses)
  {
    const double alpha = parameters.pic_fraction;
    if (update_stresses)
      velocity_gradients.resize(particle_handler->get_max_local_particle_index());
    const std::vector<typename Triangulation<dim>::active_cell_iterator> cells =
      cells_with_particles();

    // what a range of cells reports; maxima and the failure with the lowest
    // particle id do not depend on how the cells are split among threads
    struct Report
    {
      double                max_speed = 0, max_particle_speed = 0;
      bool                  failed = false, too_far = false;
      types::particle_index failed_id = numbers::invalid_unsigned_int;
      Point<dim>            failure_location;

      void
      fail(const bool distance, const types::particle_index id, const Point<dim> &x)
      {
        if ((failed || too_far) && id >= failed_id)
          return;
        (distance ? too_far : failed) = true;
        failed_id                     = id;
        failure_location              = x;
      }
    };
    Report     report;
    std::mutex report_mutex;

    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(cells.size()),
      [&](const unsigned int begin, const unsigned int end) {
        Report                    local;
        typename Grid<dim>::Shape shape;
        for (unsigned int c = begin; c < end; ++c)
          {
            const typename Grid<dim>::CellData &data = grid.cell_data(cells[c]);
            for (auto &particle : particle_handler->particles_in_cell(cells[c]))
              {
                const auto         props = particle.get_properties();
                const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
                grid.evaluate(data, particle.get_reference_location(), shape);
                Tensor<1, dim> velocity_change, grid_velocity;
                Tensor<2, dim> L;
                for (unsigned int v = 0; v < shape.n_nodes; ++v)
                  {
                    const unsigned int node  = shape.nodes[v];
                    const double *     v_new = &new_velocity[node * dim];
                    const double *     v_old = &old_velocity[node * dim];
                    // each particle reads its own body's field
                    if (use_contact && body_fields.is_contact_node(node))
                      {
                        const auto &record = body_fields.record(node, body);
                        v_new              = &record.new_velocity[0];
                        v_old              = &record.old_velocity[0];
                      }
                    const double N = shape.values[v];
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        if (update_positions)
                          {
                            velocity_change[d] += N * (v_new[d] - v_old[d]);
                            grid_velocity[d] += N * v_new[d];
                          }
                        if (update_stresses)
                          for (unsigned int e = 0; e < dim; ++e)
                            L[d][e] += v_new[d] * shape.gradients[v][e];
                      }
                  }
                if (update_positions)
                  {
                    double speed2 = 0;
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        double &v = props[layout.velocity + d];
                        v = (1. - alpha) * (v + velocity_change[d]) + alpha * grid_velocity[d];
                        speed2 += v * v;
                      }
                    // a particle may not cross more than one cell per step
                    const Tensor<1, dim> displacement = time_step * grid_velocity;
                    Point<dim>           location     = particle.get_location();
                    for (unsigned int d = 0; d < dim; ++d)
                      if (std::abs(displacement[d]) * data.inverse_h[d] > 1.)
                        local.fail(true, particle.get_id(), location);
                    location += displacement;
                    particle.set_location(location);
                    local.max_speed =
                      std::max(local.max_speed, std::sqrt(speed2) + body_wave_speed[body]);
                    local.max_particle_speed = std::max(local.max_particle_speed, std::sqrt(speed2));
                    if (!std::isfinite(speed2))
                      local.fail(false, particle.get_id(), location);
                  }
                if (update_stresses)
                  velocity_gradients[particle.get_local_index()] = L;
              }
          }
        std::lock_guard<std::mutex> lock(report_mutex);
        report.max_speed          = std::max(report.max_speed, local.max_speed);
        report.max_particle_speed = std::max(report.max_particle_speed, local.max_particle_speed);
        if (local.failed || local.too_far)
          report.fail(local.too_far, local.failed_id, local.failure_location);
      },
      16);
    const double max_speed = report.max_speed, max_particle_speed = report.max_particle_speed;
    const bool   failed = report.failed, too_far = report.too_far;
    const Point<dim> failure_location = report.failure_location;
    if (update_stresses)
      update_particle_stresses(cells);
    if (update_positions)
      {
        if (mesh_refinement)
          {
            // the fastest point's travel since the last adaptation
            std::vector<double> speeds = {max_speed, max_particle_speed};
            Utilities::MPI::max(speeds, communicator, speeds);
            max_signal_speed = speeds[0];
            travel_since_adaptation += speeds[1] * time_step;
          }
        else
          max_signal_speed = Utilities::MPI::max(max_speed, communicator);
      }
    report_failure(failed, failure_location, "a velocity or stress is not a finite number (NaN or infinity)");
    report_failure(too_far, failure_location,
                   "a material point moved more than one cell in one step "
                   "(reduce 'Time/CFL number')");
  }

  template <int dim>
  std::vector<typename Triangulation<dim>::active_cell_iterator>
  Simulator<dim>::cells_with_particles() const
  {
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && particle_handler->n_particles_in_cell(cell) > 0)
        cells.push_back(cell);
    return cells;
  }

  template <int dim>
  void
  Simulator<dim>::update_particle_stresses(
    const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells)
  {
    // The cells with particles, then a threaded loop over them: each
    // particle's F and stress depend only on its own data and L, so the
    // result does not depend on the number of threads.
    TimerOutput::Scope scope(timer, "stress update (in grid to particles)");
    std::mutex            failure_mutex;
    types::particle_index failed_id = numbers::invalid_unsigned_int;
    Point<dim>            failure_location;
    bool                  failed = false;
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(cells.size()),
      [&](const unsigned int begin, const unsigned int end) {
        Tensor<2, dim> identity;
        for (unsigned int d = 0; d < dim; ++d)
          identity[d][d] = 1.;
        for (unsigned int c = begin; c < end; ++c)
          for (auto &particle : particle_handler->particles_in_cell(cells[c]))
            {
              const auto           props = particle.get_properties();
              const unsigned int   body  = static_cast<unsigned int>(props[layout.body]);
              const Tensor<2, dim> L     = velocity_gradients[particle.get_local_index()];
              Tensor<2, dim>       F     = ParticleLayout<dim>::deformation_gradient(props);
              F                          = (identity + time_step * L) * F;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  props[layout.deformation + i * dim + j] = F[i][j];
              SymmetricTensor<2, 3> stress = ParticleLayout<dim>::stress_tensor(props);
              materials[body]->update_stress(embed<dim>(L, 0.),
                                             embed<dim>(F, 1.),
                                             time_step,
                                             stress,
                                             layout.n_history > 0 ? &props[layout.history] :
                                                                    nullptr);
              bool finite = true;
              for (unsigned int c = 0; c < 6; ++c)
                {
                  props[layout.stress + c] = stress.access_raw_entry(c);
                  finite = finite && std::isfinite(stress.access_raw_entry(c));
                }
              if (!finite)
                {
                  // report the failing particle with the lowest id, whatever
                  // the threads' order
                  std::lock_guard<std::mutex> lock(failure_mutex);
                  if (!failed || particle.get_id() < failed_id)
                    {
                      failed           = true;
                      failed_id        = particle.get_id();
                      failure_location = particle.get_location();
                    }
                }
            }
      },
      16);
    report_failure(failed, failure_location,
                   "a velocity or stress is not a finite number (NaN or infinity)");
  }

  template <int dim>
  unsigned int
  Simulator<dim>::cell_weight(const typename Triangulation<dim>::cell_iterator &cell,
                              const typename Triangulation<dim>::CellStatus     status) const
  {
    unsigned int n_particles = 0;
    switch (status)
      {
        case Triangulation<dim>::CELL_PERSIST:
          n_particles = particle_handler->n_particles_in_cell(cell);
          break;
        case Triangulation<dim>::CELL_REFINE:
          // called for each future child with the parent: an equal share
          n_particles = particle_handler->n_particles_in_cell(cell) /
                        GeometryInfo<dim>::max_children_per_cell;
          break;
        case Triangulation<dim>::CELL_COARSEN:
          for (const auto &child : cell->child_iterators())
            n_particles += particle_handler->n_particles_in_cell(child);
          break;
        default:
          Assert(false, ExcInternalError());
      }
    return cell_cost + particle_cost * n_particles;
  }

  template <int dim>
  void
  Simulator<dim>::connect_cell_weights()
  {
    // from now on p4est weighs the cells by their material points at every
    // repartition: rebalance() and adaptation
    weight_connection = triangulation.signals.weight.connect(
      [this](const typename Triangulation<dim>::cell_iterator &cell,
             const typename Triangulation<dim>::CellStatus     status) {
        return cell_weight(cell, status);
      });
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
  Simulator<dim>::print_balance() const
  {
    const auto [fewest, most] = particles_per_rank();
    const unsigned long long cells     = triangulation.n_locally_owned_active_cells();
    const unsigned long long particles = particle_handler->n_locally_owned_particles();
    const unsigned long long work      = cell_cost * cells + particle_cost * particles;
    const unsigned long long ghost_nodes =
      grid.n_relevant_nodes() - nodal_data.get_partitioner()->locally_owned_size() / (1 + 2 * dim);
    pcout << "particles per rank: " << fewest << " .. " << most
          << "; cells per rank: " << Utilities::MPI::min(cells, communicator) << " .. "
          << Utilities::MPI::max(cells, communicator) << "; ghost nodes per rank: "
          << Utilities::MPI::min(ghost_nodes, communicator) << " .. "
          << Utilities::MPI::max(ghost_nodes, communicator) << "; work per rank (" << cell_cost
          << " per cell + " << particle_cost << " per material point): "
          << Utilities::MPI::min(work, communicator) << " .. "
          << Utilities::MPI::max(work, communicator) << std::endl;
  }

  template <int dim>
  std::pair<unsigned long long, unsigned long long>
  Simulator<dim>::particles_per_rank() const
  {
    const unsigned long long local = particle_handler->n_locally_owned_particles();
    return {Utilities::MPI::min(local, communicator), Utilities::MPI::max(local, communicator)};
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
    message << "the run stopped at step " << step_number << ", time "
            << std::setprecision(10) << time << ": " << what
            << ", at position " << to_string(where);
    throw std::runtime_error(message.str());
  }

  template <int dim>
  void
  Simulator<dim>::sort_particles()
  {
    const unsigned long long before = particle_handler->n_global_particles();
    lost_particles = 0;
    particle_handler->sort_particles_into_subdomains_and_cells();
    if (use_contact && parallel)
      particle_handler->exchange_ghost_particles(true);
    const unsigned long long lost = Utilities::MPI::sum(lost_particles, communicator);
    if (lost > 0)
      {
        if (!parameters.allow_outflow)
          report_failure(lost_particles > 0, lost_location,
                         std::to_string(lost) + " material point(s) left the grid "
                         "(set 'Output/Allow outflow = true' to let them go)");
        pcout << "step " << step_number << ": " << lost
              << " material point(s) left the grid" << std::endl;
      }
    (void)before;
  }

  template <int dim>
  void
  Simulator<dim>::step()
  {
    if (!initialized)
      initialize();
    time_step = compute_time_step();
    const bool usl = parameters.update_scheme == UpdateScheme::usl;
    {
      TimerOutput::Scope scope(timer, "particles to grid");
      particles_to_grid(true);
    }
    {
      TimerOutput::Scope scope(timer, "grid update and boundaries");
      update_grid_velocities(true);
    }
    if (usl)
      {
        TimerOutput::Scope scope(timer, "grid to particles and stresses");
        grid_to_particles(true, true);
      }
    else
      {
        {
          TimerOutput::Scope scope(timer, "grid to particles and stresses");
          grid_to_particles(true, false);
        }
        {
          TimerOutput::Scope scope(timer, "particles to grid");
          if (use_contact && parallel)
            particle_handler->update_ghost_particles();
          particles_to_grid(false);
        }
        {
          TimerOutput::Scope scope(timer, "grid update and boundaries");
          update_grid_velocities(false);
        }
        TimerOutput::Scope scope(timer, "grid to particles and stresses");
        grid_to_particles(false, true);
      }
    {
      TimerOutput::Scope scope(timer, "sort particles");
      sort_particles();
    }
    time += time_step;
    ++step_number;
    // adapt every 'Refinement interval' steps, or (interval 0) when a point
    // may have moved half of the smallest cell since the last adaptation
    const unsigned int interval = parameters.refinement.interval;
    if (mesh_refinement &&
        (interval > 0 ? step_number % interval == 0 :
                        travel_since_adaptation >= 0.5 * grid.minimum_cell_size()))
      {
        TimerOutput::Scope scope(timer, "mesh adaptation");
        adapt_mesh();
      }
  }

  template <int dim>
  Statistics<dim>
  Simulator<dim>::compute_statistics() const
  {
    const unsigned int n_bodies = parameters.bodies.size();
    // kinetic, strain, gravity, momentum (dim), per body: mass, m x, m v
    // per body: mass, m x (dim), m v (dim), angular momentum about the
    // origin (3), inertia tensor about the origin (9)
    constexpr unsigned int per_body = 1 + 2 * dim + 3 + 9;
    const unsigned int     n_values = 3 + dim + n_bodies * per_body;
    std::vector<double>    sums(n_values, 0.);
    for (const auto &particle : *particle_handler)
      {
        const auto         props = particle.get_properties();
        const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
        const double       mass  = props[layout.mass];
        const Point<dim>   x     = particle.get_location();
        double             v2    = 0;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += props[layout.velocity + d] * props[layout.velocity + d];
        sums[0] += 0.5 * mass * v2;
        sums[1] += props[layout.initial_volume] *
                   materials[body]->strain_energy_density(
                     ParticleLayout<dim>::stress_tensor(props),
                     embed<dim>(ParticleLayout<dim>::deformation_gradient(props), 1.));
        sums[2] -= mass * (parameters.gravity * x);
        double *const body_sums = &sums[3 + dim + body * per_body];
        body_sums[0] += mass;
        Tensor<1, 3> r, v;
        for (unsigned int d = 0; d < dim; ++d)
          {
            sums[3 + d] += mass * props[layout.velocity + d];
            body_sums[1 + d] += mass * x[d];
            body_sums[1 + dim + d] += mass * props[layout.velocity + d];
            r[d] = x[d];
            v[d] = props[layout.velocity + d];
          }
        const Tensor<1, 3> angular = mass * cross_product_3d(r, v);
        for (unsigned int d = 0; d < 3; ++d)
          body_sums[1 + 2 * dim + d] += angular[d];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            body_sums[4 + 2 * dim + 3 * i + j] += mass * ((i == j ? r * r : 0.) - r[i] * r[j]);
      }
    Utilities::MPI::sum(sums, communicator, sums);

    Statistics<dim> s;
    s.kinetic_energy = sums[0];
    s.strain_energy  = sums[1];
    s.gravity_energy = sums[2];
    for (unsigned int d = 0; d < dim; ++d)
      s.momentum[d] = sums[3 + d];
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const double *const body_sums = &sums[3 + dim + b * per_body];
        const double        mass      = body_sums[0];
        s.body_mass.push_back(mass);
        Point<dim>     x;
        Tensor<1, dim> v;
        Tensor<1, 3>   x3, v3, angular;
        Tensor<2, 3>   inertia;
        for (unsigned int d = 0; d < dim; ++d)
          {
            x[d] = x3[d] = body_sums[1 + d] / mass;
            v[d] = v3[d] = body_sums[1 + dim + d] / mass;
          }
        s.body_position.push_back(x);
        s.body_velocity.push_back(v);
        // shift angular momentum and inertia to the centre of mass:
        // L_c = L_o - M x_c x v_c, I_c = I_o - M (|x_c|^2 1 - x_c x_c)
        for (unsigned int i = 0; i < 3; ++i)
          {
            angular[i] = body_sums[1 + 2 * dim + i];
            for (unsigned int j = 0; j < 3; ++j)
              inertia[i][j] = body_sums[4 + 2 * dim + 3 * i + j] -
                              mass * ((i == j ? x3 * x3 : 0.) - x3[i] * x3[j]);
          }
        angular -= mass * cross_product_3d(x3, v3);
        Tensor<1, 3> omega;
        if (dim == 2)
          omega[2] = inertia[2][2] > 0 ? angular[2] / inertia[2][2] : 0.;
        else if (determinant(inertia) > 0)
          omega = invert(inertia) * angular;
        s.body_angular_velocity.push_back(omega);
      }
    s.n_particles = particle_handler->n_global_particles();
    s.n_cells     = triangulation.n_global_active_cells();
    if (use_contact)
      {
        s.contact_heat = Utilities::MPI::sum(contact->frictional_heat, communicator);
        for (const auto &force : contact->pair_forces)
          s.pair_forces.push_back(Utilities::MPI::sum(force, communicator));
      }
    return s;
  }

  template <int dim>
  void
  Simulator<dim>::check_energy(const Statistics<dim> &s)
  {
    // what the scene can hold: the initial energy plus the largest release
    // of gravitational energy so far and the work of moving walls (a body
    // rising again after a bounce gives no new energy)
    largest_gravity_release =
      std::max(largest_gravity_release, initial_gravity_energy - s.gravity_energy);
    const double budget =
      initial_energy + largest_gravity_release + std::max(boundary_work, 0.) + energy_floor;
    const double energy = s.kinetic_energy + s.strain_energy;
    if (!(energy <= parameters.energy_growth_limit * budget))
      {
        std::ostringstream message;
        message << "the run became unstable at step " << step_number
                << ", time " << std::setprecision(10) << time
                << ": kinetic + strain energy " << energy
                << " exceeds 'Output/Energy growth limit' = "
                << parameters.energy_growth_limit << " times the energy "
                << "supplied (" << budget << ")";
        // locate the fastest particle
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
        const double global_fastest = Utilities::MPI::max(fastest, communicator);
        const unsigned int rank = Utilities::MPI::min(
          fastest == global_fastest ? Utilities::MPI::this_mpi_process(communicator) :
                                      numbers::invalid_unsigned_int,
          communicator);
        where = Utilities::MPI::broadcast(communicator, where, rank);
        message << "; fastest material point at " << to_string(where);
        throw std::runtime_error(message.str());
      }
  }

  template <int dim>
  void
  Simulator<dim>::write_particles()
  {
    TimerOutput::Scope     scope(timer, "output");
    Particles::DataOut<dim> data_out;
    std::vector<std::string> history_names;
    for (const auto &material : materials)
      if (material->n_history() == layout.n_history)
        history_names = material->history_names();
    const std::vector<std::string> names = layout.names(history_names);
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(names.size(), DataComponentInterpretation::component_is_scalar);
    for (unsigned int d = 0; d < dim; ++d)
      interpretation[layout.velocity + d] = DataComponentInterpretation::component_is_part_of_vector;
    data_out.build_patches(*particle_handler, names, interpretation);
    const unsigned int counter = output_counter++;
    particle_series.write(data_out,
                          particle_handler->n_locally_owned_particles() > 0,
                          counter,
                          time,
                          communicator);
    if (use_contact && parameters.contact_node_output)
      write_contact_nodes(counter);
    if (grid_output)
      grid_output->write(grid, *particle_handler, counter, time, base_level);
    next_output_time = time + parameters.output_interval;
  }

  template <int dim>
  void
  Simulator<dim>::write_contact_nodes(const unsigned int counter)
  {
    // one point per body record at each locally owned contact node, as an
    // unstructured grid of vertices (ASCII: these files are small)
    const unsigned int n_owned_nodes =
      nodal_data.get_partitioner()->locally_owned_size() / (1 + 2 * dim);
    std::vector<const typename BodyFields<dim>::Record *> records;
    std::vector<unsigned int>                             nodes;
    for (const unsigned int node : body_fields.get_contact_nodes())
      if (node < n_owned_nodes)
        {
          const auto [begin, end] = body_fields.node_records(node);
          for (auto *r = begin; r != end; ++r)
            {
              records.push_back(r);
              nodes.push_back(node);
            }
        }
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const std::string  stem    = "contact_nodes_" + Utilities::int_to_string(counter, 5);
    const auto         piece   = [&](const unsigned int r) {
      return stem + "." + Utilities::int_to_string(r, 4) + ".vtu";
    };
    {
      std::ofstream out(parameters.output_directory + "/" + piece(rank));
      out << std::setprecision(9);
      const unsigned int n = records.size();
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
          << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
          << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const unsigned int node : nodes)
        {
          const Point<dim> &x = grid.node_positions()[node];
          out << x[0] << ' ' << x[1] << ' ' << (dim == 3 ? x[dim - 1] : 0.) << '\n';
        }
      out << "</DataArray></Points>\n<Cells>\n"
          << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << i << '\n';
      out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << i + 1 << '\n';
      out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << "1\n";
      out << "</DataArray>\n</Cells>\n<PointData>\n"
          << "<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
      for (const auto *r : records)
        out << r->body << '\n';
      out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"state\" format=\"ascii\">\n";
      for (const auto *r : records)
        out << r->state << '\n';
      out << "</DataArray>\n";
      for (const std::string field : {"normal", "contact_force"})
        {
          out << "<DataArray type=\"Float64\" Name=\"" << field
              << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
          for (const auto *r : records)
            {
              const Tensor<1, dim> &t = field == "normal" ? r->normal : r->contact_force;
              out << t[0] << ' ' << t[1] << ' ' << (dim == 3 ? t[dim - 1] : 0.) << '\n';
            }
          out << "</DataArray>\n";
        }
      out << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    }
    if (rank != 0)
      return;
    {
      std::ofstream out(parameters.output_directory + "/" + stem + ".pvtu");
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\">\n"
          << "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints><PDataArray type=\"Float64\" "
             "NumberOfComponents=\"3\"/></PPoints>\n<PPointData>\n"
          << "<PDataArray type=\"Int32\" Name=\"body\"/>\n<PDataArray type=\"Int32\" Name=\"state\"/>\n"
          << "<PDataArray type=\"Float64\" Name=\"normal\" NumberOfComponents=\"3\"/>\n"
          << "<PDataArray type=\"Float64\" Name=\"contact_force\" NumberOfComponents=\"3\"/>\n"
          << "</PPointData>\n";
      for (unsigned int r = 0; r < n_ranks; ++r)
        out << "<Piece Source=\"" << piece(r) << "\"/>\n";
      out << "</PUnstructuredGrid>\n</VTKFile>\n";
    }
    contact_node_files.emplace_back(time, stem + ".pvtu");
    std::ofstream pvd(parameters.output_directory + "/contact_nodes.pvd");
    DataOutBase::write_pvd_record(pvd, contact_node_files);
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
    const double       first_time = time;
    const unsigned int first_step = step_number;
    while (!finished())
      {
        step();
        const bool last = finished();
        const bool progress = step_number % parameters.progress_interval == 0 || last;
        if (step_number % parameters.statistics_interval == 0 || progress)
          {
            TimerOutput::Scope    scope(timer, "statistics");
            const Statistics<dim> s = compute_statistics();
            check_energy(s);
            if (step_number % parameters.statistics_interval == 0 || last)
              statistics_file->write_row(step_number, time, time_step, boundary_work, s);
            if (progress)
              {
                const double elapsed = wall.wall_time();
                double       fraction = (time - first_time) / (parameters.end_time - first_time);
                if (parameters.maximum_steps > first_step)
                  fraction = std::max(fraction,
                                      double(step_number - first_step) /
                                        (parameters.maximum_steps - first_step));
                pcout << "step " << std::setw(7) << step_number << "  t = " << std::setprecision(4)
                      << std::scientific << time << "  dt = " << time_step
                      << "  E_kin = " << s.kinetic_energy << "  E_strain = " << s.strain_energy
                      << std::fixed << std::setprecision(1) << "  wall " << elapsed << " s, ~"
                      << elapsed * (1. - fraction) / std::max(fraction, 1e-12) << " s left"
                      << std::defaultfloat << std::setprecision(6) << std::endl;
              }
          }
        const bool output_due = write_output && time >= next_output_time * (1 - 1e-12);
        if (output_due)
          write_particles();
        // the checkpoint holds the state an uninterrupted run has at this
        // step: before the extra particle output of the last step
        if (write_checkpoints && (step_number % parameters.checkpoint_interval == 0 || last))
          save_checkpoint();
        if (write_output && last && !output_due)
          write_particles();
      }
    if (parameters.print_timings)
      timer.print_summary();
    if (!parameters.output_directory.empty())
      pcout << "Output written to " << parameters.output_directory << "/ (statistics.csv"
            << (write_output ? ", " + particle_series.series_file() : "")
            << (write_output && grid_output ? ", " + grid_output->series.series_file() : "")
            << (write_checkpoints ? ", checkpoint/" : "") << ")" << std::endl;
    pcout << "Finished " << step_number << " steps to t = " << time << " in "
          << wall.wall_time() << " s wall time" << std::endl;
  }

  template class Simulator<2>;
  template class Simulator<3>;
} // namespace sable::mpm
