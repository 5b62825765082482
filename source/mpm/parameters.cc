#include <deal.II/base/utilities.h>

#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>
#include <sable/mpm/parameters.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    std::string
    zeros(const unsigned int n)
    {
      std::string s = "0";
      for (unsigned int i = 1; i < n; ++i)
        s += ", 0";
      return s;
    }

    template <int dim>
    Tensor<1, dim>
    read_vector(const ParameterHandler &prm,
                const std::string &     entry,
                const std::string &     path)
    {
      const std::vector<double> values =
        Utilities::string_to_double(Utilities::split_string_list(prm.get(entry)));
      check_input(values.size() == dim,
                  path + entry,
                  prm.get(entry),
                  std::to_string(dim) + " comma-separated numbers");
      Tensor<1, dim> result;
      for (unsigned int d = 0; d < dim; ++d)
        result[d] = values[d];
      return result;
    }

    /// "1: a, 2: b" -> {{"1", "a"}, {"2", "b"}}
    std::vector<std::pair<std::string, std::string>>
    split_map(const std::string &text)
    {
      std::vector<std::pair<std::string, std::string>> result;
      for (const std::string &item : Utilities::split_string_list(text, ','))
        {
          const auto pair = Utilities::split_string_list(item, ':');
          if (pair.size() == 2)
            result.emplace_back(pair[0], pair[1]);
        }
      return result;
    }

    /// The number in @p text, or NaN if it is not one.
    double
    to_double(const std::string &text)
    {
      try
        {
          std::size_t end   = 0;
          const double value = std::stod(text, &end);
          if (end == text.size())
            return value;
        }
      catch (...)
        {}
      return std::numeric_limits<double>::quiet_NaN();
    }

    /// A friction coefficient: a number >= 0, or 'stick' (infinity).
    double
    parse_friction(const std::string &text, const std::string &entry)
    {
      if (text == "stick" || text == "inf")
        return std::numeric_limits<double>::infinity();
      const double value = to_double(text);
      check_input(value >= 0, entry, text, "a coefficient >= 0 or 'stick'");
      return value;
    }

    const char *material_models = "linear elastic|neo-Hookean|von Mises";

    void
    declare_material(ParameterHandler &prm)
    {
      prm.declare_entry("Material",
                        "linear elastic",
                        Patterns::Selection(material_models),
                        "Constitutive model: linear elastic (hypoelastic, "
                        "Jaumann rate), neo-Hookean (compressible) or von "
                        "Mises (J2 plasticity, linear isotropic hardening).");
      prm.declare_entry("Density", "1000", Patterns::Double(), "kg/m^3, > 0.");
      prm.declare_entry("Young's modulus",
                        "0",
                        Patterns::Double(),
                        "Pa. Give either Young's modulus and Poisson's ratio "
                        "or Bulk modulus and Shear modulus.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(),
                        "In (-1, 0.5); used with Young's modulus.");
      prm.declare_entry("Bulk modulus", "0", Patterns::Double(), "Pa.");
      prm.declare_entry("Shear modulus", "0", Patterns::Double(), "Pa.");
      prm.declare_entry("Yield stress",
                        "0",
                        Patterns::Double(),
                        "Initial von Mises yield stress, Pa (von Mises only).");
      prm.declare_entry("Hardening modulus",
                        "0",
                        Patterns::Double(),
                        "Linear isotropic hardening modulus H, Pa: "
                        "sigma_y = sigma_y0 + H * equivalent plastic strain.");
    }

    MaterialParameters
    parse_material(const ParameterHandler &prm, const std::string &path)
    {
      MaterialParameters m;
      m.model   = prm.get("Material");
      m.density = prm.get_double("Density");
      check_input(m.density > 0,
                  path + "Density",
                  m.density,
                  "a number > 0 (kg/m^3)");
      const double young   = prm.get_double("Young's modulus");
      const double poisson = prm.get_double("Poisson's ratio");
      const double bulk    = prm.get_double("Bulk modulus");
      const double shear   = prm.get_double("Shear modulus");
      if (bulk != 0. || shear != 0.)
        {
          check_input(young == 0.,
                      path + "Young's modulus",
                      young,
                      "0 (unset) when Bulk and Shear modulus are given");
          check_input(bulk > 0,
                      path + "Bulk modulus",
                      bulk,
                      "a number > 0 (Pa)");
          check_input(shear > 0,
                      path + "Shear modulus",
                      shear,
                      "a number > 0 (Pa)");
          m.bulk_modulus  = bulk;
          m.shear_modulus = shear;
        }
      else
        {
          check_input(young > 0,
                      path + "Young's modulus",
                      young,
                      "a number > 0 (Pa), or give Bulk and Shear modulus");
          check_input(poisson > -1. && poisson < 0.5,
                      path + "Poisson's ratio",
                      poisson,
                      "the open interval (-1, 0.5)");
          m.set_young_poisson(young, poisson);
        }
      m.yield_stress      = prm.get_double("Yield stress");
      m.hardening_modulus = prm.get_double("Hardening modulus");
      if (m.model == "von Mises")
        {
          check_input(m.yield_stress > 0,
                      path + "Yield stress",
                      m.yield_stress,
                      "a number > 0 (Pa) for the von Mises material");
          check_input(m.hardening_modulus >= 0,
                      path + "Hardening modulus",
                      m.hardening_modulus,
                      "a number >= 0 (Pa)");
        }
      return m;
    }
  } // namespace

  void
  MaterialParameters::set_young_poisson(const double young,
                                        const double poisson)
  {
    bulk_modulus  = young / (3. * (1. - 2. * poisson));
    shear_modulus = young / (2. * (1. + poisson));
  }

  template <int dim>
  std::pair<Point<dim>, Point<dim>>
  BodyParameters<dim>::bounding_box() const
  {
    if (shape == Shape::box)
      return {lower_corner, upper_corner};
    Point<dim> lo = center, hi = center;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] -= radius;
        hi[d] += radius;
      }
    return {lo, hi};
  }

  template <int dim>
  bool
  BodyParameters<dim>::contains(const Point<dim> &x) const
  {
    if (shape == Shape::disk)
      return (x - center).norm_square() <= radius * radius;
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lower_corner[d] || x[d] > upper_corner[d])
        return false;
    return true;
  }

  template <int dim>
  Point<dim>
  BodyParameters<dim>::top_point(const Tensor<1, dim> &gravity) const
  {
    if (shape == Shape::disk)
      {
        const double g = gravity.norm();
        return g > 0 ? center - radius * gravity / g : center;
      }
    Point<dim> top;
    for (unsigned int d = 0; d < dim; ++d)
      top[d] = gravity[d] > 0 ? lower_corner[d] : upper_corner[d];
    return top;
  }

  template <int dim>
  void
  declare_parameters(ParameterHandler &prm, const unsigned int n_bodies)
  {
    const std::string zero = zeros(dim);
    prm.declare_entry("Output directory",
                      "",
                      Patterns::Anything(),
                      "Directory for all output of the run, created after "
                      "the parameters are checked. Empty: output/<name of "
                      "the parameter file without .prm>.");
    prm.declare_entry("Number of bodies",
                      "1",
                      Patterns::Integer(1, 1000000),
                      "Bodies are described in subsections 'Body 0', "
                      "'Body 1', ...");
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
                      "MUSL",
                      Patterns::Selection("USL|MUSL"),
                      "USL updates stresses with the grid velocities of the "
                      "momentum update; MUSL first maps the updated particle "
                      "momenta back to the grid. USL is unstable at nodes "
                      "with little mass unless the CFL number is small (about "
                      "0.02 for a body crossing cells); MUSL is not.");
    prm.declare_entry("PIC fraction",
                      "0",
                      Patterns::Double(),
                      "Blend of PIC into the FLIP velocity update, in [0, 1] "
                      "(0: pure FLIP, 1: pure PIC).");
    prm.declare_entry("Balance particles across ranks",
                      "true",
                      Patterns::Bool(),
                      "With two or more MPI ranks: after seeding, repartition "
                      "the grid so that each rank gets about the same work, "
                      "counting a cell as 1 and a material point as 6 (the "
                      "costs measured in doc/benchmarks.md), instead of the "
                      "same number of cells. No effect on one rank.");
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
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("Types",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255),
                                    Patterns::Selection(
                                      "free|fixed|slip|friction|moving")),
                      "Condition per boundary id, e.g. '0: slip, 2: "
                      "friction'. Ids not listed are free.");
    prm.declare_entry("Friction coefficients",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255),
                                    Patterns::Double()),
                      "Coulomb coefficient per friction boundary, e.g. "
                      "'2: 0.3'.");
    prm.declare_entry("Friction wall contact",
                      "material",
                      Patterns::Selection("approach|material"),
                      "When a friction wall acts at a wall node. approach: "
                      "whenever the node's velocity approaches the wall "
                      "(SPEC step 6 with the wall as the other body). "
                      "material: only if, in addition, the material points "
                      "around the node reach the wall within the step "
                      "(the nearest point's edge, x_p -+ l_p/2 with l_p^dim "
                      "its current volume, at most dt times the node's "
                      "approach speed from the wall). A node up to a cell "
                      "away from the body's surface, whose velocity the "
                      "surface points' stress dominates, then carries no "
                      "contact force.");
    prm.declare_entry("Wall velocities",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255),
                                    Patterns::List(Patterns::Double(),
                                                   dim,
                                                   dim,
                                                   ";")),
                      "Velocity per moving boundary, components separated "
                      "by ';', e.g. '3: 0.1; 0'.");
    prm.leave_subsection();

    prm.enter_subsection("Contact");
    prm.declare_entry("Model",
                      "none",
                      Patterns::Selection("none|bardenhagen 2000|bardenhagen 2001"),
                      "Contact between bodies. none: all bodies share one "
                      "velocity field (no slip, no separation, no cost). "
                      "bardenhagen 2000: a velocity field per body, Coulomb "
                      "friction while bodies approach. bardenhagen 2001: also "
                      "while the normal traction is compressive.");
    prm.declare_entry("Normals",
                      "mass weighted",
                      Patterns::Selection("mass weighted|average"),
                      "How the bodies' normals at a node are made collinear "
                      "(so contact conserves momentum): 'average' is the "
                      "papers' n = (n1 - n2)/|n1 - n2| of the unit mass-"
                      "gradient directions; 'mass weighted' weights each "
                      "direction by the body's nodal mass, so that a large "
                      "flat body's normal is not tilted by a small body's "
                      "corner (see doc/mpm.md).");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Anything(),
                      "Coulomb coefficient >= 0 between any two groups not "
                      "listed in 'Group friction'; 'stick' for no slip.");
    prm.declare_entry("Group friction",
                      "",
                      Patterns::Anything(),
                      "Coefficients per pair of body groups, e.g. "
                      "'0-1: 0.5, 1-1: stick'.");
    prm.declare_entry("Impulse scaling",
                      "0.5",
                      Patterns::Anything(),
                      "gamma in [0.5, 1] of the contact-impulse scaling "
                      "(paper 002, with the erratum min(...,1)), or 'off'.");
    prm.declare_entry("Passes",
                      "momentum update, strain update",
                      Patterns::MultipleSelection("momentum update|strain update"),
                      "Where contact acts: on the velocities after the "
                      "momentum update, and on the velocities the strain "
                      "update uses (MUSL's remapped velocities).");
    prm.declare_entry("Reported pairs",
                      "all",
                      Patterns::Anything(),
                      "Body pairs whose total contact force goes to "
                      "statistics.csv, e.g. '0-1, 1-2'; 'all' (every pair "
                      "when there are at most 4 bodies) or 'none'.");
    prm.leave_subsection();

    prm.enter_subsection("Mesh refinement");
    prm.declare_entry("Criteria",
                      "",
                      Patterns::MultipleSelection("body surface|contact|particle count|region"),
                      "Where the grid is refined between steps (empty: a fixed "
                      "grid). 'body surface': cells on either side of a body's "
                      "surface and between bodies; 'contact': cells where "
                      "bodies meet each other or a friction wall (a body "
                      "held by a fixed or slip wall is not refined there); 'particle count': cells holding more than "
                      "'Maximum particles per cell' material points; 'region': "
                      "cells inside the box 'Region lower/upper corner'. "
                      "Cells no criterion asks for are coarsened again, down "
                      "to the minimum level.");
    prm.declare_entry("Maximum level",
                      "1",
                      Patterns::Integer(0, 12),
                      "Finest refinement level, counted from the starting grid "
                      "(Grid/Subdivisions), in 0..12. Body geometry criteria "
                      "refine to it before the bodies are seeded.");
    prm.declare_entry("Minimum level",
                      "0",
                      Patterns::Integer(0, 12),
                      "Coarsest level anywhere: the starting grid is refined "
                      "globally to it; at most the maximum level.");
    prm.declare_entry("Refinement interval",
                      "0",
                      Patterns::Integer(0),
                      "Steps between mesh adaptations; 0: adapt whenever the "
                      "fastest material point may have moved half of the "
                      "smallest cell since the last adaptation. A body stays in "
                      "its refined band only if it crosses less than about one "
                      "fine cell between adaptations.");
    prm.declare_entry("Maximum particles per cell",
                      "16",
                      Patterns::Integer(1),
                      "'particle count' criterion: cells with more points are "
                      "refined; cells are coarsened when their parent would "
                      "hold at most this many.");
    prm.declare_entry("Region lower corner", zero, Patterns::List(Patterns::Double(), dim, dim),
                      "'region' criterion: lower corner of the refined box, m.");
    prm.declare_entry("Region upper corner", zero, Patterns::List(Patterns::Double(), dim, dim),
                      "'region' criterion: upper corner of the refined box, m.");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("Particle output interval",
                      "0",
                      Patterns::Double(0),
                      "Simulated time between particle files, s "
                      "(0: no particle output).");
    prm.declare_entry("Output format",
                      "vtu",
                      Patterns::Selection("vtu|hdf5"),
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
    prm.declare_entry("Statistics interval",
                      "1",
                      Patterns::Integer(1),
                      "Steps between rows of statistics.csv.");
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
    prm.declare_entry("Allow outflow",
                      "false",
                      Patterns::Bool(),
                      "Whether particles may leave the grid (they are removed "
                      "and counted); otherwise leaving stops the run.");
    prm.leave_subsection();

    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        prm.declare_entry("Shape",
                          "disk",
                          Patterns::Selection("disk|sphere|box"),
                          "disk (2D) or sphere (3D), or box.");
        prm.declare_entry("Center", zero, Patterns::List(Patterns::Double(), dim, dim), "Disk/sphere centre, m.");
        prm.declare_entry("Radius", "0", Patterns::Double(), "Disk/sphere radius, m, > 0.");
        prm.declare_entry("Lower corner", zero, Patterns::List(Patterns::Double(), dim, dim), "Box lower corner, m.");
        prm.declare_entry("Upper corner", zero, Patterns::List(Patterns::Double(), dim, dim), "Box upper corner, m.");
        prm.declare_entry("Particles per cell direction",
                          "2",
                          Patterns::Integer(),
                          "k in 1..4: k^dim material points per cell, at the "
                          "centres of equal sub-cells.");
        declare_material(prm);
        prm.declare_entry("Velocity", zero, Patterns::List(Patterns::Double(), dim, dim), "Initial velocity, m/s.");
        prm.declare_entry("Angular velocity",
                          dim == 2 ? "0" : "0, 0, 0",
                          Patterns::List(Patterns::Double(),
                                         dim == 2 ? 1 : 3,
                                         dim == 2 ? 1 : 3),
                          "Initial rigid rotation about the centre, rad/s "
                          "(2D: one number, counter-clockwise).");
        prm.declare_entry("Refine surface",
                          "true",
                          Patterns::Bool(),
                          "Whether the 'body surface' refinement criterion "
                          "refines around this body's surface (false, e.g., for "
                          "a large plane a grain rolls on: only where the "
                          "grain touches it, with the 'contact' criterion).");
        prm.declare_entry("Group",
                          "0",
                          Patterns::Integer(0),
                          "Contact group; friction is set per pair of groups "
                          "(Contact/Group friction).");
        prm.declare_entry("Lithostatic initial stress",
                          "false",
                          Patterns::Bool(),
                          "Start from sigma = -p I with grad p = rho g and "
                          "p = 0 at the body's top (linear elastic and von "
                          "Mises bodies).");
        prm.leave_subsection();
      }
  }

  template <int dim>
  void
  check_body(const BodyParameters<dim> &body, const std::string &name)
  {
    const std::string path = name + "/";
    if (body.shape == BodyParameters<dim>::Shape::disk)
      check_input(body.radius > 0, path + "Radius", body.radius, "a number > 0 (m)");
    else
      for (unsigned int d = 0; d < dim; ++d)
        check_input(body.upper_corner[d] > body.lower_corner[d],
                    path + "Upper corner",
                    body.upper_corner,
                    "each component larger than the Lower corner's");
    check_input(body.particles_per_direction >= 1 &&
                  body.particles_per_direction <= 4,
                path + "Particles per cell direction",
                body.particles_per_direction,
                "an integer in 1..4");
    const MaterialParameters &m = body.material;
    check_input(m.model == "linear elastic" || m.model == "neo-Hookean" ||
                  m.model == "von Mises",
                path + "Material",
                m.model,
                material_models);
    check_input(m.density > 0, path + "Density", m.density, "a number > 0 (kg/m^3)");
    check_input(m.bulk_modulus > 0, path + "Bulk modulus", m.bulk_modulus, "a number > 0 (Pa)");
    check_input(m.shear_modulus > 0, path + "Shear modulus", m.shear_modulus, "a number > 0 (Pa)");
    if (m.model == "von Mises")
      check_input(m.yield_stress > 0, path + "Yield stress", m.yield_stress, "a number > 0 (Pa)");
    check_input(!body.lithostatic_stress || m.model != "neo-Hookean",
                path + "Lithostatic initial stress",
                "true",
                "false for neo-Hookean bodies (their stress follows from F)");
  }

  template <int dim>
  void
  check_parameters(const SimulatorParameters<dim> &p)
  {
    check_input(p.end_time > 0, "Time/End time", p.end_time, "a number > 0 (s)");
    check_input(p.cfl > 0 && p.cfl <= 1, "Time/CFL number", p.cfl, "the interval (0, 1]");
    check_input(p.pic_fraction >= 0 && p.pic_fraction <= 1,
                "Solver/PIC fraction", p.pic_fraction, "the interval [0, 1]");
    check_input(p.energy_growth_limit > 1,
                "Output/Energy growth limit", p.energy_growth_limit, "a number > 1");
    check_input(p.statistics_interval >= 1, "Output/Statistics interval", p.statistics_interval, "an integer >= 1");
    check_input(p.progress_interval >= 1, "Output/Progress interval", p.progress_interval, "an integer >= 1");
    check_input(!p.bodies.empty(), "Number of bodies", 0, "at least one body");
#ifndef DEAL_II_WITH_HDF5
    check_input(p.output_format != OutputFormat::hdf5,
                "Output/Output format", "hdf5",
                "vtu (the deal.II library in use was built without HDF5)");
#endif
    for (const auto &[id, boundary] : p.boundaries)
      {
        if (boundary.type == BoundaryType::friction)
          check_input(boundary.friction >= 0,
                      "Boundary conditions/Friction coefficients",
                      std::to_string(id) + ": " + std::to_string(boundary.friction),
                      "a coefficient >= 0 for each friction boundary, "
                      "e.g. '" + std::to_string(id) + ": 0.3'");
      }
    for (unsigned int b = 0; b < p.bodies.size(); ++b)
      check_body(p.bodies[b], "Body " + std::to_string(b));

    const MeshRefinementParameters<dim> &r = p.refinement;
    check_input(r.minimum_level <= r.maximum_level,
                "Mesh refinement/Minimum level",
                r.minimum_level,
                "a level <= 'Maximum level' = " + std::to_string(r.maximum_level));
    if (r.enabled())
      check_input(r.maximum_level > r.minimum_level,
                  "Mesh refinement/Maximum level",
                  r.maximum_level,
                  "a level above 'Minimum level' = " + std::to_string(r.minimum_level) +
                    " when refinement criteria are set");
    if (r.uses(MeshRefinementParameters<dim>::Criterion::particle_count))
      check_input(r.maximum_particles_per_cell >= 1,
                  "Mesh refinement/Maximum particles per cell",
                  r.maximum_particles_per_cell,
                  "an integer >= 1");
    if (r.uses(MeshRefinementParameters<dim>::Criterion::region))
      for (unsigned int d = 0; d < dim; ++d)
        {
          std::ostringstream value;
          value << r.region_upper_corner;
          check_input(r.region_upper_corner[d] > r.region_lower_corner[d],
                      "Mesh refinement/Region upper corner",
                      value.str(),
                      "each component larger than the Region lower corner's");
        }
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
      prm.parse_input(filename, "", /*skip_undefined=*/true);
      apply_parameter_settings(prm, settings, /*skip_undeclared=*/true);
      n_bodies = prm.get_integer("Number of bodies");
    }
    ParameterHandler prm;
    declare_common_parameters(prm);
    declare_parameters<dim>(prm, n_bodies);
    prm.parse_input(filename);
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
    p.update_scheme = prm.get("Update scheme") == "MUSL" ? UpdateScheme::musl : UpdateScheme::usl;
    p.pic_fraction  = prm.get_double("PIC fraction");
    p.balance_particles = prm.get_bool("Balance particles across ranks");
    prm.leave_subsection();

    GridParameters<dim> &grid = scene.grid;
    prm.enter_subsection("Grid");
    grid.lower_corner = Point<dim>(read_vector<dim>(prm, "Lower corner", "Grid/"));
    grid.upper_corner = Point<dim>(read_vector<dim>(prm, "Upper corner", "Grid/"));
    for (const int n : Utilities::string_to_int(Utilities::split_string_list(prm.get("Subdivisions"))))
      grid.subdivisions.push_back(n);
    for (const int id : Utilities::string_to_int(Utilities::split_string_list(prm.get("Boundary ids"))))
      grid.face_ids.push_back(id);
    const std::string grid_box =
      "[" + prm.get("Lower corner") + "] - [" + prm.get("Upper corner") + "]";
    for (unsigned int d = 0; d < dim; ++d)
      check_input(grid.upper_corner[d] > grid.lower_corner[d],
                  "Grid/Upper corner",
                  prm.get("Upper corner"),
                  "each component larger than the Lower corner's");
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    for (const auto &[id, type] : split_map(prm.get("Types")))
      {
        BoundaryParameters<dim> &boundary = p.boundaries[std::stoi(id)];
        boundary.type = type == "fixed"    ? BoundaryType::fixed :
                        type == "slip"     ? BoundaryType::slip :
                        type == "friction" ? BoundaryType::friction :
                        type == "moving"   ? BoundaryType::moving :
                                             BoundaryType::free;
        // a friction boundary without a coefficient is reported by
        // check_parameters()
        boundary.friction = boundary.type == BoundaryType::friction ? -1. : 0.;
      }
    for (const auto &[id, value] : split_map(prm.get("Friction coefficients")))
      {
        const auto it = p.boundaries.find(std::stoi(id));
        check_input(it != p.boundaries.end() &&
                      it->second.type == BoundaryType::friction,
                    "Boundary conditions/Friction coefficients",
                    id + ": " + value,
                    "coefficients only for boundary ids whose type is friction");
        it->second.friction = Utilities::string_to_double(value);
      }
    for (auto &[id, boundary] : p.boundaries)
      boundary.material_contact = boundary.type == BoundaryType::friction &&
                                  prm.get("Friction wall contact") == "material";
    for (const auto &[id, value] : split_map(prm.get("Wall velocities")))
      {
        const auto it = p.boundaries.find(std::stoi(id));
        check_input(it != p.boundaries.end() &&
                      it->second.type == BoundaryType::moving,
                    "Boundary conditions/Wall velocities",
                    id + ": " + value,
                    "velocities only for boundary ids whose type is moving");
        const std::vector<double> v = Utilities::string_to_double(
          Utilities::split_string_list(value, ';'));
        for (unsigned int d = 0; d < dim; ++d)
          it->second.velocity[d] = v[d];
      }
    prm.leave_subsection();

    prm.enter_subsection("Contact");
    {
      ContactParameters &c = p.contact;
      const std::string  model = prm.get("Model");
      c.model = model == "bardenhagen 2000" ? ContactParameters::Model::bardenhagen_2000 :
                model == "bardenhagen 2001" ? ContactParameters::Model::bardenhagen_2001 :
                                              ContactParameters::Model::none;
      c.mass_weighted_normals = prm.get("Normals") == "mass weighted";
      c.friction = parse_friction(prm.get("Friction coefficient"), "Contact/Friction coefficient");
      for (const auto &[pair, value] : split_map(prm.get("Group friction")))
        {
          const auto groups = Utilities::split_string_list(pair, '-');
          check_input(groups.size() == 2,
                      "Contact/Group friction", pair + ": " + value,
                      "entries '<group>-<group>: <coefficient or stick>'");
          const unsigned int a = Utilities::string_to_int(groups[0]);
          const unsigned int b = Utilities::string_to_int(groups[1]);
          c.group_friction[{std::min(a, b), std::max(a, b)}] =
            parse_friction(value, "Contact/Group friction");
        }
      const std::string scaling = prm.get("Impulse scaling");
      if (scaling == "off")
        c.impulse_scaling = 0.;
      else
        {
          c.impulse_scaling = to_double(scaling);
          check_input(c.impulse_scaling >= 0.5 && c.impulse_scaling <= 1.,
                      "Contact/Impulse scaling", scaling, "a number in [0.5, 1] or 'off'");
        }
      const std::string passes = prm.get("Passes");
      c.on_momentum_update = passes.find("momentum update") != std::string::npos;
      c.on_strain_update   = passes.find("strain update") != std::string::npos;
      const std::string pairs = prm.get("Reported pairs");
      if (pairs == "all")
        {
          if (n_bodies <= 4)
            for (unsigned int a = 0; a < n_bodies; ++a)
              for (unsigned int b = a + 1; b < n_bodies; ++b)
                c.reported_pairs.emplace_back(a, b);
        }
      else if (pairs != "none")
        for (const std::string &pair : Utilities::split_string_list(pairs, ','))
          {
            const auto bodies = Utilities::split_string_list(pair, '-');
            check_input(bodies.size() == 2 &&
                          Utilities::string_to_int(bodies[0]) < int(n_bodies) &&
                          Utilities::string_to_int(bodies[1]) < int(n_bodies) &&
                          bodies[0] != bodies[1],
                        "Contact/Reported pairs", pair,
                        "pairs '<body>-<body>' of two different bodies below Number of bodies");
            const unsigned int a = Utilities::string_to_int(bodies[0]);
            const unsigned int b = Utilities::string_to_int(bodies[1]);
            c.reported_pairs.emplace_back(std::min(a, b), std::max(a, b));
          }
    }
    prm.leave_subsection();

    prm.enter_subsection("Mesh refinement");
    {
      using Criterion = typename MeshRefinementParameters<dim>::Criterion;
      MeshRefinementParameters<dim> &r = p.refinement;
      for (const std::string &name : Utilities::split_string_list(prm.get("Criteria")))
        r.criteria.push_back(name == "body surface" ? Criterion::body_surface :
                             name == "contact"      ? Criterion::contact :
                             name == "particle count" ? Criterion::particle_count :
                                                        Criterion::region);
      r.maximum_level = prm.get_integer("Maximum level");
      r.minimum_level = prm.get_integer("Minimum level");
      r.interval      = prm.get_integer("Refinement interval");
      r.maximum_particles_per_cell = prm.get_integer("Maximum particles per cell");
      r.region_lower_corner =
        Point<dim>(read_vector<dim>(prm, "Region lower corner", "Mesh refinement/"));
      r.region_upper_corner =
        Point<dim>(read_vector<dim>(prm, "Region upper corner", "Mesh refinement/"));
    }
    prm.leave_subsection();

    prm.enter_subsection("Output");
    p.output_interval     = prm.get_double("Particle output interval");
    p.output_format       = prm.get("Output format") == "hdf5" ? OutputFormat::hdf5 : OutputFormat::vtu;
    p.checkpoint_interval = prm.get_integer("Checkpoint interval");
    p.contact_node_output = prm.get_bool("Contact node output");
    p.grid_output         = prm.get_bool("Grid output");
    p.statistics_interval = prm.get_integer("Statistics interval");
    p.progress_interval   = prm.get_integer("Progress interval");
    p.energy_growth_limit = prm.get_double("Energy growth limit");
    p.allow_outflow       = prm.get_bool("Allow outflow");
    prm.leave_subsection();

    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const std::string name = "Body " + std::to_string(b);
        const std::string path = name + "/";
        prm.enter_subsection(name);
        BodyParameters<dim> body;
        body.shape  = prm.get("Shape") == "box" ? BodyParameters<dim>::Shape::box :
                                                  BodyParameters<dim>::Shape::disk;
        body.center = Point<dim>(read_vector<dim>(prm, "Center", path));
        body.radius = prm.get_double("Radius");
        body.lower_corner = Point<dim>(read_vector<dim>(prm, "Lower corner", path));
        body.upper_corner = Point<dim>(read_vector<dim>(prm, "Upper corner", path));
        const int k = prm.get_integer("Particles per cell direction");
        check_input(k >= 1 && k <= 4, path + "Particles per cell direction", k, "an integer in 1..4");
        body.particles_per_direction = k;
        body.material = parse_material(prm, path);
        body.velocity = read_vector<dim>(prm, "Velocity", path);
        const std::vector<double> omega = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Angular velocity")));
        if (dim == 2)
          body.angular_velocity[2] = omega[0];
        else
          for (unsigned int d = 0; d < 3; ++d)
            body.angular_velocity[d] = omega[d];
        body.lithostatic_stress = prm.get_bool("Lithostatic initial stress");
        body.group              = prm.get_integer("Group");
        body.refine_surface     = prm.get_bool("Refine surface");
        const bool        is_box   = body.shape == BodyParameters<dim>::Shape::box;
        const std::string location_entry = is_box ? "Lower corner" : "Center";
        const std::string location = prm.get(location_entry);
        prm.leave_subsection();

        check_body(body, name);
        const auto box = body.bounding_box();
        for (unsigned int d = 0; d < dim; ++d)
          check_input(box.first[d] >= grid.lower_corner[d] &&
                        box.second[d] <= grid.upper_corner[d],
                      path + location_entry,
                      location,
                      "a body lying inside the grid " + grid_box);
        p.bodies.push_back(body);
      }
    check_parameters(p);
    return scene;
  }
} // namespace sable::mpm

// explicit instantiations
namespace sable::mpm
{
#define SABLE_INSTANTIATE(dim)                                                  \
  template struct BodyParameters<dim>;                                         \
  template void declare_parameters<dim>(ParameterHandler &, unsigned int);     \
  template void check_body<dim>(const BodyParameters<dim> &,                   \
                                const std::string &);                          \
  template void check_parameters<dim>(const SimulatorParameters<dim> &);       \
  template Scene<dim> read_scene<dim>(const std::string &,                     \
                                      const std::vector<ParameterSetting> &);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
