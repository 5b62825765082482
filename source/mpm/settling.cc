#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/base/significant_digits.h>
#include <sable/mpm/seeding.h>
#include <sable/mpm/simulator.h>

#include <algorithm>
#include <limits>

namespace sable::mpm
{
  template <int dim>
  void
  Simulator<dim>::settle_under_gravity()
  {
    for (auto &particle : *particle_handler)
      {
        auto props = particle.get_properties();
        for (unsigned int d = 0; d < dim; ++d)
          props[layout.velocity + d] = 0.;
        if (layout.affine_stored)
          layout.set_affine(props, Tensor<2, dim>());
      }
    const auto publish_velocities = [&]() {
      if (contact && parallel)
        particle_handler->update_ghost_particles();
    };
    publish_velocities();

    // kinetic damping: step at rest under gravity, and whenever the kinetic
    // energy has passed a peak, take all of it away; settled when a peak
    // stays below the tolerance times the strain energy. The energy left
    // rings on, and a contact held by friction near its limit slips where
    // the ringing adds to the load: the tolerance is relative to the
    // stored energy, which sets the forces, not to the mass and the cell
    // the settling gravity acts in every pass until the clock starts
    const Tensor<1, dim> run_gravity = parameters.gravity;
    parameters.gravity               = parameters.settling_gravity;
    const auto stick_everywhere = [&](const bool stick) {
      boundary_conditions.stick_everywhere(stick);
      if (contact)
        contact->get_model().stick_everywhere(stick);
    };
    stick_everywhere(parameters.settling_stick);
    // moving walls and drivers (advance()) start with the run
    boundary_conditions.hold_moving_walls(true);
    double       previous = 0, kinetic = 0, peak = std::numeric_limits<double>::max();
    double       strain_energy = 0;
    unsigned int n             = 0;
    settling                   = true;
    for (; n < parameters.settling_steps; ++n)
      {
        advance();
        kinetic = 0;
        for (const auto &particle : *particle_handler)
          {
            const auto props = particle.get_properties();
            for (unsigned int d = 0; d < dim; ++d)
              kinetic += 0.5 * props[layout.mass] * props[layout.velocity + d] *
                         props[layout.velocity + d];
          }
        kinetic = Utilities::MPI::sum(kinetic, communicator);
        if (kinetic < previous)
          {
            peak          = previous;
            strain_energy = compute_statistics().strain_energy;
            if (peak <= parameters.settling_tolerance * strain_energy)
              break;
            for (auto &particle : *particle_handler)
              {
                auto props = particle.get_properties();
                for (unsigned int d = 0; d < dim; ++d)
                  props[layout.velocity + d] = 0.;
                if (layout.affine_stored)
                  layout.set_affine(props, Tensor<2, dim>());
              }
            publish_velocities();
            previous = 0;
          }
        else
          previous = kinetic;
      }
    settling           = false;
    parameters.gravity = run_gravity;
    stick_everywhere(false);
    boundary_conditions.hold_moving_walls(false);
    // disks seeded conforming settle slowly on a floor or a body, and on
    // a friction floor at 25.6 cells per diameter not in 40,000 steps
    // (doc/validation.md, "Disks at rest: lattice and conforming seeding")
    const bool conforming_disks =
      std::any_of(parameters.bodies.begin(), parameters.bodies.end(), [](const auto &body) {
        return body.shape == BodyParameters<dim>::Shape::disk &&
               body.seeding_used() == BodyParameters<dim>::Seeding::conforming;
      });
    check_input(n < parameters.settling_steps,
                "Solver/Settling steps",
                parameters.settling_steps,
                "enough steps for the bodies to settle (" +
                  (peak <= std::numeric_limits<double>::max() / 2 ?
                     "the last peak of the kinetic energy was " + significant_digits(peak) +
                       " J, above 'Solver/Settling tolerance' = " +
                       significant_digits(parameters.settling_tolerance) + " times the strain energy " +
                       significant_digits(strain_energy) + " J" :
                     "the kinetic energy was still rising, " + significant_digits(kinetic) + " J") +
                  "; a body free to slide or roll under the gravity never settles: hold "
                  "a block on a slope by friction while it settles, 'Solver/Settling "
                  "friction = stick', or settle a disk under the part of gravity normal "
                  "to the slope, 'Solver/Settling gravity'" +
                  (conforming_disks ?
                     std::string("; disks seeded conforming may need over ten times the steps of "
                                 "disks seeded on the lattice, and on a friction floor may not "
                                 "settle at all (doc/mpm.md, \"Starting settled\")") :
                     std::string()) +
                  ")");
    pcout << "Settled under gravity in " << n + 1 << " steps (" << state.time
          << " s of damped motion)" << std::endl;

    // the run starts now, from the settled state, each body moving with its
    // velocity and spinning about its settled centre of mass, a driver with
    // its velocity at time 0
    const Statistics<dim> settled = compute_statistics();
    prescribed_velocities.update(0.);
    double                max_speed = 0;
    for (auto &particle : *particle_handler)
      {
        auto                       props = particle.get_properties();
        const unsigned int         b     = static_cast<unsigned int>(props[layout.body]);
        const BodyParameters<dim> &body  = parameters.bodies[b];
        // about the centre's image nearest the point (periodic grids)
        const Point<dim> &x      = particle.get_location();
        const Point<dim>  centre = settled.body_position[b] +
                                  grid.periodicity().image_shift(settled.body_position[b], x);
        Tensor<1, 3>      r;
        for (unsigned int d = 0; d < dim; ++d)
          r[d] = x[d] - centre[d];
        const Tensor<1, 3> spin = cross_product_3d(body.angular_velocity, r);
        Tensor<1, dim>     v;
        for (unsigned int d = 0; d < dim; ++d)
          props[layout.velocity + d] = v[d] = prescribed_velocities.is_prescribed(b) ?
                                                prescribed_velocities.velocity(b)[d] :
                                                body.velocity[d] + spin[d];
        if (layout.affine_stored)
          layout.set_affine(props, spin_velocity_gradient<dim>(body.angular_velocity));
        // displacements count from time 0, the settled state
        if (layout.initial_position_stored)
          for (unsigned int d = 0; d < dim; ++d)
            props[layout.initial_position() + d] = particle.get_location()[d];
        max_speed = std::max(max_speed, body_wave_speed[b] + v.norm());
      }
    publish_velocities();
    state.max_signal_speed = Utilities::MPI::max(max_speed, communicator);
    state.time             = 0;
    state.step_number      = 0;
    state.boundary_work    = 0;
    state.driver_impulse   = {{0, 0, 0}};
    boundary_conditions.frictional_heat = 0;
    correction_loss                     = 0;
    if (contact)
      {
        auto &model               = contact->get_model();
        model.frictional_heat     = 0;
        model.momentum_defect     = 0;
        model.momentum_correction = 0;
        for (auto &force : model.pair_forces)
          force = 0;
        for (auto &moment : model.pair_moments)
          moment = 0;
        // pulls carried from the settling steps would cap the run's friction
        model.set_pulling_impulses({});
      }
  }

  template void Simulator<2>::settle_under_gravity();
  template void Simulator<3>::settle_under_gravity();
} // namespace sable::mpm
