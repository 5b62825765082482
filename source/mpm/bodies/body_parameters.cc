#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/base/named_choice.h>
#include <sable/mpm/bodies/body_parameters.h>
#include <sable/mpm/parameter_tools.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>

namespace sable::mpm
{
  namespace
  {
    template <int dim>
    const NamedChoice<typename BodyParameters<dim>::Shape> &
    shapes()
    {
      using Shape = typename BodyParameters<dim>::Shape;
      static const NamedChoice<Shape> choice{{"disk", Shape::disk},
                                             {"sphere", Shape::disk},
                                             {"box", Shape::box},
                                             {"points", Shape::points},
                                             {"mesh", Shape::mesh}};
      return choice;
    }

    template <int dim>
    const NamedChoice<typename BodyParameters<dim>::Seeding> &
    seedings()
    {
      using Seeding = typename BodyParameters<dim>::Seeding;
      static const NamedChoice<Seeding> choice{{"automatic", Seeding::automatic},
                                               {"lattice", Seeding::lattice},
                                               {"conforming", Seeding::conforming},
                                               {"clipped", Seeding::clipped}};
      return choice;
    }

    /// @p file as given if absolute, else in @p folder
    std::string
    in_folder(const std::string &folder, const std::string &file)
    {
      const std::filesystem::path path(file);
      return path.is_absolute() || folder.empty() ? file : (std::filesystem::path(folder) / path).string();
    }
  } // namespace

  template <int dim>
  void
  BodyParameters<dim>::read_points(const std::string &folder)
  {
    cloud = read_point_file<dim>(in_folder(folder, points_file));
  }

  template <int dim>
  void
  BodyParameters<dim>::read_mesh(const std::string &folder, const std::string &path)
  {
    check_input(mesh_scale > 0, path + "Mesh scale", mesh_scale, "a number > 0");
    check_input(!mesh_file.empty(), path + "Mesh file", "", "the name of a mesh file (Shape = mesh)");
    try
      {
        mesh = read_body_mesh<dim>(in_folder(folder, mesh_file), mesh_scale, mesh_translation);
      }
    catch (const InputError &error)
      {
        check_input(false, path + "Mesh file", mesh_file, error.what());
      }
  }

  template <int dim>
  Point<dim>
  BodyParameters<dim>::centre() const
  {
    if (shape == Shape::disk)
      return center;
    if (shape == Shape::box)
      return Point<dim>((Tensor<1, dim>(lower_corner) + Tensor<1, dim>(upper_corner)) / 2.);
    if (shape == Shape::mesh)
      return mesh.centroid();
    Tensor<1, dim> sum;
    double         volume = 0;
    for (unsigned int i = 0; i < cloud.positions.size(); ++i)
      {
        sum += cloud.volumes[i] * Tensor<1, dim>(cloud.positions[i]);
        volume += cloud.volumes[i];
      }
    return Point<dim>(volume > 0 ? sum / volume : sum);
  }

  template <int dim>
  std::pair<Point<dim>, Point<dim>>
  BodyParameters<dim>::bounding_box() const
  {
    if (shape == Shape::points)
      {
        Point<dim> lo = cloud.positions.empty() ? Point<dim>() : cloud.positions[0], hi = lo;
        for (const Point<dim> &x : cloud.positions)
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], x[d]);
              hi[d] = std::max(hi[d], x[d]);
            }
        return {lo, hi};
      }
    if (shape == Shape::box)
      return {lower_corner, upper_corner};
    if (shape == Shape::mesh)
      return mesh.bounding_box();
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
    if (shape == Shape::points)
      return false;
    if (shape == Shape::disk)
      return (x - center).norm_square() <= radius * radius;
    if (shape == Shape::mesh)
      return mesh.contains(x);
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lower_corner[d] || x[d] > upper_corner[d])
        return false;
    return true;
  }

  template <int dim>
  double
  BodyParameters<dim>::depth_inside(const Point<dim> &x) const
  {
    if (shape == Shape::points)
      return 0.;
    if (shape == Shape::disk)
      return std::max(0., radius - (x - center).norm());
    if (shape == Shape::mesh)
      {
        if (!mesh.contains(x))
          return 0.;
        // the nearest boundary facet (a negative edge margin takes it even
        // near an edge)
        return mesh.face_below(x, std::numeric_limits<double>::max(), -1.).depth;
      }
    double depth = std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < dim; ++d)
      depth = std::min({depth, x[d] - lower_corner[d], upper_corner[d] - x[d]});
    return std::max(0., depth);
  }

  template <int dim>
  FaceBelow<dim>
  BodyParameters<dim>::face_below(const Point<dim> &x,
                                  const double      depth_limit,
                                  const double      edge_margin) const
  {
    FaceBelow<dim> face;
    // a disk's or sphere's points carry none: their mass gradient is
    // already the radial direction up to the lattice's staircase (carried
    // radial normals let unequal disks gain 1.7% energy head-on); they
    // carry their vectors to the circle instead (to_round_surface())
    if (shape == Shape::box)
      {
        // the nearest face, unless a face of another axis is within
        // edge_margin: near an edge or a corner the face is ambiguous
        std::array<double, dim> depth;
        unsigned int            axis = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            depth[d] = std::min(x[d] - lower_corner[d], upper_corner[d] - x[d]);
            if (depth[d] < depth[axis])
              axis = d;
          }
        bool corner = false;
        for (unsigned int d = 0; d < dim; ++d)
          corner = corner || (d != axis && depth[d] <= edge_margin);
        if (depth[axis] <= depth_limit && !corner)
          {
            face.normal[axis] =
              x[axis] - lower_corner[axis] <= upper_corner[axis] - x[axis] ? -1. : 1.;
            face.depth = depth[axis];
          }
      }
    else if (shape == Shape::mesh)
      face = mesh.face_below(x, depth_limit, edge_margin);
    return face;
  }

  template <int dim>
  Tensor<1, dim>
  BodyParameters<dim>::to_round_surface(const Point<dim> &x, const double depth_limit) const
  {
    if (shape != Shape::disk)
      return {};
    const Tensor<1, dim> radial   = x - center;
    const double         distance = radial.norm();
    const double         depth    = radius - distance;
    if (distance == 0 || depth < 0 || depth > depth_limit)
      return {};
    return (depth / distance) * radial;
  }

  template <int dim>
  Point<dim>
  BodyParameters<dim>::top_point(const Tensor<1, dim> &gravity) const
  {
    if (shape == Shape::points)
      {
        // the point highest against gravity
        Point<dim> top = cloud.positions.empty() ? Point<dim>() : cloud.positions[0];
        for (const Point<dim> &x : cloud.positions)
          if (gravity * (x - top) < 0)
            top = x;
        return top;
      }
    if (shape == Shape::mesh)
      return mesh.top_point(gravity);
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
  BodyParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    const std::string zero = zero_vector(dim);
    prm.declare_entry("Shape",
                      "disk",
                      shapes<dim>().pattern(),
                      "disk (2D) or sphere (3D), box, points (one material "
                      "point per row of 'Points file') or mesh (the cells of "
                      "'Mesh file').");
    prm.declare_entry("Points file",
                      "",
                      Patterns::Anything(),
                      "Shape = points: a CSV file with a header naming its "
                      "columns x, y (, z in 3D), volume (m^dim) and optionally "
                      "vx, vy (, vz) (m/s, else 'Velocity' and 'Angular "
                      "velocity' about the volume-weighted centroid), then one "
                      "row per material point, its mass density times volume. "
                      "A relative path is read from the parameter file's folder.");
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "Shape = mesh: a volume mesh read with deal.II's GridIn, "
                      "Gmsh (.msh), legacy VTK (.vtk) or UCD (.inp, .ucd): "
                      "triangles and quadrilaterals in 2D, tetrahedra and "
                      "hexahedra in 3D; or in 3D a closed surface, STL (.stl, "
                      "ASCII or binary). Material points are seeded as for the "
                      "other shapes, at the sub-cell centres of the grid that "
                      "lie in a cell of the mesh (inside the surface). A "
                      "relative path is read from the parameter file's folder.");
    prm.declare_entry("Mesh scale",
                      "1",
                      Patterns::Double(),
                      "Shape = mesh: factor (> 0) on the mesh's coordinates, "
                      "e.g. 0.001 for a mesh in mm; applied before 'Mesh "
                      "translation'.");
    prm.declare_entry("Mesh translation",
                      zero,
                      Patterns::List(Patterns::Double(), dim, dim),
                      "Shape = mesh: shift of the (scaled) mesh, m.");
    prm.declare_entry("Center", zero, Patterns::List(Patterns::Double(), dim, dim), "Disk/sphere centre, m.");
    prm.declare_entry("Radius", "0", Patterns::Double(), "Disk/sphere radius, m, > 0.");
    prm.declare_entry("Lower corner", zero, Patterns::List(Patterns::Double(), dim, dim), "Box lower corner, m.");
    prm.declare_entry("Upper corner", zero, Patterns::List(Patterns::Double(), dim, dim), "Box upper corner, m.");
    prm.declare_entry("Prescribed velocity",
                      "",
                      Patterns::Anything(),
                      "Empty (a free body), or m/s (" + std::to_string(dim) +
                        " numbers): the body is a rigid driver, e.g. a "
                        "loading pin; all its points move with this velocity "
                        "from 'Prescribed velocity start time' on and stay "
                        "at rest before, whatever the forces on them, and "
                        "the other bodies meet it through contact as a body "
                        "of unbounded mass (a contact model is needed). Its "
                        "stress stays as seeded. The work it does counts as "
                        "boundary work in the energy balance.");
    prm.declare_entry("Prescribed velocity start time",
                      "0",
                      Patterns::Double(),
                      "s, >= 0: when the prescribed velocity sets in (a step).");
    declare_template_parameters(prm);
  }

  template <int dim>
  void
  BodyParameters<dim>::declare_template_parameters(ParameterHandler &prm)
  {
    const std::string zero = zero_vector(dim);
    prm.declare_entry("Particles per cell direction",
                      "2",
                      Patterns::Integer(0),
                      "k in 1..4: k^dim material points per cell, at the "
                      "centres of equal sub-cells.");
    prm.declare_entry("Seeding",
                      "automatic",
                      seedings<dim>().pattern(),
                      "'automatic': clipped for a disk or sphere, the lattice "
                      "for every other shape. Disk/sphere: 'lattice' puts the "
                      "points on the grid's sub-cell centres (their edge is a "
                      "staircase within half a spacing of the surface); "
                      "'clipped' on the same lattice, but each sub-cell the "
                      "surface cuts carries the part inside it, at that "
                      "part's centroid (none shallower than a quarter "
                      "spacing or smaller than a quarter sub-cell: such "
                      "parts join their neighbours), so the mass follows the "
                      "circle; 'conforming' on rings (2D) or shells (3D) of "
                      "equal spacing h/k parallel to the surface (h the "
                      "smallest cell the body overlaps), the outermost half "
                      "a spacing inside it, as contact's surface estimate "
                      "assumes. A disk rolling on a plane body at 16 cells "
                      "per diameter lags 4-14% seeded on the lattice, within "
                      "0.8% clipped, 0.3% conforming; resting on a floor, a "
                      "lattice disk or sphere sinks about half as far as the "
                      "converged one at 12.8 cells per diameter, clipped or "
                      "conforming 13-21% further (doc/validation.md).");
    MaterialParameters::declare_parameters(prm);
    prm.declare_entry("Velocity", zero, Patterns::List(Patterns::Double(), dim, dim), "Initial velocity, m/s.");
    prm.declare_entry("Angular velocity",
                      dim == 2 ? "0" : "0, 0, 0",
                      Patterns::List(Patterns::Double(), dim == 2 ? 1 : 3, dim == 2 ? 1 : 3),
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
  }

  template <int dim>
  void
  BodyParameters<dim>::parse_parameters(ParameterHandler &prm, const std::string &path)
  {
    shape        = shapes<dim>().value(prm.get("Shape"));
    center       = Point<dim>(read_vector<dim>(prm, "Center", path));
    radius       = prm.get_double("Radius");
    lower_corner = Point<dim>(read_vector<dim>(prm, "Lower corner", path));
    upper_corner = Point<dim>(read_vector<dim>(prm, "Upper corner", path));
    points_file             = prm.get("Points file");
    mesh_file               = prm.get("Mesh file");
    mesh_scale              = prm.get_double("Mesh scale");
    mesh_translation        = read_vector<dim>(prm, "Mesh translation", path);
    prescribed = !Utilities::trim(prm.get("Prescribed velocity")).empty();
    if (prescribed)
      prescribed_velocity = read_vector<dim>(prm, "Prescribed velocity", path);
    prescribed_start_time = prm.get_double("Prescribed velocity start time");
    parse_template_parameters(prm, path);
  }

  template <int dim>
  void
  BodyParameters<dim>::parse_template_parameters(ParameterHandler &prm, const std::string &path)
  {
    seeding                 = seedings<dim>().value(prm.get("Seeding"));
    particles_per_direction = prm.get_integer("Particles per cell direction");
    material.parse_parameters(prm, path);
    velocity = read_vector<dim>(prm, "Velocity", path);
    const std::vector<double> omega =
      Utilities::string_to_double(Utilities::split_string_list(prm.get("Angular velocity")));
    if (dim == 2)
      angular_velocity[2] = omega[0];
    else
      for (unsigned int d = 0; d < 3; ++d)
        angular_velocity[d] = omega[d];
    lithostatic_stress = prm.get_bool("Lithostatic initial stress");
    group              = prm.get_integer("Group");
    refine_surface     = prm.get_bool("Refine surface");
  }

  template <int dim>
  void
  BodyParameters<dim>::check(const std::string &path) const
  {
    if (shape == Shape::disk)
      check_input(radius > 0, path + "Radius", radius, "a number > 0 (m)");
    else if (shape == Shape::points)
      check_input(!cloud.positions.empty(),
                  path + "Points file",
                  points_file,
                  "a file of material points (Shape = points)");
    else if (shape == Shape::mesh)
      check_input(mesh.measure() > 0,
                  path + "Mesh file",
                  mesh_file,
                  "a mesh of cells with a volume > 0 (Shape = mesh), read with read_mesh()");
    else
      for (unsigned int d = 0; d < dim; ++d)
        check_input(upper_corner[d] > lower_corner[d],
                    path + "Upper corner",
                    upper_corner,
                    "each component larger than the Lower corner's");
    check_input(seeding == Seeding::automatic || seeding == Seeding::lattice ||
                  shape == Shape::disk,
                path + "Seeding",
                seedings<dim>().name(seeding),
                "'automatic' or 'lattice' unless Shape is disk or sphere");
    check_input(particles_per_direction >= 1 && particles_per_direction <= 4,
                path + "Particles per cell direction",
                particles_per_direction,
                "an integer in 1..4");
    material.check(path);
    check_input(prescribed_start_time >= 0,
                path + "Prescribed velocity start time",
                prescribed_start_time,
                "a number >= 0 (s)");
    check_input(!lithostatic_stress || material.model != "neo-Hookean",
                path + "Lithostatic initial stress",
                "true",
                "false for neo-Hookean bodies (their stress follows from F)");
  }

  template struct BodyParameters<2>;
  template struct BodyParameters<3>;
} // namespace sable::mpm
