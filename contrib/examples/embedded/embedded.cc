// A deal.II program that builds its own mesh and hands it to sable: an
// elastic disk thrown against a slip wall, stepped from this program's own
// loop, which writes statistics every step and particle files every tenth
// step into the directory given as the first argument (default
// output/embedded). Prints the disk's centre of mass and returns non-zero
// if momentum in the wall-parallel direction was not conserved.
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>

#include <sable/mpm/simulator.h>

#include <cmath>
#include <iostream>

int
main(int argc, char **argv)
{
  using namespace dealii;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // the program's own triangulation: a refined square, boundary ids 0..3
  parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(triangulation, 0., 1., /*colorize=*/true);
  triangulation.refine_global(5);

  sable::mpm::SimulatorParameters<2> parameters;
  parameters.end_time      = 0.05;
  parameters.print_timings = false;
  parameters.output_directory = argc > 1 ? argv[1] : "output/embedded";
  parameters.boundaries[0].type = sable::mpm::BoundaryType::slip; // x = 0
  // a friction wall at y = 1, which the disk does not reach in this time
  parameters.boundaries[3].type     = sable::mpm::BoundaryType::friction;
  parameters.boundaries[3].friction = 0.3;

  sable::mpm::Simulator<2> simulator(triangulation, parameters);

  sable::mpm::BodyParameters<2> disk;
  disk.shape  = sable::mpm::BodyParameters<2>::Shape::disk;
  disk.center = Point<2>(0.3, 0.5);
  disk.radius = 0.2;
  disk.material.set_young_poisson(1e6, 0.3);
  disk.material.density = 1000;
  disk.velocity[0] = -2.;
  disk.velocity[1] = 1.;
  simulator.add_body(disk);

  simulator.initialize();
  const auto start = simulator.compute_statistics();
  simulator.write_output();
  while (simulator.get_time() < parameters.end_time * (1 - 1e-12))
    {
      simulator.step();
      simulator.write_statistics();
      if (simulator.get_step_number() % 10 == 0)
        simulator.write_output();
    }
  const auto end = simulator.compute_statistics();

  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "steps " << simulator.get_step_number() << ", centre of mass ("
              << end.body_position[0] << "), velocity (" << end.body_velocity[0]
              << ")" << std::endl;
  // the slip wall takes only x-momentum: y-momentum stays
  const double error =
    std::abs(end.momentum[1] - start.momentum[1]) / std::abs(start.momentum[1]);
  return error < 1e-12 && end.body_velocity[0][0] > -2. ? 0 : 1;
}
