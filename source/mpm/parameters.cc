#include <deal.II/base/utilities.h>

#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>
#include <sable/base/parameter_file.h>
#include <sable/base/named_choice.h>
#include <sable/mpm/bodies/bodies_file.h>
#include <sable/mpm/parameter_tools.h>
#include <sable/mpm/parameters.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    const NamedChoice<UpdateScheme> update_schemes{{"USL", UpdateScheme::usl},
                                                   {"MUSL", UpdateScheme::musl},
                                                   {"USAVG", UpdateScheme::usavg},
                                                   {"automatic", UpdateScheme::automatic}};
    const NamedChoice<OutputFormat> output_formats{{"vtu", OutputFormat::vtu},
                                                   {"hdf5", OutputFormat::hdf5}};
    const NamedChoice<ShapeFunctions> shape_function_kinds{{"linear", ShapeFunctions::linear},
                                                           {"gimp", ShapeFunctions::gimp}};
  } // namespace

  std::string
  update_scheme_name(const UpdateScheme scheme)
  {
    return update_schemes.name(scheme);
  }

  template <int dim>
  void
  declare_parameters(ParameterHandler &prm, const unsigned int n_bodies)
  {
    const std::string zero = zero_vector(dim);
    prm.declare_entry("Output directory",
                      "",
                      Patterns::Anything(),
                      "Directory for all output of the run, created after "
                      "the parameters are checked. Empty: output/<name of "
                      "the parameter file without .prm>. A run does not "
                      "start if it holds an earlier run's outputs (sable "
                      "--overwrite removes them, --resume continues that "
                      "run) or another run writes into it (the lock file "
                      "sable.lock).");
    prm.declare_entry("Number of bodies",
                      "1",
                      Patterns::Integer(0, 1000000),
                      "Bodies are described in subsections 'Body 0', "
                      "'Body 1', ...; the bodies of 'Bodies file/File' come "
                      "after them. At least one body in all.");
    prm.declare_entry("Gravity",
                      zero,
                      Patterns::List(Patterns::Double(), dim, dim),
                      "Gravitational acceleration vector, m/s^2. A zero "
                      "vector costs no work.");

    prm.enter_subsection("Time");
    prm.declare_entry("End time", "1", Patterns::Double(), "s, > 0.");
    prm.declare_entry("Maximum number of steps",
                      "0",
                      Patterns::Integer(0),
                      "Stop after this many steps (0: no limit).");
    prm.declare_entry("CFL number",
                      "0.5",
                      Patterns::Double(),
                      "C in (0, 1]: dt = C h_min / max_p(c_p + |v_p|).");
    prm.leave_subsection();

    prm.enter_subsection("Solver");
    prm.declare_entry("Update scheme",
                      "automatic",
                      update_schemes.pattern(),
                      "USL updates stresses with the grid velocities of the "
                      "momentum update; MUSL first maps the updated particle "
                      "momenta back to the grid. USL is unstable at nodes "
                      "with little mass unless the CFL number is small (about "
                      "0.02 for a body crossing cells); MUSL is not. USAVG "
                      "updates the stresses in two halves, with the momenta "
                      "at the start of the step mapped to the grid before the "
                      "momentum update and with MUSL's remapped momenta after "
                      "it (a midpoint rule; points near friction walls take "
                      "MUSL's whole step): bodies that touch, or ring while "
                      "they move or spin across the grid, keep their energy "
                      "where MUSL gains it at CFL numbers above 0.25 "
                      "(doc/mpm.md, Stability); about 1.4 times MUSL's time "
                      "per step. automatic: USAVG in a scene with contact "
                      "between bodies (Contact/Model not none, two or more "
                      "bodies), MUSL otherwise.");
    prm.declare_entry("PIC fraction",
                      "0",
                      Patterns::Double(),
                      "Blend of PIC into the FLIP velocity update, in [0, 1] "
                      "(0: pure FLIP, 1: pure PIC).");
    prm.declare_entry("Affine transfers",
                      "false",
                      Patterns::Bool(),
                      "Carry each point's velocity gradient C into the "
                      "particle-to-grid transfer, m_i v_i = sum N_i m_p (v_p + "
                      "C_p (x_i - x_p)) (the affine transfers of APIC; with "
                      "the FLIP update, affine FLIP). A rigid motion then "
                      "reaches the grid exactly, and a spinning body keeps "
                      "its spin (doc/mpm.md, Spinning bodies). Needs "
                      "'Grid/Shape functions' = gimp and 'Update scheme' = "
                      "USL (unstable otherwise); dim x dim more properties "
                      "per point.");
    prm.declare_entry("Balance particles across ranks",
                      "true",
                      Patterns::Bool(),
                      "With two or more MPI ranks: after seeding, repartition "
                      "the grid so that each rank gets about the same work, "
                      "counting a cell as 1 and a material point as 6 (the "
                      "costs measured in doc/benchmarks.md), instead of the "
                      "same number of cells. No effect on one rank.");
    prm.declare_entry("Settling steps",
                      "0",
                      Patterns::Integer(0),
                      "Before the run, let the bodies settle at rest under "
                      "gravity, their supports and contacts, for at most this "
                      "many steps (kinetic damping: every velocity is set to "
                      "zero whenever the kinetic energy passes a peak), until "
                      "a peak of the kinetic energy is below 'Settling "
                      "tolerance' times the strain energy; then the "
                      "clock starts at 0 with the bodies' initial velocities "
                      "and spins, the settled positions, stresses and "
                      "deformation gradients. For every material: bodies set "
                      "down on a support do not drop and bounce. 0: start as "
                      "seeded. A run that has not settled within the steps "
                      "stops with a message.");
    prm.declare_entry("Settling gravity",
                      "",
                      Patterns::Anything(),
                      "Gravitational acceleration while the bodies settle, "
                      "m/s^2 (dim comma-separated numbers); empty: the "
                      "scene's Gravity. A body on a slope that slides or "
                      "rolls under the scene's gravity never settles: settle "
                      "it under the part of gravity normal to the slope (for "
                      "Gravity = g sin(theta), -g cos(theta): 0, -g "
                      "cos(theta)), and the scene's Gravity acts from time 0. "
                      "Used only with Settling steps > 0.");
    prm.declare_entry("Settling friction",
                      "scene",
                      Patterns::Selection("scene|stick"),
                      "The friction between bodies and at friction walls "
                      "while the bodies settle. 'scene': the scene's. "
                      "'stick': no slip anywhere, so that a body that slides "
                      "or rolls under the scene's gravity (a block or a disk "
                      "on a slope) settles under that gravity where it was "
                      "set down, its support with it, and starts from that "
                      "equilibrium at time 0 with the scene's friction. "
                      "Used only with Settling steps > 0.");
    prm.declare_entry("Settling tolerance",
                      "1e-8",
                      Patterns::Double(0),
                      "Settled when a peak of the kinetic energy is below "
                      "this fraction of the strain energy, in (0, 1). What "
                      "is left rings on: its force amplitude is about the "
                      "square root of this fraction of the settled forces "
                      "(1e-8: 1e-4). A block held by friction 4% above its "
                      "slope creeps 5% of a cell in 0.5 s when the ringing "
                      "is 8% of its weight, 1e-7 cell at 1e-8.");
    prm.leave_subsection();

    prm.enter_subsection("Grid");
    prm.declare_entry("Lower corner",
                      zero,
                      Patterns::List(Patterns::Double(), dim, dim),
                      "Lower corner of the box-shaped background grid, m.");
    prm.declare_entry("Upper corner",
                      dim == 2 ? "1, 1" : "1, 1, 1",
                      Patterns::List(Patterns::Double(), dim, dim),
                      "Upper corner of the background grid, m.");
    prm.declare_entry("Subdivisions",
                      dim == 2 ? "10, 10" : "10, 10, 10",
                      Patterns::List(Patterns::Integer(1), dim, dim),
                      "Number of cells in each direction.");
    prm.declare_entry("Boundary ids",
                      dim == 2 ? "0, 1, 2, 3" : "0, 1, 2, 3, 4, 5",
                      Patterns::List(Patterns::Integer(0, 255),
                                     2 * dim,
                                     2 * dim),
                      "Boundary id of the faces x-, x+, y-, y+ (, z-, z+).");
    prm.declare_entry("Periodic axes",
                      "",
                      Patterns::List(Patterns::Selection(dim == 2 ? "x|y" : "x|y|z"), 0, dim),
                      "Axes along which the grid is periodic, e.g. 'y': its "
                      "two faces normal to the axis are one, material "
                      "points leaving through one come back in through the "
                      "other, and contact acts across them. Bodies may cross "
                      "these faces (they are seeded wrapped). Needs at least "
                      "3 cells along the axis; its faces take no boundary "
                      "condition.");
    prm.declare_entry("Shape functions",
                      "linear",
                      shape_function_kinds.pattern(),
                      "How points and nodes exchange mass, momentum and force. "
                      "linear: the cell's linear functions (plain MPM; a "
                      "point's weights and their gradients jump as it crosses "
                      "a cell face). gimp: uniform GIMP (Bardenhagen & Kober "
                      "2004), each point spread over a square (cube) of its "
                      "seeding spacing (shrunk next to the grid's faces, where "
                      "the weights become the linear ones), which makes the "
                      "weights and gradients continuous; a point then reaches up to 3 nodes per "
                      "direction. gimp needs a uniform grid (no Mesh "
                      "refinement) and one MPI rank (threads are allowed).");
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    BoundaryParameters<dim>::declare_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Contact");
    ContactParameters::declare_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Mesh refinement");
    MeshRefinementParameters<dim>::declare_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("Particle output interval",
                      "0",
                      Patterns::Double(0),
                      "Simulated time between particle files, s "
                      "(0: no particle output).");
    prm.declare_entry("Output format",
                      "vtu",
                      output_formats.pattern(),
                      "Format of the particle files (and of the grid "
                      "files, see 'Grid output'). vtu: one "
                      "particles_NNNNN.pvtu (with a .vtu per rank) per output "
                      "time and the series particles.pvd. hdf5: one "
                      "particles_NNNNN.h5 per output time, written by all "
                      "ranks together (MPI-IO), and the series "
                      "particles.xdmf for ParaView/VisIt.");
    prm.declare_entry("Checkpoint interval",
                      "0",
                      Patterns::Integer(0),
                      "Steps between checkpoints (0: none). A checkpoint "
                      "(the directory 'checkpoint' in the output directory: "
                      "mesh, material points and simulator state) is also "
                      "written when the run ends. 'sable scene.prm --resume' "
                      "continues from it.");
    prm.declare_entry("Contact node output",
                      "false",
                      Patterns::Bool(),
                      "With each particle output, write the contact nodes "
                      "(contact_nodes_NNNNN.pvtu): per body at each node its "
                      "normal, contact force and state (0 free, 1 stick, "
                      "2 slip).");
    prm.declare_entry("Grid output",
                      "false",
                      Patterns::Bool(),
                      "With each particle output, also write the background "
                      "grid (its active cells, as refined at that time) in "
                      "the 'Output format': grid_NNNNN.pvtu and grid.pvd, or "
                      "grid_NNNNN.h5 and grid.xdmf, numbered as the particle "
                      "files. Vertex fields: mass (kg) and velocity (m/s, "
                      "momentum / mass, 0 where the mass is 0), the material "
                      "points' mass and momentum at the output time (after "
                      "the step's grid-to-particle update and particle "
                      "move) scattered to the nodes with the transfers' "
                      "shape functions; hanging nodes show the mass and "
                      "momentum interpolated from the coarse side. Cell "
                      "fields: material_points (number in the cell), level "
                      "(refinement level) and rank (owning MPI rank).");
    prm.declare_entry("Smoothed stress output",
                      "false",
                      Patterns::Bool(),
                      "Also write with the particle output a smooth stress: "
                      "each body's point stresses projected onto the grid "
                      "nodes (weighted by shape function times volume) and "
                      "interpolated back to its points, as the tensor "
                      "smoothed_stress with its smoothed_pressure, "
                      "smoothed_von_mises and smoothed_stress_difference "
                      "(sigma_1 - sigma_2 of the stress in the x-y plane, "
                      "for photoelastic fringes). Computed at output steps "
                      "only.");
    prm.declare_entry("Displacement output",
                      "false",
                      Patterns::Bool(),
                      "Write each material point's displacement (position "
                      "minus its position at time 0, after any settling, m) "
                      "with the particle output. The points then keep their "
                      "initial position: dim more values per point in memory "
                      "and in checkpoints, so this entry cannot change on "
                      "--resume.");
    prm.declare_entry("Statistics interval",
                      "0",
                      Patterns::Integer(0),
                      "Steps between rows of statistics.csv. 0: a row at "
                      "the steps that write particle output ('Particle output "
                      "interval') or a progress line ('Progress interval'), "
                      "and at the last step. The energy guards ('Energy growth "
                      "limit', 'Energy drift limit') are evaluated with the "
                      "statistics: on these steps only.");
    prm.declare_entry("Progress interval",
                      "100",
                      Patterns::Integer(1),
                      "Steps between progress lines on the console.");
    prm.declare_entry("Energy growth limit",
                      "10",
                      Patterns::Double(),
                      "Stop the run when kinetic + strain energy exceeds this "
                      "factor (> 1) times the energy the scene can hold: the "
                      "initial energy plus the work of gravity and walls.");
    prm.declare_entry("Energy drift limit",
                      "0.5",
                      Patterns::Double(),
                      "Stop the run when the energy balance (the column "
                      "energy_drift of statistics.csv: kinetic + strain + "
                      "gravitational energy + plastic work + wall and contact "
                      "friction heat + the impacts' loss - boundary work, change "
                      "since the start over the energy the scene can hold) gains "
                      "more than this fraction, > 0. A loss (PIC's damping, "
                      "material leaving the grid) does not stop the run. A warning is "
                      "printed once the drift either way exceeds 0.01 (or this "
                      "limit if smaller).");
    prm.declare_entry("Allow outflow",
                      "false",
                      Patterns::Bool(),
                      "Whether particles may leave the grid (they are removed "
                      "and counted); otherwise leaving stops the run.");
    prm.leave_subsection();

    prm.enter_subsection("Bodies file");
    BodiesFile<dim>::declare_parameters(prm);
    prm.leave_subsection();

    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        BodyParameters<dim>::declare_parameters(prm);
        prm.leave_subsection();
      }
  }

  bool
  may_change_on_resume(const std::string &name)
  {
    static const std::set<std::string> free = {"Threads",
                                               "Output directory",
                                               "Time/End time",
                                               "Time/Maximum number of steps",
                                               "Time/CFL number",
                                               "Solver/Balance particles across ranks",
                                               "Solver/Settling steps",
                                               "Solver/Settling gravity",
                                               "Solver/Settling tolerance",
                                               "Solver/Settling friction"};
    return free.count(name) > 0 || (name.rfind("Output/", 0) == 0 && name != "Output/Output format" &&
                                    name != "Output/Displacement output");
  }

  template <int dim>
  void
  check_parameters(const SimulatorParameters<dim> &p)
  {
    check_input(p.end_time > 0, "Time/End time", p.end_time, "a number > 0 (s)");
    check_input(p.cfl > 0 && p.cfl <= 1, "Time/CFL number", p.cfl, "the interval (0, 1]");
    check_input(p.settling_tolerance > 0 && p.settling_tolerance < 1,
                "Solver/Settling tolerance",
                p.settling_tolerance,
                "the interval (0, 1)");
    check_input(p.pic_fraction >= 0 && p.pic_fraction <= 1,
                "Solver/PIC fraction", p.pic_fraction, "the interval [0, 1]");
    check_input(p.energy_growth_limit > 1,
                "Output/Energy growth limit", p.energy_growth_limit, "a number > 1");
    check_input(p.energy_drift_limit > 0,
                "Output/Energy drift limit", p.energy_drift_limit, "a number > 0");
    check_input(p.progress_interval >= 1, "Output/Progress interval", p.progress_interval, "an integer >= 1");
    check_input(!p.bodies.empty(),
                "Number of bodies",
                0,
                "at least one body (or the bodies of 'Bodies file/File')");
#ifndef DEAL_II_WITH_HDF5
    check_input(p.output_format != OutputFormat::hdf5,
                "Output/Output format", "hdf5",
                "vtu (the deal.II library in use was built without HDF5)");
#endif
    BoundaryParameters<dim>::check(p.boundaries);
    for (unsigned int b = 0; b < p.bodies.size(); ++b)
      p.bodies[b].check(p.bodies[b].name(b));
    // a pair of groups no body belongs to is a typo that would leave the
    // pair meant with the default coefficient
    std::set<unsigned int> groups;
    for (const auto &body : p.bodies)
      groups.insert(body.group);
    std::string group_list;
    for (const unsigned int g : groups)
      group_list += (group_list.empty() ? "" : ", ") + std::to_string(g);
    for (const auto &[pair, mu] : p.contact.group_friction)
      check_input(groups.count(pair.first) > 0 && groups.count(pair.second) > 0,
                  "Contact/Group friction",
                  std::to_string(pair.first) + "-" + std::to_string(pair.second),
                  "pairs of the groups the bodies belong to ('Group' of each body: " +
                    group_list + ")");
    p.refinement.check();
    // measured in doc/mpm.md, Spinning bodies: with linear functions the
    // gradient of a node of little mass stays large while its weight
    // vanishes, and its noisy velocity spreads through C; under MUSL the
    // remap would use the last step's C, a lag that pumps energy
    check_input(!p.affine_transfers || (p.shape_functions == ShapeFunctions::gimp &&
                                        p.update_scheme == UpdateScheme::usl),
                "Solver/Affine transfers",
                "true",
                "false unless Grid/Shape functions = gimp and Solver/Update scheme = USL "
                "(affine transfers are unstable with linear functions or MUSL)");
    check_input(p.shape_functions == ShapeFunctions::linear || !p.refinement.enabled(),
                "Grid/Shape functions",
                "gimp",
                "linear on a grid with Mesh refinement (GIMP needs a uniform grid)");
  }

  template <int dim>
  Scene<dim>
  read_scene(const std::string &filename, const std::vector<ParameterSetting> &settings)
  {
    unsigned int n_bodies = 0;
    {
      ParameterHandler prm;
      declare_common_parameters(prm);
      declare_parameters<dim>(prm, 0);
      parse_parameter_file(prm, filename, /*skip_undefined=*/true);
      apply_parameter_settings(prm, settings, /*skip_undeclared=*/true);
      n_bodies = prm.get_integer("Number of bodies");
    }
    ParameterHandler prm;
    declare_common_parameters(prm);
    declare_parameters<dim>(prm, n_bodies);
    parse_parameter_file(prm, filename);
    apply_parameter_settings(prm, settings);

    Scene<dim>                scene;
    SimulatorParameters<dim> &p = scene.simulator;
    p.output_directory = prm.get("Output directory");
    if (p.output_directory.empty())
      p.output_directory =
        "output/" + std::filesystem::path(filename).stem().string();
    p.gravity = read_vector<dim>(prm, "Gravity", "");

    prm.enter_subsection("Time");
    p.end_time      = prm.get_double("End time");
    p.maximum_steps = prm.get_integer("Maximum number of steps");
    p.cfl           = prm.get_double("CFL number");
    prm.leave_subsection();

    prm.enter_subsection("Solver");
    p.update_scheme = update_schemes.value(prm.get("Update scheme"));
    p.pic_fraction  = prm.get_double("PIC fraction");
    p.affine_transfers = prm.get_bool("Affine transfers");
    p.balance_particles = prm.get_bool("Balance particles across ranks");
    p.settling_steps    = prm.get_integer("Settling steps");
    p.settling_tolerance = prm.get_double("Settling tolerance");
    p.settling_stick     = prm.get("Settling friction") == "stick";
    p.settling_gravity   = prm.get("Settling gravity").empty() ?
                             p.gravity :
                             read_vector<dim>(prm, "Settling gravity", "Solver/");
    prm.leave_subsection();

    GridParameters<dim> &grid = scene.grid;
    prm.enter_subsection("Grid");
    grid.lower_corner = Point<dim>(read_vector<dim>(prm, "Lower corner", "Grid/"));
    grid.upper_corner = Point<dim>(read_vector<dim>(prm, "Upper corner", "Grid/"));
    for (const int n : Utilities::string_to_int(Utilities::split_string_list(prm.get("Subdivisions"))))
      grid.subdivisions.push_back(n);
    for (const int id : Utilities::string_to_int(Utilities::split_string_list(prm.get("Boundary ids"))))
      grid.face_ids.push_back(id);
    p.shape_functions = shape_function_kinds.value(prm.get("Shape functions"));
    for (const std::string &axis : Utilities::split_string_list(prm.get("Periodic axes")))
      {
        const unsigned int d = axis[0] - 'x';
        grid.periodic[d]     = true;
        check_input(grid.subdivisions[d] >= 3,
                    "Grid/Subdivisions",
                    prm.get("Subdivisions"),
                    "at least 3 cells along the periodic axis " + axis);
        // the potential energy would jump at the seam
        check_input(p.gravity[d] == 0.,
                    "Gravity",
                    std::to_string(p.gravity[d]) + " along " + axis,
                    "0 along the periodic axis " + axis + " (Grid/Periodic axes)");
      }
    const std::string grid_ids = prm.get("Boundary ids");
    const std::string grid_box =
      "[" + prm.get("Lower corner") + "] - [" + prm.get("Upper corner") + "]";
    for (unsigned int d = 0; d < dim; ++d)
      check_input(grid.upper_corner[d] > grid.lower_corner[d],
                  "Grid/Upper corner",
                  prm.get("Upper corner"),
                  "each component larger than the Lower corner's");
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    p.boundaries = BoundaryParameters<dim>::parse_parameters(prm);
    {
      // a condition on an id no face has would silently do nothing
      const std::set<types::boundary_id> ids(grid.face_ids.begin(), grid.face_ids.end());
      std::string                        allowed;
      for (const types::boundary_id id : ids)
        allowed += (allowed.empty() ? "" : ", ") + std::to_string(id);
      // the faces of a periodic axis are not boundaries
      std::set<types::boundary_id> periodic_ids;
      for (unsigned int d = 0; d < dim; ++d)
        if (grid.periodic[d])
          periodic_ids.insert({grid.face_ids[2 * d], grid.face_ids[2 * d + 1]});
      std::string walls;
      for (const types::boundary_id id : ids)
        if (periodic_ids.count(id) == 0)
          walls += (walls.empty() ? "" : ", ") + std::to_string(id);
      for (const auto &[id, type] : split_map(prm.get("Types")))
        {
          check_input(ids.count(std::stoi(id)) > 0,
                      "Boundary conditions/Types",
                      id + ": " + type,
                      "boundary ids of the grid's faces, " + allowed + " (Grid/Boundary ids = " +
                        grid_ids + ")");
          check_input(periodic_ids.count(std::stoi(id)) == 0,
                      "Boundary conditions/Types",
                      id + ": " + type,
                      "ids of faces that are not periodic, " +
                        (walls.empty() ? std::string("none") : walls) +
                        " (the faces of Grid/Periodic axes take no condition; "
                        "Grid/Boundary ids = " + grid_ids + ")");
        }
    }
    prm.leave_subsection();

    // the bodies of a bodies file come after the n_bodies of 'Body k'
    const std::string folder = std::filesystem::path(filename).parent_path().string();
    std::vector<BodyParameters<dim>> file_bodies;
    {
      prm.enter_subsection("Bodies file");
      BodiesFile<dim> bodies_file;
      bodies_file.parse_parameters(prm);
      prm.leave_subsection();
      file_bodies = bodies_file.create_bodies(folder, grid.lower_corner, grid.upper_corner, grid.periodic);
    }

    prm.enter_subsection("Contact");
    p.contact.parse_parameters(prm, n_bodies + file_bodies.size());
    prm.leave_subsection();

    prm.enter_subsection("Mesh refinement");
    p.refinement.parse_parameters(prm);
    prm.leave_subsection();

    prm.enter_subsection("Output");
    p.output_interval     = prm.get_double("Particle output interval");
    p.output_format       = output_formats.value(prm.get("Output format"));
    p.checkpoint_interval = prm.get_integer("Checkpoint interval");
    p.contact_node_output = prm.get_bool("Contact node output");
    p.grid_output         = prm.get_bool("Grid output");
    p.displacement_output = prm.get_bool("Displacement output");
    p.smoothed_stress_output = prm.get_bool("Smoothed stress output");
    p.statistics_interval = prm.get_integer("Statistics interval");
    p.progress_interval   = prm.get_integer("Progress interval");
    p.energy_growth_limit = prm.get_double("Energy growth limit");
    p.energy_drift_limit  = prm.get_double("Energy drift limit");
    p.allow_outflow       = prm.get_bool("Allow outflow");
    prm.leave_subsection();

    std::vector<std::string> locations; // the entry placing each body
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        BodyParameters<dim> body;
        body.parse_parameters(prm, "Body " + std::to_string(b) + "/");
        if (body.shape == BodyParameters<dim>::Shape::points)
          body.read_points(folder);
        if (body.shape == BodyParameters<dim>::Shape::mesh)
          body.read_mesh(folder, "Body " + std::to_string(b) + "/");
        locations.push_back(body.shape == BodyParameters<dim>::Shape::box    ? "Lower corner" :
                            body.shape == BodyParameters<dim>::Shape::points ? "Points file" :
                            body.shape == BodyParameters<dim>::Shape::mesh   ? "Mesh file" :
                                                                               "Center");
        locations.back() += " = " + prm.get(locations.back());
        prm.leave_subsection();
        p.bodies.push_back(body);
      }
    p.bodies.insert(p.bodies.end(), file_bodies.begin(), file_bodies.end());
    check_parameters(p);
    p.scene_entries = parameter_entries(prm);

    // every body inside the grid (the grid is the scene's, not a parameter
    // of the Simulator, which checks its own triangulation); the bodies of
    // a file were checked as they were made. Along a periodic axis: its
    // centre, and a body no longer than the period.
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const auto       box    = p.bodies[b].bounding_box();
        const Point<dim> centre = p.bodies[b].centre();
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double period = grid.upper_corner[d] - grid.lower_corner[d];
            if (grid.periodic[d] && box.second[d] - box.first[d] > period * (1. + 1e-12))
              throw InputError("invalid input: 'Body " + std::to_string(b) + "/" + locations[b] +
                               "'; allowed: a body no longer than the period " +
                               std::to_string(period) + " along the periodic axis " +
                               std::string(1, "xyz"[d]));
            const double low  = grid.periodic[d] ? centre[d] : box.first[d];
            const double high = grid.periodic[d] ? centre[d] : box.second[d];
            if (low < grid.lower_corner[d] || high > grid.upper_corner[d])
              throw InputError("invalid input: 'Body " + std::to_string(b) + "/" + locations[b] +
                               "'; allowed: a body lying inside the grid " + grid_box +
                               (grid.periodic[d] ? " (its centre, along the periodic axis " +
                                                     std::string(1, "xyz"[d]) + ")" :
                                                   std::string()));
          }
      }
    return scene;
  }
} // namespace sable::mpm

// explicit instantiations
namespace sable::mpm
{
#define SABLE_INSTANTIATE(dim)                                                  \
  template void declare_parameters<dim>(ParameterHandler &, unsigned int);     \
  template void check_parameters<dim>(const SimulatorParameters<dim> &);       \
  template Scene<dim> read_scene<dim>(const std::string &,                     \
                                      const std::vector<ParameterSetting> &);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
