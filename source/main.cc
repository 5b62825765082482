// The `sable` program: reads a scene from a .prm file and runs it.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>
#include <sable/base/output_directory.h>
#include <sable/base/parameter_settings.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/run_scene.h>
#include <sable/qusgm/run_scene.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: sable [--threads N] [--set \"Subsection/Entry=value\"]... <scene.prm>\n"
           "             [--overwrite | --resume]\n"
           "       sable --print-parameters [mpm|qusgm] [2|3]\n"
           "       sable --help\n\n"
           "Runs the granular-mechanics scene described by the parameter file.\n"
           "'set Model = mpm|qusgm' picks the material point method with\n"
           "frictional contact or the quasi-static sphere-pack model;\n"
           "'set Dimension = 2|3' the MPM space dimension. Output goes to\n"
           "'set Output directory'. --print-parameters writes every entry\n"
           "with its default and documentation (see doc/parameters.md).\n\n"
           "A run does not start if its output directory holds the results\n"
           "of an earlier run (statistics.csv, increments.csv, particle or\n"
           "grain files, a checkpoint) or another sable run writes into it\n"
           "(the lock file sable.lock). --overwrite removes those earlier\n"
           "outputs first (only sable's own files, nothing else).\n"
           "--resume continues the run from the last checkpoint in\n"
           "its output directory (written with 'Output/Checkpoint interval'\n"
           "> 0), to the End time and step limit the file gives now;\n"
           "statistics.csv is continued as if the run had not stopped.\n"
           "The scene must be the one the checkpoint was written with\n"
           "(MPM: materials, bodies, grid, boundaries, contact; QuSGM:\n"
           "pack, walls, contact, minimiser); only the time limits or\n"
           "number of increments, the output and a few solver entries\n"
           "may change (doc/mpm.md, \"Resuming a run\"; doc/qusgm.md).\n"
           "--threads N runs N threads per MPI rank (0: one per core);\n"
           "it overrides the environment variable SABLE_THREADS and the\n"
           "scene's 'set Threads' (default 1).\n"
           "--set \"Subsection/.../Entry=value\" (or --set=...; repeatable)\n"
           "gives an entry of the scene a new value after the file is read,\n"
           "as if the file said 'set Entry = value' in that subsection;\n"
           "a top-level entry is just \"Entry=value\" (also Model and\n"
           "Dimension). The names are those of --print-parameters; an\n"
           "unknown entry or a value outside the entry's pattern stops the\n"
           "program before any work. Example, the first 20 steps of a scene:\n"
           "  sable prm/quick_demo.prm --set \"Time/Maximum number of steps=20\"\n"
           "        --set \"Output directory=output/short\"\n";
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
  // no thread limit here: set_threads() below sets it (default one)
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, dealii::numbers::invalid_unsigned_int);
  sable::set_threads(1);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
    {
      // --threads N (or --threads=N) and --set S (or --set=S) anywhere;
      // taken out of argv
      std::string              threads_option;
      std::vector<std::string> set_options;
      bool                     resume = false, overwrite = false;
      if (const char *environment = std::getenv("SABLE_THREADS"))
        threads_option = environment;
      for (int i = 1; i < argc; ++i)
        {
          const std::string argument = argv[i];
          int               taken    = 0;
          if (argument == "--threads")
            {
              sable::check_input(i + 1 < argc, "--threads", "(missing)",
                                 "an integer >= 0 (0: one thread per core)");
              threads_option = argv[i + 1];
              taken          = 2;
            }
          else if (argument.rfind("--threads=", 0) == 0)
            {
              threads_option = argument.substr(10);
              taken          = 1;
            }
          else if (argument == "--set")
            {
              sable::check_input(i + 1 < argc, "--set", "(missing)",
                                 "\"Subsection/.../Entry=value\"");
              set_options.push_back(argv[i + 1]);
              taken = 2;
            }
          else if (argument.rfind("--set=", 0) == 0)
            {
              set_options.push_back(argument.substr(6));
              taken = 1;
            }
          else if (argument == "--resume" || argument == "--overwrite")
            {
              (argument == "--resume" ? resume : overwrite) = true;
              taken = 1;
            }
          if (taken > 0)
            {
              for (int j = i; j + taken < argc; ++j)
                argv[j] = argv[j + taken];
              argc -= taken;
              --i;
            }
        }
      int threads = -1;
      if (!threads_option.empty())
        {
          std::size_t end = 0;
          try
            {
              threads = std::stoi(threads_option, &end);
            }
          catch (const std::exception &)
            {
              end = 0;
            }
          sable::check_input(end == threads_option.size() && threads >= 0,
                             "--threads (or SABLE_THREADS)", threads_option,
                             "an integer >= 0 (0: one thread per core)");
        }

      std::vector<sable::ParameterSetting> settings;
      for (const std::string &option : set_options)
        settings.push_back(sable::parse_parameter_setting(option));

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
      sable::check_input(!(resume && overwrite), "--resume and --overwrite", "both given",
                         "one of them: --resume continues the earlier run, --overwrite "
                         "replaces it");
      if (argc > 2 || first.rfind("-", 0) == 0)
        {
          if (root)
            {
              std::cerr << "sable: unexpected argument(s)\n";
              print_usage(std::cerr);
            }
          return 1;
        }

      const sable::CommonParameters common =
        sable::read_common_parameters(first, settings);
      sable::set_threads(threads >= 0 ? threads : common.threads);
      const sable::OutputMode mode = resume    ? sable::OutputMode::resume :
                                     overwrite ? sable::OutputMode::overwrite :
                                                 sable::OutputMode::fresh;
      if (common.model == sable::Model::qusgm)
        {
          sable::qusgm::run_scene(first, MPI_COMM_WORLD, mode, settings);
        }
      else if (common.dimension == 3)
        sable::mpm::run_scene<3>(first, MPI_COMM_WORLD, mode, settings);
      else
        sable::mpm::run_scene<2>(first, MPI_COMM_WORLD, mode, settings);
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
