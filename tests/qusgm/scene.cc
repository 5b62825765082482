// Load paths and the Hooke fit of K and G; the QuSGM scene runner: bad input is refused with a message naming the
// entry before any output exists; a tiny scene runs end to end and writes
// increments.csv with the documented header and one row per increment.
#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/qusgm/load_path.h>
#include <sable/qusgm/macroscopic.h>
#include <sable/qusgm/run_scene.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.h"

using sable_tests::check;
namespace fs = std::filesystem;

namespace
{
  const fs::path work = fs::current_path() / "qusgm_scene.work";

  std::string
  scene(const std::string &name, const std::string &body)
  {
    const fs::path file = work / (name + ".prm");
    std::ofstream  out(file);
    out << "set Model = qusgm\nset Output directory = "
        << (work / ("out_" + name)).string() << "\n"
        << body;
    return file.string();
  }

  void
  write(const std::string &name, const std::string &text)
  {
    std::ofstream(work / name) << text;
  }

  void
  expect_error(const std::string &name,
               const std::string &body,
               const std::string &expected)
  {
    const std::string file = scene(name, body);
    std::string       message;
    try
      {
        sable::qusgm::run_scene(file, MPI_COMM_WORLD);
      }
    catch (const sable::InputError &e)
      {
        message = e.what();
      }
    std::cout << name << ": " << message << std::endl;
    check(name + ": refused with a message naming '" + expected + "'",
          message.find(expected) != std::string::npos);
    check(name + ": no output written", !fs::exists(work / ("out_" + name)));
  }

  const std::string from_file =
    "subsection Pack\n  set Source = file\n  set File = pack.csv\nend\n";
} // namespace

namespace
{
  // Load paths and the Hooke fit: an isotropic linear material with known
  // K and G must be recovered from each path's strain increments.
  void
  test_load_paths_and_fit()
  {
    using namespace sable::qusgm;
    const double k = 1.3e9, g = 0.8e9;
    for (const std::string type : {"isotropic", "uniaxial strain", "triaxial"})
      {
        LoadPath path;
        path.type             = LoadPath::parse_type(type);
        path.axis             = 1;
        path.strain_increment = 2e-4;
        path.lateral_ratio    = -0.3;
        const auto d_eps = path.strain_increments();
        const double trace = d_eps[0] + d_eps[1] + d_eps[2];
        std::array<double, 3> d_sigma;
        for (unsigned int a = 0; a < 3; ++a)
          d_sigma[a] = k * trace + 2 * g * (d_eps[a] - trace / 3);
        const auto [k_fit, g_fit] = fit_moduli(d_sigma, d_eps);
        sable_tests::check_relative(type + ": fitted K", k_fit, k, 1e-12);
        if (type == "isotropic")
          check(type + ": G undetermined (nan)", std::isnan(g_fit));
        else
          sable_tests::check_relative(type + ": fitted G", g_fit, g, 1e-12);
        check(type + ": axial strain increment",
              d_eps[1] == 2e-4 &&
                (type != "uniaxial strain" || (d_eps[0] == 0 && d_eps[2] == 0)) &&
                (type != "triaxial" || (d_eps[0] == -0.6e-4 && d_eps[2] == -0.6e-4)));
        const auto moves = LoadPath::wall_moves(d_eps, {{1, 2, 4}});
        check(type + ": symmetric wall moves",
              moves[1] == 2e-4 && moves[4] == -2e-4 &&
                moves[0] == 0.5 * d_eps[0] && moves[3] == -0.5 * d_eps[0]);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_load_paths_and_fit();
  fs::remove_all(work);
  fs::create_directories(work);

  write("pack.csv", "x,y,z,r\n0,0,0,1e-4\n3e-4,0,0,0\n");
  expect_error("zero_radius", from_file, "radius");
  write("pack_nu.csv", "0 0 0 1e-4 70e9 0.5 2420\n");
  expect_error("poisson_ratio",
               "subsection Pack\n  set Source = file\n  set File = pack_nu.csv\nend\n",
               "Poisson's ratio");
  expect_error("negative_radius",
               "subsection Pack\n  set Minimum radius = -1e-4\nend\n",
               "Pack/Minimum radius");
  expect_error("pack_poisson_ratio",
               "subsection Pack\n  set Poisson's ratio = 0.7\nend\n",
               "Pack/Poisson's ratio");
  expect_error("negative_friction",
               "subsection Contact\n  set Friction coefficient = -0.1\nend\n",
               "Contact/Friction coefficient");
  write("pack_ok.csv", "0 0 0 1e-4\n2e-4 0 0 1e-4\n");
  expect_error("overlapping_walls",
               "subsection Pack\n  set Source = file\n  set File = pack_ok.csv\nend\n"
               "subsection Walls\n  set Positions = 1e-3, -1e-3, -1e-3, -1e-3, 1e-3, 1e-3\nend\n",
               "Walls");
  write("pack_empty.csv", "x,y,z,r\n# nothing\n");
  expect_error("empty_pack",
               "subsection Pack\n  set Source = file\n  set File = pack_empty.csv\nend\n",
               "number of grains");
  expect_error("no_grains_generated",
               "subsection Pack\n  set Number of grains = 0\nend\n",
               "Pack/Number of grains");
  write("pack_bad.csv", "0 0 0 1e-4\n1e-4 2e-4 abc 1e-4\n");
  expect_error("malformed_pack",
               "subsection Pack\n  set Source = file\n  set File = pack_bad.csv\nend\n",
               "line 2");
  expect_error("missing_pack",
               "subsection Pack\n  set Source = file\n  set File = nothing.csv\nend\n",
               "Pack file");
  expect_error("unknown_entry", "set Time step = 1\n", "Time step");

  // A tiny scene end to end: two grains squeezed between walls along x.
  write("pair.csv", "1e-4 1e-4 1e-4 1e-4\n3e-4 1e-4 1e-4 1e-4\n");
  const std::string file = scene(
    "pair",
    "subsection Pack\n  set Source = file\n  set File = pair.csv\nend\n"
    "subsection Walls\n  set Positions = 0, -1e-3, -1e-3, 4e-4, 1e-3, 1e-3\nend\n"
    "subsection Preparation\n  set Enabled = false\nend\n"
    "subsection Load path\n  set Type = uniaxial strain\n  set Axis = x\n"
    "  set Number of increments = 3\n  set Strain increment = 1e-3\nend\n"
    "subsection Minimizer\n  set Method = lbfgs\n  set Force tolerance = 1e-10\n"
    "  set Energy tolerance = 0\n  set Gradient tolerance = 0\nend\n"
    "subsection Output\n  set Iteration log = true\nend\n");
  bool ok = true;
  try
    {
      sable::qusgm::run_scene(file, MPI_COMM_WORLD);
    }
  catch (const std::exception &e)
    {
      std::cout << "pair scene failed: " << e.what() << std::endl;
      ok = false;
    }
  check("pair scene runs", ok);
  std::ifstream csv(work / "out_pair" / "increments.csv");
  std::string   header, line;
  std::getline(csv, header);
  check("increments.csv header",
        header.rfind("increment,stage,strain_x,strain_y,strain_z,stress_x", 0) == 0 &&
          header.find("bulk_modulus,shear_modulus,sliding_ratio") != std::string::npos);
  unsigned int rows = 0;
  double       stress_x = 0;
  while (std::getline(csv, line))
    {
      ++rows;
      std::stringstream fields(line);
      std::string       field;
      for (unsigned int column = 0; std::getline(fields, field, ','); ++column)
        if (column == 5)
          stress_x = std::stod(field);
    }
  check("increments.csv has one row per increment", rows == 3);
  // Chain of two spheres between walls: 3e-3 strain of L = 4e-4, walls
  // of 2e-3 x 2e-3 (SPEC C, simple-cubic column).
  {
    const double e_gg = 70e9 / (2 * (1 - 0.04));
    const double e_gw = 1 / ((1 - 0.04) / 70e9 + (1 - 0.495 * 0.495) / 7e12);
    const double k_gg = 4. / 3 * e_gg * std::sqrt(0.5e-4);
    const double k_gw = 4. / 3 * e_gw * std::sqrt(1e-4);
    const double f =
      std::pow(3e-3 * 4e-4 / (std::pow(k_gg, -2. / 3) + 2 * std::pow(k_gw, -2. / 3)), 1.5);
    sable_tests::check_relative("pair scene: stress_x in increments.csv against "
                                "the chain solution",
                                stress_x, f / 4e-6, 1e-6);
  }
  {
    std::ifstream log(work / "out_pair" / "iterations.log");
    std::string   first;
    std::getline(log, first);
    check("iteration log written with its header",
          first.find("iteration pi gradient_norm step active_contacts "
                     "sliding_contacts") != std::string::npos);
  }
  check("VTU of the last increment written",
        fs::exists(work / "out_pair" / "grains-00003.vtu") &&
          fs::exists(work / "out_pair" / "grains.pvd") &&
          fs::exists(work / "out_pair" / "contacts-00003.vtu"));
  return sable_tests::exit_code();
}
