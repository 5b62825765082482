#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <sable/mpm/contact/multi_body_contact.h>
#include <sable/mpm/contact/per_body_sums.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace sable::mpm
{
  namespace
  {
    /// The rotation R of the polar decomposition F = R U (det F > 0): in 2D
    /// in closed form, in 3D by Higham's iteration X <- (X + X^-T) / 2.
    template <int dim>
    Tensor<2, dim>
    rotation_of(const Tensor<2, dim> &F)
    {
      Tensor<2, dim> R;
      if constexpr (dim == 2)
        {
          const double c = F[0][0] + F[1][1], s = F[1][0] - F[0][1];
          const double norm = std::hypot(c, s);
          if (norm == 0)
            return unit_symmetric_tensor<dim>();
          R[0][0] = R[1][1] = c / norm;
          R[1][0]           = s / norm;
          R[0][1]           = -s / norm;
        }
      else
        {
          R = F;
          for (unsigned int iteration = 0; iteration < 20; ++iteration)
            {
              const Tensor<2, dim> next   = 0.5 * (R + transpose(invert(R)));
              const double         change = (next - R).norm();
              R                           = next;
              if (change < 1e-12)
                break;
            }
        }
      return R;
    }
  } // namespace

  template <int dim>
  MultiBodyContact<dim>::MultiBodyContact(
    const ContactParameters &        parameters,
    const std::vector<unsigned int> &body_groups)
    : parameters(parameters)
    , with_traction(parameters.model == ContactParameters::Model::bardenhagen_2001)
    , with_position(parameters.detection == ContactParameters::Detection::surface_position)
    , with_regression(parameters.normals == ContactParameters::Normals::logistic_regression ||
                      parameters.normals == ContactParameters::Normals::fitted_at_edges)
    , model(parameters, body_groups)
    , n_bodies(body_groups.size())
  {}

  template <int dim>
  void
  MultiBodyContact<dim>::update_body_rotations(const ParticleCells<dim> &cells,
                                               const MPI_Comm            communicator)
  {
    // once: the bodies some of whose points carry a normal (a point keeps
    // the one it was seeded with); a scene of disks, or of grains so small
    // that every point lies near an edge, has none and skips the rest
    if (bodies_with_normals.empty())
      {
        std::vector<unsigned int> flags(n_bodies, 0);
        for (unsigned int c = 0; c < cells.n_owned(); ++c)
          for (const auto &particle : cells[c].particles)
            {
              const auto props = particle.get_properties();
              if (layout.reference_surface_normal(props).norm_square() > 0)
                flags[static_cast<unsigned int>(props[ParticleLayout<dim>::body])] = 1;
            }
        Utilities::MPI::max(flags, communicator, flags);
        bodies_with_normals.assign(flags.begin(), flags.end());
        any_body_with_normals =
          std::find(flags.begin(), flags.end(), 1u) != flags.end();
        body_rotations.assign(n_bodies, unit_symmetric_tensor<dim>());
        if (any_body_with_normals)
          find_face_directions(cells, communicator);
      }
    if (!any_body_with_normals)
      return;
    // per body: sum V0 F and sum V0 over its points on all ranks
    const unsigned int        n_entries = dim * dim + 1;
    const auto add_point = [](const auto &props, const auto &, double *sum) {
      const double volume = props[ParticleLayout<dim>::initial_volume];
      for (unsigned int k = 0; k < dim * dim; ++k)
        sum[k] += volume * props[ParticleLayout<dim>::deformation + k];
      sum[dim * dim] += volume;
    };
    const std::vector<double> sums =
      sum_per_body<dim>(cells, bodies_with_normals, n_entries, communicator, add_point);
    for (unsigned int b = 0; b < n_bodies; ++b)
      if (bodies_with_normals[b])
      {
        const double *const sum = &sums[b * n_entries];
        Tensor<2, dim>      mean;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            mean[i][j] = sum[dim * dim] > 0 ? sum[i * dim + j] / sum[dim * dim] : double(i == j);
        body_rotations[b] = rotation_of(mean);
      }
    model.turn_face_directions(body_rotations);
  }

  template <int dim>
  void
  MultiBodyContact<dim>::find_face_directions(const ParticleCells<dim> &cells,
                                              const MPI_Comm            communicator)
  {
    // directions within about 2.5 degrees are one face's (as the facets'
    // corner test at seeding)
    const auto add_distinct = [](std::vector<Tensor<1, dim>> &list, const Tensor<1, dim> &n) {
      for (const auto &known : list)
        if (known * n > 0.999)
          return;
      list.push_back(n);
    };
    std::vector<std::vector<Tensor<1, dim>>> per_body(n_bodies);
    for (unsigned int c = 0; c < cells.n_owned(); ++c)
      for (const auto &particle : cells[c].particles)
        {
          const auto           props = particle.get_properties();
          const Tensor<1, dim> n     = layout.reference_surface_normal(props);
          const unsigned int   body  = static_cast<unsigned int>(props[ParticleLayout<dim>::body]);
          if (n.norm_square() > 0 && per_body[body].size() <= max_face_directions)
            add_distinct(per_body[body], n);
        }
    // every rank's lists, as (body, direction) rows
    std::vector<double> rows;
    for (unsigned int b = 0; b < n_bodies; ++b)
      for (const auto &n : per_body[b])
        {
          rows.push_back(b);
          for (unsigned int d = 0; d < dim; ++d)
            rows.push_back(n[d]);
        }
    // (raw MPI: deal.II's all_gather serialises the numbers as text)
    const int        n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    std::vector<int> counts(n_ranks), offsets(n_ranks + 1, 0);
    const int        count = rows.size();
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, communicator);
    for (int r = 0; r < n_ranks; ++r)
      offsets[r + 1] = offsets[r] + counts[r];
    std::vector<double> all_rows(offsets[n_ranks]);
    MPI_Allgatherv(rows.data(), count, MPI_DOUBLE, all_rows.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, communicator);
    for (auto &list : per_body)
      list.clear();
    for (std::size_t i = 0; i + dim < all_rows.size(); i += dim + 1)
      {
        Tensor<1, dim> n;
        for (unsigned int d = 0; d < dim; ++d)
          n[d] = all_rows[i + 1 + d];
        auto &list = per_body[static_cast<unsigned int>(all_rows[i])];
        if (list.size() <= max_face_directions)
          add_distinct(list, n);
      }
    std::vector<Tensor<1, dim>> directions;
    std::vector<unsigned int>   start(1, 0);
    for (const auto &list : per_body)
      {
        if (list.size() <= max_face_directions)
          directions.insert(directions.end(), list.begin(), list.end());
        start.push_back(directions.size());
      }
    model.set_face_directions(std::move(directions), std::move(start));
  }

  template <int dim>
  void
  MultiBodyContact<dim>::mark_contact_nodes(const ParticleCells<dim> &      cells,
                                            const Grid<dim> &               grid,
                                            const ParticleLayout<dim> &     layout,
                                            const BoundaryConditions<dim> & boundary_conditions)
  {
    wall_nodes = &boundary_conditions.constrained_nodes();
    if (layout.surface_normal_stored)
      update_body_rotations(cells, grid.triangulation.get_communicator());
    if (centre_lines)
      update_body_centres(cells, grid.triangulation.get_communicator());
    if (keep_moments)
      moments.update_bodies(cells, round_body, grid.triangulation.get_communicator());
    fields.clear(grid.n_relevant_nodes());
    const bool gimp = grid.get_shape_functions() == ShapeFunctions::gimp;
    // with linear shape functions, the bodies of each cell's points, kept
    // until the cells' points change (a sort or a rebinning)
    if (!gimp && cells.version() != cell_bodies_version)
      {
        gather_cell_bodies(cells, layout);
        cell_bodies_version = cells.version();
      }
    // only the cells with points, colour by colour: blocks of one colour
    // share no node, so their threads mark different nodes; the extra
    // (node, body) pairs are collected per range of cells and sorted by
    // allocate(), so the table does not depend on the threads
    std::mutex mutex;
    cells.for_each_coloured_range([&](const unsigned int *begin, const unsigned int *end) {
      std::vector<std::pair<unsigned int, unsigned int>> extra;
      // GIMP: per body of the cell, the box of nodes its points reach (the
      // 4^dim nodes a cell's points may reach would make most nodes near a
      // grain contact nodes)
      struct Reach
      {
        unsigned int         body;
        std::array<int, dim> lower, upper;
      };
      std::vector<Reach>        reaches;
      std::vector<unsigned int> reached;
      double                    last_volume = -1, spacing = 0;
      for (const unsigned int *c = begin; c != end; ++c)
        {
          const auto &cell = cells[*c];
          if (gimp)
            {
              reaches.clear();
              for (const auto &particle : cell.particles)
                {
                  const auto         props = particle.get_properties();
                  const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
                  auto reach = std::find_if(reaches.begin(), reaches.end(), [&](const Reach &r) {
                    return r.body == body;
                  });
                  if (reach == reaches.end())
                    {
                      Reach r;
                      r.body = body;
                      r.lower.fill(2);
                      r.upper.fill(-1);
                      reaches.push_back(r);
                      reach = reaches.end() - 1;
                    }
                  if (props[layout.initial_volume] != last_volume)
                    {
                      last_volume = props[layout.initial_volume];
                      spacing     = ParticleLayout<dim>::spacing_of_volume(last_volume);
                    }
                  grid.widen_reach(*cell.data,
                                   particle.get_reference_location(),
                                   spacing,
                                   reach->lower,
                                   reach->upper);
                }
              for (const Reach &r : reaches)
                {
                  reached.clear();
                  grid.nodes_in_reach(*cell.data, r.lower, r.upper, reached);
                  for (const unsigned int node : reached)
                    fields.add(node, r.body, extra);
                }
              continue;
            }
          const auto [nodes, n_nodes] = grid.cell_nodes(*cell.data);
          for (unsigned int k = 0; k < n_nodes; ++k)
            for (unsigned int b = cell_bodies_start[*c]; b < cell_bodies_start[*c + 1]; ++b)
              fields.add(nodes[k], cell_bodies[b], extra);
        }
      if (!extra.empty())
        {
          std::lock_guard<std::mutex> lock(mutex);
          fields.add_extra_bodies(extra);
        }
    });
    fields.allocate();
    planes_fitted = false;
    if (with_regression)
      {
        samples.resize(fields.n_all_records());
        for (auto &record_samples : samples)
          record_samples.clear();
      }
  }

  template <int dim>
  void
  MultiBodyContact<dim>::set_body_shapes(const std::vector<double> &surface_radii,
                                         const std::vector<double> &volumes,
                                         const std::vector<double> &masses,
                                         const bool                 periodic_grid)
  {
    model.set_body_shapes(surface_radii, volumes, masses);
    // two round bodies' mass gradients at a coarse contact tilt by tens of
    // degrees from node to node, and a tilted normal lets the bodies slide
    // into each other under load: the settling pile's disks overlapped by
    // a quarter cell (doc/validation.md, "Energy balance of a settling
    // pile"); neither the plane fitted between their points nor their
    // line of centres tilts so ('Contact/Round pair normals')
    round_body.resize(surface_radii.size());
    for (unsigned int b = 0; b < surface_radii.size(); ++b)
      round_body[b] = std::isfinite(surface_radii[b]);
    const bool round_pairs = parameters.normals == ContactParameters::Normals::flatter_body &&
                             std::count(round_body.begin(), round_body.end(), true) >= 2;
    centre_lines    = round_pairs && !periodic_grid &&
                   parameters.round_pair_normals ==
                     ContactParameters::RoundPairNormals::line_of_centres;
    fit_round_pairs = round_pairs && !centre_lines;
    keep_moments    = !periodic_grid &&
                   parameters.round_body_moments == ContactParameters::RoundBodyMoments::kept &&
                   std::count(round_body.begin(), round_body.end(), true) > 0;
    with_regression = with_regression || fit_round_pairs;
  }

  template <int dim>
  void
  MultiBodyContact<dim>::update_body_centres(const ParticleCells<dim> &cells,
                                             const MPI_Comm            communicator)
  {
    model.set_body_centres(centres_of_mass(cells, round_body, communicator));
  }

  template <int dim>
  void
  MultiBodyContact<dim>::fit_separating_planes(const Grid<dim> &grid)
  {
    const std::vector<unsigned int> &nodes = fields.get_contact_nodes();
    fitted_normals.resize(fields.n_all_records());
    // with 'fitted at edges' a node's planes are fitted only where two of
    // its bodies meet at an edge
    const bool only_at_edges = parameters.normals == ContactParameters::Normals::fitted_at_edges;
    const auto any_meet_at_edge = [](const Record *begin, const Record *end) {
      for (const Record *a = begin; a != end; ++a)
        for (const Record *b = a + 1; b != end; ++b)
          if (a->mass > 0 && b->mass > 0 &&
              BardenhagenContact<dim>::meet_at_edge(a->outward_direction(), b->outward_direction()))
            return true;
      return false;
    };
    const auto only_round = [this](const Record *begin, const Record *end) {
      for (const Record *r = begin; r != end; ++r)
        if (r->mass > 0 && !round_body[r->body])
          return false;
      return true;
    };
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(nodes.size()),
      [&](const unsigned int first, const unsigned int last) {
        std::vector<NodeSample<dim>> others;
        for (unsigned int i = first; i < last; ++i)
          {
            const unsigned int    node         = nodes[i];
            const Point<dim> &    origin       = grid.node_positions()[node];
            const Tensor<1, dim> &size         = grid.node_spacing()[node];
            const auto [begin, end]            = fields.node_records(node);
            const std::size_t     first_record = fields.index_of(*begin);
            const std::size_t     n_records    = end - begin;
            if ((only_at_edges && !any_meet_at_edge(begin, end)) ||
                (fit_round_pairs && !only_round(begin, end)))
              {
                for (std::size_t r = first_record; r < first_record + n_records; ++r)
                  fitted_normals[r] = Tensor<1, dim>();
                continue;
              }
            if (n_records == 2)
              {
                // one plane for both: the fit is symmetric in the two clouds
                fitted_normals[first_record] =
                  separating_normal(samples[first_record], samples[first_record + 1], origin, size);
                fitted_normals[first_record + 1] = -fitted_normals[first_record];
                continue;
              }
            for (std::size_t r = first_record; r < first_record + n_records; ++r)
              {
                others.clear();
                for (std::size_t o = first_record; o < first_record + n_records; ++o)
                  if (o != r)
                    others.insert(others.end(), samples[o].begin(), samples[o].end());
                fitted_normals[r] = separating_normal(samples[r], others, origin, size);
              }
          }
      },
      64);
  }

  template <int dim>
  void
  MultiBodyContact<dim>::gather_cell_bodies(const ParticleCells<dim> & cells,
                                            const ParticleLayout<dim> &layout)
  {
    // each block's bodies, cell after cell, and each cell's count; then
    // the counts become offsets and the blocks are joined in order
    constexpr unsigned int                 block_size = 512;
    const unsigned int                     n_cells    = cells.size();
    const unsigned int                     n_blocks   = (n_cells + block_size - 1) / block_size;
    std::vector<std::vector<unsigned int>> block_bodies(n_blocks);
    cell_bodies_start.assign(n_cells + 1, 0);
    parallel::apply_to_subranges(
      0u,
      n_blocks,
      [&](const unsigned int first_block, const unsigned int end_block) {
        for (unsigned int block = first_block; block < end_block; ++block)
          {
            std::vector<unsigned int> &bodies = block_bodies[block];
            for (unsigned int c = block * block_size;
                 c < std::min(n_cells, (block + 1) * block_size);
                 ++c)
              {
                const std::size_t first = bodies.size();
                for (const auto &particle : cells[c].particles)
                  {
                    const unsigned int body =
                      static_cast<unsigned int>(particle.get_properties()[layout.body]);
                    if (std::find(bodies.begin() + first, bodies.end(), body) == bodies.end())
                      bodies.push_back(body);
                  }
                cell_bodies_start[c + 1] = bodies.size() - first;
              }
          }
      },
      1);
    for (unsigned int c = 0; c < n_cells; ++c)
      cell_bodies_start[c + 1] += cell_bodies_start[c];
    cell_bodies.clear();
    for (const std::vector<unsigned int> &bodies : block_bodies)
      cell_bodies.insert(cell_bodies.end(), bodies.begin(), bodies.end());
  }

  template <int dim>
  template <GridPass pass>
  void
  MultiBodyContact<dim>::correct_velocities(const Grid<dim> &              grid,
                                            BoundaryConditions<dim> &      boundary_conditions,
                                            const Tensor<1, dim> &         gravity,
                                            const double                   time_step,
                                            const unsigned int             n_owned_nodes)
  {
    constexpr bool momentum_update = pass == GridPass::momentum_update;
    compute_velocities(momentum_update, gravity, time_step);
    if (!momentum_update && heat_at_remap)
      count_heat_on_remapped(boundary_conditions, time_step, n_owned_nodes);
    const bool drivers = prescribed != nullptr && prescribed->any();
    if (momentum_update)
      {
        driver_work    = 0;
        driver_impulse = 0;
      }
    if (drivers)
      hold_drivers(true, false, n_owned_nodes);
    if (momentum_update && with_regression && !planes_fitted)
      fit_separating_planes(grid);
    // MUSL's remap pass (heat_at_remap) scatters the same masses again and
    // keeps the momentum update's mass gradients, positions and stresses:
    // its contact pass takes the pairs' geometry the first one kept (not
    // with drivers, whose records are scaled and scaled back in between)
    using Geometry          = typename BardenhagenContact<dim>::Geometry;
    const bool both_passes  = heat_at_remap && parameters.on_momentum_update &&
                             parameters.on_strain_update && !drivers;
    const Geometry geometry = !both_passes    ? Geometry::compute :
                              momentum_update ? Geometry::keep :
                                                Geometry::reuse;
    if (momentum_update ? parameters.on_momentum_update : parameters.on_strain_update)
      model.apply(fields,
                  grid.node_spacing(),
                  time_step,
                  n_owned_nodes,
                  momentum_update,
                  grid.triangulation.get_communicator(),
                  // a moment about the origin means nothing across a
                  // periodic seam
                  grid.periodicity().any() ? nullptr : &grid.node_positions(),
                  with_regression ? &fitted_normals : nullptr,
                  geometry,
                  &grid.node_support_volumes());
    if (drivers)
      hold_drivers(false, momentum_update, n_owned_nodes);
    if (!boundary_conditions.empty())
      boundary_conditions.apply_to_bodies(fields, !momentum_update, n_owned_nodes);
    keep_corrections(boundary_conditions);
    // the points take the momentum update's corrections (MUSL's remap
    // pass corrects only the velocities of the strain update)
    if (momentum_update && keep_moments)
      moments.collect(
        fields, grid.node_positions(), n_owned_nodes, grid.triangulation.get_communicator());
  }

  template <int dim>
  void
  MultiBodyContact<dim>::compute_velocities(const bool            with_forces,
                                            const Tensor<1, dim> &gravity,
                                            const double          time_step)
  {
    // node by node: threads change nothing
    const std::vector<unsigned int> &contact_nodes = fields.get_contact_nodes();
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(contact_nodes.size()),
      [&](const unsigned int first, const unsigned int last) {
        for (unsigned int i = first; i < last; ++i)
          {
            const auto [begin, end] = fields.node_records(contact_nodes[i]);
            for (Record *r = begin; r != end; ++r)
              {
                if (r->mass <= 0.)
                  continue;
                const Tensor<1, dim> velocity = r->momentum / r->mass;
                if (with_forces)
                  {
                    r->old_velocity = velocity;
                    r->new_velocity = velocity + time_step * (r->force / r->mass + gravity);
                  }
                else
                  r->new_velocity = velocity;
                // the velocity before the corrections, until the end
                r->correction = r->new_velocity;
              }
          }
      },
      256);
  }

  template <int dim>
  void
  MultiBodyContact<dim>::correct_initial_velocities(
    const Grid<dim> &              grid,
    const BoundaryConditions<dim> &boundary_conditions,
    const double                   time_step,
    const unsigned int             n_owned_nodes)
  {
    compute_velocities(false, Tensor<1, dim>(), time_step);
    // the points do not move before the momentum update: these planes
    // stand for it too
    if (with_regression)
      {
        fit_separating_planes(grid);
        planes_fitted = true;
      }
    if (parameters.on_momentum_update || parameters.on_strain_update)
      model.apply_to_initial(fields,
                             grid.node_spacing(),
                             time_step,
                             n_owned_nodes,
                             grid.triangulation.get_communicator(),
                             grid.periodicity().any() ? nullptr : &grid.node_positions(),
                             with_regression ? &fitted_normals : nullptr,
                             &grid.node_support_volumes());
    if (!boundary_conditions.empty())
      boundary_conditions.apply_to_initial_bodies(fields);
    keep_corrections(boundary_conditions);
  }

  template <int dim>
  void
  MultiBodyContact<dim>::keep_corrections(const BoundaryConditions<dim> &boundary_conditions)
  {
    const std::vector<unsigned int> &contact_nodes = fields.get_contact_nodes();
    const std::vector<bool> *        moving =
      boundary_conditions.empty() ? nullptr : &boundary_conditions.moving_wall_nodes();
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(contact_nodes.size()),
      [&](const unsigned int first, const unsigned int last) {
        for (unsigned int i = first; i < last; ++i)
          {
            const bool at_moving_wall = moving != nullptr && (*moving)[contact_nodes[i]];
            const auto [begin, end]   = fields.node_records(contact_nodes[i]);
            for (Record *r = begin; r != end; ++r)
              r->correction = r->mass <= 0. || at_moving_wall ?
                                Tensor<1, dim>() :
                                Tensor<1, dim>(r->new_velocity - r->correction);
          }
      },
      256);
  }

  template <int dim>
  void
  MultiBodyContact<dim>::count_heat_on_remapped(BoundaryConditions<dim> &boundary_conditions,
                                                const double             time_step,
                                                const unsigned int       n_owned_nodes)
  {
    const std::vector<unsigned int> &nodes      = fields.get_contact_nodes();
    constexpr unsigned int           chunk_size = 256;
    const unsigned int               n_chunks   = (nodes.size() + chunk_size - 1) / chunk_size;
    // per chunk: the contact's and the walls' heat
    std::vector<std::pair<double, double>> chunk_heat(n_chunks, {0., 0.});
    parallel::apply_to_subranges(
      0u,
      n_chunks,
      [&](const unsigned int first_chunk, const unsigned int last_chunk) {
        for (unsigned int chunk = first_chunk; chunk < last_chunk; ++chunk)
          {
            const unsigned int last =
              std::min<unsigned int>((chunk + 1) * chunk_size, nodes.size());
            for (unsigned int i = chunk * chunk_size; i < last; ++i)
              {
                if (nodes[i] >= n_owned_nodes)
                  continue;
                // friction does no positive work on the slip: a node whose
                // bodies' points moved, after the step, along the impulses
                // they got (the correction overshot, or noise where they
                // stick) adds no heat
                const auto [begin, end] = fields.node_records(nodes[i]);
                double contact_heat = 0, wall_heat = 0;
                for (const Record *r = begin; r != end; ++r)
                  if (r->mass > 0.)
                    {
                      contact_heat -= time_step * (r->friction_force * r->new_velocity);
                      wall_heat -= r->mass * (r->wall_change * r->new_velocity);
                    }
                chunk_heat[chunk].first += std::max(contact_heat, 0.);
                chunk_heat[chunk].second += std::max(wall_heat, 0.);
              }
          }
      },
      1);
    for (const auto &[contact_heat, wall_heat] : chunk_heat)
      {
        model.frictional_heat += contact_heat;
        boundary_conditions.frictional_heat += wall_heat;
      }
  }

  template <int dim>
  void
  MultiBodyContact<dim>::hold_drivers(const bool         before,
                                      const bool         record_work,
                                      const unsigned int n_owned_nodes)
  {
    const double factor = before ? driver_mass_factor : 1. / driver_mass_factor;
    for (const unsigned int node : fields.get_contact_nodes())
      {
        const auto [begin, end] = fields.node_records(node);
        for (Record *r = begin; r != end; ++r)
          if (prescribed->is_prescribed(r->body))
            {
              const Tensor<1, dim> &velocity = prescribed->velocity(r->body);
              // the impulse the driver gave the others: minus its own
              // momentum change
              if (!before && record_work && node < n_owned_nodes)
                {
                  const Tensor<1, dim> impulse = r->mass * (velocity - r->new_velocity);
                  driver_work += impulse * velocity;
                  driver_impulse += impulse;
                }
              r->mass *= factor;
              r->momentum *= factor;
              r->mass_position *= factor;
              r->mass_spacing *= factor;
              r->mass_stress *= factor;
              // the face normals' sums with the mass: the contact compares
              // them with it (nine tenths of the mass under one face), and a
              // driven box or mesh body lost its face normals. The located
              // faces' sums stay as they are, so a driven body's gap comes
              // from its centroids: located, A4's fixed ceiling carried no
              // load (doc/validation.md, "A rigid wedge")
              r->mass_surface_normal *= factor;
              r->mass_surface *= factor;
              r->old_velocity = velocity;
              r->new_velocity = velocity;
            }
      }
  }

  template class MultiBodyContact<2>;
  template class MultiBodyContact<3>;
  template void MultiBodyContact<2>::correct_velocities<GridPass::momentum_update>(
    const Grid<2> &, BoundaryConditions<2> &, const Tensor<1, 2> &, double, unsigned int);
  template void MultiBodyContact<2>::correct_velocities<GridPass::remapped_momenta>(
    const Grid<2> &, BoundaryConditions<2> &, const Tensor<1, 2> &, double, unsigned int);
  template void MultiBodyContact<3>::correct_velocities<GridPass::momentum_update>(
    const Grid<3> &, BoundaryConditions<3> &, const Tensor<1, 3> &, double, unsigned int);
  template void MultiBodyContact<3>::correct_velocities<GridPass::remapped_momenta>(
    const Grid<3> &, BoundaryConditions<3> &, const Tensor<1, 3> &, double, unsigned int);
} // namespace sable::mpm
