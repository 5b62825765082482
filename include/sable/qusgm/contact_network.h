// Candidate contacts (grain-grain and grain-wall) found with a cell list,
// with the reference loads each contact carries from one load increment to
// the next.
#ifndef sable_qusgm_contact_network_h
#define sable_qusgm_contact_network_h

#include <sable/qusgm/grain_partition.h>
#include <sable/qusgm/pack.h>
#include <sable/qusgm/pack_io.h>

#include <boost/serialization/version.hpp>

#include <cstdint>
#include <vector>

namespace sable::qusgm
{
  /// Material constants of the contact laws (SPEC Part C).
  struct ContactModel
  {
    double friction = 0.3;   ///< mu between grains
    double wall_friction = 0.3; ///< mu between grains and walls
    bool   torsion  = true;  ///< torsional couples (eq. 9-12)
    bool   gravity  = false; ///< weight m g along -z
    double gravity_acceleration = 9.81;

    /// Normal load of the Coulomb caps mu P, (3 pi/16) a mu P.
    enum class FrictionCap
    {
      reference, ///< P0, a0 of the increment (the paper's eq. 6-7, 11-12)
      current    ///< P, a at the equilibrium found (caps updated, re-solved)
    };
    FrictionCap friction_cap = FrictionCap::reference;
    /// A contact counts as sliding when |Q| >= (1 - tolerance) Q_max.
    double sliding_tolerance = 0;
    /// Which contacts at the cap count as sliding.
    enum class SlidingCount
    {
      at_cap, ///< every one (|Q| = Q_max)
      eq_7b   ///< those where the paper's eq. 7b as printed gives |Q| = Q_max:
              ///< Q^p . u_s >= 0 (in continued loading it gives |Q| > Q_max)
    };
    SlidingCount sliding_count = SlidingCount::at_cap;
    /// When a contact's stick or slip is decided.
    enum class StickSlip
    {
      per_evaluation, ///< from the trial force at every evaluation of Pi
      per_increment   ///< once, from the trial force at the initial guess:
                      ///< a contact that sticks there has no cap until the
                      ///< increment ends
    };
    StickSlip stick_slip = StickSlip::per_evaluation;

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int version)
    {
      ar &friction &wall_friction &torsion &gravity &gravity_acceleration;
      if (version >= 1)
        ar &friction_cap &sliding_tolerance &sliding_count &stick_slip;
    }

    bool
    frictional() const
    {
      return friction > 0 || wall_friction > 0;
    }
  };

  /**
   * One contact. Constant within a load increment: the reference overlap,
   * loads and the quantities the linearised laws take from the reference
   * configuration (P0, a0, A0). `other` is a grain index for a grain-grain
   * contact and the wall index for a grain-wall contact.
   */
  struct Contact
  {
    unsigned int i, other;
    double       k_n;          ///< Hertz coefficient (4/3) E* sqrt(R*)
    double       h0;           ///< reference overlap (<= 0: no contact)
    double       p0;           ///< reference normal force
    Tensor<1, 3> q0;           ///< reference tangential force on grain i
    double       m0;           ///< reference torsional couple on i about n_i
    double       k_s, k_t;     ///< stick stiffnesses at the reference
    double       q_max, m_max; ///< Coulomb caps mu P0, (3 pi/16) a0 mu P0
    double       lever_i;      ///< distance from centre i to contact centre
    double       lever_j;      ///< same for grain j (grain-grain only)

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &i &other &k_n &h0 &p0 &q0 &m0 &k_s &k_t &q_max &m_max &lever_i &lever_j;
    }

    std::uint64_t
    key(const unsigned int n_grains) const
    {
      return std::uint64_t(i) * (n_grains + 6) + other;
    }
  };

  /**
   * Candidate contacts within a skin distance, built with a cell list in
   * O(N). `pairs` holds grain-grain contacts (i < other), `wall_contacts`
   * grain-wall contacts; both sorted by key, so that rebuilding carries the
   * reference loads over by pair.
   *
   * With more than one MPI rank, a network holds the contacts of the
   * grains its rank owns (see GrainPartition): a pair across two ranks is
   * held by both.
   */
  class ContactNetwork
  {
  public:
    std::vector<Contact> pairs;
    std::vector<Contact> wall_contacts;

    /// Distribute the grains over the ranks of @p communicator from the
    /// next build() on (default: MPI_COMM_SELF, all grains on one rank).
    void
    set_communicator(const MPI_Comm new_communicator)
    {
      communicator = new_communicator;
      partition    = GrainPartition();
    }

    /// Who owns which grain; set by build() for the pack it is given.
    const GrainPartition &
    get_partition() const
    {
      return partition;
    }

    /// True if this rank holds the contact's energy, counts and loads in
    /// sums over the whole pack (the rank of its first grain).
    bool
    owns(const Contact &c) const
    {
      return partition.is_owned(c.i);
    }

    /**
     * Find every grain pair and grain-wall pair closer than @p skin at the
     * current positions (reference + u) and walls, keeping the reference
     * state of contacts already present and initialising new ones from the
     * reference configuration.
     */
    void
    build(const Pack                  &pack,
          const Walls                 &reference_walls,
          const std::vector<Point<3>> &current,
          const Walls                 &current_walls,
          const ContactModel          &model,
          double                       skin);

    /// True if a grain or wall moved more than half the skin since build().
    bool
    needs_rebuild(const std::vector<Point<3>> &current,
                  const Walls                 &current_walls,
                  double                       extra_motion = 0.) const;

    /**
     * Recompute the reference quantities of every contact from the pack's
     * (reference) configuration, keeping q0 and m0 but capping them at the
     * new Coulomb limits and projecting q0 onto the new contact plane.
     */
    void
    update_reference(const Pack         &pack,
                     const Walls        &walls,
                     const ContactModel &model);

    /**
     * Give the contacts of @p loads their reference tangential force and
     * couple, at the reference configuration (@p pack, @p walls). Builds
     * the network if it is empty. Loads on the contact plane and within
     * the Coulomb caps are taken as they are (to the last digit); others
     * are projected onto the plane and capped, like the loads carried from
     * one increment to the next. Throws InputError (naming the load's file
     * and line) for a contact whose grains do not overlap. Every rank calls
     * it with all loads.
     */
    void
    set_reference_loads(const Pack                     &pack,
                        const Walls                    &walls,
                        const ContactModel             &model,
                        double                          skin,
                        const std::vector<ContactLoad> &loads);

    /// The contacts of all ranks in @p held (pairs or wall_contacts) on
    /// rank 0, each once, in key order; collective.
    std::vector<Contact>
    gather_on_root(const std::vector<Contact> &held, unsigned int n_grains) const;

    unsigned int n_builds = 0;
    double       skin     = 0;

  private:
    void
    initialise(Contact            &c,
               bool                wall,
               const Pack         &pack,
               const Walls        &walls,
               const ContactModel &model) const;

    std::vector<Point<3>> positions_at_build;
    Walls                 walls_at_build;
    MPI_Comm              communicator = MPI_COMM_SELF;
    GrainPartition        partition;
  };
} // namespace sable::qusgm

// Version 1 added the friction cap, the sliding count and tolerance and
// the stick-slip decision.
BOOST_CLASS_VERSION(sable::qusgm::ContactModel, 1)

#endif
