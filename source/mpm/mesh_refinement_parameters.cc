#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/base/named_choice.h>
#include <sable/mpm/mesh_refinement_parameters.h>
#include <sable/mpm/parameter_tools.h>

#include <sstream>

namespace sable::mpm
{
  namespace
  {
    template <int dim>
    const NamedChoice<typename MeshRefinementParameters<dim>::Criterion> &
    criteria_names()
    {
      using Criterion = typename MeshRefinementParameters<dim>::Criterion;
      static const NamedChoice<Criterion> choice{{"body surface", Criterion::body_surface},
                                                 {"contact", Criterion::contact},
                                                 {"particle count", Criterion::particle_count},
                                                 {"region", Criterion::region}};
      return choice;
    }
  } // namespace

  template <int dim>
  void
  MeshRefinementParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    const auto &      names = criteria_names<dim>();
    const std::string zero  = zero_vector(dim);
    prm.declare_entry("Criteria",
                      "",
                      Patterns::MultipleSelection(names.names()),
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
                      "refine to it before the bodies are seeded; later a "
                      "cell with points is refined only while its children "
                      "keep at least one of them per direction (the "
                      "spacing they were seeded at).");
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
  }

  template <int dim>
  void
  MeshRefinementParameters<dim>::parse_parameters(const ParameterHandler &prm)
  {
    const auto &names = criteria_names<dim>();
    MeshRefinementParameters<dim> &r = *this;
    for (const std::string &name : Utilities::split_string_list(prm.get("Criteria")))
      r.criteria.push_back(names.value(name));
    r.maximum_level = prm.get_integer("Maximum level");
    r.minimum_level = prm.get_integer("Minimum level");
    r.interval      = prm.get_integer("Refinement interval");
    r.maximum_particles_per_cell = prm.get_integer("Maximum particles per cell");
    r.region_lower_corner =
      Point<dim>(read_vector<dim>(prm, "Region lower corner", "Mesh refinement/"));
    r.region_upper_corner =
      Point<dim>(read_vector<dim>(prm, "Region upper corner", "Mesh refinement/"));
  }

  template <int dim>
  void
  MeshRefinementParameters<dim>::check() const
  {
    const MeshRefinementParameters<dim> &r = *this;
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

  template struct MeshRefinementParameters<2>;
  template struct MeshRefinementParameters<3>;
} // namespace sable::mpm
