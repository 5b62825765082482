// The QuSGM scene runner: parameters, checks, preparation, load path,
// output.
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/timer.h>

#include <sable/base/input_error.h>
#include <sable/base/parameter_file.h>
#include <sable/base/common_parameters.h>
#include <sable/qusgm/load_path.h>
#include <sable/qusgm/pack_io.h>
#include <sable/qusgm/preparation.h>
#include <sable/base/checkpoint_directory.h>
#include <sable/qusgm/checkpoint.h>
#include <sable/qusgm/run_scene.h>
#include <sable/qusgm/simulation.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace sable::qusgm
{
  using dealii::ParameterHandler;
  namespace Patterns = dealii::Patterns;

  void
  declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Output directory", "",
                      Patterns::Anything(),
                      "Where the run writes increments.csv, the grain VTU "
                      "files and the final pack. Empty: output/<scene name>. "
                      "A run does not start if it holds an earlier run's "
                      "outputs (sable --overwrite removes them, --resume "
                      "continues that run) or another run writes into it "
                      "(the lock file sable.lock).");
    prm.enter_subsection("Pack");
    {
      prm.declare_entry("Source", "generate", Patterns::Selection("generate|file|state"),
                        "generate: a loose random polydisperse pack (then "
                        "prepare it); file: read grains from the pack file 'File'; "
                        "state: continue from a state directory written by sable "
                        "('File' = e.g. output/<scene>/final_state: grains, walls, "
                        "box of zero strain and the contacts' tangential loads; "
                        "needs 'Preparation/Enabled = false' and no 'Walls/Positions').");
      prm.declare_entry("File", "", Patterns::Anything(),
                        "Pack file (SI units), recognised by its content: columns "
                        "named by a header line (x, y, z, r|radius|diameter, "
                        "optional E, nu, rho|density, id; or exactly x y z r without "
                        "a header), Yade's text export (#format x_y_z_r), or a "
                        "LAMMPS/LIGGGHTS text dump (ITEM: ATOMS id x y z radius ..., "
                        "last snapshot). With Source = state, the state directory. "
                        "Relative to the parameter file's directory.");
      prm.declare_entry("Maximum initial overlap", "0.1", Patterns::Double(),
                        "A pack from a file or state is refused, naming the grains, "
                        "if two grains overlap by more than this fraction of the "
                        "smaller radius, or a grain and a wall by more than this "
                        "fraction of its radius (Hertz contacts are small).");
      prm.declare_entry("Number of grains", "500", Patterns::Integer(),
                        "Grains of a generated pack.");
      prm.declare_entry("Minimum radius", "0.07e-3", Patterns::Double(),
                        "Radii are uniform between the minimum and maximum [m].");
      prm.declare_entry("Maximum radius", "0.13e-3", Patterns::Double(), "[m]");
      prm.declare_entry("Young's modulus", "70e9", Patterns::Double(),
                        "Mean grain Young's modulus [Pa] (also the default for "
                        "pack files without that column).");
      prm.declare_entry("Young's modulus deviation", "0.1", Patterns::Double(),
                        "Standard deviation of the grain moduli relative to the "
                        "mean (normal distribution).");
      prm.declare_entry("Poisson's ratio", "0.2", Patterns::Double(),
                        "Grain Poisson's ratio, -1 < nu < 0.5.");
      prm.declare_entry("Density", "2420", Patterns::Double(),
                        "[kg/m^3], > 0 (also the default for pack files without it).");
      prm.declare_entry("Initial solid fraction", "0.3", Patterns::Double(),
                        "Solid fraction of the generated loose pack.");
      prm.declare_entry("Random seed", "1", Patterns::Integer(0));
    }
    prm.leave_subsection();
    prm.enter_subsection("Walls");
    {
      prm.declare_entry("Young's modulus", "7e12", Patterns::Double(),
                        "Wall Young's modulus [Pa] (paper: 100 times the grains').");
      prm.declare_entry("Poisson's ratio", "0.495", Patterns::Double());
      prm.declare_entry("Positions", "", Patterns::Anything(),
                        "x_min, y_min, z_min, x_max, y_max, z_max [m] of the "
                        "walls around a pack file; empty: the tightest box.");
    }
    prm.leave_subsection();
    prm.enter_subsection("Contact");
    {
      prm.declare_entry("Friction coefficient", "0.3", Patterns::Double(),
                        "Coulomb friction between grains, mu >= 0 (0: "
                        "frictionless, no tangential or torsional work).");
      prm.declare_entry("Wall friction coefficient", "0.3", Patterns::Double(),
                        "Coulomb friction between grains and walls, >= 0.");
      prm.declare_entry("Torsion", "true", Patterns::Bool(),
                        "Torsional couples at frictional contacts.");
      prm.declare_entry("Gravity", "false", Patterns::Bool(),
                        "Weight of the grains along -z.");
      prm.declare_entry("Gravity acceleration", "9.81", Patterns::Double(), "[m/s^2]");
      prm.declare_entry("Friction cap", "reference", Patterns::Selection("reference|current"),
                        "Normal load of the Coulomb caps mu P, (3 pi/16) a mu P: "
                        "'reference' the increment's reference P0, a0 (the "
                        "paper's eq. 6-7); 'current' the equilibrium's own P, a "
                        "(the increment is solved again with updated caps until "
                        "no cap changes by more than 1e-3 of the largest).");
      prm.declare_entry("Sliding tolerance", "0", Patterns::Double(),
                        "A contact counts as sliding when |Q| >= (1 - tolerance) "
                        "Q_max; 0 <= tolerance < 1 (0: the paper's |Q| = Q_max).");
      prm.declare_entry("Sliding count", "at cap", Patterns::Selection("at cap|eq. 7b"),
                        "Which contacts at the cap count as sliding: 'at cap' "
                        "every one; 'eq. 7b' only those for which the paper's "
                        "reduced stiffness (eq. 7b as printed, with |Q^p.u_s|) "
                        "gives |Q| = Q_max, Q^p.u_s >= 0: in continued loading "
                        "(Q^p.u_s < 0) it gives |Q| > Q_max, which the paper's "
                        "definition does not count.");
      prm.declare_entry("Stick-slip decision", "per evaluation",
                        Patterns::Selection("per evaluation|per increment"),
                        "When a contact's stick or slip is decided: 'per "
                        "evaluation' from the trial force Q* = Q^p - k* u_s "
                        "wherever Pi is evaluated; 'per increment' once, from "
                        "Q* at the increment's initial guess (with wall "
                        "sub-increments, that of the first): a contact that "
                        "sticks there keeps the stick stiffness without a cap "
                        "until the increment ends, and its load is capped when "
                        "it becomes the next reference.");
    }
    prm.leave_subsection();
    prm.enter_subsection("Preparation");
    {
      prm.declare_entry("Enabled", "true", Patterns::Bool(),
                        "Prepare the pack as in the paper's section 3.2 before "
                        "the load path: (a) frictionless isotropic compaction "
                        "with grain growth, (b) frictional uniaxial strain "
                        "until the sliding ratio saturates.");
      prm.declare_entry("Target confining stress", "10e6", Patterns::Double(),
                        "sigma_c at the end of stage (a) [Pa].");
      prm.declare_entry("Compaction strain increment", "4e-3", Patterns::Double(),
                        "Largest isotropic strain step of stage (a).");
      prm.declare_entry("Minimum coordination", "4", Patterns::Integer(1),
                        "Grains with fewer contacts grow in stage (a).");
      prm.declare_entry("Maximum growth", "0.05", Patterns::Double(),
                        "Largest radius growth of a grain per growth round, "
                        "relative to its radius.");
      prm.declare_entry("Maximum compaction increments", "2000", Patterns::Integer(1));
      prm.declare_entry("Maximum growth rounds", "40", Patterns::Integer(0));
      prm.declare_entry("Friction activation", "true", Patterns::Bool(),
                        "Run stage (b).");
      prm.declare_entry("Activation strain increment", "1e-4", Patterns::Double());
      prm.declare_entry("Maximum activation increments", "200", Patterns::Integer(1));
      prm.declare_entry("Saturation window", "5", Patterns::Integer(1),
                        "Stage (b) ends when the sliding ratio varies by less "
                        "than the tolerance over this many increments.");
      prm.declare_entry("Saturation tolerance", "0.01", Patterns::Double());
    }
    prm.leave_subsection();
    prm.enter_subsection("Load path");
    {
      prm.declare_entry("Type", "uniaxial strain",
                        Patterns::Selection("isotropic|uniaxial strain|triaxial"));
      prm.declare_entry("Axis", "z", Patterns::Selection("x|y|z"),
                        "Axial direction of uniaxial strain and triaxial paths.");
      prm.declare_entry("Strain increment", "1e-4", Patterns::Double(),
                        "Axial strain per increment, compression positive.");
      prm.declare_entry("Number of increments", "10", Patterns::Integer(0));
      prm.declare_entry("Lateral strain ratio", "0.5", Patterns::Double(),
                        "Triaxial: lateral strain increment / axial one.");
    }
    prm.leave_subsection();
    prm.enter_subsection("Minimizer");
    {
      prm.declare_entry("Method", "nlcg", Patterns::Selection("nlcg|lbfgs"),
                        "nlcg: the paper's Fletcher-Reeves conjugate gradients "
                        "with a bounded Brent line search; lbfgs: limited-"
                        "memory BFGS with a weak-Wolfe line search (faster).");
      prm.declare_entry("Steepest descent restart", "10", Patterns::Integer(0),
                        "k_SD: nlcg restarts with steepest descent this often.");
      prm.declare_entry("Wall sub-increments", "10", Patterns::Integer(1),
                        "The wall move of an increment is applied in this many parts.");
      prm.declare_entry("Iterations per sub-increment", "10", Patterns::Integer(1),
                        "k_inc: iterations between wall sub-increments.");
      prm.declare_entry("Maximum iterations", "20000", Patterns::Integer(1), "k_max");
      prm.declare_entry("Energy tolerance", "1e-11", Patterns::Double(0),
                        "epsilon_1: stop when Pi decreases by less than this "
                        "fraction of |Pi| (0: off).");
      prm.declare_entry("Gradient tolerance", "1e-13", Patterns::Double(0),
                        "epsilon_2: stop when |grad Pi|^2 < epsilon_2 N (E R^2)^2 (0: off).");
      prm.declare_entry("Force tolerance", "0", Patterns::Double(0),
                        "Stop when the largest residual force (or moment/R) is "
                        "below this fraction of the largest contact force (0: off).");
      prm.declare_entry("Increment force tolerance", "0", Patterns::Double(0),
                        "Stop when the largest residual is below this fraction of "
                        "the largest change of a contact force in the increment (0: off).");
      prm.declare_entry("Displacement cap", "0.01", Patterns::Double(),
                        "Largest move of a grain per iteration, relative to its radius.");
      prm.declare_entry("Line search bits", "24", Patterns::Integer(4, 52),
                        "Accuracy of the Brent line search (bits of the step).");
      prm.declare_entry("LBFGS history", "8", Patterns::Integer(1, 100));
      prm.declare_entry("Initial guess", "affine",
                        Patterns::Selection("affine|previous increment"),
                        "affine: the field that carries the walls (the paper's "
                        "eq. A1); previous increment: the last increment's "
                        "solution, scaled, when the walls repeat its move "
                        "(needs 'Wall sub-increments = 1'; else affine).");
      prm.declare_entry("Stagnation window", "100", Patterns::Integer(0),
                        "Stop an increment unconverged ('stagnation' in the console "
                        "and in increments.csv's stopped_by) when this many iterations "
                        "bring neither a largest residual 1% below the lowest so far "
                        "nor a lower Pi (beyond round-off); 0: run to 'Maximum "
                        "iterations'.");
      prm.declare_entry("Skin", "0.3", Patterns::Double(),
                        "Contact search distance beyond touching, relative to "
                        "the mean radius.");
    }
    prm.leave_subsection();
    prm.enter_subsection("Output");
    {
      prm.declare_entry("VTU increments", "last", Patterns::Anything(),
                        "Increments of the load path to write as grains-NNNNN.vtu: "
                        "'none', or a comma-separated list of increment numbers "
                        "(0: the prepared pack), 'last' and 'all'.");
      prm.declare_entry("Checkpoint interval", "0", Patterns::Integer(0),
                        "Write a checkpoint (output directory/checkpoint) when the "
                        "pack is prepared and then every this many increments of "
                        "the load path; 0: none. 'sable scene.prm --resume' "
                        "continues from the last one, on any number of MPI ranks, "
                        "as if the run had not stopped. The parameter file is read "
                        "again on resume: keep the pack and the load path.");
      prm.declare_entry("Iteration log", "false", Patterns::Bool(),
                        "Write every minimiser iteration (iteration, Pi, |grad Pi|, "
                        "step, active and sliding contacts) to iterations.log.");
    }
    prm.leave_subsection();
  }

  namespace
  {
    std::string
    resolve(const std::string &path, const std::string &parameter_file)
    {
      namespace fs = std::filesystem;
      if (path.empty() || fs::path(path).is_absolute())
        return path;
      return (fs::path(parameter_file).parent_path() / path).string();
    }
  } // namespace

  void
  run_scene(const std::string &                  filename,
            MPI_Comm                             communicator,
            const OutputMode                     mode,
            const std::vector<ParameterSetting> &parameter_settings)
  {
    const bool resume = mode == OutputMode::resume;
    const auto start = std::chrono::steady_clock::now();
    const bool root  = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);

    ParameterHandler prm;
    declare_common_parameters(prm);
    declare_parameters(prm);
    try
      {
        parse_parameter_file(prm, filename);
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::ostringstream message;
        e.print_info(message);
        throw InputError("cannot use the parameter file '" + filename +
                         "': " + message.str());
      }
    apply_parameter_settings(prm, parameter_settings);
    // what a checkpoint keeps and a resume compares
    const std::vector<std::pair<std::string, std::string>> entries = parameter_entries(prm);

    // --- Read and check everything before any work or output.
    ContactModel model;
    prm.enter_subsection("Contact");
    model.friction             = prm.get_double("Friction coefficient");
    model.wall_friction        = prm.get_double("Wall friction coefficient");
    model.torsion              = prm.get_bool("Torsion");
    model.gravity              = prm.get_bool("Gravity");
    model.gravity_acceleration = prm.get_double("Gravity acceleration");
    model.friction_cap         = prm.get("Friction cap") == "current" ?
                                   ContactModel::FrictionCap::current :
                                   ContactModel::FrictionCap::reference;
    model.sliding_tolerance = prm.get_double("Sliding tolerance");
    model.sliding_count     = prm.get("Sliding count") == "eq. 7b" ?
                                ContactModel::SlidingCount::eq_7b :
                                ContactModel::SlidingCount::at_cap;
    model.stick_slip = prm.get("Stick-slip decision") == "per increment" ?
                         ContactModel::StickSlip::per_increment :
                         ContactModel::StickSlip::per_evaluation;
    prm.leave_subsection();
    check_input(model.sliding_tolerance >= 0 && model.sliding_tolerance < 1,
                "Contact/Sliding tolerance", model.sliding_tolerance, "0 <= tolerance < 1");
    check_input(model.friction >= 0, "Contact/Friction coefficient",
                model.friction, "mu >= 0");
    check_input(model.wall_friction >= 0, "Contact/Wall friction coefficient",
                model.wall_friction, "mu >= 0");

    Walls walls;
    std::string wall_positions;
    prm.enter_subsection("Walls");
    walls.youngs_modulus = prm.get_double("Young's modulus");
    walls.poisson_ratio  = prm.get_double("Poisson's ratio");
    wall_positions       = prm.get("Positions");
    prm.leave_subsection();
    check_input(walls.youngs_modulus > 0, "Walls/Young's modulus",
                walls.youngs_modulus, "E > 0");
    check_input(walls.poisson_ratio > -1 && walls.poisson_ratio < 0.5,
                "Walls/Poisson's ratio", walls.poisson_ratio, "-1 < nu < 0.5");

    PackGenerationSettings generation;
    std::string            source, pack_file;
    prm.enter_subsection("Pack");
    source                              = prm.get("Source");
    pack_file                           = resolve(prm.get("File"), filename);
    generation.n_grains                 = std::max(0L, prm.get_integer("Number of grains"));
    const int n_grains_given            = prm.get_integer("Number of grains");
    generation.min_radius               = prm.get_double("Minimum radius");
    generation.max_radius               = prm.get_double("Maximum radius");
    generation.youngs_modulus           = prm.get_double("Young's modulus");
    generation.youngs_modulus_deviation = prm.get_double("Young's modulus deviation");
    generation.poisson_ratio            = prm.get_double("Poisson's ratio");
    generation.density                  = prm.get_double("Density");
    generation.solid_fraction           = prm.get_double("Initial solid fraction");
    generation.seed                     = prm.get_integer("Random seed");
    const double max_overlap            = prm.get_double("Maximum initial overlap");
    prm.leave_subsection();
    check_input(max_overlap > 0 && max_overlap < 1, "Pack/Maximum initial overlap",
                max_overlap, "0 < fraction < 1");
    check_input(generation.poisson_ratio > -1 && generation.poisson_ratio < 0.5,
                "Pack/Poisson's ratio", generation.poisson_ratio, "-1 < nu < 0.5");
    check_input(generation.youngs_modulus > 0, "Pack/Young's modulus",
                generation.youngs_modulus, "E > 0");
    check_input(generation.density > 0, "Pack/Density", generation.density, "> 0");
    if (source == "generate")
      {
        check_input(n_grains_given > 1, "Pack/Number of grains", n_grains_given,
                    "at least two grains (a pack)");
        check_input(generation.min_radius > 0, "Pack/Minimum radius",
                    generation.min_radius, "radius > 0");
        check_input(generation.max_radius >= generation.min_radius,
                    "Pack/Maximum radius", generation.max_radius,
                    ">= Minimum radius");
        check_input(generation.youngs_modulus_deviation >= 0 &&
                      generation.youngs_modulus_deviation < 1. / 3,
                    "Pack/Young's modulus deviation",
                    generation.youngs_modulus_deviation, "0 <= deviation < 1/3");
      }
    else
      check_input(!pack_file.empty(), "Pack/File", "(empty)",
                  source == "file" ? "a pack file when Source = file" :
                                     "a state directory when Source = state");

    PreparationSettings preparation;
    bool                prepare;
    prm.enter_subsection("Preparation");
    prepare                             = prm.get_bool("Enabled");
    preparation.target_confining_stress = prm.get_double("Target confining stress");
    preparation.compaction_strain       = prm.get_double("Compaction strain increment");
    preparation.min_coordination        = prm.get_integer("Minimum coordination");
    preparation.max_growth              = prm.get_double("Maximum growth");
    preparation.max_compaction_steps    = prm.get_integer("Maximum compaction increments");
    preparation.max_growth_rounds       = prm.get_integer("Maximum growth rounds");
    preparation.friction_stage          = prm.get_bool("Friction activation");
    preparation.friction_strain         = prm.get_double("Activation strain increment");
    preparation.max_friction_steps      = prm.get_integer("Maximum activation increments");
    preparation.saturation_window       = prm.get_integer("Saturation window");
    preparation.saturation_tolerance    = prm.get_double("Saturation tolerance");
    prm.leave_subsection();
    if (source == "state")
      check_input(!prepare, "Preparation/Enabled (with Pack/Source = state)", "true",
                  "false: a state continues a prepared pack with its contacts' "
                  "tangential loads, which a preparation would discard");
    if (prepare)
      {
        check_input(preparation.target_confining_stress > 0,
                    "Preparation/Target confining stress",
                    preparation.target_confining_stress, "> 0");
        check_input(preparation.compaction_strain > 0 &&
                      preparation.compaction_strain < 0.1,
                    "Preparation/Compaction strain increment",
                    preparation.compaction_strain, "0 < step < 0.1");
        check_input(preparation.max_growth >= 0 && preparation.max_growth < 0.5,
                    "Preparation/Maximum growth", preparation.max_growth,
                    "0 <= growth < 0.5");
        check_input(preparation.friction_strain > 0 && preparation.friction_strain < 0.01,
                    "Preparation/Activation strain increment",
                    preparation.friction_strain, "0 < step < 0.01");
      }

    LoadPath path;
    prm.enter_subsection("Load path");
    const std::string path_name = prm.get("Type");
    path.type             = LoadPath::parse_type(path_name);
    path.axis             = prm.get("Axis")[0] - 'x';
    path.strain_increment = prm.get_double("Strain increment");
    path.n_increments     = prm.get_integer("Number of increments");
    path.lateral_ratio    = prm.get_double("Lateral strain ratio");
    prm.leave_subsection();
    check_input(std::abs(path.strain_increment) < 0.01,
                "Load path/Strain increment", path.strain_increment,
                "|increment| < 0.01 (small increments: the laws are linearised)");

    MinimizerSettings settings;
    prm.enter_subsection("Minimizer");
    const std::string method_name = prm.get("Method");
    settings.method = prm.get("Method") == "lbfgs" ? MinimizerSettings::Method::lbfgs :
                                                     MinimizerSettings::Method::nlcg;
    settings.steepest_descent_restart     = prm.get_integer("Steepest descent restart");
    settings.sub_increments               = prm.get_integer("Wall sub-increments");
    settings.iterations_per_sub_increment = prm.get_integer("Iterations per sub-increment");
    settings.max_iterations               = prm.get_integer("Maximum iterations");
    settings.energy_tolerance             = prm.get_double("Energy tolerance");
    settings.gradient_tolerance           = prm.get_double("Gradient tolerance");
    settings.force_tolerance              = prm.get_double("Force tolerance");
    settings.increment_force_tolerance    = prm.get_double("Increment force tolerance");
    settings.displacement_cap             = prm.get_double("Displacement cap");
    settings.line_search_bits             = prm.get_integer("Line search bits");
    settings.lbfgs_history                = prm.get_integer("LBFGS history");
    settings.skin                         = prm.get_double("Skin");
    settings.stagnation_window            = prm.get_integer("Stagnation window");
    settings.predictor = prm.get("Initial guess") == "previous increment";
    prm.leave_subsection();
    check_input(settings.displacement_cap > 0 && settings.displacement_cap <= 0.1,
                "Minimizer/Displacement cap", settings.displacement_cap,
                "0 < cap <= 0.1 (the paper: 1e-3 to 1e-1)");
    check_input(settings.skin >= 4 * settings.displacement_cap && settings.skin <= 2,
                "Minimizer/Skin", settings.skin,
                "4 x Displacement cap <= skin <= 2");
    check_input(settings.energy_tolerance > 0 || settings.gradient_tolerance > 0 ||
                  settings.force_tolerance > 0 || settings.increment_force_tolerance > 0,
                "Minimizer/Energy, Gradient, Force and Increment force tolerance",
                "all 0", "at least one stopping test");

    std::string vtu_list;
    bool        iteration_log;
    prm.enter_subsection("Output");
    vtu_list      = prm.get("VTU increments");
    iteration_log = prm.get_bool("Iteration log");
    const unsigned int checkpoint_interval = prm.get_integer("Checkpoint interval");
    prm.leave_subsection();
    std::set<unsigned int> vtu_increments;
    bool vtu_all = false, vtu_last = false;
    if (vtu_list != "none" && !vtu_list.empty())
      for (const std::string &item : dealii::Utilities::split_string_list(vtu_list))
        {
          if (item == "all" || item == "last")
            {
              (item == "all" ? vtu_all : vtu_last) = true;
              continue;
            }
          char *end = nullptr;
          const long value = std::strtol(item.c_str(), &end, 10);
          check_input(*end == '\0' && value >= 0, "Output/VTU increments", vtu_list,
                      "none, or a comma-separated list of increment numbers, last, all");
          vtu_increments.insert(value);
        }

    std::string output = prm.get("Output directory");
    if (output.empty())
      output = "output/" + std::filesystem::path(filename).stem().string();

    // The pack (its checks are input checks too).
    const GrainDefaults defaults{generation.youngs_modulus, generation.poisson_ratio,
                                 generation.density};
    Pack                pack;
    PackState           state;
    std::string         pack_description;
    if (source == "state")
      {
        check_input(wall_positions.empty(), "Walls/Positions (with Pack/Source = state)",
                    wall_positions, "empty: the state directory holds the walls");
        state = read_state(pack_file, defaults);
        pack  = state.pack;
        walls.position   = state.walls.position;
        pack_description = "state directory";
        walls.check();
      }
    if (source == "file")
      {
        pack = read_pack(pack_file, defaults, &pack_description);
        const Walls tight = bounding_walls(pack);
        if (wall_positions.empty())
          walls.position = tight.position;
        else
          {
            const auto values = dealii::Utilities::string_to_double(
              dealii::Utilities::split_string_list(wall_positions));
            check_input(values.size() == 6, "Walls/Positions", wall_positions,
                        "six numbers x_min, y_min, z_min, x_max, y_max, z_max");
            for (unsigned int w = 0; w < 6; ++w)
              walls.position[w] = values[w];
          }
        walls.check();
      }
    if (source != "generate")
      {
        for (unsigned int i = 0; i < pack.size(); ++i)
          for (unsigned int a = 0; a < 3; ++a)
            check_input(pack.centre[i][a] > walls.position[a] &&
                          pack.centre[i][a] < walls.position[a + 3],
                        "Walls/Positions (" + pack.name(i) + " centre)",
                        pack.centre[i], "every grain centre inside the walls");
        check_overlaps(pack, walls, max_overlap,
                       source == "state" ? "State " + pack_file + "/grains.csv" :
                                           "Pack file " + pack_file);
      }
    else
      {
        const double e_w = walls.youngs_modulus, nu_w = walls.poisson_ratio;
        pack = generate_loose_pack(generation, walls);
        walls.youngs_modulus = e_w;
        walls.poisson_ratio  = nu_w;
      }
    pack.check("Pack");

    // The output directory (locked for the run) and the checkpoint to
    // resume from, before any work.
    const OutputDirectory output_directory(output, mode, communicator, std::cout);
    const std::string     checkpoint =
      resume ? find_checkpoint(output, communicator, std::cout) : std::string();

    // --- Work and output. Every rank runs the whole scene (the grains'
    // contacts are shared out, see GrainPartition); the first one writes.
    dealii::ConditionalOStream out(std::cout, root);
    dealii::TimerOutput timer(out, dealii::TimerOutput::never,
                              dealii::TimerOutput::wall_times);
    out << "QuSGM scene " << filename << ": " << pack.size() << " grains, mu = "
        << model.friction << " (walls " << model.wall_friction << "), torsion "
        << (model.torsion ? "on" : "off") << ", minimiser " << method_name
        << ", " << n_ranks << " MPI rank(s) x " << dealii::MultithreadInfo::n_threads()
        << " thread(s)" << std::endl;
    if (source != "generate")
      out << "Pack: " << pack_file << " (" << pack_description << ")" << std::endl;
    // The iteration log evaluates the contact state, which every rank
    // takes part in, so the other ranks log to nowhere.
    std::ofstream log_file;
    std::ostream  no_log(nullptr);
    if (iteration_log && root)
      log_file.open(output + "/iterations.log", resume ? std::ios::app : std::ios::out);

    Simulation sim(pack, walls, model, settings, out, &timer, communicator);
    sim.axis = path.axis;
    if (source == "state" && !resume)
      sim.set_pack_state(state);
    RunProgress progress;
    if (resume)
      {
        progress = load_checkpoint(sim, checkpoint);
        // the checkpoint's scene, not another one (its pack, walls and
        // contact model would silently replace the file's)
        const std::string differences =
          entry_differences(progress.scene_entries, entries, may_change_on_resume);
        if (!differences.empty())
          throw std::runtime_error(
            "cannot resume from '" + checkpoint +
            "': the scene differs from the one the checkpoint was written with:" + differences +
            "\nOnly Load path/Number of increments, the Output entries, Threads and the "
            "Output directory may change on resume. Give these entries their earlier values, or "
            "start the run again with --overwrite.");
        // the table as it was at the checkpoint, continued from there
        const unsigned int rows = sim.n_increments;
        on_root(communicator, [&]() {
          keep_table_rows(output + "/increments.csv",
                          [rows](const unsigned long increment) { return increment <= rows; });
        });
        out << "Resumed from " << checkpoint << " after " << progress.load_increments
            << " increment(s) of the load path (" << rows << " in increments.csv)" << std::endl;
      }
    progress.scene_entries = entries;
    if (root)
      sim.open_table(output + "/increments.csv", resume);
    if (iteration_log)
      sim.iteration_log = root ? static_cast<std::ostream *>(&log_file) : &no_log;
    std::vector<std::pair<double, std::string>> &vtu_records     = progress.grain_files;
    std::vector<std::pair<double, std::string>> &contact_records = progress.contact_files;
    auto write_vtu = [&](const unsigned int increment) {
      dealii::TimerOutput::Scope scope(timer, "output");
      const std::string name =
        "grains-" + dealii::Utilities::int_to_string(increment, 5) + ".vtu";
      const ContactState state = sim.current_state();
      const std::string  contacts =
        write_contacts_vtu(output,
                           "contacts-" + dealii::Utilities::int_to_string(increment, 5),
                           sim.pack, sim.walls, sim.network, sim.model);
      if (!root)
        return;
      write_grains_vtu(output + "/" + name, sim.pack, state);
      vtu_records.emplace_back(increment, name);
      contact_records.emplace_back(increment, contacts);
      std::ofstream pvd(output + "/grains.pvd");
      dealii::DataOutBase::write_pvd_record(pvd, vtu_records);
      std::ofstream contacts_pvd(output + "/contacts.pvd");
      dealii::DataOutBase::write_pvd_record(contacts_pvd, contact_records);
    };

    // The state to carry on elsewhere (collective; the first rank writes).
    const auto write_state_files = [&](const std::string &name) {
      dealii::TimerOutput::Scope scope(timer, "output");
      const PackState            state_now = sim.pack_state();
      if (root)
        write_state(state_now, output + "/" + name);
    };
    const auto checkpoint_now = [&]() {
      dealii::TimerOutput::Scope scope(timer, "checkpoint");
      save_checkpoint(sim, progress, output, communicator);
    };
    if (prepare && !resume)
      {
        out << "Preparation: frictionless isotropic compaction to "
            << preparation.target_confining_stress * 1e-6
            << " MPa with growth of grains with fewer than "
            << preparation.min_coordination << " contacts, then friction activation"
            << std::endl;
        prepare_pack(sim, model, preparation);
        write_state_files("prepared_state");
      }
    if (!resume)
      {
        if (source != "state")
          sim.reset_undeformed();
        if (vtu_all || vtu_increments.count(0))
          write_vtu(0);
        if (checkpoint_interval > 0)
          checkpoint_now();
      }
    out << "Load path: " << path_name << ", " << path.n_increments
        << " increments of " << path.strain_increment << std::endl;
    for (unsigned int k = progress.load_increments + 1; k <= path.n_increments; ++k)
      {
        sim.set_progress(k, path.n_increments);
        sim.strain_step(path.strain_increments(), "test");
        if (vtu_all || vtu_increments.count(k) || (vtu_last && k == path.n_increments))
          write_vtu(k);
        progress.load_increments = k;
        if (checkpoint_interval > 0 && k % checkpoint_interval == 0)
          checkpoint_now();
      }
    write_state_files("final_state");

    timer.print_summary();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "Output written to " << output << "/ (increments.csv"
        << (vtu_records.empty() ? "" : ", grains.pvd, contacts.pvd") << ", final_state/)" << std::endl
        << "Total wall time: " << seconds << " s" << std::endl;
  }
} // namespace sable::qusgm
