// Conservation properties of the particle-grid transfers of
// sable::mpm::Simulator (public API only), in 2D and 3D, serial and on
// several MPI ranks (ctest runs this program on 1 and 2 ranks):
//
// Two linear-elastic bodies (a disk/sphere and a box, different densities)
// with initial velocities and angular velocities move towards each other
// inside the grid (less than a cell apart, so they share grid nodes and
// collide in the single velocity field: the internal forces are not
// trivial), no boundary conditions. For USL, MUSL and USAVG, PIC fraction 0 and
// 0.5, without and with gravity g, over 20 steps:
//  - total momentum P (compute_statistics().momentum) after each step equals
//    P before the step + M g dt (M = total mass, dt = get_time_step()):
//    P2G conserves momentum by the partition of unity, the nodal internal
//    forces sum to zero because sum_i grad N_i = 0, and the FLIP/PIC update
//    hands sum_i m_i (v_i^new - v_i^old) = dt sum_i f_i + M g dt back to
//    the particles. Only round-off remains: tolerance 1e-12 relative to
//    S = sum_p m_p |v_p| (+ M |g| dt), the size of the terms summed;
//  - the same over the whole run: P_N = P_0 + M g t_N (1e-12 of S);
//  - each body's mass (compute_statistics().body_mass) equals
//    density x (number of its particles) x (cell volume / ppd^dim), the
//    lattice's seeding rule (the disk is seeded on the lattice), at every step (1e-12: the seeding uses the measure of
//    each cell, whose vertices i/n are not exact binary fractions, ~1e-15,
//    plus summation round-off), and its value before the first step:
//    particle masses never change, only the summation order may (moving
//    between cells and ranks), <= n eps ~ 5e-14 for n < 500 particles per
//    body: 1e-13;
//  - the global particle count never changes;
//  - on more than one rank: both ranks own particles (the MPI exchange is
//    exercised);
//  - the same on adapted grids (a refined region and refined body surfaces,
//    re-adapted every 3 steps): the folded hanging-node shape functions keep
//    the partition of unity and sum_k grad N_k = 0, so the same round-off
//    bounds hold; the grid has hanging vertices and changes during the run;
//  - the same with GIMP shape functions (one rank), whose weights reach the
//    nodes of the neighbouring cells;
//  - the nodes' support volumes (Grid::node_support_volumes(), which the
//    contact's overlap test reads) add up to the grid's volume, 1e-12, on
//    the initial grid and after the run (the adapted grid changed).

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <sable/mpm/parameters.h>
#include <sable/mpm/run_scene.h>
#include <sable/mpm/simulator.h>

#include <cmath>
#include <iostream>
#include <set>
#include <string>

#include "test_support.h"

using namespace dealii;
using sable_tests::check;
using sable_tests::check_relative;

namespace
{
  template <int dim>
  struct ParticleSums
  {
    std::vector<unsigned long long> n_per_body;
    double                          momentum_scale = 0; // sum_p m_p |v_p|
    unsigned long long              min_local      = 0;
  };

  template <int dim>
  ParticleSums<dim>
  particle_sums(const sable::mpm::Simulator<dim> &simulator, const unsigned int n_bodies,
                MPI_Comm communicator)
  {
    using Layout = sable::mpm::ParticleLayout<dim>;
    ParticleSums<dim> sums;
    sums.n_per_body.assign(n_bodies, 0);
    unsigned long long local = 0;
    for (const auto &particle : simulator.get_particle_handler())
      {
        const auto props = particle.get_properties();
        ++sums.n_per_body[static_cast<unsigned int>(props[Layout::body])];
        double v2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += props[Layout::velocity + d] * props[Layout::velocity + d];
        sums.momentum_scale += props[Layout::mass] * std::sqrt(v2);
        ++local;
      }
    Utilities::MPI::sum(sums.n_per_body, communicator, sums.n_per_body);
    sums.momentum_scale = Utilities::MPI::sum(sums.momentum_scale, communicator);
    sums.min_local      = Utilities::MPI::min(local, communicator);
    return sums;
  }

  template <int dim>
  void
  run_case(const sable::mpm::UpdateScheme scheme, const double pic_fraction,
           const bool with_gravity, const bool adaptive = false, const bool gimp = false)
  {
    using namespace sable::mpm;
    const MPI_Comm     communicator = MPI_COMM_WORLD;
    const unsigned int n_ranks      = Utilities::MPI::n_mpi_processes(communicator);
    const std::string  name = std::to_string(dim) + "D " +
                             (scheme == UpdateScheme::usl  ? "USL" :
                              scheme == UpdateScheme::musl ? "MUSL" :
                                                             "USAVG") + ", PIC " +
                             std::to_string(pic_fraction).substr(0, 3) +
                             (with_gravity ? ", gravity" : ", no gravity") +
                             (adaptive ? ", adaptive grid" : "") + (gimp ? ", GIMP" : "") +
                             ", " +
                             std::to_string(n_ranks) + " rank(s): ";

    const unsigned int  n_cells = dim == 2 ? 32 : 10;
    GridParameters<dim> grid;
    for (unsigned int d = 0; d < dim; ++d)
      grid.upper_corner[d] = 1.;
    grid.subdivisions.assign(dim, n_cells);
    for (unsigned int f = 0; f < 2 * dim; ++f)
      grid.face_ids.push_back(f);
    parallel::distributed::Triangulation<dim> triangulation(communicator);
    make_grid(grid, triangulation);
    const double h = 1. / n_cells;

    SimulatorParameters<dim> parameters;
    parameters.end_time         = 1e3; // we call step() ourselves
    // USL with FLIP is prone to the small-nodal-mass instability at body
    // edges: rotating bodies at CFL 0.5 blow up after ~15-50 steps (MUSL
    // does not); 0.2 keeps every scheme stable over this short run.
    parameters.cfl              = 0.2;
    parameters.update_scheme    = scheme;
    parameters.pic_fraction     = pic_fraction;
    parameters.output_directory = "";
    parameters.print_timings    = false;
    parameters.shape_functions  = gimp ? ShapeFunctions::gimp : ShapeFunctions::linear;
    if (with_gravity)
      {
        parameters.gravity[1] = -9.81;
        if (dim == 3)
          parameters.gravity[2] = 2.5;
      }

    // a disk/sphere and a box less than a cell apart, approaching each other
    BodyParameters<dim> disk, box;
    disk.shape = BodyParameters<dim>::Shape::disk;
    disk.radius = dim == 2 ? 0.15 : 0.2;
    for (unsigned int d = 0; d < dim; ++d)
      disk.center[d] = 0.5;
    disk.center[0] = 0.35;
    disk.particles_per_direction = 2;
    // equal points: the seeding rule's masses below
    disk.seeding = BodyParameters<dim>::Seeding::lattice;
    disk.material.model          = "linear elastic";
    disk.material.density        = 1000.;
    disk.material.set_young_poisson(1e5, 0.3);
    disk.velocity[0]          = 0.8;
    disk.velocity[1]          = 0.1;
    disk.angular_velocity[2]  = 3.;
    if (dim == 3)
      {
        disk.velocity[2]         = -0.2;
        disk.angular_velocity[0] = 1.;
        disk.angular_velocity[1] = -2.;
      }

    box.shape = BodyParameters<dim>::Shape::box;
    // (on the adapted grid the surfaces sit in cells of half the size)
    const double gap = (adaptive ? 0.3 : 0.6) * h;
    box.lower_corner[0] = disk.center[0] + disk.radius + gap;
    box.upper_corner[0] = box.lower_corner[0] + 0.2;
    for (unsigned int d = 1; d < dim; ++d)
      {
        box.lower_corner[d] = 0.36;
        box.upper_corner[d] = 0.64;
      }
    box.particles_per_direction = dim == 2 ? 3 : 2;
    box.material.model          = "linear elastic";
    box.material.density        = 2500.;
    box.material.set_young_poisson(3e5, 0.25);
    box.velocity[0]         = -0.6;
    box.velocity[1]         = 0.2;
    box.angular_velocity[2] = -2.;
    if (dim == 3)
      box.angular_velocity[0] = 1.5;

    if (adaptive)
      {
        // the left half refined once, the bodies' surfaces twice, re-adapted
        // every 3 steps: particles sit on both sides of level boundaries
        // and move between cells of different levels
        using Criterion = typename MeshRefinementParameters<dim>::Criterion;
        parameters.refinement.criteria      = {Criterion::region, Criterion::body_surface};
        parameters.refinement.maximum_level = 1;
        parameters.refinement.interval      = 3;
        parameters.refinement.region_upper_corner[0] = 0.4;
        for (unsigned int d = 1; d < dim; ++d)
          parameters.refinement.region_upper_corner[d] = 1.;
      }

    parameters.bodies = {disk};
    Simulator<dim> simulator(triangulation, parameters);
    simulator.add_body(box);
    simulator.initialize();

    const std::vector<const BodyParameters<dim> *> bodies = {&disk, &box};
    const unsigned int                              n_bodies = bodies.size();

    Statistics<dim>         statistics = simulator.compute_statistics();
    const ParticleSums<dim> initial_sums = particle_sums(simulator, n_bodies, communicator);

    // the seeding rule: every particle of body b has mass
    // rho_b * cell volume / ppd^dim (on an adapted grid the cells differ)
    const auto expected_masses = [&](const ParticleSums<dim> &sums) {
      std::vector<double> masses(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
        masses[b] = adaptive ? statistics.body_mass[b] :
                               bodies[b]->material.density * sums.n_per_body[b] *
                                 std::pow(h / bodies[b]->particles_per_direction, dim);
      return masses;
    };
    const std::vector<double> masses = expected_masses(initial_sums);
    // the nodes' support volumes (the integrals of their shape functions)
    // add up to the grid's volume by the partition of unity, folded
    // hanging vertices included
    const auto check_support_volumes = [&](const std::string &when) {
      const sable::mpm::Grid<dim> &grid    = simulator.get_grid();
      const unsigned int           n_owned = grid.make_partitioner(1)->locally_owned_size();
      double                       sum     = 0;
      for (unsigned int node = 0; node < n_owned; ++node)
        sum += grid.node_support_volumes()[node];
      check_relative(name + "the nodes' support volumes add up to the grid's volume (" + when +
                       ")",
                     Utilities::MPI::sum(sum, communicator),
                     1.,
                     1e-12,
                     1.);
    };
    check_support_volumes("initial grid");
    if (adaptive)
      {
        const unsigned int hanging = Utilities::MPI::sum(
          simulator.get_grid().n_hanging_cells(), communicator);
        check(name + "the grid has cells with hanging vertices (" + std::to_string(hanging) + ")",
              hanging > 0);
      }
    double                    total_mass = 0;
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        total_mass += masses[b];
        check(name + "body " + std::to_string(b) + " has " +
                std::to_string(initial_sums.n_per_body[b]) + " particles",
              initial_sums.n_per_body[b] > 50);
      }
    const unsigned long long n_particles = statistics.n_particles;
    check(name + "initial particle count " + std::to_string(n_particles) +
            " = sum over bodies",
          n_particles == initial_sums.n_per_body[0] + initial_sums.n_per_body[1] &&
            n_particles == simulator.get_particle_handler().n_global_particles());
    if (n_ranks > 1)
      check(name + "every rank owns particles (smallest count " +
              std::to_string(initial_sums.min_local) + ")",
            initial_sums.min_local > 0);

    const Tensor<1, dim> initial_momentum = statistics.momentum;
    const std::vector<double> initial_body_mass = statistics.body_mass;
    double max_step_error = 0, max_mass_error = 0, max_mass_change = 0, scale = 0;
    bool                 count_constant = true, bodies_met = false;
    std::set<unsigned long long> cell_counts;
    const unsigned int   n_steps = 20;
    for (unsigned int n = 0; n < n_steps; ++n)
      {
        const Tensor<1, dim> before = statistics.momentum;
        simulator.step();
        statistics                = simulator.compute_statistics();
        cell_counts.insert(statistics.n_cells);
        const ParticleSums<dim> s = particle_sums(simulator, n_bodies, communicator);
        const double dt = simulator.get_time_step();
        const double step_scale =
          std::max(s.momentum_scale, initial_sums.momentum_scale) +
          total_mass * parameters.gravity.norm() * dt;
        scale = std::max(scale, step_scale);
        const Tensor<1, dim> expected = before + total_mass * dt * parameters.gravity;
        for (unsigned int d = 0; d < dim; ++d)
          max_step_error = std::max(max_step_error,
                                    std::abs(statistics.momentum[d] - expected[d]) / step_scale);
        for (unsigned int b = 0; b < n_bodies; ++b)
          {
            max_mass_error = std::max(max_mass_error,
                                      std::abs(statistics.body_mass[b] - masses[b]) / masses[b]);
            max_mass_change = std::max(max_mass_change,
                                       std::abs(statistics.body_mass[b] - initial_body_mass[b]) /
                                         initial_body_mass[b]);
          }
        count_constant = count_constant && statistics.n_particles == n_particles &&
                         simulator.get_particle_handler().n_global_particles() == n_particles &&
                         s.n_per_body == initial_sums.n_per_body;
        // the bodies' velocities must have changed from their initial
        // (rigid + gravity) ones by the collision
        const Tensor<1, dim> free_velocity =
          disk.velocity + simulator.get_time() * parameters.gravity;
        bodies_met = bodies_met || (statistics.body_velocity[0] - free_velocity).norm() > 1e-3;
      }
    check(name + "the bodies interacted (velocity of body 0 changed by the collision)",
          bodies_met);
    check_relative(name + "max over steps |P_n+1 - (P_n + M g dt)| / sum m|v|", max_step_error, 0.,
                   1e-12, 1.);
    for (unsigned int d = 0; d < dim; ++d)
      check_relative(name + "P_" + std::to_string(d) + " after " + std::to_string(n_steps) +
                       " steps = P_0 + M g t",
                     statistics.momentum[d],
                     initial_momentum[d] + total_mass * simulator.get_time() * parameters.gravity[d],
                     1e-12, scale);
    // (on an adapted grid the expected masses are the measured initial
    // ones, which the next check compares with already)
    if (!adaptive)
      check_relative(name + "max over steps and bodies |body mass - rho n V_particle| / mass",
                     max_mass_error, 0., 1e-12, 1.);
    check_relative(name + "max over steps and bodies |body mass - initial body mass| / mass",
                   max_mass_change, 0., 1e-13, 1.);
    check(name + "particle count constant (" + std::to_string(n_particles) + ")", count_constant);
    check_support_volumes("after the run");
    if (adaptive)
      check(name + "the grid changed during the run (" + std::to_string(cell_counts.size()) +
              " cell counts)",
            cell_counts.size() > 1);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // every rank computes the same global numbers; let rank 0 report them
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);

  using sable::mpm::UpdateScheme;
  for (const UpdateScheme scheme : {UpdateScheme::usl, UpdateScheme::musl, UpdateScheme::usavg})
    for (const double pic : {0., 0.5})
      for (const bool gravity : {false, true})
        {
          run_case<2>(scheme, pic, gravity);
          run_case<3>(scheme, pic, gravity);
        }
  // the same on adapted grids with hanging nodes
  run_case<2>(UpdateScheme::musl, 0., true, true);
  run_case<3>(UpdateScheme::musl, 0., true, true);
  run_case<2>(UpdateScheme::usl, 0.5, true, true);
  run_case<2>(UpdateScheme::usavg, 0., true, true);
  // GIMP (one rank only): its weights keep the partition of unity and
  // sum_k grad N_k = 0, next to the grid's faces too
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    for (const UpdateScheme scheme : {UpdateScheme::usl, UpdateScheme::musl, UpdateScheme::usavg})
      {
        run_case<2>(scheme, 0., true, false, true);
        run_case<3>(scheme, 0.5, true, false, true);
      }
  return sable_tests::exit_code();
}
