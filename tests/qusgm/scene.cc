// Load paths and the Hooke fit of K and G; the QuSGM scene runner: bad input is refused with a message naming the
// entry before any output exists; a tiny scene runs end to end and writes
// increments.csv with the documented header and one row per increment.
#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/qusgm/load_path.h>
#include <sable/qusgm/macroscopic.h>
#include <sable/qusgm/run_scene.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
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
  write("pack_nu.csv", "x y z r E nu rho\n0 0 0 1e-4 70e9 0.5 2420\n3e-4 0 0 1e-4 70e9 0.2 2420\n");
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
  // The first increment of a pack from a file has moduli: the pair in
  // equilibrium under load at the start (wall overlaps delta_w, grain
  // overlap delta_g with equal Hertz forces), then one uniaxial increment
  // along x; K and G against the chain solution.
  {
    const double e_gg = 70e9 / (2 * (1 - 0.04));
    const double e_gw = 1 / ((1 - 0.04) / 70e9 + (1 - 0.495 * 0.495) / 7e12);
    const double k_gg = 4. / 3 * e_gg * std::sqrt(0.5e-4);
    const double k_gw = 4. / 3 * e_gw * std::sqrt(1e-4);
    const double radius = 1e-4, delta_w = 0.5e-6, d_eps = 1e-3, area = 4e-6;
    const double delta_g = delta_w * std::pow(k_gw / k_gg, 2. / 3);
    const double x0 = radius - delta_w, x1 = x0 + 2 * radius - delta_g,
                 length0 = x1 + radius - delta_w;
    std::ostringstream pack, walls;
    pack << std::setprecision(17) << "x y z r\n"
         << x0 << " 1e-4 1e-4 " << radius << '\n'
         << x1 << " 1e-4 1e-4 " << radius << '\n';
    walls << std::setprecision(17) << "0, -1e-3, -1e-3, " << length0 << ", 1e-3, 1e-3";
    write("pair_preloaded.csv", pack.str());
    const std::string file = scene(
      "pair_preloaded",
      "subsection Pack\n  set Source = file\n  set File = pair_preloaded.csv\nend\n"
      "subsection Walls\n  set Positions = " + walls.str() + "\nend\n"
      "subsection Preparation\n  set Enabled = false\nend\n"
      "subsection Load path\n  set Type = uniaxial strain\n  set Axis = x\n"
      "  set Number of increments = 1\n  set Strain increment = 1e-3\nend\n"
      "subsection Minimizer\n  set Method = lbfgs\n  set Force tolerance = 1e-12\n"
      "  set Energy tolerance = 0\n  set Gradient tolerance = 0\nend\n");
    sable::qusgm::run_scene(file, MPI_COMM_WORLD);
    std::ifstream            table(work / "out_pair_preloaded" / "increments.csv");
    std::string              names, values;
    std::getline(table, names);
    std::getline(table, values);
    std::map<std::string, std::string> row;
    {
      std::stringstream n(names), v(values);
      std::string       name, value;
      while (std::getline(n, name, ','))
        {
          std::getline(v, value, ',');
          row[name] = value;
        }
    }
    const double sigma0 = k_gw * std::pow(delta_w, 1.5) / area;
    const double f = std::pow((2 * delta_w + delta_g + d_eps * length0) /
                                (std::pow(k_gg, -2. / 3) + 2 * std::pow(k_gw, -2. / 3)),
                              1.5);
    const double d_sigma = f / area - sigma0;
    std::cout << "pair_preloaded row: " << values << std::endl;
    check("first increment: bulk and shear modulus written (not empty)",
          !row["bulk_modulus"].empty() && !row["shear_modulus"].empty());
    if (!row["bulk_modulus"].empty() && !row["shear_modulus"].empty())
      {
        // uniaxial strain e along x: K = d_sigma_x / (3 e), G = d_sigma_x / (2 e)
        sable_tests::check_relative("first increment: K from the initial stress",
                                    std::stod(row["bulk_modulus"]), d_sigma / (3 * d_eps), 1e-10);
        sable_tests::check_relative("first increment: G from the initial stress",
                                    std::stod(row["shear_modulus"]), d_sigma / (2 * d_eps), 1e-10);
      }
    check("stress over the current and the nominal area agree along the loaded axis "
          "(its walls keep their area)",
          row["stress_x"] == row["nominal_stress_x"]);
    check("sliding ratio written where contacts exist", !row["sliding_ratio"].empty());
    check("stopped_by names the force test", row["stopped_by"] == "force");
  }
  check("VTU of the last increment written",
        fs::exists(work / "out_pair" / "grains-00003.vtu") &&
          fs::exists(work / "out_pair" / "grains.pvd") &&
          fs::exists(work / "out_pair" / "contacts-00003.vtu"));
  return sable_tests::exit_code();
}
