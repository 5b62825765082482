// The work functional Pi(theta) of one load increment and its exact
// gradient (SPEC Part C, eq. 14-18).
#ifndef sable_qusgm_work_functional_h
#define sable_qusgm_work_functional_h

#include <deal.II/lac/vector.h>

#include <sable/qusgm/contact_network.h>
#include <sable/qusgm/pack.h>

#include <array>
#include <vector>

namespace sable::qusgm
{
  using dealii::Vector;

  /// Loads and counts of a configuration (after or during an increment).
  struct ContactState
  {
    std::array<double, 6>     wall_force{};   ///< normal force on each wall
    unsigned int              n_contacts = 0; ///< grain-grain + grain-wall
    unsigned int              n_grain_contacts = 0;
    unsigned int              n_sliding        = 0;
    std::vector<unsigned int> coordination; ///< contacts per grain
    double                    max_contact_force = 0; ///< largest |P|
    double                    mean_normal_force = 0;
    double                    max_residual      = 0; ///< max |F_i|, |M_i|/R_i
  };

  /**
   * Pi over the 6N unknowns theta = [u_1..u_N, Omega_1 R_1..Omega_N R_N]
   * (u_i at 3i, Omega_i R_i at 3N + 3i) relative to the reference
   * configuration held in the Pack and the ContactNetwork, with the walls
   * at their current positions.
   *
   * Normal contacts: the Hertz energy; its gradient is the Hertz force.
   * Tangential and torsional contacts: the Coulomb-capped springs of
   * contact_laws.h, written in the current geometry (contact normal of the
   * current centres, reference load rotated onto the current plane) and
   * differentiated exactly, including the terms from the rotation of the
   * contact plane. Reference quantities (P0, a0, A0) fix the caps,
   * stiffnesses and lever arms, as the linearised laws prescribe; a contact
   * carries tangential load for the whole increment if it was closed at
   * the reference.
   */
  class WorkFunctional
  {
  public:
    WorkFunctional(const Pack           &pack,
                   const ContactNetwork &network,
                   const ContactModel   &model);

    void
    set_walls(const Walls &current_walls)
    {
      walls = current_walls;
    }

    const Walls &
    current_walls() const
    {
      return walls;
    }

    double
    value(const Vector<double> &theta) const;

    double
    value_and_gradient(const Vector<double> &theta, Vector<double> &gradient) const;

    /// Forces, counts and the residual at theta.
    ContactState
    state(const Vector<double> &theta) const;

    /// Current centres: reference + u.
    void
    positions(const Vector<double> &theta, std::vector<Point<3>> &x) const;

    /**
     * Make theta the new reference: move the grains, store the current
     * tangential loads and couples as the next increment's reference loads.
     */
    void
    commit(const Vector<double> &theta,
           Pack                 &pack,
           ContactNetwork       &network,
           Walls                &reference_walls) const;

    /**
     * Set the Coulomb caps of the frictional contacts of @p network (the
     * one this functional evaluates) to mu P and (3 pi/16) a mu P with the
     * normal load and contact radius at theta (zero for a contact that has
     * opened). Returns the largest change of a shear cap relative to the
     * largest new one.
     */
    double
    update_caps(const Vector<double> &theta, ContactNetwork &network_to_update) const;

    /**
     * Decide stick or slip of every frictional contact of @p network_to_update
     * (the one this functional evaluates) once, from the trial forces at
     * theta: a contact whose shear (torsional) trial force is within its cap
     * loses that cap until the next reference is set.
     */
    void
    freeze_stick_slip(const Vector<double> &theta, ContactNetwork &network_to_update) const;

    /// Largest |F_i|, |M_i|/R_i over the grains for a gradient vector.
    static double
    max_residual(const Vector<double> &gradient);

    mutable unsigned int n_evaluations = 0;

    /// Set by every gradient evaluation: the largest normal force and the
    /// largest change of a normal force since the reference.
    mutable double last_max_contact_force = 0;
    mutable double last_max_force_change  = 0;

  private:

    template <bool with_gradient>
    double
    evaluate(const Vector<double> &theta,
             Vector<double>       *gradient,
             ContactState         *state,
             std::vector<Tensor<1, 3>> *q_out,
             std::vector<double>       *m_out) const;

    /// Rebuild the grain -> contacts index if the network was rebuilt.
    void
    update_incidence() const;

    const Pack           &pack;
    const ContactNetwork &network;
    const ContactModel    model;
    Walls                 walls;

    /// Contacts per chunk of the threaded loop; fixed, so that the sums do
    /// not depend on the number of threads.
    static constexpr std::size_t chunk_size = 128;
    struct ChunkSums
    {
      double max_p = 0, max_dp = 0;
    };
    /// Energy and gradient contributions of a grain-grain contact: -force
    /// to grain i's and +force to grain j's displacement block, rotation_i
    /// and rotation_j to their rotation blocks.
    struct PairResult
    {
      double       energy;
      Tensor<1, 3> force, rotation_i, rotation_j;
    };
    struct WallResult
    {
      double       energy;
      Tensor<1, 3> gradient, rotation;
    };
    mutable std::vector<ChunkSums>  chunk_sums;
    mutable std::vector<PairResult> pair_results;
    mutable std::vector<WallResult> wall_results;
    /// per grain: gradient blocks and share of Pi (see evaluate())
    mutable std::vector<double> grain_values;
    /// per grain: normal forces on the walls and sum of normal forces
    mutable std::vector<double> grain_loads;
    /// grain i's contacts: incidence[incidence_start[i] .. incidence_start[i+1]),
    /// 2k / 2k+1 for grain i / j of pair k, 2 n_pairs + k for wall contact k;
    /// rebuilt when the network's n_builds or sizes change
    mutable std::vector<unsigned int>  incidence_start;
    mutable std::vector<std::size_t>   incidence;
    mutable std::array<std::size_t, 4> incidence_key{};
  };
} // namespace sable::qusgm

#endif
