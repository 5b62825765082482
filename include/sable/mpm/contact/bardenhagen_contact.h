#ifndef sable_mpm_contact_bardenhagen_contact_h
#define sable_mpm_contact_bardenhagen_contact_h

#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/contact/pair_table.h>
#include <sable/mpm/parameters.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace sable::mpm
{
  /**
   * Multi-velocity-field frictional contact of Bardenhagen et al. (2000,
   * 2001), SPEC Part A steps 3-7, applied node by node to the per-body
   * velocities at contact nodes (BodyFields::Record::new_velocity):
   *
   * - normals from the mass gradients; at a two-body node one common normal
   *   so that contact conserves momentum exactly: the flatter body's
   *   (default), the heavier one's at the node, or
   *   n = (w1 n1 - w2 n2)/|w1 n1 - w2 n2| with w the nodal masses or 1
   *   (papers), or the plane fitted between the bodies' points
   *   ('Contact/Normals');
   *   at nodes with three or more bodies each pair of bodies in turn as at
   *   a two-body node, with equal and opposite impulses (momentum kept to
   *   round-off), or ('centre of mass') each body with its own normal, made
   *   to point away from the mass-weighted mean of the others', against the
   *   all-body centre of mass (a momentum error, reported by the dense-pack
   *   benchmark);
   * - release: 2000 acts while the bodies approach; 2001 also while the
   *   mass-weighted normal traction at the node is compressive;
   * - Coulomb friction with mu' = min(mu, |dv_t|/|dv_n|), mu = infinity
   *   sticks; with the 2001 release, which may hold separating nodes
   *   together with pulling normal impulses, the friction of each pair of
   *   bodies is also capped by mu times the pair's net normal impulse over
   *   all its nodes, so that the interface obeys Coulomb as a whole: one
   *   pass corrects every node uncapped and measures both, then the nodes
   *   where a capped pair's friction acted are corrected again from their
   *   saved velocities;
   * - impulse scaling (paper 002 eq. 22 with the erratum: the factor is
   *   min(gamma/(rate dt), 1)), one factor per node so momentum is kept.
   */
  template <int dim>
  class BardenhagenContact
  {
  public:
    /// What apply() does with each pair's contact geometry at a node (the
    /// common normal, whether the pair's normal traction is compressive,
    /// the gap between the surfaces), which depends on the records' masses,
    /// mass gradients, mass positions and stresses but not on their
    /// velocities. MUSL's remap pass scatters the same masses again and
    /// keeps the rest, so its contact pass can reuse the geometry of the
    /// momentum update's: the same numbers without computing them again.
    enum class Geometry
    {
      /// compute it where needed
      compute,
      /// compute it and keep it for a later apply() on the same records
      keep,
      /// take what the last apply() with keep computed, computing only
      /// what it did not need
      reuse
    };

    BardenhagenContact(const ContactParameters &        parameters,
                       const std::vector<unsigned int> &body_groups);

    /**
     * Apply contact at every contact node. @p spacing gives the cell size
     * per direction at each node (for the impulse scaling). With
     * @p record_forces (the pass after the momentum update, whose changes
     * reach the particles) frictional heat, pair forces and the output
     * fields of the records are accumulated, for nodes below
     * @p n_owned_nodes only, so that sums over ranks count each node once.
     * With @p node_positions also the reported pairs' moments. With
     * @p fitted_normals ('Normals = logistic regression' or 'fitted at
     * edges'), per record
     * (BodyFields::index_of()) the unit normal out of its body of the plane
     * fitted between its points and the other bodies' at the node, zero
     * where none could be fitted. With @p geometry reuse, the records'
     * masses, mass gradients, mass positions, spacings, stresses and fitted
     * normals must be those of the last call with keep, bit for bit.
     */
    void
    apply(BodyFields<dim> &                  fields,
          const std::vector<Tensor<1, dim>> &spacing,
          const double                       dt,
          const unsigned int                 n_owned_nodes,
          const bool                         record_forces,
          const MPI_Comm                     communicator   = MPI_COMM_SELF,
          const std::vector<Point<dim>> *    node_positions = nullptr,
          const std::vector<Tensor<1, dim>> *fitted_normals = nullptr,
          const Geometry                     geometry       = Geometry::compute,
          const std::vector<double> *        support_volumes = nullptr);

    /// The contact on the velocities at the start of a step (USAVG's first
    /// half): decided afresh, as in the momentum update, but nothing is
    /// kept of it: heat, sums, pair forces and the pairs' carried pull stay
    /// as they were.
    void
    apply_to_initial(BodyFields<dim> &                  fields,
                     const std::vector<Tensor<1, dim>> &spacing,
                     const double                       dt,
                     const unsigned int                 n_owned_nodes,
                     const MPI_Comm                     communicator,
                     const std::vector<Point<dim>> *    node_positions,
                     const std::vector<Tensor<1, dim>> *fitted_normals,
                     const std::vector<double> *        support_volumes = nullptr);

    /// With 'Normals = fitted at edges': whether two bodies whose unit
    /// outward directions at a node are @p normal_a and @p normal_b meet
    /// there at an edge, not face to face, and take the fitted plane's
    /// normal: the directions are less than about 154 degrees apart (faces
    /// in contact are 180 degrees apart, disks of 8 cells' radius 166 a
    /// cell off their line of centres; a block's corner on a face 135, the
    /// corners of two blocks whose front ends are flush 145), or one is
    /// missing.
    static bool
    meet_at_edge(const Tensor<1, dim> &normal_a, const Tensor<1, dim> &normal_b)
    {
      return normal_a * normal_b > -0.9;
    }

    /// Per body, the centre of its mass this step; where two round bodies
    /// (finite surface radius, set_body_shapes()) meet, their contact
    /// normal is then the line between their centres, as for rigid disks
    /// and spheres. An empty list (the default) leaves their normal to
    /// 'Contact/Normals'.
    void
    set_body_centres(const std::vector<Point<dim>> &centres)
    {
      body_centres = centres;
    }

    /// Per body, the radius of curvature of its surface (infinite for a
    /// box or a mesh body) and its volume, for 'Normals = flatter body';
    /// without them the normal is the larger mass's at each node. With its
    /// mass, the body's reference volume per unit mass, for the overlap
    /// test of surface_gap().
    void
    set_body_shapes(const std::vector<double> &surface_radii,
                    const std::vector<double> &volumes,
                    const std::vector<double> &masses)
    {
      body_surface_radii = surface_radii;
      body_volumes       = volumes;
      body_specific_volumes.resize(volumes.size());
      for (unsigned int b = 0; b < volumes.size(); ++b)
        body_specific_volumes[b] = masses[b] > 0 ? volumes[b] / masses[b] : 0.;
      // contact points need a round body and a flat one
      const auto round = [](const double r) { return std::isfinite(r); };
      round_and_flat_bodies = std::any_of(surface_radii.begin(), surface_radii.end(), round) &&
                              !std::all_of(surface_radii.begin(), surface_radii.end(), round);
    }

    /// Per body, the factor by which apply() sees its records' masses: a
    /// driven body's are scaled (MultiBodyContact::hold_drivers()), the
    /// sums locating its surface are not. Unset: 1 for every body.
    void
    set_body_mass_factors(const std::vector<double> &factors)
    {
      body_mass_factors = factors;
    }

    /// Per body, the directions of its faces in the reference
    /// configuration: the distinct normals its points carry
    /// (MultiBodyContact), body b's from @p start[b] to @p start[b + 1];
    /// none for a body of too many (a curved mesh), whose mixed records
    /// are corners.
    void
    set_face_directions(std::vector<Tensor<1, dim>> reference, std::vector<unsigned int> start)
    {
      reference_face_directions = std::move(reference);
      face_directions           = reference_face_directions;
      face_direction_start      = std::move(start);
    }

    /// Turn each body's face directions by its rotation @p rotations[b].
    void
    turn_face_directions(const std::vector<Tensor<2, dim>> &rotations)
    {
      for (unsigned int b = 0; b + 1 < face_direction_start.size(); ++b)
        for (unsigned int k = face_direction_start[b]; k < face_direction_start[b + 1]; ++k)
          face_directions[k] = rotations[b] * reference_face_directions[k];
    }

    /// Frictional work converted to heat so far (this rank's nodes;
    /// Statistics::contact_heat): the friction impulses times the slip the
    /// bodies show afterwards, which MultiBodyContact counts at the
    /// remapped velocities under MUSL; here, at the nodes, under USL
    /// (count_heat_at_nodes()).
    double frictional_heat = 0;

    /// While @p stick, every pair of bodies sticks (infinite friction),
    /// whatever the scene's coefficients: bodies settling on a slope
    /// (Solver/Settling friction).
    void
    stick_everywhere(const bool stick)
    {
      sticking = stick;
    }

    /// Whether apply() counts the heat from the nodal velocities the
    /// correction leaves (USL; the default), or leaves it to the remapped
    /// velocities (MUSL).
    void
    count_heat_at_nodes(const bool at_nodes)
    {
      heat_at_nodes = at_nodes;
    }
    /// The pulling impulses carried to the next step (the same on every
    /// rank), as (first body, second body, impulse) triples, for
    /// checkpoints.
    std::vector<double>
    get_pulling_impulses() const
    {
      std::vector<double> triples;
      pulling_impulse.for_each([&](const auto &pair, const double impulse) {
        triples.insert(triples.end(), {double(pair.first), double(pair.second), impulse});
      });
      return triples;
    }

    /// Restore what get_pulling_impulses() gave.
    void
    set_pulling_impulses(const std::vector<double> &triples)
    {
      pulling_impulse.clear();
      for (std::size_t i = 0; i + 2 < triples.size(); i += 3)
        pulling_impulse[{static_cast<unsigned int>(triples[i]),
                         static_cast<unsigned int>(triples[i + 1])}] = triples[i + 2];
    }

    /// Momentum the corrections did not conserve, sum over nodes of
    /// |sum_a m_a dv_a| (non-zero only at nodes with three or more bodies),
    /// and the size of the corrections, sum over nodes and bodies of
    /// |m_a dv_a|, both so far (this rank's nodes).
    double momentum_defect     = 0;
    double momentum_correction = 0;
    /// Contact force on the first body of each reported pair from the
    /// second, in the last momentum-update pass (this rank's nodes).
    std::vector<Tensor<1, dim>> pair_forces;
    /// Their moment about the origin, sum over the nodes of x_i x f_i (3
    /// components; in 2D only z), in the same pass; zero unless apply() was
    /// given the node positions.
    std::vector<Tensor<1, 3>> pair_moments;

    /// The pairs of pair_forces, (a, b) with a < b.
    const std::vector<std::pair<unsigned int, unsigned int>> &
    get_reported_pairs() const
    {
      return parameters.reported_pairs;
    }

  private:
    /// The normal impulse (compressive > 0) and the friction impulse one
    /// body of a pair receives at one node, before the pair's cap.
    struct PairImpulse
    {
      std::pair<unsigned int, unsigned int> pair;
      double                                normal;
      double                                friction;
      /// whether the node is this rank's: only those count in the pair's
      /// totals, but any node where a capped pair's friction acted is
      /// corrected again
      bool owned;
      /// the node's index within its chunk
      unsigned int node = 0;
    };

    /// The gap between two bodies' surfaces along a normal at a node
    /// (surface_gap()): they touch where separation <= touching.
    struct SurfaceGap
    {
      double separation = 0, touching = 0;
    };

    /// A pair's contact geometry at a node, kept between apply()s
    /// (Geometry). The normal is kept for every pair whose bodies both
    /// have mass there; the traction state (at nodes of three or more
    /// bodies) and the gap only once a pass has needed them.
    struct PairGeometry
    {
      /// the common unit normal out of the pair's first body (zero: the
      /// pair has no contact there)
      Tensor<1, dim> normal;
      SurfaceGap     gap;
      /// whether the 2001 rule's traction holds the pair together
      bool compressed       = false;
      bool compressed_known = false;
      bool gap_known        = false;
    };

    /// What one node adds to the running sums above, and its pair impulses.
    struct NodeSums
    {
      double                      frictional_heat     = 0;
      double                      momentum_defect     = 0;
      double                      momentum_correction = 0;
      std::vector<Tensor<1, dim>> pair_forces;
      std::vector<PairImpulse>    pair_impulses;
    };

    /// One chunk of contact nodes: what each node adds to the sums, added
    /// node by node once every node is final, and the pair impulses.
    struct ChunkResults
    {
      struct Totals
      {
        double frictional_heat, momentum_defect, momentum_correction;
      };
      std::vector<Totals>         node_totals;
      /// per node, the reported pairs' forces
      std::vector<Tensor<1, dim>> node_pair_forces;
      std::vector<PairImpulse>    pair_impulses;
      /// the records' velocities before the uncapped pass, node after
      /// node, and where each node's start
      std::vector<Tensor<1, dim>> saved_velocities;
      std::vector<unsigned int>   saved_offsets;
      /// with Geometry::keep, the pairs' geometry, node after node (a
      /// two-body node one pair, a pairwise node one per pair of its
      /// bodies), and where each node's start
      std::vector<PairGeometry>   geometry;
      std::vector<unsigned int>   geometry_offsets;
    };

    /// Per-body scratch of one node (nodes rarely hold more than a few
    /// bodies), one per thread.
    struct Scratch
    {
      std::vector<Tensor<1, dim>> normal, change, own, friction;
      std::vector<double>         tangential_speed, tangential_change;
      std::vector<bool>           slipping;
      /// the volume of the node's support (zero: not known)
      double support_volume = 0;
      /// pairwise contact: the change of the pair's first body and the
      /// pair's heat per unit scale
      struct PairChange
      {
        unsigned int   a, b;
        Tensor<1, dim> change;
        double         tau, slip_speed, heat_mass;
      };
      std::vector<PairChange> pairs;
      NodeSums                sums;
      /// the nodes of a chunk to correct again
      std::vector<unsigned int> nodes_to_redo;
      /// the node being corrected
      unsigned int node = 0;
    };

    /// Contact nodes per chunk of the threaded loop, which keeps its
    /// nodes' results (ChunkResults).
    static constexpr unsigned int chunk_size = 256;

    /// Contact at one node: changes only that node's records; with
    /// @p measure, also adds the node's pair impulses to @p sums.
    void
    apply_at_node(typename BodyFields<dim>::Record *begin,
                  typename BodyFields<dim>::Record *end,
                  const Tensor<1, dim> &            spacing,
                  const double                      dt,
                  const bool                        owned,
                  const bool                        record_forces,
                  const bool                        measure,
                  PairGeometry *                    geometry,
                  Scratch &                         scratch,
                  NodeSums &                        sums) const;

    /// apply_at_node() at a node of three or more bodies with
    /// 'Nodes with three or more bodies = pairwise'.
    void
    apply_pairwise_at_node(typename BodyFields<dim>::Record *begin,
                           typename BodyFields<dim>::Record *end,
                           const Tensor<1, dim> &            spacing,
                           const double                      dt,
                           const bool                        owned,
                           const bool                        record_forces,
                           const bool                        measure,
                           PairGeometry *                    geometry,
                           Scratch &                         scratch,
                           NodeSums &                        sums) const;

    /// The common unit normal (out of @p a) of two bodies at a node, from
    /// their unit mass-gradient directions @p normal_a and @p normal_b, as
    /// 'Contact/Normals' says; zero where the directions cancel.
    Tensor<1, dim>
    pair_normal(const typename BodyFields<dim>::Record &a,
                const typename BodyFields<dim>::Record &b,
                const Tensor<1, dim> &                  normal_a,
                const Tensor<1, dim> &                  normal_b) const;

    /// With 'Normals = flatter body': whether body @p p's surface is
    /// flatter than body @p q's: the larger radius of curvature (a box or
    /// mesh before a disk or sphere, a larger disk before a smaller one),
    /// then the larger volume (within 1e-9), then the body listed first.
    bool
    flatter(const unsigned int p, const unsigned int q) const;

    /// With 'Normals = fitted at edges': whether two bodies with unit
    /// outward directions @p normal_a and @p normal_b at a node meet there
    /// at an edge, where contact acts only while they approach (the 2000
    /// rule; the 2001 rule's release by traction acts where they face
    /// each other).
    bool
    approach_only_at_edge(const Tensor<1, dim> &normal_a, const Tensor<1, dim> &normal_b) const;

    /// The unit normal of the face that @p r's body's surface is at the
    /// node (BodyFields::Record::mass_surface_normal), or zero at a corner
    /// or where its points carry none: nine tenths of the record's mass
    /// carries a normal and the normals agree within about a degree, or,
    /// where the points of two faces meet in the record (a cell or two
    /// from an edge), nine tenths of the mass lies under one of the body's
    /// face directions (set_face_directions()).
    Tensor<1, dim>
    face_normal(const typename BodyFields<dim>::Record &r) const;

    /// Whether nine tenths of @p r's mass carries a face normal and those
    /// normals agree within about a degree: the points lie under one flat
    /// face.
    static bool
    on_one_face(const typename BodyFields<dim>::Record &r)
    {
      return r.mass_surface > 0 && r.mass_surface >= 0.9 * r.mass &&
             r.mass_surface_normal.norm() >= (1 - 1e-4) * r.mass_surface;
    }

    /// Whether @p r's points lie under one face (on_one_face()) and nine
    /// tenths of its mass carries the vector to it: Record::mass_surface_point
    /// then locates the surface.
    static bool
    surface_known(const typename BodyFields<dim>::Record &r)
    {
      return (on_one_face(r) || r.mass_surface == 0) && r.mass_on_surface >= 0.9 * r.mass;
    }

    /// With 'Detection = surface position': the gap between the surfaces
    /// of the bodies of @p a and @p b along @p normal (out of a).
    SurfaceGap
    surface_gap(const typename BodyFields<dim>::Record &a,
                const typename BodyFields<dim>::Record &b,
                const Tensor<1, dim> &                  normal,
                const Tensor<1, dim> &                  spacing,
                const double                            support = 0) const;

    /// surface_gap(), or with @p geometry the gap it keeps (computed and
    /// kept there if not yet).
    SurfaceGap
    pair_gap(const typename BodyFields<dim>::Record &a,
             const typename BodyFields<dim>::Record &b,
             const Tensor<1, dim> &                  normal,
             const Tensor<1, dim> &                  spacing,
             const double                            support,
             PairGeometry *                          geometry) const;

    /// Whether the reference volumes of @p a and @p b at their node exceed
    /// the volume @p support of the node's support (Grid::
    /// node_support_volumes(); zero: not known) by more than
    /// overlap_tolerance, each filling at least overlap_least_share of
    /// it: the bodies overlap there, whatever their centroids say.
    bool
    overlapping(const typename BodyFields<dim>::Record &a,
                const typename BodyFields<dim>::Record &b,
                const double                            support) const;

    /// Whether surfaces @p gap apart, closing at @p closing, meet within
    /// @p dt.
    static bool
    surfaces_meet(const SurfaceGap &gap, const double closing, const double dt)
    {
      return gap.separation - dt * std::max(closing, 0.) <= gap.touching;
    }

    /// The mass of record @p r as its body has it: a driven body's records
    /// carry their masses scaled (set_body_mass_factors()).
    double
    unscaled_mass(const typename BodyFields<dim>::Record &r) const
    {
      return r.body < body_mass_factors.size() ? r.mass / body_mass_factors[r.body] : r.mass;
    }

    /// Whether one of the records is a disk's or sphere's and the other a
    /// box's or mesh body's.
    bool
    round_against_face(const typename BodyFields<dim>::Record &a,
                       const typename BodyFields<dim>::Record &b) const;

    /**
     * A round body touching a flat face at a point (`Round body surfaces =
     * contact point`, source/mpm/contact/contact_points.cc): the round
     * body's lowest point along the face's normal, and the nodes around it
     * that take its impulse instead of the node kernel.
     */
    struct ContactPoint
    {
      unsigned int   round, flat;
      Tensor<1, dim> point, normal;
      /// the gap between the point and the face, and the cell's size
      /// along the normal
      double gap, cell;
      /// the mean normal traction there is compressive (the 2001 rule
      /// holds the point)
      bool compressed;
      /// the momentum update's normal and friction impulses at the point
      double         first_normal_impulse = 0;
      Tensor<1, dim> first_friction;
      struct Node
      {
        unsigned int node;
        /// the node's linear weight at the point (sum 1 over all ranks),
        /// and each body's share of a normal impulse
        double weight, round_share, flat_share;
        bool   owned;
      };
      std::vector<Node> nodes;
    };

    /// Find the contact points of this momentum update (before the node
    /// kernel, which then leaves their nodes alone).
    void
    find_contact_points(const BodyFields<dim> &             fields,
                        const std::vector<Tensor<1, dim>> &spacing,
                        const std::vector<Point<dim>> &    positions,
                        const unsigned int                 n_owned_nodes,
                        const MPI_Comm                     communicator);

    /// Stop the approach at each contact point, with Coulomb friction there.
    void
    act_at_contact_points(BodyFields<dim> & fields,
                          const double      dt,
                          const bool        record_forces,
                          const MPI_Comm    communicator);

    /// Whether the node kernel leaves @p node to a contact point.
    bool
    at_contact_point(const unsigned int node) const
    {
      return node < contact_point_nodes.size() && contact_point_nodes[node] != 0;
    }

    /// The number of pairs whose geometry a node of @p n bodies keeps.
    unsigned int
    n_kept_pairs(const unsigned int n) const;

    /// What every node of one call of apply() reads.
    struct Pass
    {
      BodyFields<dim> &                  fields;
      const std::vector<Tensor<1, dim>> &spacing;
      /// per node, the volume of its support (nullptr: not known)
      const std::vector<double> *        support_volumes;
      const double                       dt;
      const unsigned int                 n_owned_nodes;
      const bool                         record_forces;
    };

    /// Run apply_at_node() over the contact nodes of chunk @p chunk; with
    /// @p measure, saving the records' velocities first.
    void
    apply_to_chunk(const Pass &pass, const bool measure, const unsigned int chunk, Scratch &scratch);

    /// Run apply_at_node() at node @p index of chunk @p chunk, storing
    /// what it adds to the sums in the chunk's results.
    void
    apply_to_node(const Pass &       pass,
                  const bool         measure,
                  const unsigned int chunk,
                  const unsigned int index,
                  Scratch &          scratch);

    /// Correct again, from their saved velocities, the nodes of chunk
    /// @p chunk where the friction of a capped pair acted.
    void
    redo_capped_nodes(const Pass &pass, const unsigned int chunk, Scratch &scratch);

    /// The friction cap per pair from the measured impulses, summed over
    /// all ranks: mu N_net / F_t where the friction exceeds mu N_net.
    void
    compute_friction_scales(const MPI_Comm communicator, const bool momentum_update);

    /// With @p momentum_measure (the momentum update's measuring pass):
    /// an empty impulse of the pair of @p body_a and @p body_b, which share
    /// a node where contact does not act, if the pair has a pulling
    /// impulse to keep.
    void
    keep_pulling_impulse(const unsigned int body_a,
                         const unsigned int body_b,
                         const bool         momentum_measure,
                         const bool         owned,
                         NodeSums &         sums) const;

    const ContactParameters   parameters;
    bool                      sticking = false;

    /// The friction coefficient between the bodies of @p body_a and
    /// @p body_b (infinite while sticking).
    double
    friction_between_bodies(const unsigned int body_a, const unsigned int body_b) const
    {
      return sticking ? std::numeric_limits<double>::infinity() :
                        parameters.friction_between(body_groups[body_a], body_groups[body_b]);
    }
    std::vector<unsigned int> body_groups;
    std::vector<double>       body_surface_radii, body_volumes, body_mass_factors;
    /// per body, reference volume per unit mass (set_body_shapes())
    std::vector<double> body_specific_volumes;
    /// per body, the centre of its mass (set_body_centres(); empty unless
    /// round pairs take the line of centres as their normal)
    std::vector<Point<dim>> body_centres;
    /// set_face_directions(), and the same turned by
    /// turn_face_directions()
    std::vector<Tensor<1, dim>> reference_face_directions, face_directions;
    std::vector<unsigned int>   face_direction_start;
    /// index into pair_forces of the pair (a, b), a < b; or invalid
    std::vector<unsigned int> reported_pair_index;
    const bool                use_traction;
    /// the 2001 rule with a friction that can be capped: the pass measures
    /// the pairs' impulses and saves the velocities to correct again
    const bool                cap_friction;
    bool                      heat_at_nodes = true;
    /// surfaces closer than this, in cells, touch (surfaces_meet())
    static constexpr double touching_tolerance = 0.01;
    /// sideways offset of the centroids, in cells, that surfaces_meet()
    /// does not count
    static constexpr double sideways_tolerance = 0.25;
    /// fraction by which two bodies' reference volumes at a node may exceed
    /// its support before overlapping() says they overlap: above the
    /// round-off of two lattices that fill a support exactly (faces along
    /// grid lines; with no margin, one and two MPI ranks decided such
    /// nodes differently), below the overfill of the settling pile's
    /// disks pressed into each other (up to 48%)
    static constexpr double overlap_tolerance = 0.01;
    /// the least share of the node's support each of the two bodies must
    /// fill for overlapping() to say they overlap
    static constexpr double overlap_least_share = 0.05;
    /// with 'flatter body' or 'largest mass' normals: two bodies whose unit outward
    /// directions at a node have a larger dot product (less than 120
    /// degrees apart) do not face each other there (pair_normal())
    static constexpr double facing_limit = -0.5;

    unsigned int
    pair_index(const unsigned int a, const unsigned int b) const;

    /// The records of this apply() and their fitted normals (nullptr
    /// without), for fitted_normal(); what it does with the pairs' geometry.
    const BodyFields<dim> *            pass_fields = nullptr;
    Geometry                           pass_geometry = Geometry::compute;
    const std::vector<Tensor<1, dim>> *pass_fitted = nullptr;

    /// The fitted normal of record @p r in this apply() (only with
    /// pass_fitted).
    const Tensor<1, dim> &
    fitted_normal(const typename BodyFields<dim>::Record &r) const
    {
      return (*pass_fitted)[pass_fields->index_of(r)];
    }

    std::vector<ChunkResults> chunk_results;
    /// per pair, this pass's net normal and friction impulses
    PairTable<std::pair<double, double>> pair_totals;
    /// this pass's friction scale of the pairs whose friction is capped
    PairTable<double> friction_scale;
    /// per pair in contact, the net pulling normal impulse of earlier
    /// momentum updates that no compressive one has offset yet (the 2001
    /// rule holds separating nodes with pulling impulses; friction is
    /// bounded by the net normal impulse over time, not only per step),
    /// and the table being built for the next step
    PairTable<double> pulling_impulse, next_pulling_impulse;
    /// this step's contact points, and per node whether one took it
    std::vector<ContactPoint>  contact_points;
    std::vector<unsigned char> contact_point_nodes;
    /// the scene has disks or spheres and boxes or mesh bodies
    bool round_and_flat_bodies = false;
  };
} // namespace sable::mpm

#endif
