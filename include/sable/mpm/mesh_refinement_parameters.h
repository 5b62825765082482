#ifndef sable_mpm_mesh_refinement_parameters_h
#define sable_mpm_mesh_refinement_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Local refinement of the background grid between steps (Mesh
   * refinement subsection). Levels count from the grid the scene (or the
   * embedding program) starts with.
   */
  template <int dim>
  struct MeshRefinementParameters
  {
    enum class Criterion
    {
      body_surface,   ///< cells at a body's surface or between bodies
      contact,        ///< cells where bodies meet each other or a friction wall
      particle_count, ///< cells holding more than a number of points
      region          ///< cells inside a box
    };
    /// Empty: the grid never changes.
    std::vector<Criterion> criteria;
    /// Finest level a criterion refines to.
    unsigned int maximum_level = 0;
    /// Coarsest level anywhere: the starting grid is refined to it.
    unsigned int minimum_level = 0;
    /// Steps between mesh adaptations; 0: whenever a point may have moved
    /// half of the smallest cell since the last one.
    unsigned int interval = 0;
    /// particle count criterion
    unsigned int maximum_particles_per_cell = 16;
    /// region criterion
    Point<dim> region_lower_corner = {};
    Point<dim> region_upper_corner = {};

    bool
    enabled() const
    {
      return !criteria.empty();
    }

    bool
    uses(const Criterion criterion) const
    {
      return std::find(criteria.begin(), criteria.end(), criterion) != criteria.end();
    }

    /// Declare the entries of the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read the current subsection (values are checked by check()).
    void
    parse_parameters(const ParameterHandler &prm);

    /// Throw InputError for invalid values.
    void
    check() const;
  };
} // namespace sable::mpm

#endif
