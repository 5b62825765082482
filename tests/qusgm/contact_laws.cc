// Contact laws of QuSGM against closed forms: Hertz force, energy and
// contact radius for two spheres and a sphere on a wall; the gradient of
// the work functional against central finite differences with sticking,
// sliding and torsion active; a contact sheared at fixed normal load to the
// Coulomb cap, unloaded and reloaded; which contacts count as sliding under
// each rule; caps from the current normal load.
#include <sable/qusgm/contact_network.h>
#include <sable/qusgm/work_functional.h>

#include <cmath>
#include <random>

#include "test_support.h"

using namespace sable::qusgm;
using dealii::Point;
using dealii::Tensor;
using dealii::Vector;
using sable_tests::check;
using sable_tests::check_relative;

namespace
{
  Walls
  far_walls()
  {
    Walls walls;
    walls.position      = {{-1, -1, -1, 1, 1, 1}};
    walls.youngs_modulus = 7e12;
    walls.poisson_ratio  = 0.495;
    return walls;
  }

  void
  build(const Pack &pack, const Walls &walls, ContactNetwork &network,
        const ContactModel &model)
  {
    network.build(pack, walls, pack.centre, walls, model, 0.3 * pack.mean_radius());
  }

  // Two spheres and a sphere on a wall against the Hertz closed forms.
  void
  test_hertz()
  {
    const double r1 = 1e-4, r2 = 0.7e-4, e1 = 70e9, e2 = 50e9, nu1 = 0.2,
                 nu2 = 0.3, h = 1.3e-7;
    Tensor<1, 3> n;
    n[0] = 0.48;
    n[1] = -0.6;
    n[2] = 0.64;
    n /= n.norm();
    Pack pack;
    pack.add_grain(Point<3>(), r1, e1, nu1, 2500);
    pack.add_grain(Point<3>() - (r1 + r2 - h) * n, r2, e2, nu2, 2500);
    ContactModel model;
    model.friction = 0.3;
    model.wall_friction = 0.3;
    ContactNetwork network;
    const Walls    walls = far_walls();
    build(pack, walls, network, model);
    WorkFunctional functional(pack, network, model);
    functional.set_walls(walls);

    const double r_star = 1. / (1. / r1 + 1. / r2);
    const double e_star =
      1. / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
    const double p_exact = 4. / 3. * e_star * std::sqrt(r_star) * std::pow(h, 1.5);
    Vector<double>     theta(12), gradient(12);
    const ContactState s = functional.state(theta);
    check("two spheres: one contact", s.n_contacts == 1 && network.pairs.size() == 1);
    check_relative("two spheres: Hertz force", s.max_contact_force, p_exact, 1e-12);
    functional.value_and_gradient(theta, gradient);
    Tensor<1, 3> f1;
    for (unsigned int d = 0; d < 3; ++d)
      f1[d] = -gradient[d];
    check_relative("two spheres: force along the line of centres",
                   f1 * n, p_exact, 1e-12);
    check_relative("two spheres: no force across the line of centres",
                   (f1 - (f1 * n) * n).norm(), 0, 1e-12, p_exact);
    check_relative("two spheres: force balance", (f1 + Tensor<1, 3>(
                     {-gradient[3], -gradient[4], -gradient[5]})).norm(), 0, 1e-12, p_exact);

    // Energy: move grain 1 along n by dh, Pi changes by the Hertz energy.
    const double dh = 0.4e-7;
    for (unsigned int d = 0; d < 3; ++d)
      theta[d] = -dh * n[d];
    const double energy_exact = 8. / 15. * e_star * std::sqrt(r_star) *
                                (std::pow(h + dh, 2.5) - std::pow(h, 2.5));
    check_relative("two spheres: Hertz energy", functional.value(theta),
                   energy_exact, 1e-10);

    // Contact radius a = sqrt(R* h) through the stick stiffness
    // 8 a ((2 - nu1)/G1 + (2 - nu2)/G2)^-1, and the lever arm from the
    // intersection circle of the undeformed spheres.
    const double g1 = e1 / (2 * (1 + nu1)), g2 = e2 / (2 * (1 + nu2));
    const double a  = std::sqrt(r_star * h);
    check_relative("two spheres: stick stiffness (contact radius)",
                   network.pairs[0].k_s,
                   8 * a / ((2 - nu1) / g1 + (2 - nu2) / g2), 1e-12);
    const double d = r1 + r2 - h;
    const double x1 = (d * d + r1 * r1 - r2 * r2) / (2 * d);
    check_relative("two spheres: lever arm to the contact centre",
                   network.pairs[0].lever_i, x1, 1e-9);
    check_relative("two spheres: Coulomb cap", network.pairs[0].q_max,
                   0.3 * p_exact, 1e-12);
    check_relative("two spheres: torsion stiffness", network.pairs[0].k_t,
                   16. / 3. * a * a * a / (1 / g1 + 1 / g2), 1e-12);

    // Sphere on the lower z wall.
    Pack single;
    single.add_grain(Point<3>(0.1e-4, -0.2e-4, -1 + r1 - h), r1, e1, nu1, 2500);
    ContactNetwork wall_network;
    build(single, walls, wall_network, model);
    WorkFunctional wall_functional(single, wall_network, model);
    wall_functional.set_walls(walls);
    Vector<double>     theta1(6), gradient1(6);
    const ContactState sw = wall_functional.state(theta1);
    const double       e_star_w =
      1. / ((1 - nu1 * nu1) / e1 + (1 - 0.495 * 0.495) / 7e12);
    // The overlap as stored (the centre coordinate rounds near z = -1).
    const double h_w    = r1 - (single.centre[0][2] + 1.);
    const double p_wall = 4. / 3. * e_star_w * std::sqrt(r1) * std::pow(h_w, 1.5);
    check("sphere on wall: one contact", sw.n_contacts == 1);
    check_relative("sphere on wall: Hertz force", sw.wall_force[2], p_wall, 1e-12);
    wall_functional.value_and_gradient(theta1, gradient1);
    check_relative("sphere on wall: force along +z", -gradient1[2], p_wall, 1e-12);
    check_relative("sphere on wall: no force along the wall",
                   std::hypot(gradient1[0], gradient1[1]), 0, 1e-12, p_wall);
    theta1[2] = -dh;
    check_relative("sphere on wall: Hertz energy", wall_functional.value(theta1),
                   8. / 15. * e_star_w * std::sqrt(r1) *
                     (std::pow(h_w + dh, 2.5) - std::pow(h_w, 2.5)),
                   1e-8);
  }

  // Gradient against central differences on a random pack with reference
  // loads, some contacts sticking, some sliding, torsion on.
  void
  test_gradient()
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> uni(0, 1);
    Pack                                   pack;
    const double                           r = 1e-4;
    // A jittered 3x3x2 lattice with overlaps.
    for (unsigned int k = 0; k < 2; ++k)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int i = 0; i < 3; ++i)
          {
            const double ri = r * (0.8 + 0.4 * uni(rng));
            pack.add_grain(Point<3>(1.9 * r * i + 0.05 * r * uni(rng),
                                    1.9 * r * j + 0.05 * r * uni(rng),
                                    1.9 * r * k + 0.05 * r * uni(rng)),
                           ri,
                           70e9 * (0.9 + 0.2 * uni(rng)),
                           0.15 + 0.1 * uni(rng),
                           2420);
          }
    Walls walls = bounding_walls(pack);
    for (unsigned int w = 0; w < 6; ++w)
      walls.position[w] += Walls::sign(w) * 0.02 * r; // press the walls in
    ContactModel model;
    model.friction = 0.3;
    model.wall_friction = 0.3;
    model.torsion  = true;
    model.gravity  = true;
    ContactNetwork network;
    build(pack, walls, network, model);
    // Random reference loads, half of them at the cap.
    auto set_loads = [&](Contact &c) {
      if (c.p0 <= 0)
        return;
      Tensor<1, 3> q;
      for (unsigned int d = 0; d < 3; ++d)
        q[d] = uni(rng) - 0.5;
      const double fraction = uni(rng) < 0.5 ? 1. : 0.7 * uni(rng);
      c.q0 = q;
      c.m0 = (uni(rng) < 0.5 ? -1 : 1) * fraction * c.m_max;
      // Project onto the contact plane through update_reference below.
      c.q0 *= fraction * c.q_max / q.norm();
    };
    for (Contact &c : network.pairs)
      set_loads(c);
    for (Contact &c : network.wall_contacts)
      set_loads(c);
    network.update_reference(pack, walls, model);
    check("gradient pack: contacts with reference loads",
          network.pairs.size() > 10 && network.wall_contacts.size() > 5);

    WorkFunctional functional(pack, network, model);
    Walls          moved = walls;
    moved.position[2] += 0.01 * r;
    moved.position[5] -= 0.01 * r;
    functional.set_walls(moved);
    const unsigned int n = pack.size();
    Vector<double>     theta(6 * n), gradient(6 * n);
    for (unsigned int k = 0; k < 6 * n; ++k)
      theta[k] = 2e-3 * r * (uni(rng) - 0.5);
    functional.value_and_gradient(theta, gradient);
    const ContactState s = functional.state(theta);
    std::cout << "gradient pack: " << n << " grains, " << s.n_contacts
              << " contacts, " << s.n_sliding << " sliding" << std::endl;
    check("gradient pack: sliding and sticking contacts present",
          s.n_sliding > 2 && s.n_sliding + 2 < s.n_contacts);

    Vector<double> fd(6 * n);
    const double   delta = 1e-5 * 2e-3 * r;
    for (unsigned int k = 0; k < 6 * n; ++k)
      {
        Vector<double> plus(theta), minus(theta);
        plus[k] += delta;
        minus[k] -= delta;
        fd[k] = (functional.value(plus) - functional.value(minus)) / (2 * delta);
      }
    Vector<double> difference(fd);
    difference -= gradient;
    check_relative("gradient against central differences (l2, relative)",
                   difference.l2_norm() / gradient.l2_norm(), 0, 1e-6, 1.);
    // The rotational part alone (moments) must also agree.
    double rot_diff = 0, rot_norm = 0;
    for (unsigned int k = 3 * n; k < 6 * n; ++k)
      {
        rot_diff += std::pow(fd[k] - gradient[k], 2);
        rot_norm += std::pow(gradient[k], 2);
      }
    check_relative("moment part of the gradient against central differences",
                   std::sqrt(rot_diff / rot_norm), 0, 1e-6, 1.);
  }

  // Two spheres sheared at fixed normal load: Q = k* u up to mu P, then
  // |Q| = mu P; unloading and reloading follow k* again.
  void
  test_shear_to_cap()
  {
    const double r = 1e-4, h = 1e-7, mu = 0.3;
    Pack         pack;
    pack.add_grain(Point<3>(0, 0, 0), r, 70e9, 0.2, 2420);
    pack.add_grain(Point<3>(2 * r - h, 0, 0), r, 70e9, 0.2, 2420);
    ContactModel model;
    model.friction = mu;
    model.wall_friction = mu;
    model.torsion  = false;
    const Walls    walls = far_walls();
    ContactNetwork network;
    build(pack, walls, network, model);
    const double p0 = network.pairs[0].p0, k_s = network.pairs[0].k_s;
    const double cap_shift = mu * p0 / k_s; // relative shift at the cap

    Walls reference = walls;
    // Shear grain 1 along +y relative to grain 2 by s (each moves s/2).
    // The returned tangential force on grain 1 is -dPi/du_1y.
    auto shear = [&](const double s, const bool keep, unsigned int *sliding) {
      WorkFunctional functional(pack, network, model);
      functional.set_walls(reference);
      Vector<double> theta(12), gradient(12);
      theta[1] = 0.5 * s;
      theta[4] = -0.5 * s;
      functional.value_and_gradient(theta, gradient);
      if (sliding)
        *sliding = functional.state(theta).n_sliding;
      // Tangential part of the force on grain 1 (the normal force tilts
      // with the line of centres).
      Tensor<1, 3> f, n = (pack.centre[0] - pack.centre[1]);
      n[1] += s;
      n /= n.norm();
      for (unsigned int d = 0; d < 3; ++d)
        f[d] = -gradient[d];
      const Tensor<1, 3> q = f - (f * n) * n;
      if (keep)
        functional.commit(theta, pack, network, reference);
      return q[1];
    };
    const double q_half = shear(0.5 * cap_shift, false, nullptr);
    check_relative("shear below the cap: Q = -k* u", q_half,
                   -k_s * 0.5 * cap_shift, 1e-5);
    unsigned int sliding = 0;
    const double q_cap   = shear(0.99 * cap_shift, false, &sliding);
    check_relative("shear just below the cap: Q = -k* u", q_cap,
                   -k_s * 0.99 * cap_shift, 1e-5);
    check("shear just below the cap: sticking", sliding == 0);
    const double q_slide = shear(2. * cap_shift, true, &sliding);
    check_relative("shear beyond the cap: |Q| = mu P", q_slide, -mu * p0, 1e-5);
    check("shear beyond the cap: sliding", sliding == 1);
    // Unload by half the cap shift: stick stiffness again.
    const double p0_now = network.pairs[0].p0;
    // The centres moved apart by s^2/(2d): the overlap barely changes.
    check_relative("normal load after the shear (Hertz at the new overlap)",
                   p0_now,
                   network.pairs[0].k_n *
                     std::pow(2 * r - (pack.centre[0] - pack.centre[1]).norm(), 1.5),
                   1e-12);
    check_relative("normal load nearly unchanged by the shear", p0_now, p0, 1e-3);
    const double k_s_now = network.pairs[0].k_s;
    const double q_unload = shear(-0.5 * cap_shift, true, &sliding);
    check_relative("unloading follows the stick stiffness", q_unload,
                   -mu * p0_now + k_s_now * 0.5 * cap_shift, 1e-5);
    check("unloading: sticking", sliding == 0);
    // Reload: stick stiffness up to the cap, then the cap.
    const double q_reload = shear(0.25 * cap_shift, false, &sliding);
    check_relative("reloading follows the stick stiffness", q_reload,
                   -mu * p0_now + k_s_now * 0.5 * cap_shift -
                     network.pairs[0].k_s * 0.25 * cap_shift,
                   1e-5);
    const double q_recap = shear(cap_shift, false, &sliding);
    check_relative("reloading past the cap: |Q| = mu P", q_recap,
                   -mu * network.pairs[0].p0, 1e-6);
    check("reloading past the cap: sliding", sliding == 1);
  }

  // Which contacts count as sliding: two spheres sheared at fixed normal
  // load past the cap from zero load, then further in the same direction
  // (continued loading), then back past the opposite cap (reversal).
  // 'at cap' counts all three; 'eq. 7b' only the first and the last (the
  // paper's eq. 7b gives |Q| > mu P in continued loading). A tolerance
  // counts a contact just below the cap.
  void
  test_sliding_count()
  {
    const double r = 1e-4, h = 1e-7, mu = 0.3;
    Pack         pack;
    pack.add_grain(Point<3>(0, 0, 0), r, 70e9, 0.2, 2420);
    pack.add_grain(Point<3>(2 * r - h, 0, 0), r, 70e9, 0.2, 2420);
    ContactModel model;
    model.friction      = mu;
    model.wall_friction = mu;
    model.torsion       = false;
    Walls          reference = far_walls();
    ContactNetwork network;
    build(pack, reference, network, model);
    const double cap_shift = mu * network.pairs[0].p0 / network.pairs[0].k_s;

    // Sliding count under each rule for a shear s of grain 1 against 2.
    auto count = [&](const double s, const bool keep) {
      std::array<unsigned int, 3> n{};
      Vector<double>              theta(12);
      theta[1] = 0.5 * s;
      theta[4] = -0.5 * s;
      ContactModel rule = model;
      for (unsigned int k = 0; k < 3; ++k)
        {
          rule.sliding_count     = k == 1 ? ContactModel::SlidingCount::eq_7b :
                                            ContactModel::SlidingCount::at_cap;
          rule.sliding_tolerance = k == 2 ? 0.01 : 0.;
          WorkFunctional functional(pack, network, rule);
          functional.set_walls(reference);
          n[k] = functional.state(theta).n_sliding;
          if (keep && k == 2)
            functional.commit(theta, pack, network, reference);
        }
      return n;
    };
    using Counts = std::array<unsigned int, 3>; // at cap, eq. 7b, 1% tolerance
    check("0.995 of the cap: only the tolerance counts it",
          count(0.995 * cap_shift, false) == Counts{{0, 0, 1}});
    check("past the cap from zero load: every rule counts it",
          count(2 * cap_shift, true) == Counts{{1, 1, 1}});
    check("continued loading at the cap: eq. 7b does not count it",
          count(cap_shift, true) == Counts{{1, 0, 1}});
    check("reversal past the opposite cap: every rule counts it",
          count(-3 * cap_shift, true) == Counts{{1, 1, 1}});
  }

  // Caps from the current normal load: pressing two spheres further
  // (overlap 1.5 h) and updating the caps gives mu P and (3 pi/16) a mu P
  // at the new overlap; a shear past the cap then carries mu P, not mu P0.
  void
  test_current_cap()
  {
    const double r = 1e-4, h = 1e-7, mu = 0.3;
    Pack         pack;
    pack.add_grain(Point<3>(0, 0, 0), r, 70e9, 0.2, 2420);
    pack.add_grain(Point<3>(2 * r - h, 0, 0), r, 70e9, 0.2, 2420);
    ContactModel model;
    model.friction      = mu;
    model.wall_friction = mu;
    model.friction_cap  = ContactModel::FrictionCap::current;
    const Walls    walls = far_walls();
    ContactNetwork network;
    build(pack, walls, network, model);
    const Contact  reference = network.pairs[0];
    WorkFunctional functional(pack, network, model);
    functional.set_walls(walls);
    Vector<double> theta(12);
    theta[0]             = 0.25 * h;
    theta[3]             = -0.25 * h;
    const double p       = reference.k_n * std::pow(1.5 * h, 1.5);
    const double change  = functional.update_caps(theta, network);
    check_relative("current cap: mu P at the new overlap", network.pairs[0].q_max, mu * p, 1e-12);
    check_relative("current cap: torsion (3 pi/16) a mu P",
                   network.pairs[0].m_max,
                   3 * M_PI / 16 * std::sqrt(0.5 * r * 1.5 * h) * mu * p,
                   1e-12);
    check_relative("current cap: change reported relative to the new cap",
                   change, (p - reference.p0) / p, 1e-12);
    check("current cap: stiffness and reference load unchanged",
          network.pairs[0].k_s == reference.k_s && network.pairs[0].p0 == reference.p0);
    // Shear past the new cap; the committed load is the force carried.
    const double shift = 3 * mu * p / reference.k_s;
    theta[1]           = 0.5 * shift;
    theta[4]           = -0.5 * shift;
    Walls moved        = walls;
    functional.commit(theta, pack, network, moved);
    // (the shear moves the centres apart by s^2/2d: P drops by 4e-4; with
    // the reference cap the force would be mu P0 = 0.54 mu P)
    check_relative("current cap: normal load after the shear", network.pairs[0].p0, p, 1e-3);
    check_relative("current cap: sliding force mu P",
                   network.pairs[0].q0.norm(), mu * network.pairs[0].p0, 1e-12);
  }
} // namespace

int
main()
{
  test_hertz();
  test_gradient();
  test_shear_to_cap();
  test_sliding_count();
  test_current_cap();
  return sable_tests::exit_code();
}
