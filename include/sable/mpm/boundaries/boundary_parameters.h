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
  template <int dim>
  struct BoundaryParameters
  {
    using Map = std::map<types::boundary_id, BoundaryParameters<dim>>;

    BoundaryType   type     = BoundaryType::free;
    double         friction = 0.;
    Tensor<1, dim> velocity = {};
    /// Friction walls only: act only where the material points reach the wall
    /// within the step (Boundary conditions/Friction wall contact =
    /// material), not wherever a node with mass approaches it.
    bool material_contact = true;

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
