#ifndef sable_mpm_contact_contact_parameters_h
#define sable_mpm_contact_contact_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// Multi-body contact (SPEC Part A steps 3-7; subsection 'Contact').
  struct ContactParameters
  {
    enum class Model
    {
      none,             ///< one velocity field: no-slip, no separation
      bardenhagen_2000, ///< act while bodies approach
      bardenhagen_2001  ///< ... or while the normal traction is compressive
    };
    Model model = Model::none;
    /// How a node's body normals are made collinear (two-body nodes).
    enum class Normals
    {
      /// the bodies' mass-gradient directions weighted by their nodal
      /// masses, n = (m1 n1 - m2 n2)/|m1 n1 - m2 n2|
      mass_weighted,
      /// equal weights, n = (n1 - n2)/|n1 - n2| (the papers)
      average,
      /// the normal of the body with the larger mass at the node, whose
      /// surface the node resolves better (a flat plane's, not the corner
      /// of a block resting on it); where the two bodies' directions are
      /// less than 120 degrees apart (faces ending edge to edge, as at the
      /// flush ends of stacked blocks) the average
      largest_mass,
      /// for each pair of bodies, the normal of the one with the flatter
      /// surface at every node where they face each other: one surface for
      /// the whole interface (a box's or a mesh body's before a disk's, the
      /// larger disk's before the smaller one's; between equally flat
      /// ones the larger body's by volume, then the one listed first);
      /// where their directions are less than 120 degrees apart the
      /// average, as with 'largest mass'
      flatter_body,
      /// the normal of the plane that best separates the two bodies'
      /// points near the node (logistic regression, Nairn, Hammerquist &
      /// Smith 2020): geometry, not mass, decides
      logistic_regression,
      /// 'largest mass' where the two bodies' directions face each other
      /// (faces in contact, round bodies); the fitted plane's normal where
      /// they do not (corners and ends within one node's reach, as where
      /// a block passes the front end of the block it slides on), and
      /// there contact acts only while the bodies approach
      fitted_at_edges
    };
    Normals normals = Normals::flatter_body;
    /// With 'flatter body', the normal where only round bodies (disks,
    /// spheres) meet at a node.
    enum class RoundPairNormals
    {
      /// the plane fitted between their points, as 'logistic regression'
      fitted_plane,
      /// the line between their centres of mass, the normal of rigid
      /// disks in contact (not on periodic grids, where a centre may lie
      /// across a seam: there the fitted plane)
      line_of_centres
    };
    RoundPairNormals round_pair_normals = RoundPairNormals::fitted_plane;
    /// What a round body (disk, sphere) receives of the moment that the
    /// contact's and the walls' corrections exert about its centre.
    enum class RoundBodyMoments
    {
      /// what the transfer to its points delivers: each node's correction
      /// taken about the points' centroid near the node
      transferred,
      /// the moment taken at the nodes: what the transfer loses is given
      /// to the body as a rigid rotation (RoundBodyMoments; not on
      /// periodic grids)
      kept
    };
    RoundBodyMoments round_body_moments = RoundBodyMoments::transferred;
    /// Which two-body nodes may act: every node the bodies share (the
    /// papers), or only where the bodies' surfaces have met, judged from
    /// the distance between their mass centroids at the node along the
    /// normal (in the spirit of NairnMPM's position check): acts if
    /// d - dt * approach <= (c_a + c_b) h_n, with c the centroid offset of
    /// a body whose points fill the cells up to its surface.
    enum class Detection
    {
      shared_nodes,
      surface_position
    };
    Detection detection = Detection::surface_position;
    /// Where a disk's or sphere's surface is taken to lie at a node where
    /// it meets a flat face, with surface-position detection.
    enum class RoundSurfaces
    {
      /// where its points' vectors to its circle end (the face's is found
      /// so too): contact at touch at any registration with the grid
      located,
      /// the centroid's offset, the node taken to lie on the surface
      centroid_offset,
      /// located, and where a disk touches one face over less than a cell,
      /// it meets the face at one point, its lowest along the face's
      /// normal, whose impulse the nodes around it share (2D; spheres are
      /// located)
      contact_point
    };
    RoundSurfaces round_surfaces = RoundSurfaces::contact_point;
    /// Contact at nodes that three or more bodies share.
    enum class MultiBodyNodes
    {
      /// each pair of bodies in turn, as at a two-body node, with equal and
      /// opposite impulses: momentum is kept to round-off
      pairwise,
      /// each body against the centre of mass of all, with its own normal
      /// turned away from the others' (momentum not exactly kept)
      centre_of_mass
    };
    MultiBodyNodes multi_body_nodes = MultiBodyNodes::pairwise;
    /// Coulomb coefficient for pairs of groups not listed below;
    /// infinity means sticking contact.
    double                                                  friction = 0.;
    std::map<std::pair<unsigned int, unsigned int>, double> group_friction;
    /// Impulse scaling factor gamma in [0.5, 1]; 0 switches scaling off.
    double impulse_scaling = 0.5;
    /// Apply contact to the velocities after the momentum update, and to
    /// the velocities the strain update uses (MUSL's remapped velocities).
    bool on_momentum_update = true;
    bool on_strain_update   = true;
    /// Pairs of bodies whose contact force goes to statistics.csv.
    std::vector<std::pair<unsigned int, unsigned int>> reported_pairs;

    double
    friction_between(const unsigned int group_a, const unsigned int group_b) const
    {
      const auto it =
        group_friction.find({std::min(group_a, group_b), std::max(group_a, group_b)});
      return it == group_friction.end() ? friction : it->second;
    }

    /// Whether some pair of groups may have a finite, positive friction
    /// coefficient (the default one or a group pair's): only there can the
    /// 2001 rule's friction cap act.
    bool
    any_finite_friction() const
    {
      const auto finite_positive = [](const double mu) { return mu > 0 && std::isfinite(mu); };
      bool any = finite_positive(friction);
      for (const auto &[groups, mu] : group_friction)
        any = any || finite_positive(mu);
      return any;
    }

    /// Declare the entries of the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read the current subsection of a scene with @p n_bodies bodies
    /// (Reported pairs name bodies); values are checked as they are read.
    void
    parse_parameters(const ParameterHandler &prm, const unsigned int n_bodies);
  };
} // namespace sable::mpm

#endif
