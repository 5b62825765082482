// A deal.II program that builds its own mesh and hands it to sable: an
// elastic disk thrown against a slip wall, stepped from this program's own
// loop. Prints the disk's centre of mass and returns non-zero if momentum
// in the wall-parallel direction was not conserved.
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
  parameters.boundaries[0].type = sable::mpm::BoundaryType::slip; // x = 0

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
  while (simulator.get_time() < parameters.end_time * (1 - 1e-12))
    simulator.step();
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
