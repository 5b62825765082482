// Hertz, Mindlin-Deresiewicz and torsion laws for one contact (SPEC Part C).
// Small inline functions: they sit in the innermost loop of every evaluation
// of the work functional.
#ifndef sable_qusgm_contact_laws_h
#define sable_qusgm_contact_laws_h

#include <deal.II/base/tensor.h>

#include <cmath>

namespace sable::qusgm::contact_laws
{
  using dealii::Tensor;

  /// R* = (1/R_i + 1/R_j)^-1 (the paper prints the inverse; SPEC erratum).
  inline double
  effective_radius(const double r_i, const double r_j)
  {
    return r_i * r_j / (r_i + r_j);
  }

  /// E* = ((1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j)^-1.
  inline double
  effective_modulus(const double e_i,
                    const double nu_i,
                    const double e_j,
                    const double nu_j)
  {
    return 1. / ((1. - nu_i * nu_i) / e_i + (1. - nu_j * nu_j) / e_j);
  }

  /// Hertz coefficient k_n = (4/3) E* sqrt(R*), so that P = k_n h^(3/2).
  inline double
  hertz_coefficient(const double e_star, const double r_star)
  {
    return 4. / 3. * e_star * std::sqrt(r_star);
  }

  inline double
  hertz_force(const double k_n, const double h)
  {
    return h > 0 ? k_n * h * std::sqrt(h) : 0.;
  }

  /// Elastic energy stored by the normal compression, (2/5) k_n h^(5/2).
  inline double
  hertz_energy(const double k_n, const double h)
  {
    return h > 0 ? 0.4 * k_n * h * h * std::sqrt(h) : 0.;
  }

  /// Stick stiffness k*_s = 8 a ((2 - nu_i)/G_i + (2 - nu_j)/G_j)^-1.
  inline double
  shear_stiffness(const double a,
                  const double nu_i,
                  const double g_i,
                  const double nu_j,
                  const double g_j)
  {
    return 8. * a / ((2. - nu_i) / g_i + (2. - nu_j) / g_j);
  }

  /// Torsional stick stiffness k*_t = (16/3) a^3 (1/G_i + 1/G_j)^-1.
  inline double
  torsion_stiffness(const double a, const double g_i, const double g_j)
  {
    return 16. / 3. * a * a * a / (1. / g_i + 1. / g_j);
  }

  /// Torsional cap (3 pi / 16) a mu P.
  inline double
  torsion_cap(const double a, const double mu, const double p)
  {
    return 3. * M_PI / 16. * a * mu * p;
  }

  /// Radius A of the circle where the undeformed surfaces of two spheres at
  /// centre distance d intersect (0 if they do not).
  inline double
  intersection_radius(const double r_i, const double r_j, const double d)
  {
    const double product = (-d + r_i - r_j) * (-d - r_i + r_j) *
                           (-d + r_i + r_j) * (d + r_i + r_j);
    return product > 0 ? std::sqrt(product) / (2. * d) : 0.;
  }

  /**
   * The Coulomb-capped spring in potential form. For the trial force
   * y = Q^p - k u (stick), the force is the projection of y on the disc
   * |Q| <= cap, and the work done against it is
   *   W(u) = [f(Q^p) - f(Q^p - k u)] / k,
   *   f(y) = |y|^2 / 2 - max(|y| - cap, 0)^2 / 2,
   * whose derivative with respect to u is exactly that force. While the
   * contact sticks W = Q^p.u - k |u|^2 / 2 (the paper's eq. 17a); once the
   * trial force passes the cap the force has magnitude cap (sliding).
   */
  /// Scalar version (torsion about the contact normal).
  inline double
  capped_potential(const double y, const double cap)
  {
    const double excess = std::abs(y) - cap;
    return 0.5 * y * y - (excess > 0 ? 0.5 * excess * excess : 0.);
  }

  inline double
  capped_force(const double y, const double cap)
  {
    return std::abs(y) > cap ? (y > 0 ? cap : -cap) : y;
  }

  /// Vector version (tangential force in the contact plane).
  inline double
  capped_potential(const Tensor<1, 3> &y, const double cap)
  {
    const double norm   = y.norm();
    const double excess = norm - cap;
    return 0.5 * norm * norm - (excess > 0 ? 0.5 * excess * excess : 0.);
  }

  inline Tensor<1, 3>
  capped_force(const Tensor<1, 3> &y, const double cap)
  {
    const double norm = y.norm();
    return norm > cap ? (cap / norm) * y : y;
  }
} // namespace sable::qusgm::contact_laws

#endif
