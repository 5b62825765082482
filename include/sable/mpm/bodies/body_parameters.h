#ifndef sable_mpm_bodies_body_parameters_h
#define sable_mpm_bodies_body_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <sable/mpm/bodies/body_mesh.h>
#include <sable/mpm/bodies/point_file.h>
#include <sable/mpm/materials/material_parameters.h>

#include <string>
#include <utility>

namespace sable::mpm
{
  using namespace dealii;

  /// One body: its shape, seeding, material, initial motion and stress,
  /// contact group (subsection 'Body <b>').
  template <int dim>
  struct BodyParameters
  {
    enum class Shape
    {
      disk, ///< a disk in 2D, a sphere in 3D
      box,
      points, ///< material points read from 'Points file'
      mesh    ///< the cells of the volume mesh in 'Mesh file'
    };
    Shape        shape  = Shape::disk;
    /// Where a disk's or sphere's points go.
    enum class Seeding
    {
      automatic,  ///< clipped for disks and spheres, the lattice for the rest
      lattice,    ///< k^dim points per cell, at the centres of equal sub-cells
      conforming, ///< rings (2D) or shells (3D) parallel to the surface
      clipped ///< the lattice, each sub-cell the surface cuts clipped to it
    };
    Seeding      seeding = Seeding::automatic;
    /// The seeding the body's points get: 'automatic' resolved by the shape
    Seeding
    seeding_used() const
    {
      if (seeding != Seeding::automatic)
        return seeding;
      return shape == Shape::disk ? Seeding::clipped : Seeding::lattice;
    }
    Point<dim>   center = {};
    double       radius = 0.;
    Point<dim>   lower_corner = {};
    Point<dim>   upper_corner = {};
    unsigned int particles_per_direction = 2;
    /// Shape = points: the file (as given, and as found) and its points
    std::string     points_file;
    PointCloud<dim> cloud;
    /// Shape = mesh: the file as given, the map x -> scale x + translation
    /// of its vertices, and the mesh
    std::string    mesh_file;
    double         mesh_scale = 1.;
    Tensor<1, dim> mesh_translation;
    BodyMesh<dim>  mesh;

    MaterialParameters material;

    Tensor<1, dim> velocity = {};
    /// A rigid driver: every point moves with prescribed_velocity from
    /// prescribed_start_time on (at rest before), whatever the forces; the
    /// other bodies meet it through contact as a body of unbounded mass.
    bool           prescribed = false;
    Tensor<1, dim> prescribed_velocity = {};
    double         prescribed_start_time = 0.;
    /// Rigid rotation about the body centre (2D uses only the z component).
    Tensor<1, 3> angular_velocity = {};
    /// Initialise σ = −p I with ∇p = ρ g, p = 0 at the body's top.
    bool lithostatic_stress = false;
    /// Contact group: friction coefficients are set per pair of groups.
    unsigned int group = 0;
    /// Refine around this body's surface (Mesh refinement criterion
    /// 'body surface').
    bool refine_surface = true;
    /// A grain held by a face of the grid ('Bodies file/Lower x wall
    /// velocity', ...): the body may reach beyond the grid, where no
    /// material point is seeded; its centre lies inside.
    bool clipped_by_grid = false;
    /// Whether statistics.csv has the body's columns (position, velocity,
    /// spin): the bodies of 'Body k' subsections, not those of a bodies file.
    bool statistics_columns = true;
    /// Where the body was described, for messages ("Body 3/" when empty,
    /// else e.g. "pack.csv, line 12: ").
    std::string origin;

    /// The prefix of the body's entries in messages: origin, or
    /// "Body <b>/" for the body of index @p b.
    std::string
    name(const unsigned int b) const
    {
      return origin.empty() ? "Body " + std::to_string(b) + "/" : origin;
    }

    /// The body itself in messages: "Body <b>" or "pack.csv, line 12".
    std::string
    label(const unsigned int b) const
    {
      const std::string prefix = name(b);
      return prefix.substr(0, prefix.find_last_not_of(":/ ") + 1);
    }

    /// Shape = points: read the points file, found relative to @p folder
    /// (that of the parameter file) unless its path is absolute.
    void
    read_points(const std::string &folder);

    /// Shape = mesh: read the mesh file, found relative to @p folder unless
    /// its path is absolute. A missing or unreadable file, a mesh of
    /// another dimension or a scale <= 0 is an InputError naming
    /// @p path ("Body 0/") and the entry.
    void
    read_mesh(const std::string &folder, const std::string &path);

    /// Centre of rotation of 'Angular velocity': the disk's or box's
    /// centre, the volume-weighted centroid of points or of a mesh.
    Point<dim>
    centre() const;

    /// Axis-aligned bounding box of the shape.
    std::pair<Point<dim>, Point<dim>>
    bounding_box() const;
    /// Whether @p x is inside a disk, box or mesh (never for points).
    bool
    contains(const Point<dim> &x) const;
    /// How deep @p x lies inside a disk, box or mesh: its distance to the
    /// surface, 0 outside (and always for points).
    double
    depth_inside(const Point<dim> &x) const;
    /// The flat face nearest @p x (a box's, or a mesh's boundary facet):
    /// its outward unit normal and the depth of @p x below it; a zero
    /// normal if @p x lies deeper than @p depth_limit, if a face of another
    /// direction is within @p edge_margin (near an edge or a corner), or if
    /// the shape has no flat faces (disk, sphere, points).
    FaceBelow<dim>
    face_below(const Point<dim> &x, const double depth_limit, const double edge_margin) const;

    /// A disk's or sphere's vector from @p x to the nearest point of its
    /// surface, if @p x lies inside within @p depth_limit of it; zero
    /// otherwise and for every other shape.
    Tensor<1, dim>
    to_round_surface(const Point<dim> &x, const double depth_limit) const;

    /// The point of the shape lowest in the potential −g·x (where p = 0).
    Point<dim>
    top_point(const Tensor<1, dim> &gravity) const;

    /// Declare a body's entries in the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read the current subsection; @p path ("Body 0/") prefixes entries
    /// in messages.
    void
    parse_parameters(ParameterHandler &prm, const std::string &path);

    /// The entries a body shares with the bodies of a bodies file (seeding,
    /// material, initial motion, contact group, refinement), without those
    /// of the shape and of a prescribed velocity.
    static void
    declare_template_parameters(ParameterHandler &prm);

    /// Read the entries of declare_template_parameters().
    void
    parse_template_parameters(ParameterHandler &prm, const std::string &path);

    /// Throw InputError (naming path + entry) for invalid values: the one
    /// check of a body, for scene files and add_body() alike.
    void
    check(const std::string &path) const;
  };
} // namespace sable::mpm

#endif
