#ifndef sable_mpm_contact_coulomb_h
#define sable_mpm_contact_coulomb_h

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>

namespace sable::mpm
{
  using namespace dealii;

  /// What coulomb_correction() does to one velocity.
  template <int dim>
  struct CoulombCorrection
  {
    /// the velocity change, and its friction (tangential) part
    Tensor<1, dim> change;
    Tensor<1, dim> friction;
    /// |dv_t| before the correction, and how much of it was removed
    double tangential_speed  = 0;
    double tangential_change = 0;

    /// The fraction of the tangential velocity removed (1 without any).
    double
    tangential_fraction() const
    {
      return tangential_speed > 0 ? tangential_change / tangential_speed : 1.;
    }
  };

  /**
   * The Coulomb correction of SPEC Part A step 6, shared by body-body
   * contact and friction walls: of a velocity @p relative_velocity relative
   * to the other side (the centre of mass of a contact node, or a wall at
   * rest) with outward unit normal @p normal, remove the normal part
   * dv_n = dv . n and as much of the tangential part dv_t as Coulomb allows,
   * tau = min(mu max(dv_n, 0), |dv_t|): friction is bounded by the
   * compressive normal impulse, and a separating velocity (dv_n < 0) gives
   * none. mu = infinity sticks (the whole relative velocity is removed).
   */
  template <int dim>
  inline CoulombCorrection<dim>
  coulomb_correction(const Tensor<1, dim> &relative_velocity,
                     const Tensor<1, dim> &normal,
                     const double          mu)
  {
    CoulombCorrection<dim> result;
    const double           dv_n = relative_velocity * normal;
    const Tensor<1, dim>   dv_t = relative_velocity - dv_n * normal;
    result.tangential_speed     = dv_t.norm();
    if (std::isinf(mu))
      {
        result.change            = -relative_velocity;
        result.friction          = -dv_t;
        result.tangential_change = result.tangential_speed;
        return result;
      }
    const double tau = std::min(mu * std::max(dv_n, 0.), result.tangential_speed);
    result.change    = -dv_n * normal;
    if (result.tangential_speed > 0 && tau > 0)
      {
        result.friction = -(tau / result.tangential_speed) * dv_t;
        result.change += result.friction;
      }
    result.tangential_change = tau;
    return result;
  }

  /**
   * MUSL's remap pass corrects a step that the momentum update corrected
   * already; Coulomb's law holds for the step's impulses together. Of the
   * friction @p added (the change that would stop the slip the remap pass
   * sees), the largest fraction, at most 1, that keeps its sum with the
   * momentum update's friction @p earlier within @p cap (mu times the two
   * passes' pressing normal changes), or within |earlier| if that is more:
   * the remap pass only ever opposes the slip it sees, and stops short
   * rather than undo what the momentum update did.
   */
  template <int dim>
  inline double
  fraction_within_cap(const Tensor<1, dim> &earlier, const Tensor<1, dim> &added, const double cap)
  {
    const double a = added * added;
    if (a == 0)
      return 0;
    const double bound = std::max(cap, earlier.norm());
    const double b     = earlier * added;
    const double c     = earlier * earlier - bound * bound;
    return std::min(1., (-b + std::sqrt(std::max(b * b - a * c, 0.))) / a);
  }
} // namespace sable::mpm

#endif
