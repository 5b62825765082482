#ifndef sable_mpm_boundaries_boundary_parameters_h
#define sable_mpm_boundaries_boundary_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <map>

namespace sable::mpm
{
  using namespace dealii;

  enum class BoundaryType
  {
    free,
    fixed,
    slip,
    friction,
    moving
  };

  /// The condition on the grid faces of one boundary id (subsection
  /// 'Boundary conditions').
  /// When a friction wall acts at a wall node (Boundary conditions/Friction
  /// wall contact).
  enum class WallContact
  {
    approach,        ///< whenever the node approaches the wall
    material,        ///< and the nearest point's edge reaches the wall in the step
    surface_position ///< and the body's surface, from the node's mass centroid, does
  };

  template <int dim>
  struct BoundaryParameters
  {
    using Map = std::map<types::boundary_id, BoundaryParameters<dim>>;

    BoundaryType   type     = BoundaryType::free;
    double         friction = 0.;
    Tensor<1, dim> velocity = {};
    /// Friction walls only: where the wall acts (Boundary conditions/
    /// Friction wall contact).
    WallContact wall_contact = WallContact::surface_position;

    /// Declare the entries of the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The conditions per boundary id the current subsection gives.
    static Map
    parse_parameters(const ParameterHandler &prm);

    /// Throw InputError for invalid values (every friction boundary has a
    /// coefficient >= 0).
    static void
    check(const Map &boundaries);
  };
} // namespace sable::mpm

#endif
