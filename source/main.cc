// The `sable` program: reads a scene from a .prm file and runs it.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/run_scene.h>
#include <sable/qusgm/run_scene.h>

#include <iostream>
#include <string>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: sable <scene.prm> [--resume]\n"
           "       sable --print-parameters [mpm|qusgm] [2|3]\n"
           "       sable --help\n\n"
           "Runs the granular-mechanics scene described by the parameter file.\n"
           "'set Model = mpm|qusgm' picks the material point method with\n"
           "frictional contact or the quasi-static sphere-pack model;\n"
           "'set Dimension = 2|3' the MPM space dimension. Output goes to\n"
           "'set Output directory'. --print-parameters writes every entry\n"
           "with its default and documentation (see doc/parameters.md).\n\n"
           "--resume (MPM) continues the run from the last checkpoint in\n"
           "its output directory (written with 'Output/Checkpoint interval'\n"
           "> 0), to the End time and step limit the file gives now;\n"
           "statistics.csv is continued as if the run had not stopped.\n";
  }

  void
  print_parameters(const std::string &model, const unsigned int dim)
  {
    dealii::ParameterHandler prm;
    sable::declare_common_parameters(prm);
    if (model == "qusgm")
      sable::qusgm::declare_parameters(prm);
    else if (dim == 3)
      sable::mpm::declare_parameters<3>(prm, 1);
    else
      sable::mpm::declare_parameters<2>(prm, 1);
    prm.print_parameters(std::cout, dealii::ParameterHandler::PRM);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
    {
      if (argc < 2)
        {
          if (root)
            print_usage(std::cerr);
          return 1;
        }
      const std::string first = argv[1];
      if (first == "--help" || first == "-h")
        {
          if (root)
            print_usage(std::cout);
          return 0;
        }
      if (first == "--print-parameters")
        {
          const std::string  model = argc > 2 ? argv[2] : "mpm";
          const unsigned int dim   = argc > 3 ? std::stoi(argv[3]) : 2;
          if (root)
            print_parameters(model, dim);
          return 0;
        }
      const bool resume = argc == 3 && std::string(argv[2]) == "--resume";
      if ((argc > 2 && !resume) || first.rfind("-", 0) == 0)
        {
          if (root)
            {
              std::cerr << "sable: unexpected argument(s)\n";
              print_usage(std::cerr);
            }
          return 1;
        }

      const sable::CommonParameters common =
        sable::read_common_parameters(first);
      if (common.model == sable::Model::qusgm)
        {
          if (resume)
            throw sable::InputError("--resume: checkpoints exist for MPM scenes only "
                                    "('Model = mpm'), this scene is QuSGM");
          sable::qusgm::run_scene(first, MPI_COMM_WORLD);
        }
      else if (common.dimension == 3)
        sable::mpm::run_scene<3>(first, MPI_COMM_WORLD, resume);
      else
        sable::mpm::run_scene<2>(first, MPI_COMM_WORLD, resume);
    }
  catch (const sable::InputError &error)
    {
      if (root)
        std::cerr << "sable: " << error.what() << std::endl;
      return 2;
    }
  catch (const dealii::ExceptionBase &error)
    {
      // deal.II's own report (e.g. a parameter file line that does not match
      // its pattern): the explanation without the source location and
      // stack trace
      if (root)
        {
          std::cerr << "sable: error: ";
          error.print_info(std::cerr);
          std::cerr << std::endl;
        }
      return 2;
    }
  catch (const std::exception &error)
    {
      if (root)
        std::cerr << "sable: error: " << error.what() << std::endl;
      return 3;
    }
  return 0;
}
