// Fail loudly: packs QuSGM cannot use are refused before any output with
// a message naming the grains (overlaps beyond the settable fraction of
// the radius, with a grain or a wall; coincident grains; one grain; zero
// density); a preparation that cannot compact the pack (an increment at
// its iteration limit, or no contacts when its increments run out) stops
// with a message, its increments so far in increments.csv; the minimiser
// stops when it stagnates and says so, instead of running to its
// iteration limit.
#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/qusgm/preparation.h>
#include <sable/qusgm/run_scene.h>
#include <sable/qusgm/simulation.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.h"

using namespace sable::qusgm;
using sable_tests::check;
namespace fs = std::filesystem;

namespace
{
  const fs::path work = fs::current_path() / "qusgm_failures.work";

  std::string
  scene(const std::string &name, const std::string &body)
  {
    const fs::path file = work / (name + ".prm");
    std::ofstream(file) << "set Model = qusgm\nset Output directory = "
                        << (work / ("out_" + name)).string() << "\n"
                        << body;
    return file.string();
  }

  void
  write(const std::string &name, const std::string &text)
  {
    std::ofstream(work / name) << text;
  }

  /// Run the scene; return the message of the exception of type E (empty
  /// if none was thrown).
  template <typename E>
  std::string
  run(const std::string &file)
  {
    try
      {
        run_scene(file, MPI_COMM_WORLD);
      }
    catch (const E &e)
      {
        return e.what();
      }
    return "";
  }

  void
  expect_refused(const std::string              &name,
                 const std::string              &body,
                 const std::vector<std::string> &parts)
  {
    const std::string message = run<sable::InputError>(scene(name, body));
    std::cout << name << ": " << message << std::endl;
    bool        all = !message.empty();
    std::string wanted;
    for (const std::string &part : parts)
      {
        all &= message.find(part) != std::string::npos;
        wanted += " '" + part + "'";
      }
    check(name + ": refused, naming" + wanted, all);
    check(name + ": nothing written", !fs::exists(work / ("out_" + name)));
  }

  std::string
  from(const std::string &file, const std::string &more = "")
  {
    return "subsection Pack\n  set Source = file\n  set File = " + file + "\n" + more +
           "end\nsubsection Preparation\n  set Enabled = false\nend\n"
           "subsection Load path\n  set Number of increments = 0\nend\n";
  }

  std::vector<std::vector<std::string>>
  rows(const fs::path &csv)
  {
    std::ifstream                         in(csv);
    std::string                           line;
    std::vector<std::vector<std::string>> result;
    while (std::getline(in, line))
      {
        std::vector<std::string> fields;
        std::stringstream        s(line);
        std::string              field;
        while (std::getline(s, field, ','))
          fields.push_back(field);
        if (!line.empty() && line.back() == ',')
          fields.push_back("");
        result.push_back(fields);
      }
    return result;
  }

  void
  refuse_packs()
  {
    const std::string walls = "subsection Walls\n  set Positions = 0, 0, 0, 6e-4, 3e-4, 3e-4\nend\n";
    // 2e-5 m = 20% of the radius, beyond the default 10%; accepted at 25%.
    write("overlap.csv", "id x y z r\n11 1e-4 1e-4 1e-4 1e-4\n12 2.8e-4 1e-4 1e-4 1e-4\n");
    expect_refused("grain_overlap", from("overlap.csv") + walls,
                   {"overlap of grain 0 (id 11) and grain 1 (id 12)", "2e-05",
                    "Pack/Maximum initial overlap = 0.1"});
    const std::string accepted = scene(
      "grain_overlap_allowed",
      from("overlap.csv", "  set Maximum initial overlap = 0.25\n") + walls);
    check("grain_overlap: accepted with 'Maximum initial overlap = 0.25'",
          run<std::exception>(accepted).empty() &&
            fs::exists(work / "out_grain_overlap_allowed" / "final_state" / "grains.csv"));

    write("pair.csv", "x y z r\n1e-4 1e-4 1e-4 1e-4\n3e-4 1e-4 1e-4 1e-4\n");
    expect_refused("wall_overlap",
                   from("pair.csv") +
                     "subsection Walls\n  set Positions = 0.2e-4, 0, 0, 6e-4, 3e-4, 3e-4\nend\n",
                   {"overlap of grain 0 and wall x_min", "2e-05", "times the radius"});

    write("coincident.csv",
          "id,x,y,z,r\n5,1e-4,1e-4,1e-4,1e-4\n6,3e-4,1e-4,1e-4,1e-4\n9,1e-4,1e-4,1e-4,1e-4\n");
    expect_refused("coincident", from("coincident.csv") + walls,
                   {"grain 0 (id 5) and grain 2 (id 9)", "coincide"});

    write("one.csv", "x y z r\n1e-4 1e-4 1e-4 1e-4\n");
    expect_refused("one_grain", from("one.csv"), {"number of grains = 1", "at least two grains"});
    expect_refused("one_grain_generated", "subsection Pack\n  set Number of grains = 1\nend\n",
                   {"Pack/Number of grains = 1", "at least two grains"});

    write("weightless.csv", "x y z r rho\n1e-4 1e-4 1e-4 1e-4 2420\n3e-4 1e-4 1e-4 1e-4 0\n");
    expect_refused("zero_density_in_file", from("weightless.csv") + walls,
                   {"grain 1 density = 0", "rho > 0"});
    expect_refused("zero_density", "subsection Pack\n  set Density = 0\nend\n",
                   {"Pack/Density = 0", "> 0"});

    expect_refused("state_with_preparation",
                   "subsection Pack\n  set Source = state\n  set File = somewhere\nend\n",
                   {"Preparation/Enabled", "false"});
  }

  void
  preparation_failures()
  {
    const std::string pack = "subsection Pack\n  set Number of grains = 40\n  set Random seed = 4\nend\n";
    // Coarse compaction steps and five iterations per increment (the walls
    // moved at once, so the limit applies from the start): the first
    // increment with contacts cannot converge.
    const std::string limited =
      scene("iteration_limit",
            pack +
              "subsection Preparation\n  set Compaction strain increment = 0.05\nend\n"
              "subsection Minimizer\n  set Method = lbfgs\n  set Maximum iterations = 5\n"
              "  set Wall sub-increments = 1\n"
              "  set Energy tolerance = 0\n  set Gradient tolerance = 0\n"
              "  set Force tolerance = 1e-6\nend\n");
    const std::string message = run<PreparationError>(limited);
    std::cout << "iteration_limit: " << message << std::endl;
    const auto table = rows(work / "out_iteration_limit" / "increments.csv");
    check("iteration limit in preparation: stops with a message naming the increment and the limit",
          table.size() > 1 &&
            message.find("increment " + table.back()[0] + " (") != std::string::npos &&
            message.find("'Minimizer/Maximum iterations' = 5") != std::string::npos);
    check("iteration limit in preparation: its last row is that increment, 5 iterations, "
          "stopped by the iteration limit",
          table.size() > 1 && table.back().size() == table[0].size() &&
            table.back()[19] == "5" && table.back().back() == "iteration limit" &&
            table[0][19] == "iterations");
    check("iteration limit in preparation: no prepared state, no load path",
          !fs::exists(work / "out_iteration_limit" / "prepared_state") &&
            !fs::exists(work / "out_iteration_limit" / "final_state"));

    // Three increments cannot bring the walls of a loose pack to its grains.
    const std::string short_run =
      scene("no_contacts",
            pack + "subsection Preparation\n  set Maximum compaction increments = 3\nend\n");
    const std::string none = run<PreparationError>(short_run);
    std::cout << "no_contacts: " << none << std::endl;
    const auto loose = rows(work / "out_no_contacts" / "increments.csv");
    check("no contacts after the compaction increments: stops with a message",
          none.find("after 3 increments") != std::string::npos &&
            none.find("sigma_c = 0 Pa with 0 contacts") != std::string::npos);
    check("no contacts: increments.csv holds the three increments, each without contacts",
          loose.size() == 4 && loose[1][18] == "0" && loose[3][18] == "0" &&
            loose[0][18] == "contacts");
  }

  void
  stagnation()
  {
    // A column of six grains between two walls, L-BFGS asked for a force
    // balance below round-off (1e-17 of the largest contact force; it
    // reaches about 1e-12).
    Pack        pack;
    const double r = 1e-4;
    for (unsigned int k = 0; k < 6; ++k)
      pack.add_grain(Point<3>(r, r, (2 * k + 1) * r), r, 70e9, 0.2, 2420);
    Walls walls;
    walls.position = {{-10 * r, -10 * r, 0, 12 * r, 12 * r, 12 * r}};
    ContactModel model;
    model.wall_friction = 0;
    MinimizerSettings settings;
    settings.method             = MinimizerSettings::Method::lbfgs;
    settings.sub_increments     = 1;
    settings.energy_tolerance   = 0;
    settings.gradient_tolerance = 0;
    settings.force_tolerance    = 1e-17;
    settings.max_iterations     = 3000;
    std::array<double, 6> move{};
    move[2] = 1.2e-7;
    move[5] = -1.2e-7;

    for (const unsigned int window : {0u, 50u})
      {
        settings.stagnation_window = window;
        std::ostringstream         console;
        dealii::ConditionalOStream out(console, true);
        Simulation                 sim(pack, walls, model, settings, out);
        const IncrementResult     &result = sim.step(move, "test").result;
        std::cout << "window " << window << ": " << console.str();
        if (window == 0)
          check("without the stagnation stop: runs to the iteration limit (3000)",
                result.stopped_by == "iteration limit" && result.iterations == 3000 &&
                  result.last_progress < 200);
        else
          {
            check("stagnation: stops 50 iterations after the last progress, unconverged",
                  result.stopped_by == "stagnation" && !result.converged &&
                    result.iterations == result.last_progress + 50 && result.iterations < 300);
            check("stagnation: at the round-off floor (residual below 1e-10 of the largest force)",
                  result.residual < 1e-10 * result.max_contact_force);
            check("stagnation: the progress line says so",
                  console.str().find("(not converged: stagnation)") != std::string::npos);
          }
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  fs::remove_all(work);
  fs::create_directories(work);
  refuse_packs();
  preparation_failures();
  stagnation();
  return sable_tests::exit_code();
}
