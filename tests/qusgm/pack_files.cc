// Packs that travel: pack files are read by column name (any order, r or
// diameter, optional E nu rho id), Yade's text export and LAMMPS dumps are
// read, and every unknown, doubled, ambiguous or missing column is refused
// with a message naming the file, line and column. A run's state (grains,
// walls, contacts with their tangential history) written to files is read
// back to the same doubles, written again to the same bytes, and a run
// continued from it gives the same increment, bit for bit, as the run that
// did not stop. increments.csv holds 17 significant digits and leaves an
// undefined value empty.
#include <sable/base/input_error.h>
#include <sable/qusgm/macroscopic.h>
#include <sable/qusgm/pack_io.h>
#include <sable/qusgm/simulation.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>

#include "test_support.h"

using namespace sable::qusgm;
using sable_tests::check;
namespace fs = std::filesystem;

namespace
{
  const fs::path             work = fs::current_path() / "qusgm_pack_files.work";
  dealii::ConditionalOStream quiet(std::cout, false);
  const GrainDefaults        defaults{70e9, 0.2, 2420};

  std::string
  write(const std::string &name, const std::string &text)
  {
    std::ofstream(work / name) << text;
    return (work / name).string();
  }

  std::string
  contents(const fs::path &file)
  {
    std::ifstream      in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// Read @p text as a pack file; it must be refused with a message that
  /// contains the file name and every one of @p parts.
  void
  expect_refused(const std::string              &name,
                 const std::string              &text,
                 const std::vector<std::string> &parts)
  {
    const std::string file = write(name, text);
    std::string       message;
    try
      {
        read_pack(file, defaults);
      }
    catch (const sable::InputError &e)
      {
        message = e.what();
      }
    std::cout << name << ": " << message << std::endl;
    bool all = !message.empty() && message.find(file) != std::string::npos;
    for (const std::string &part : parts)
      all &= message.find(part) != std::string::npos;
    std::string wanted;
    for (const std::string &part : parts)
      wanted += " '" + part + "'";
    check(name + ": refused, naming the file and" + wanted, all);
  }

  void
  read_by_name()
  {
    // The header of the issue: the id must not be read as x.
    const Pack a = read_pack(write("id_first.csv",
                                   "id,x,y,z,r\n"
                                   "7,0.10000000000000001,2e-4,3e-4,1e-4\n"
                                   "3,5e-4,2e-4,3e-4,1.2e-4\n"),
                             defaults);
    check("id,x,y,z,r: ids 7 and 3, x of grain 0 exactly 0.1, radii 1e-4 and 1.2e-4",
          a.size() == 2 && a.id[0] == 7 && a.id[1] == 3 && a.centre[0][0] == 0.1 &&
            a.centre[0][1] == 2e-4 && a.centre[1][0] == 5e-4 && a.radius[0] == 1e-4 &&
            a.radius[1] == 1.2e-4 && a.youngs_modulus[0] == 70e9 && a.density[1] == 2420);

    // Any order, any case, a diameter, semicolons, material columns.
    const Pack b = read_pack(write("reordered.csv",
                                   "Diameter;Z;y;X;E;nu;density\n"
                                   "2e-4;3e-4;2e-4;1e-4;60e9;0.25;2600\n"
                                   "3e-4;3e-4;2e-4;4e-4;50e9;0.3;2500\n"),
                             defaults);
    check("reordered columns with a diameter: r = d/2, x, z, E, nu, rho as given",
          b.size() == 2 && b.radius[0] == 1e-4 && b.radius[1] == 1.5e-4 &&
            b.centre[0][0] == 1e-4 && b.centre[0][2] == 3e-4 && b.centre[1][0] == 4e-4 &&
            b.youngs_modulus[1] == 50e9 && b.poisson_ratio[0] == 0.25 &&
            b.density[1] == 2500 && b.id[0] == 0 && b.id[1] == 1);

    const Pack c = read_pack(write("plain.txt", "0 0 0 1e-4\n3e-4 0 0 1e-4\n"), defaults);
    check("no header: x y z r with the default E, nu, rho",
          c.size() == 2 && c.centre[1][0] == 3e-4 && c.radius[1] == 1e-4 &&
            c.youngs_modulus[0] == 70e9 && c.poisson_ratio[0] == 0.2 && c.density[0] == 2420);

    const Pack d = read_pack(write("comment_header.txt",
                                   "# made by hand\n#x y z r\n1e-4 2e-4 3e-4 1e-4\n"
                                   "4e-4 2e-4 3e-4 1e-4\n"),
                             defaults);
    check("comment header '#x y z r'", d.size() == 2 && d.centre[0][2] == 3e-4);

    // Yade's text export: tab separated, #format line.
    const Pack e = read_pack(write("yade.txt",
                                   "#format x_y_z_r\n0.001\t0.002\t0.003\t0.0005\n"
                                   "0.002\t0.002\t0.003\t0.0004\n"),
                             defaults);
    check("Yade #format x_y_z_r", e.size() == 2 && e.centre[0][1] == 0.002 && e.radius[1] == 0.0004);
    const Pack f = read_pack(write("yade_ids.txt",
                                   "#format id_x_y_z_r_matId\n# a comment\n"
                                   "12\t0.001\t0.002\t0.003\t0.0005\t1\n"
                                   "4\t0.002\t0.002\t0.003\t0.0004\t2\n"),
                             defaults);
    check("Yade #format id_x_y_z_r_matId: ids 12 and 4, matId not used",
          f.size() == 2 && f.id[0] == 12 && f.id[1] == 4 && f.centre[1][0] == 0.002 &&
            f.youngs_modulus[1] == 70e9);
    const Pack g = read_pack(write("yade_attrs.txt",
                                   "#format x_y_z_r_attrs\n# x y z r E\n"
                                   "0.001\t0.002\t0.003\t0.0005\t3e10\n"
                                   "0.002\t0.002\t0.003\t0.0004\t4e10\n"),
                             defaults);
    check("Yade #format x_y_z_r_attrs with '# x y z r E'",
          g.size() == 2 && g.youngs_modulus[1] == 4e10);

    // LAMMPS/LIGGGHTS dump: the last snapshot, sorted by id, scaled
    // coordinates through the box, density from the mass.
    const double r = 1e-4, volume = 4. / 3. * M_PI * r * r * r, mass = 2500 * volume;
    std::ostringstream dump;
    dump << std::setprecision(17)
         << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n"
            "0 1e-3\n0 1e-3\n0 1e-3\nITEM: ATOMS id type x y z radius\n"
            "1 1 1e-4 1e-4 1e-4 1e-4\n2 1 5e-4 1e-4 1e-4 1e-4\n"
            "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n"
            "-1e-3 1e-3\n0 2e-3\n0 1e-3\nITEM: ATOMS id type xs ys zs vx radius mass\n"
         << "12 1 0.5 0.25 0.5 0.1 " << r << ' ' << mass << '\n'
         << "4 1 0.25 0.25 0.25 0 " << r << ' ' << mass << '\n'
         << "9 2 0.75 0.5 0.5 0 " << r << ' ' << mass << '\n';
    std::string description;
    const Pack  h = read_pack(write("dump.liggghts", dump.str()), defaults, &description);
    std::cout << "dump: " << description << std::endl;
    check("LAMMPS dump: last snapshot (3 atoms), sorted by id 4, 9, 12",
          h.size() == 3 && h.id[0] == 4 && h.id[1] == 9 && h.id[2] == 12);
    check("LAMMPS dump: scaled coordinates lo + s (hi - lo)",
          h.size() == 3 && h.centre[0][0] == -1e-3 + 0.25 * (1e-3 - -1e-3) &&
            h.centre[0][1] == 0 + 0.25 * (2e-3 - 0) && h.centre[1][0] == -1e-3 + 0.75 * 2e-3 &&
            h.radius[1] == r);
    sable_tests::check_relative("LAMMPS dump: density = mass / volume",
                                h.size() == 3 ? h.density[2] : 0., 2500, 1e-15);
  }

  void
  refuse_bad_headers()
  {
    expect_refused("unknown_column", "id,x,y,z,r,foo\n1,0,0,0,1e-4,3\n",
                   {"line 1, column 6", "foo", "column name"});
    expect_refused("r_and_radius", "x,y,z,r,radius\n0,0,0,1e-4,1e-4\n",
                   {"line 1, column 5", "radius", "column 4 'r' already gives the grain size"});
    expect_refused("r_and_diameter", "x y z diameter r\n0 0 0 2e-4 1e-4\n",
                   {"line 1, column 5", "column 4 'diameter' already gives the grain size"});
    expect_refused("x_twice", "x,X,y,z,r\n0,0,0,0,1e-4\n",
                   {"line 1, column 2", "already gives the x coordinate"});
    expect_refused("no_size", "x,y,z,E\n0,0,0,7e10\n",
                   {"line 1 (the header)", "a column for the grain size"});
    expect_refused("no_z", "# c\nx,y,r\n0,0,1e-4\n", {"line 2 (the header)", "z coordinate"});
    expect_refused("five_numbers_without_header", "1 0 0 0 1e-4\n2 3e-4 0 0 1e-4\n",
                   {"line 1", "four numbers x y z r, or a header line"});
    expect_refused("short_row", "x,y,z,r\n0,0,0,1e-4\n3e-4,0,0\n",
                   {"line 3", "4 fields, as the header on line 1 names"});
    expect_refused("not_a_number", "x,y,z,r\n0,0,0,1e-4\n3e-4,0,abc,1e-4\n",
                   {"line 3, column 3 (z)", "a number"});
    expect_refused("fractional_id", "id,x,y,z,r\n1.5,0,0,0,1e-4\n2,3e-4,0,0,1e-4\n",
                   {"line 2, column 1 (id)", "a whole number"});
    expect_refused("id_twice", "id,x,y,z,r\n5,0,0,0,1e-4\n5,3e-4,0,0,1e-4\n",
                   {"grain id", "each id once"});
    expect_refused("yade_unknown_attribute",
                   "#format x_y_z_r_attrs\n# x y z r agglomerate\n0 0 0 1e-4 1\n",
                   {"line 2, column 5", "agglomerate"});
    const std::string head = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\n"
                             "ITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n";
    expect_refused("dump_radius_and_diameter",
                   head + "ITEM: ATOMS id x y z radius diameter\n1 0 0 0 1 2\n2 3 0 0 1 2\n",
                   {"line 9", "one of radius and diameter"});
    expect_refused("dump_no_size", head + "ITEM: ATOMS id x y z\n1 0 0 0\n2 3 0 0\n",
                   {"line 9", "radius or diameter"});
    expect_refused("dump_triclinic_scaled",
                   "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\n"
                   "ITEM: BOX BOUNDS xy xz yz pp pp pp\n0 1 0\n0 1 0\n0 1 0\n"
                   "ITEM: ATOMS id xs ys zs radius\n1 0.5 0.5 0.5 0.1\n",
                   {"line 9", "scaled coordinates only with an orthogonal"});
    expect_refused("dump_cut_short", head + "ITEM: ATOMS id x y z radius\n1 0 0 0 1\n",
                   {"line 11", "(end of file)"});
  }

  /// 27 grains on a perturbed lattice, slightly overlapping each other and
  /// the walls: a small frictional pack with tangential loads.
  std::pair<Pack, Walls>
  small_pack()
  {
    std::mt19937                           rng(17);
    std::uniform_real_distribution<double> u(-1., 1.);
    Pack                                   pack;
    const double                           s = 2e-4;
    for (unsigned int k = 0; k < 27; ++k)
      pack.add_grain(Point<3>((k % 3 + 0.5) * s + 2e-6 * u(rng),
                              (k / 3 % 3 + 0.5) * s + 2e-6 * u(rng),
                              (k / 9 + 0.5) * s + 2e-6 * u(rng)),
                     1e-4 * (1 + 0.01 * u(rng)),
                     70e9,
                     0.2,
                     2420,
                     100 + 3 * k);
    Walls walls;
    for (unsigned int a = 0; a < 3; ++a)
      {
        walls.position[a]     = 0;
        walls.position[a + 3] = 3 * s;
      }
    return {pack, walls};
  }

  MinimizerSettings
  settings()
  {
    MinimizerSettings s;
    s.method             = MinimizerSettings::Method::lbfgs;
    s.sub_increments     = 1;
    s.energy_tolerance   = 0;
    s.gradient_tolerance = 0;
    s.force_tolerance    = 1e-10;
    return s;
  }

  bool
  same_record(const IncrementRecord &a, const IncrementRecord &b)
  {
    const MacroscopicState &x = a.macroscopic, &y = b.macroscopic;
    return x.strain == y.strain && x.stress == y.stress && x.nominal_stress == y.nominal_stress &&
           x.n_contacts == y.n_contacts && x.sliding_ratio == y.sliding_ratio &&
           x.coordination == y.coordination && a.bulk_modulus == b.bulk_modulus &&
           a.shear_modulus == b.shear_modulus && a.result.iterations == b.result.iterations &&
           a.result.residual == b.result.residual;
  }

  void
  state_round_trip()
  {
    ContactModel model;
    model.friction      = 0.3;
    model.wall_friction = 0.3;
    const auto [pack, walls]             = small_pack();
    const std::array<double, 3> d_strain = {{0.2e-3, -0.1e-3, 1e-3}};

    Simulation uninterrupted(pack, walls, model, settings(), quiet);
    uninterrupted.strain_step(d_strain, "test");
    uninterrupted.strain_step(d_strain, "test");

    Simulation stopped(pack, walls, model, settings(), quiet);
    stopped.strain_step(d_strain, "test");
    const PackState saved = stopped.pack_state();
    unsigned int    loaded = 0, walls_loaded = 0;
    for (const ContactLoad &c : saved.contacts)
      if (c.tangential_force.norm() > 0 && c.torsional_couple != 0)
        ++(c.wall ? walls_loaded : loaded);
    std::cout << "state: " << saved.contacts.size() << " closed contacts, " << loaded
              << " grain and " << walls_loaded << " wall contacts with tangential force and couple"
              << std::endl;
    check("the state carries tangential history on grain and wall contacts",
          loaded > 10 && walls_loaded > 5);

    const fs::path first = work / "state_1", second = work / "state_2";
    write_state(saved, first.string());
    const PackState read = read_state(first.string(), defaults);

    // The same doubles.
    bool same = read.pack.size() == saved.pack.size();
    for (unsigned int i = 0; same && i < saved.pack.size(); ++i)
      same = read.pack.centre[i] == saved.pack.centre[i] &&
             read.pack.radius[i] == saved.pack.radius[i] &&
             read.pack.youngs_modulus[i] == saved.pack.youngs_modulus[i] &&
             read.pack.poisson_ratio[i] == saved.pack.poisson_ratio[i] &&
             read.pack.shear_modulus[i] == saved.pack.shear_modulus[i] &&
             read.pack.density[i] == saved.pack.density[i] && read.pack.id[i] == saved.pack.id[i];
    check("grains read back to the same doubles and ids", same);
    check("walls and the box of zero strain read back to the same doubles",
          read.walls.position == saved.walls.position &&
            read.undeformed_lengths == saved.undeformed_lengths &&
            read.wall_force == saved.wall_force);
    same = read.contacts.size() == saved.contacts.size();
    for (std::size_t k = 0; same && k < saved.contacts.size(); ++k)
      {
        const ContactLoad &a = read.contacts[k], &b = saved.contacts[k];
        same = a.i == b.i && a.other == b.other && a.wall == b.wall &&
               a.tangential_force == b.tangential_force &&
               a.torsional_couple == b.torsional_couple && a.normal_force == b.normal_force &&
               a.overlap == b.overlap;
      }
    check("contacts with their tangential force and couple read back to the same doubles",
          same);
    write_state(read, second.string());
    for (const std::string name : {"grains.csv", "walls.csv", "contacts.csv", "wall_contacts.csv"})
      check(name + " written again: the same bytes",
            contents(first / name) == contents(second / name) && !contents(first / name).empty());

    // Continue from the files: the second increment of the run that did
    // not stop, bit for bit.
    Simulation resumed(read.pack, read.walls, model, settings(), quiet);
    resumed.set_pack_state(read);
    resumed.strain_step(d_strain, "test");
    std::cout << "uninterrupted: sigma_z " << uninterrupted.last.macroscopic.stress[2]
              << " K " << uninterrupted.last.bulk_modulus << ", from the state: sigma_z "
              << resumed.last.macroscopic.stress[2] << " K " << resumed.last.bulk_modulus
              << std::endl;
    check("continued from the state: the increment of the run that did not stop, bit for bit",
          same_record(resumed.last, uninterrupted.last) &&
            resumed.pack.centre == uninterrupted.pack.centre);

    // Control: without the tangential history the increment differs.
    PackState without = read;
    without.contacts.clear();
    Simulation forgetful(read.pack, read.walls, model, settings(), quiet);
    forgetful.set_pack_state(without);
    forgetful.strain_step(d_strain, "test");
    check("control: without the contacts' history the increment differs",
          forgetful.last.macroscopic.stress != uninterrupted.last.macroscopic.stress);

    // A contact between grains that do not touch, an unknown grain id.
    {
      fs::copy(first, work / "state_bad", fs::copy_options::recursive);
      std::ofstream(work / "state_bad" / "contacts.csv", std::ios::app)
        << saved.pack.id[0] << ',' << saved.pack.id[26] << ",0,0,1e-3,0,0,0\n";
      const std::size_t lines = [&]() {
        std::ifstream in(work / "state_bad" / "contacts.csv");
        std::string   line;
        std::size_t   n = 0;
        while (std::getline(in, line))
          ++n;
        return n;
      }();
      std::string message;
      try
        {
          const PackState bad = read_state((work / "state_bad").string(), defaults);
          Simulation      sim(bad.pack, bad.walls, model, settings(), quiet);
          sim.set_pack_state(bad);
        }
      catch (const sable::InputError &e)
        {
          message = e.what();
        }
      std::cout << "open contact: " << message << std::endl;
      check("a contact of grains that do not overlap is refused, naming file, line and grains",
            message.find("contacts.csv, line " + std::to_string(lines)) != std::string::npos &&
              message.find("grain 0 (id 100) and grain 26 (id 178)") != std::string::npos);
      std::ofstream(work / "state_bad" / "contacts.csv", std::ios::app)
        << "999,100,0,0,0,0,0,0\n";
      message.clear();
      try
        {
          read_state((work / "state_bad").string(), defaults);
        }
      catch (const sable::InputError &e)
        {
          message = e.what();
        }
      std::cout << "unknown id: " << message << std::endl;
      check("a contact naming an unknown grain id is refused",
            message.find("line " + std::to_string(lines + 1) + ", column 1 (i)") !=
                std::string::npos &&
              message.find("the id of a grain") != std::string::npos);
    }
  }

  void
  table_digits()
  {
    {
      IncrementTable   table((work / "table.csv").string());
      MacroscopicState m;
      m.stress         = {{0.1, 1. / 3., 2. / 3.}};
      m.nominal_stress = m.stress;
      m.sliding_ratio  = std::numeric_limits<double>::quiet_NaN();
      IncrementResult result;
      result.stopped_by = "stagnation";
      table.write(1, "test", m, std::numeric_limits<double>::quiet_NaN(), 2e9, result, 0.5);
    }
    std::ifstream in(work / "table.csv");
    std::string   header, row;
    std::getline(in, header);
    std::getline(in, row);
    std::cout << header << '\n' << row << std::endl;
    check("increments.csv: 17 significant digits (0.1, 1/3, 2/3 as "
          "0.10000000000000001, 0.33333333333333331, 0.66666666666666663), an "
          "undefined K and sliding ratio empty, G 2000000000, stopped_by last",
          row == "1,test,0,0,0,0.10000000000000001,0.33333333333333331,0.66666666666666663,"
                 "0.10000000000000001,0.33333333333333331,0.66666666666666663,0,0,,"
                 "2000000000,,0,0,0,0,0,0,,0.5,stagnation");
  }
} // namespace

int
main()
{
  fs::remove_all(work);
  fs::create_directories(work);
  read_by_name();
  refuse_bad_headers();
  table_digits();
  state_round_trip();
  return sable_tests::exit_code();
}
