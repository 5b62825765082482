// Runs a QuSGM scene through the library, like `sable scene.prm` does:
// usable before the program is built, and by the benchmark scripts.
#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/qusgm/run_scene.h>

#include <iostream>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc != 2)
    {
      std::cerr << "Usage: qusgm_run <scene.prm>\n";
      return 1;
    }
  try
    {
      sable::qusgm::run_scene(argv[1], MPI_COMM_WORLD);
    }
  catch (const sable::InputError &e)
    {
      std::cerr << "qusgm_run: " << e.what() << std::endl;
      return 2;
    }
  catch (const std::exception &e)
    {
      std::cerr << "qusgm_run: error: " << e.what() << std::endl;
      return 3;
    }
  return 0;
}
