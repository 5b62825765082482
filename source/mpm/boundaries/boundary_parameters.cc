#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/base/named_choice.h>
#include <sable/mpm/boundaries/boundary_parameters.h>
#include <sable/mpm/parameter_tools.h>

#include <set>

namespace sable::mpm
{
  namespace
  {
    const NamedChoice<BoundaryType> boundary_types{{"free", BoundaryType::free},
                                                   {"fixed", BoundaryType::fixed},
                                                   {"slip", BoundaryType::slip},
                                                   {"friction", BoundaryType::friction},
                                                   {"moving", BoundaryType::moving}};

    const NamedChoice<WallContact> wall_contacts{
      {"approach", WallContact::approach},
      {"material", WallContact::material},
      {"surface position", WallContact::surface_position}};
  } // namespace

  template <int dim>
  void
  BoundaryParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Types",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255), boundary_types.pattern()),
                      "Condition per boundary id, e.g. '0: slip, 2: "
                      "friction'. Ids not listed are free; an id no face of "
                      "the grid has (Grid/Boundary ids) is refused.");
    prm.declare_entry("Friction coefficients",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255), Patterns::Double()),
                      "Coulomb coefficient per friction boundary, e.g. "
                      "'2: 0.3'.");
    prm.declare_entry("Friction wall contact",
                      "surface position",
                      wall_contacts.pattern(),
                      "When a friction wall acts at a wall node. 'surface "
                      "position' (default): only where the body's surface, "
                      "estimated from the node's mass centroid and the "
                      "spacing its points were seeded at (on an adapted "
                      "grid a cell may hold points seeded on a coarser "
                      "one), reaches the wall within the step. A rolling disk then touches "
                      "the wall at about one node, as a rigid disk at one "
                      "point; with the criteria below a node a cell ahead "
                      "of the contact is held too, which locks the rotation "
                      "until the disk climbs over it (A1 at 16 cells per "
                      "diameter lagged 9.6%, 2.0% with it; see "
                      "doc/validation.md). approach: "
                      "whenever the node's velocity approaches the wall "
                      "(SPEC step 6 with the wall as the other body). "
                      "material: only if, in addition, the material points "
                      "around the node reach the wall within the step "
                      "(the nearest point's edge, x_p -+ l_p/2 with l_p^dim "
                      "its current volume, at most dt times the node's "
                      "approach speed from the wall). A node up to a cell "
                      "away from the body's surface, whose velocity the "
                      "surface points' stress dominates, then carries no "
                      "contact force; the staircase of a lattice-seeded "
                      "round body's points still reaches the wall a cell "
                      "ahead of its contact.");
    prm.declare_entry("Wall velocities",
                      "",
                      Patterns::Map(Patterns::Integer(0, 255),
                                    Patterns::List(Patterns::Double(), dim, dim, ";")),
                      "Velocity of each moving boundary (every one needs "
                      "one), components separated by ';', e.g. '3: 0.1; 0'.");
  }

  template <int dim>
  typename BoundaryParameters<dim>::Map
  BoundaryParameters<dim>::parse_parameters(const ParameterHandler &prm)
  {
    Map boundaries;
    for (const auto &[id, type] : split_map(prm.get("Types")))
      {
        BoundaryParameters<dim> &boundary = boundaries[std::stoi(id)];
        boundary.type                     = boundary_types.value(type);
        // a friction boundary without a coefficient is reported by check()
        boundary.friction = boundary.type == BoundaryType::friction ? -1. : 0.;
      }
    for (const auto &[id, value] : split_map(prm.get("Friction coefficients")))
      {
        const auto it = boundaries.find(std::stoi(id));
        check_input(it != boundaries.end() && it->second.type == BoundaryType::friction,
                    "Boundary conditions/Friction coefficients",
                    id + ": " + value,
                    "coefficients only for boundary ids whose type is friction");
        it->second.friction = Utilities::string_to_double(value);
      }
    const WallContact wall_contact = wall_contacts.value(prm.get("Friction wall contact"));
    for (auto &[id, boundary] : boundaries)
      boundary.wall_contact = wall_contact;
    std::set<types::boundary_id> moving_with_velocity;
    for (const auto &[id, value] : split_map(prm.get("Wall velocities")))
      {
        const auto it = boundaries.find(std::stoi(id));
        check_input(it != boundaries.end() && it->second.type == BoundaryType::moving,
                    "Boundary conditions/Wall velocities",
                    id + ": " + value,
                    "velocities only for boundary ids whose type is moving");
        const std::vector<double> v =
          Utilities::string_to_double(Utilities::split_string_list(value, ';'));
        for (unsigned int d = 0; d < dim; ++d)
          it->second.velocity[d] = v[d];
        moving_with_velocity.insert(it->first);
      }
    // a moving wall without a velocity would hold the nodes as a fixed one
    for (const auto &[id, boundary] : boundaries)
      check_input(boundary.type != BoundaryType::moving || moving_with_velocity.count(id) > 0,
                  "Boundary conditions/Wall velocities",
                  prm.get("Wall velocities"),
                  "a velocity for each boundary id whose type is moving (id " + std::to_string(id) +
                    " has none)");
    return boundaries;
  }

  template <int dim>
  void
  BoundaryParameters<dim>::check(const Map &boundaries)
  {
    for (const auto &[id, boundary] : boundaries)
      if (boundary.type == BoundaryType::friction)
        check_input(boundary.friction >= 0,
                    "Boundary conditions/Friction coefficients",
                    std::to_string(id) + ": " + std::to_string(boundary.friction),
                    "a coefficient >= 0 for each friction boundary, "
                    "e.g. '" + std::to_string(id) + ": 0.3'");
  }

  template struct BoundaryParameters<2>;
  template struct BoundaryParameters<3>;
} // namespace sable::mpm
