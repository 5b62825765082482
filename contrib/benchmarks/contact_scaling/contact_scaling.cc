// Cost of contact against the number of grains: a fixed set of material
// points (a 2D square of 256^2 cells, 2x2 points per cell) split into
// 1, 16, 100, 1024 and 10000 square grains that tile it densely, each with
// its own random velocity, so most nodes between grains are contact nodes.
// Each configuration runs 40 steps with the Bardenhagen 2001 contact model
// (mu = 0.3) and, for comparison, single-field (contact none).
// Prints the wall time per step of each, and how much momentum the contact
// corrections did not conserve (at nodes with three or more bodies) relative
// to the size of the corrections; see doc/benchmarks.md.
//
// Usage: contact_scaling [cells per direction = 256] [steps = 40]
//                        [pairwise (default) | centre-of-mass]
//                        [grains per side: only this tiling] [timings]
//                        [normals=NAME]
// (the treatment of nodes with three or more bodies; 'timings' prints the
// wall time of each phase of the timed steps of every run; 'normals=' a
// 'Contact/Normals' other than the default, with '-' for ' ', as in
// normals=largest-mass)
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <sable/mpm/run_scene.h>
#include <sable/mpm/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace dealii;
using namespace sable::mpm;

namespace
{
  ContactParameters::Normals normals = ContactParameters().normals;

  double
  seconds_per_step(const unsigned int n_cells,
                   const unsigned int n_grains_per_side,
                   const ContactParameters::Model model,
                   const ContactParameters::MultiBodyNodes multi_body_nodes,
                   const unsigned int n_steps,
                   const bool         print_timings,
                   unsigned long long &n_particles,
                   double &            momentum_defect)
  {
    GridParameters<2> grid;
    grid.lower_corner = Point<2>(0, 0);
    grid.upper_corner = Point<2>(1, 1);
    grid.subdivisions = {n_cells, n_cells};
    grid.face_ids     = {0, 1, 2, 3};
    parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
    make_grid(grid, triangulation);

    SimulatorParameters<2> parameters;
    parameters.end_time         = 1e9;
    parameters.print_timings    = false;
    // MUSL with and without contact, so that the ratio is contact's own
    // cost (the default for contact between bodies, USAVG, costs about
    // 1.4 times MUSL's step besides: doc/benchmarks.md, "USAVG")
    parameters.update_scheme    = UpdateScheme::musl;
    parameters.contact.model    = model;
    parameters.contact.friction = 0.3;
    parameters.contact.multi_body_nodes = multi_body_nodes;
    parameters.contact.normals          = normals;
    for (unsigned int b = 0; b < 4; ++b)
      parameters.boundaries[b].type = BoundaryType::slip;

    std::mt19937                     random(42);
    std::uniform_real_distribution<> speed(-0.5, 0.5);
    const double                     width = 1. / n_grains_per_side;
    for (unsigned int i = 0; i < n_grains_per_side; ++i)
      for (unsigned int j = 0; j < n_grains_per_side; ++j)
        {
          BodyParameters<2> grain;
          grain.shape        = BodyParameters<2>::Shape::box;
          grain.lower_corner = Point<2>(i * width, j * width);
          // half-open boxes so that each material point belongs to one grain
          grain.upper_corner = Point<2>((i + 1) * width - 1e-12, (j + 1) * width - 1e-12);
          grain.particles_per_direction = 2;
          grain.material.set_young_poisson(1e6, 0.3);
          grain.material.density = 1000;
          grain.velocity         = Tensor<1, 2>({speed(random), speed(random)});
          parameters.bodies.push_back(grain);
        }
    Simulator<2> simulator(triangulation, parameters);
    simulator.initialize();
    n_particles = simulator.get_particle_handler().n_global_particles();
    simulator.step(); // warm-up: first allocation of the contact tables
    // the phases' times from here on: the warm-up step is not counted
    simulator.get_timer().reset();
    Timer timer;
    for (unsigned int n = 0; n < n_steps; ++n)
      simulator.step();
    const double seconds = timer.wall_time() / n_steps;
    if (print_timings)
      simulator.get_timer().print_summary();
    if (const auto *contact = simulator.get_contact())
      momentum_defect = contact->momentum_defect / std::max(contact->momentum_correction, 1e-300);
    return seconds;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int n_cells = argc > 1 ? std::stoi(argv[1]) : 256;
  const unsigned int n_steps = argc > 2 ? std::stoi(argv[2]) : 40;
  const auto         multi_body_nodes = argc > 3 && std::string(argv[3]) == "centre-of-mass" ?
                                          ContactParameters::MultiBodyNodes::centre_of_mass :
                                          ContactParameters::MultiBodyNodes::pairwise;
  std::vector<unsigned int> tilings = {1u, 4u, 10u, 32u, 100u};
  if (argc > 4)
    tilings = {static_cast<unsigned int>(std::stoi(argv[4]))};
  const bool print_timings = argc > 5 && std::string(argv[5]) == "timings";
  for (int i = 1; i < argc; ++i)
    if (std::string argument = argv[i]; argument.rfind("normals=", 0) == 0)
      {
        // read as the scene files' 'Contact/Normals' is
        std::string name = argument.substr(8);
        std::replace(name.begin(), name.end(), '-', ' ');
        ParameterHandler prm;
        ContactParameters::declare_parameters(prm);
        try
          {
            prm.set("Normals", name);
          }
        catch (const ExceptionBase &error)
          {
            std::cerr << "contact_scaling: " << argument << ": ";
            error.print_info(std::cerr);
            return 1;
          }
        ContactParameters contact;
        contact.parse_parameters(prm, 0);
        normals = contact.normals;
      }
  std::cout << "| grains | material points | contact none, s/step | bardenhagen 2001, s/step | "
               "contact / none | momentum defect / correction |\n|---|---|---|---|---|---|"
            << std::endl;
  for (const unsigned int per_side : tilings)
    {
      unsigned long long n_particles = 0;
      double             defect      = 0;
      const double none = seconds_per_step(n_cells, per_side, ContactParameters::Model::none,
                                           multi_body_nodes, n_steps, print_timings, n_particles, defect);
      const double with_contact = seconds_per_step(n_cells,
                                                   per_side,
                                                   ContactParameters::Model::bardenhagen_2001,
                                                   multi_body_nodes,
                                                   n_steps,
                                                   print_timings,
                                                   n_particles,
                                                   defect);
      std::cout << "| " << per_side * per_side << " | " << n_particles << " | " << std::fixed
                << std::setprecision(4) << none << " | " << with_contact << " | "
                << std::setprecision(2) << with_contact / none << " | " << std::scientific
                << defect << std::defaultfloat << " |" << std::endl;
    }
}
