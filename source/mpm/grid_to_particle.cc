#include <deal.II/base/parallel.h>

#include <sable/mpm/grid_to_particle.h>

#include <cmath>
#include <mutex>

namespace sable::mpm
{
  template <int dim>
  void
  GridToParticle<dim>::Report::fail(const bool                  distance,
                                    const types::particle_index id,
                                    const Point<dim> &          x)
  {
    // keep the lowest id, whatever order the threads report in
    if ((not_finite || too_far) && id >= failed_id)
      return;
    (distance ? too_far : not_finite) = true;
    failed_id                         = id;
    failure_location                  = x;
  }

  template <int dim>
  void
  GridToParticle<dim>::Report::merge(const Report &other)
  {
    max_signal_speed   = std::max(max_signal_speed, other.max_signal_speed);
    max_particle_speed = std::max(max_particle_speed, other.max_particle_speed);
    n_left_cell += other.n_left_cell;
    if (other.not_finite || other.too_far)
      fail(other.too_far, other.failed_id, other.failure_location);
  }

  template <int dim>
  Tensor<2, dim>
  GridToParticle<dim>::massless_gradient_part(const typename Grid<dim>::Shape &shape,
                                              const unsigned int               body,
                                              const MultiBodyContact<dim> *    contact) const
  {
    // a node without mass of the point's body has velocity 0 and added
    // nothing to L (the point adds N m_p to its nodes, so only a node of
    // weight 0 can be one); moving with the point, it adds v_p grad N_i,
    // so that L = sum (v_i - v_p) grad N_i over the nodes with mass and a
    // uniform motion has no gradient
    const std::vector<double> &mass         = fields.get_mass();
    const std::vector<double> &new_velocity = fields.get_new_velocity();
    Tensor<1, dim>             massless_gradient, interpolated;
    for (unsigned int v = 0; v < shape.n_nodes; ++v)
      {
        const unsigned int node   = shape.nodes[v];
        const auto *const  record = contact != nullptr ? contact->velocities(node, body) : nullptr;
        const double *const v_new =
          record != nullptr ? &record->new_velocity[0] : &new_velocity[node * dim];
        if (shape.values[v] == 0. && (record != nullptr ? record->mass : mass[node]) == 0.)
          massless_gradient += shape.gradients[v];
        for (unsigned int d = 0; d < dim; ++d)
          interpolated[d] += shape.values[v] * v_new[d];
      }
    return outer_product(interpolated, massless_gradient);
  }

  template <int dim>
  template <bool update_positions, bool update_strain_rates, bool affine, bool measure>
  DEAL_II_ALWAYS_INLINE inline double
  GridToParticle<dim>::transfer_cell(const PassInput &                         input,
                                     const typename ParticleCells<dim>::Cell &cell,
                                     const double                              strain_time_step,
                                     typename Grid<dim>::Shape &               shape,
                                     Report &                                  local) const
  {
    using Layout                               = ParticleLayout<dim>;
    const typename Grid<dim>::CellData &data   = *cell.data;
    const MultiBodyContact<dim> *const  contact = input.contact;
    const auto *const                   drivers = input.drivers;
    const double                        time_step = input.time_step;
    const double                        alpha     = input.alpha;
    const double *const                 new_velocity    = input.new_velocity;
    const double *const                 old_velocity    = input.old_velocity;
    const double *const                 wall_correction = input.wall_correction;
    const Periodicity<dim> *const       periodicity     = input.periodicity;
    double                              cell_loss = 0;
    for (auto &particle : cell.particles)
      {
        const auto         props = particle.get_properties();
        const unsigned int body  = static_cast<unsigned int>(props[Layout::body]);
        const bool driven = drivers != nullptr && drivers->is_prescribed(body);
        Tensor<1, dim> velocity_change, grid_velocity, correction, velocity_before;
        Tensor<2, dim> L, correction_gradient;
        if constexpr (update_positions && measure)
          for (unsigned int d = 0; d < dim; ++d)
            velocity_before[d] = props[Layout::velocity + d];
        if (driven)
          {
            // a rigid driver: its velocity, whatever the grid says
            grid_velocity = drivers->velocity(body);
            for (unsigned int d = 0; d < dim; ++d)
              props[Layout::velocity + d] = grid_velocity[d];
          }
        else
          grid.evaluate(data,
                        particle.get_reference_location(),
                        props[Layout::initial_volume],
                        shape);
        for (unsigned int v = 0; v < (driven ? 0 : shape.n_nodes); ++v)
          {
            const unsigned int node  = shape.nodes[v];
            const double *     v_new = &new_velocity[node * dim];
            const double *     v_old = &old_velocity[node * dim];
            // each particle reads its own body's field
            const auto *const record =
              contact != nullptr ? contact->velocities(node, body) : nullptr;
            if (record != nullptr)
              {
                v_new = &record->new_velocity[0];
                v_old = &record->old_velocity[0];
              }
            const double N = shape.values[v];
            if constexpr (measure)
              {
                // what the contact and the walls changed there
                Tensor<1, dim> change;
                if (record != nullptr)
                  change = record->correction;
                else if (wall_correction != nullptr)
                  for (unsigned int d = 0; d < dim; ++d)
                    change[d] = wall_correction[node * dim + d];
                if constexpr (update_positions)
                  correction += N * change;
                if constexpr (update_strain_rates)
                  correction_gradient += outer_product(change, shape.gradients[v]);
              }
            for (unsigned int d = 0; d < dim; ++d)
              {
                if constexpr (update_positions)
                  {
                    velocity_change[d] += N * (v_new[d] - v_old[d]);
                    grid_velocity[d] += N * v_new[d];
                  }
                if constexpr (update_strain_rates)
                  for (unsigned int e = 0; e < dim; ++e)
                    L[d][e] += v_new[d] * shape.gradients[v][e];
              }
          }
        if constexpr (update_positions)
          if (input.moments != nullptr && !driven)
            {
              const Tensor<1, dim> spin =
                input.moments->velocity(body, particle.get_location());
              velocity_change += spin;
              grid_velocity += spin;
              if constexpr (measure)
                correction += spin;
            }
        // with the affine transfers L becomes C, and a node of
        // weight 0 without mass next to a point on its cell's face
        // would carry its velocity 0 into the next transfer with
        // full weight (a product of weights that underflows only
        // costs a closer look)
        if constexpr (update_strain_rates)
          if (affine && !driven)
            {
              double weights = 1.;
              for (unsigned int v = 0; v < shape.n_nodes; ++v)
                weights *= shape.values[v];
              if (weights == 0.)
                L += massless_gradient_part(shape, body, contact);
            }
        if constexpr (update_positions)
          {
            double speed2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double &v = props[Layout::velocity + d];
                if (!driven)
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
            if (periodicity != nullptr)
              periodicity->wrap(location);
            particle.set_location(location);
            local.n_left_cell += !cell.contains(location);
            local.max_signal_speed =
              std::max(local.max_signal_speed, std::sqrt(speed2) + body_wave_speed[body]);
            local.max_particle_speed =
              std::max(local.max_particle_speed, std::sqrt(speed2));
            if (!std::isfinite(speed2))
              local.fail(false, particle.get_id(), location);
            if (measure && !driven)
              {
                Tensor<1, dim> mean_velocity;
                for (unsigned int d = 0; d < dim; ++d)
                  mean_velocity[d] =
                    0.5 * (velocity_before[d] + props[Layout::velocity + d]);
                cell_loss -= props[Layout::mass] * (correction * mean_velocity);
              }
          }
        if constexpr (update_strain_rates)
          if (measure && !driven)
            {
              // the strain energy with L less that with L - G: dt V (sigma
              // + dt C : (L - G/2)) : G, the elastic tangent's term of second
              // order in the step (the first-order count alone took 10% more
              // than two disks lost in a head-on impact at CFL 0.5). In
              // USAVG's first half the tangent's term is dt C : G/2: the
              // stress it leaves drives the momentum update, whose internal
              // force works on the uncorrected L, so the dt C : L of this
              // half cancels there (counted with L - G/2, the settling pile
              // gained 3.5% at CFL 0.5 instead of 0.8%)
              const Tensor<2, dim> midpoint =
                input.first_half ? Tensor<2, dim>(0.5 * correction_gradient) :
                                   Tensor<2, dim>(L - 0.5 * correction_gradient);
              const Tensor<2, dim> strain   = 0.5 * (midpoint + transpose(midpoint));
              const double shear  = body < body_shear.size() ? body_shear[body] : 0.;
              const double lambda = body < body_lambda.size() ? body_lambda[body] : 0.;
              Tensor<2, dim>       tangent_stress = 2. * shear * strain;
              const double         volumetric     = lambda * trace(strain);
              for (unsigned int d = 0; d < dim; ++d)
                tangent_stress[d][d] += volumetric;
              const double volume = determinant(Layout::deformation_gradient(props)) *
                                    props[Layout::initial_volume];
              cell_loss -= strain_time_step *
                           scalar_product(Layout::volume_stress(props) +
                                            (strain_time_step * volume) * tangent_stress,
                                          correction_gradient);
            }
        if constexpr (update_strain_rates)
          {
            velocity_gradients[particle.get_local_index()] = L;
            // the affine transfers carry the velocity gradient
            // of the stress update into the next step as C
            if constexpr (affine)
              layout.set_affine(props, L);
          }
      }
    return cell_loss;
  }

  template <int dim>
  void
  GridToParticle<dim>::find_corrected_cells(const ParticleCells<dim> &   cells,
                                            const MultiBodyContact<dim> *contact)
  {
    corrected_cells.assign(cells.n_owned(), 0);
    if (!measuring)
      return;
    const unsigned char *const wall_nodes = boundary != nullptr && !boundary->empty() ?
                                              boundary->constrained_nodes().data() :
                                              nullptr;
    parallel::apply_to_subranges(
      0u,
      cells.n_owned(),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int c = begin; c < end; ++c)
          {
            const auto    nodes   = grid.cell_nodes(*cells[c].data);
            unsigned char at_wall = 0;
            if (wall_nodes != nullptr)
              for (unsigned int k = 0; k < nodes.second; ++k)
                at_wall |= wall_nodes[nodes.first[k]];
            corrected_cells[c] = at_wall != 0 || (contact != nullptr && contact->touches(nodes));
          }
      },
      256);
  }

  template <int dim>
  template <bool update_positions, bool update_strain_rates, bool affine>
  typename GridToParticle<dim>::Report
  GridToParticle<dim>::transfer(Particles::ParticleHandler<dim> &particle_handler,
                                const ParticleCells<dim> &       cells,
                                const MultiBodyContact<dim> *    contact,
                                const double                     time_step,
                                const double                     alpha,
                                const std::vector<double> *      cell_time_steps,
                                const bool                       first_half) const
  {
    if (update_strain_rates)
      velocity_gradients.resize(particle_handler.get_max_local_particle_index());
    const std::vector<double> &new_velocity = fields.get_new_velocity();
    const std::vector<double> &old_velocity = fields.get_old_velocity();

    const PrescribedVelocities<dim> *const drivers =
      prescribed != nullptr && prescribed->any() ? prescribed : nullptr;
    // points leaving through a periodic face come back in at the other
    const Periodicity<dim> *const periodicity =
      grid.periodicity().any() ? &grid.periodicity() : nullptr;
    Report     report;
    std::mutex report_mutex;
    if (measuring)
      cell_correction_loss.assign(cells.n_owned(), 0.);
    Assert(!measuring || corrected_cells.size() == cells.n_owned(),
           ExcMessage("find_corrected_cells() must run after the cells change"));
    const RoundBodyMoments<dim> *const moments =
      update_positions && contact != nullptr ? contact->kept_moments() : nullptr;
    const PassInput input{contact,
                          moments,
                          drivers,
                          periodicity,
                          new_velocity.data(),
                          old_velocity.data(),
                          fields.get_wall_correction().empty() ?
                            nullptr :
                            fields.get_wall_correction().data(),
                          time_step,
                          alpha,
                          first_half};
    parallel::apply_to_subranges(
      0u,
      cells.n_owned(),
      [&](const unsigned int begin, const unsigned int end) {
        Report                    local;
        typename Grid<dim>::Shape shape;
        for (unsigned int c = begin; c < end; ++c)
          {
            if (cell_time_steps != nullptr && (*cell_time_steps)[c] == 0.)
              continue;
            const auto &cell         = cells[c];
            // a body's rotation reaches all its points
            const bool measure_cell =
              measuring && (corrected_cells[c] != 0 || moments != nullptr);
            const double strain_time_step =
              cell_time_steps != nullptr ? (*cell_time_steps)[c] : time_step;
            const double cell_loss =
              measure_cell ?
                transfer_cell<update_positions, update_strain_rates, affine, true>(
                  input, cell, strain_time_step, shape, local) :
                transfer_cell<update_positions, update_strain_rates, affine, false>(
                  input, cell, strain_time_step, shape, local);
            if (measure_cell)
              cell_correction_loss[c] = cell_loss;
          }
        std::lock_guard<std::mutex> lock(report_mutex);
        report.merge(local);
      },
      16);
    if (measuring)
      for (const double loss : cell_correction_loss)
        report.correction_loss += loss;
    return report;
  }

  template class GridToParticle<2>;
  template class GridToParticle<3>;
#define SABLE_INSTANTIATE(dim, positions, strain_rates, affine)                    \
  template GridToParticle<dim>::Report                                             \
  GridToParticle<dim>::transfer<positions, strain_rates, affine>(                  \
    Particles::ParticleHandler<dim> &,                                             \
    const ParticleCells<dim> &,                                                    \
    const MultiBodyContact<dim> *,                                                 \
    const double,                                                                  \
    const double,                                                                  \
    const std::vector<double> *,                                                   \
    const bool) const;
  SABLE_INSTANTIATE(2, true, false, false)
  SABLE_INSTANTIATE(2, false, true, false)
  SABLE_INSTANTIATE(2, false, true, true)
  SABLE_INSTANTIATE(2, true, true, false)
  SABLE_INSTANTIATE(2, true, true, true)
  SABLE_INSTANTIATE(3, true, false, false)
  SABLE_INSTANTIATE(3, false, true, false)
  SABLE_INSTANTIATE(3, false, true, true)
  SABLE_INSTANTIATE(3, true, true, false)
  SABLE_INSTANTIATE(3, true, true, true)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
