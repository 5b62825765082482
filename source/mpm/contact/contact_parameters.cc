#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/base/named_choice.h>
#include <sable/mpm/contact/contact_parameters.h>
#include <sable/mpm/parameter_tools.h>

namespace sable::mpm
{
  namespace
  {
    const NamedChoice<ContactParameters::Model> models{
      {"none", ContactParameters::Model::none},
      {"bardenhagen 2000", ContactParameters::Model::bardenhagen_2000},
      {"bardenhagen 2001", ContactParameters::Model::bardenhagen_2001}};

    const NamedChoice<ContactParameters::Normals> normal_methods{
      {"mass weighted", ContactParameters::Normals::mass_weighted},
      {"average", ContactParameters::Normals::average},
      {"largest mass", ContactParameters::Normals::largest_mass},
      {"flatter body", ContactParameters::Normals::flatter_body},
      {"logistic regression", ContactParameters::Normals::logistic_regression},
      {"fitted at edges", ContactParameters::Normals::fitted_at_edges}};
    const NamedChoice<ContactParameters::RoundPairNormals> round_pair_normal_choices{
      {"fitted plane", ContactParameters::RoundPairNormals::fitted_plane},
      {"line of centres", ContactParameters::RoundPairNormals::line_of_centres}};
    const NamedChoice<ContactParameters::RoundBodyMoments> round_body_moment_choices{
      {"transferred", ContactParameters::RoundBodyMoments::transferred},
      {"kept", ContactParameters::RoundBodyMoments::kept}};
    const NamedChoice<ContactParameters::Detection> detections{
      {"shared nodes", ContactParameters::Detection::shared_nodes},
      {"surface position", ContactParameters::Detection::surface_position}};
    const NamedChoice<ContactParameters::RoundSurfaces> round_surface_choices{
      {"contact point", ContactParameters::RoundSurfaces::contact_point},
      {"located", ContactParameters::RoundSurfaces::located},
      {"centroid offset", ContactParameters::RoundSurfaces::centroid_offset}};
    const NamedChoice<ContactParameters::MultiBodyNodes> multi_body_methods{
      {"pairwise", ContactParameters::MultiBodyNodes::pairwise},
      {"centre of mass", ContactParameters::MultiBodyNodes::centre_of_mass}};
  } // namespace

  void
  ContactParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "none",
                      models.pattern(),
                      "Contact between bodies. none: all bodies share one "
                      "velocity field (no slip, no separation, no cost). "
                      "bardenhagen 2000: a velocity field per body, Coulomb "
                      "friction while bodies approach. bardenhagen 2001: also "
                      "while the normal traction is compressive.");
    prm.declare_entry("Normals",
                      "flatter body",
                      normal_methods.pattern(),
                      "How the bodies' normals at a two-body node are made "
                      "collinear (so contact conserves momentum). 'flatter "
                      "body' (default) takes, for each pair of bodies, the "
                      "normal of the one with the flatter surface at every "
                      "node where they face each other: one surface for the "
                      "whole interface. A box or a mesh body is flatter than "
                      "a disk (sphere), a larger disk than a smaller one; of "
                      "two equally flat bodies the larger by volume, then "
                      "the one listed first (a plane body under a block). "
                      "A box's or a mesh body's normal there is its face's: "
                      "its points within two cells of a face (away from "
                      "edges and corners) carry the face's outward normal, "
                      "turned with the body's rotation, so that a face "
                      "inclined to the grid, a staircase of points, acts as "
                      "a plane; and where one body's points at a node lie "
                      "under one face and the other's do not (a corner), "
                      "the face's normal is taken. Where only round "
                      "bodies (disks, spheres) meet at a node, the normal "
                      "is as 'Round pair normals' says: their mass "
                      "gradients tilt from node to node at a coarse "
                      "contact, and the bodies slid into each other under "
                      "load (doc/validation.md, \"Energy balance of a "
                      "settling pile\"). "
                      "'largest mass' "
                      "takes the normal of the body with the larger mass at "
                      "each node, which may jump between the two surfaces "
                      "across an interface and take a block's corner or a "
                      "lattice disk's staircase edge (a block sliding on a "
                      "plane body up to 1.1% slow, a disk 4.6%; see "
                      "doc/validation.md). With both, where the two bodies' "
                      "directions are less than 120 degrees apart (faces "
                      "ending edge to edge, as at the flush ends of stacked "
                      "blocks) the normal is their difference, as 'average' "
                      "takes it. 'mass "
                      "weighted' weights each body's unit mass-gradient "
                      "direction by its nodal mass; 'average' is the papers' "
                      "n = (n1 - n2)/|n1 - n2| of the unit directions. "
                      "'logistic regression' fits the plane that best "
                      "separates the two bodies' points around the node "
                      "(Nairn, Hammerquist & Smith 2020; at nodes of three "
                      "or more bodies each body against the others) and "
                      "takes its normal: slower, and independent of the "
                      "bodies' masses at the node. 'fitted at edges' is "
                      "'largest mass' where the two bodies' directions face "
                      "each other (more than about 154 degrees apart: faces "
                      "in contact, round bodies) and 'logistic regression' "
                      "where they do not (corners and ends within one node's "
                      "reach, as where a block passes the front end of the "
                      "block it slides on; choose it for blocks and other "
                      "bodies with corners); at such nodes contact acts only "
                      "while the bodies approach, without the 2001 rule's "
                      "release by traction.");
    prm.declare_entry("Detection",
                      "surface position",
                      detections.pattern(),
                      "Where two bodies are in contact. 'shared nodes': at "
                      "every node both bodies' points reach (the papers; "
                      "contact may act up to about a cell before the point "
                      "clouds touch). 'surface position': only where the "
                      "distance between the bodies' mass centroids at the "
                      "node, along the normal, shows that their surfaces "
                      "meet within the step, or where their volumes there "
                      "overfill the node's support (see doc/mpm.md).");
    prm.declare_entry("Round body moments",
                      "transferred",
                      round_body_moment_choices.pattern(),
                      "What a round body (disk, sphere) receives of the "
                      "moment that the contact's and the walls' corrections "
                      "exert about its centre of mass. 'transferred' (the "
                      "default): what the transfer to its points delivers; "
                      "a correction at a node reaches the points in "
                      "proportion to their weights, so its moment is taken "
                      "about their centroid near the node, a fraction of a "
                      "cell inside the body, and a disk sliding on a body "
                      "spins too slowly (by 4-7% at 16 and 19-24% at 8 "
                      "cells per diameter). 'kept': what the transfer loses is "
                      "given to the body as a rigid rotation about its "
                      "centre of mass, so it receives the moment taken at "
                      "the nodes (doc/validation.md, \"Round body "
                      "moments\"). Not on periodic grids.");
    prm.declare_entry("Round pair normals",
                      "fitted plane",
                      round_pair_normal_choices.pattern(),
                      "With 'Normals = flatter body': the normal where only "
                      "round bodies (disks, spheres) meet at a node. "
                      "'fitted plane' (the default): the plane fitted "
                      "between their points there, as 'logistic "
                      "regression' takes it. 'line of centres': the line "
                      "between their centres of mass, the normal of rigid "
                      "disks in contact, the same at every node of the "
                      "pair; no fits, so a pile of disks steps in 0.69 "
                      "times the time, but its grains reach further into "
                      "each other in some piles (0.31 point spacings "
                      "against none in prm/gallery_pile.prm under pure "
                      "FLIP; doc/validation.md, \"Energy balance of a "
                      "settling pile\"). On a periodic grid, where a "
                      "centre may lie across a seam, the fitted plane.");
    prm.declare_entry("Round body surfaces",
                      "contact point",
                      round_surface_choices.pattern(),
                      "With 'surface position': where a disk's or sphere's "
                      "surface lies where it meets a box's or mesh body's "
                      "face. 'located': at each node, where its points' "
                      "vectors to its surface end, as the face's: contact at "
                      "touch at any registration of the face with the grid, "
                      "but the node nearest the round body's lowest point "
                      "carries its weight alone, a pivot off the contact "
                      "point (a disk set at rest on a body creeps, by up to "
                      "a sixth of a cell in 0.5 s). 'contact point' (the "
                      "default): located, and where a disk touches the face "
                      "over less than a cell, the nodes around its lowest "
                      "point share one impulse whose line passes through "
                      "that point: rests within 0.5% of a cell and rolls "
                      "within 3% in all 23 cases tried (2D; spheres in 3D "
                      "are located). 'centroid offset': from its points' "
                      "centroid at each node, taken to lie on the surface: "
                      "rolls up to 9% behind with the face between grid "
                      "lines (see doc/mpm.md). Between two round bodies the "
                      "centroid offset is used either way.");
    prm.declare_entry("Nodes with three or more bodies",
                      "pairwise",
                      multi_body_methods.pattern(),
                      "Contact at a node that three or more bodies share. "
                      "'pairwise': each pair of bodies in turn (in the order "
                      "of their numbers), as at a two-body node, with equal "
                      "and opposite impulses, so momentum is kept to round-off. "
                      "'centre of mass': each body against the centre of mass "
                      "of all, with its own normal turned away from the "
                      "others' (earlier versions; momentum is not exactly kept).");
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
                      "Body pairs whose total contact force, and its "
                      "moments about the two bodies' centres of mass, go to "
                      "statistics.csv, e.g. '0-1, 1-2'; 'all' (every pair "
                      "when there are at most 4 bodies) or 'none'.");
  }

  void
  ContactParameters::parse_parameters(const ParameterHandler &prm, const unsigned int n_bodies)
  {
    ContactParameters &c = *this;
    c.model                 = models.value(prm.get("Model"));
    c.normals               = normal_methods.value(prm.get("Normals"));
    c.detection             = detections.value(prm.get("Detection"));
    c.round_pair_normals = round_pair_normal_choices.value(prm.get("Round pair normals"));
    c.round_surfaces        = round_surface_choices.value(prm.get("Round body surfaces"));
    c.round_body_moments = round_body_moment_choices.value(prm.get("Round body moments"));
    c.multi_body_nodes = multi_body_methods.value(prm.get("Nodes with three or more bodies"));
    c.friction = parse_friction(prm.get("Friction coefficient"), "Contact/Friction coefficient");
    for (const auto &[pair, value] : split_map(prm.get("Group friction")))
      {
        const auto groups = Utilities::split_string_list(pair, '-');
        check_input(groups.size() == 2,
                    "Contact/Group friction", pair + ": " + value,
                    "entries '<group>-<group>: <coefficient or stick>'");
        const unsigned int a = Utilities::string_to_int(groups[0]);
        const unsigned int b = Utilities::string_to_int(groups[1]);
        check_input(c.group_friction.count({std::min(a, b), std::max(a, b)}) == 0,
                    "Contact/Group friction", pair + ": " + value,
                    "each pair of groups once (" + std::to_string(std::min(a, b)) + "-" +
                      std::to_string(std::max(a, b)) + " is given twice)");
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
} // namespace sable::mpm
