#include <deal.II/base/parallel.h>

#include <sable/qusgm/contact_laws.h>
#include <sable/qusgm/work_functional.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sable::qusgm
{
  using namespace contact_laws;

  namespace
  {
    inline Tensor<1, 3>
    block(const Vector<double> &v, const unsigned int offset)
    {
      Tensor<1, 3> t;
      t[0] = v[offset];
      t[1] = v[offset + 1];
      t[2] = v[offset + 2];
      return t;
    }

    inline void
    add_block(Vector<double>     &v,
              const unsigned int  offset,
              const Tensor<1, 3> &t,
              const double        factor)
    {
      v[offset] += factor * t[0];
      v[offset + 1] += factor * t[1];
      v[offset + 2] += factor * t[2];
    }
  } // namespace

  WorkFunctional::WorkFunctional(const Pack           &pack,
                                 const ContactNetwork &network,
                                 const ContactModel   &model)
    : pack(pack)
    , network(network)
    , model(model)
  {}

  double
  WorkFunctional::value(const Vector<double> &theta) const
  {
    return evaluate<false>(theta, nullptr, nullptr, nullptr, nullptr);
  }

  double
  WorkFunctional::value_and_gradient(const Vector<double> &theta,
                                     Vector<double>       &gradient) const
  {
    return evaluate<true>(theta, &gradient, nullptr, nullptr, nullptr);
  }

  ContactState
  WorkFunctional::state(const Vector<double> &theta) const
  {
    ContactState   s;
    Vector<double> gradient(theta.size());
    evaluate<true>(theta, &gradient, &s, nullptr, nullptr);
    s.max_residual = max_residual(gradient);
    return s;
  }

  void
  WorkFunctional::positions(const Vector<double>  &theta,
                            std::vector<Point<3>> &x) const
  {
    const unsigned int n = pack.size();
    x.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = pack.centre[i] + block(theta, 3 * i);
  }

  double
  WorkFunctional::max_residual(const Vector<double> &gradient)
  {
    const unsigned int n = gradient.size() / 6;
    double             r = 0;
    for (unsigned int k = 0; k < 2 * n; ++k)
      r = std::max(r, block(gradient, 3 * k).norm_square());
    return std::sqrt(r);
  }

  void
  WorkFunctional::update_incidence() const
  {
    const std::size_t n_pairs = network.pairs.size();
    const std::size_t n_walls = network.wall_contacts.size();
    const unsigned int n      = pack.size();
    if (incidence_key == std::array<std::size_t, 4>{{network.n_builds, n_pairs, n_walls, n}})
      return;
    // grain -> its contacts in contact order (pairs, then walls):
    // 2k: grain i of pair k, 2k+1: grain j, 2 n_pairs + k: wall contact k
    incidence_start.assign(n + 1, 0);
    for (const Contact &c : network.pairs)
      {
        ++incidence_start[c.i + 1];
        ++incidence_start[c.other + 1];
      }
    for (const Contact &c : network.wall_contacts)
      ++incidence_start[c.i + 1];
    for (unsigned int i = 0; i < n; ++i)
      incidence_start[i + 1] += incidence_start[i];
    incidence.resize(incidence_start[n]);
    std::vector<unsigned int> fill(incidence_start.begin(), incidence_start.end() - 1);
    for (std::size_t k = 0; k < n_pairs; ++k)
      {
        incidence[fill[network.pairs[k].i]++]     = 2 * k;
        incidence[fill[network.pairs[k].other]++] = 2 * k + 1;
      }
    for (std::size_t k = 0; k < n_walls; ++k)
      incidence[fill[network.wall_contacts[k].i]++] = 2 * n_pairs + k;
    incidence_key = {{network.n_builds, n_pairs, n_walls, n}};
  }

  template <bool with_gradient>
  double
  WorkFunctional::evaluate(const Vector<double>      &theta,
                           Vector<double>            *gradient,
                           ContactState              *state,
                           std::vector<Tensor<1, 3>> *q_out,
                           std::vector<double>       *m_out) const
  {
    ++n_evaluations;
    const unsigned int n        = pack.size();
    const unsigned int rot      = 3 * n;
    const bool         friction = model.frictional();
    const bool         torsion  = friction && model.torsion;
    // |Q| = min(|y|, cap) for the trial force y: sliding at |Q| = cap,
    // within the tolerance.
    const double slide_at   = 1. - model.sliding_tolerance;
    const bool   eq_7b      = model.sliding_count == ContactModel::SlidingCount::eq_7b;
    const auto   is_sliding = [slide_at, eq_7b](const Tensor<1, 3> &y,
                                                const double        cap,
                                                const Tensor<1, 3> &q_p,
                                                const Tensor<1, 3> &u_s) {
      return y.norm() >= slide_at * cap && (!eq_7b || q_p * u_s >= 0);
    };
    // With a ContactState: per grain the normal forces on the six walls
    // and the sum of its contacts' normal forces (a pair's counts for its
    // first grain), summed over the grains in grain order at the end.
    if (state)
      {
        state->coordination.assign(n, 0);
        grain_loads.assign(std::size_t(n) * 7, 0.);
      }

    // Contacts in chunks: each contact stores its energy and gradient
    // contributions, then every grain gathers its contacts' in contact
    // order and Pi is summed over the grains in grain order. The result is
    // the same for any number of threads and of MPI ranks (bit for bit):
    // a rank gathers its own grains, which hold all their contacts, and
    // the per-grain sums go to every rank. A contact's energy counts for
    // its first grain. With a ContactState the chunks run one after the
    // other (the counts are shared).
    const GrainPartition &partition     = network.get_partition();
    const std::size_t     n_pairs       = network.pairs.size();
    const std::size_t     n_walls       = network.wall_contacts.size();
    const std::size_t     n_pair_chunks = (n_pairs + chunk_size - 1) / chunk_size;
    const std::size_t     n_wall_chunks = (n_walls + chunk_size - 1) / chunk_size;
    chunk_sums.assign(n_pair_chunks + n_wall_chunks, ChunkSums());
    pair_results.resize(n_pairs);
    wall_results.resize(n_walls);

    // Grain-grain contacts k in [begin, end).
    const auto pair_chunk = [&](const std::size_t begin,
                                const std::size_t end,
                                ChunkSums        &sums) {
      for (std::size_t k = begin; k < end; ++k)
        {
          const Contact     &c = network.pairs[k];
          const unsigned int i = c.i, j = c.other;
          const Tensor<1, 3> u_i = block(theta, 3 * i), u_j = block(theta, 3 * j);
          const Tensor<1, 3> r =
            (pack.centre[i] + u_i) - (pack.centre[j] + u_j);
          const double d  = r.norm();
          const double h  = pack.radius[i] + pack.radius[j] - d;
          const double h0 = c.h0;
          double       energy = hertz_energy(c.k_n, h) - hertz_energy(c.k_n, h0);
          const Tensor<1, 3> n_ij = r / d;
          Tensor<1, 3>       force_i; // force on i
          Tensor<1, 3>       g;       // dW/dn at fixed u, Omega
          Tensor<1, 3>       moment_i, moment_j;
          if (h > 0)
            {
              const double p = hertz_force(c.k_n, h);
              if (with_gradient)
                {
                  force_i    = p * n_ij;
                  sums.max_p  = std::max(sums.max_p, p);
                  sums.max_dp = std::max(sums.max_dp, std::abs(p - c.p0));
                }
              if (state)
                {
                  if (network.owns(c))
                    {
                      ++state->n_contacts;
                      ++state->n_grain_contacts;
                      grain_loads[7 * std::size_t(i) + 6] += p;
                    }
                  state->coordination[i] += partition.is_owned(i);
                  state->coordination[j] += partition.is_owned(j);
                  state->max_contact_force = std::max(state->max_contact_force, p);
                }
            }
          if (friction && c.p0 > 0 && c.k_s > 0)
            {
              const Tensor<1, 3> omega_i = block(theta, rot + 3 * i) / pack.radius[i];
              const Tensor<1, 3> omega_j = block(theta, rot + 3 * j) / pack.radius[j];
              const Tensor<1, 3> du      = u_i - u_j;
              const Tensor<1, 3> lever_omega = c.lever_i * omega_i + c.lever_j * omega_j;
              const double       du_n        = n_ij * du;
              // u_s = T du + Omega_i x R_ij - Omega_j x R_ji with R_ij = -lever_i n,
              // R_ji = lever_j n.
              const Tensor<1, 3> u_s =
                du - du_n * n_ij - dealii::cross_product_3d(lever_omega, n_ij);

              // Reference load rotated onto the current contact plane.
              const double       q0_norm = c.q0.norm();
              const double       q0_n    = c.q0 * n_ij;
              const Tensor<1, 3> v       = c.q0 - q0_n * n_ij;
              const double       v_norm  = v.norm();
              const Tensor<1, 3> q_p =
                v_norm > 0 ? (q0_norm / v_norm) * v : Tensor<1, 3>();

              const Tensor<1, 3> y = q_p - c.k_s * u_s;
              const Tensor<1, 3> q = capped_force(y, c.q_max);
              energy -= (capped_potential(q_p, c.q_max) - capped_potential(y, c.q_max)) /
                        c.k_s;
              if (state && h > 0 && is_sliding(y, c.q_max, q_p, u_s) && network.owns(c))
                ++state->n_sliding;
              if (q_out)
                (*q_out)[k] = q;
              Tensor<1, 3> force_t; // tangential force on i with the chain rule
              if (with_gradient)
                {
                  force_t = q;
                  g       = -du_n * q - dealii::cross_product_3d(q, lever_omega);
                  if (v_norm > 0)
                    {
                      const Tensor<1, 3> dq    = (q_p - q) / c.k_s;
                      const Tensor<1, 3> v_hat = v / v_norm;
                      const Tensor<1, 3> e =
                        (q0_norm / v_norm) * (dq - (v_hat * dq) * v_hat);
                      g += -q0_n * e - (e * n_ij) * c.q0;
                    }
                  const Tensor<1, 3> n_cross_q = dealii::cross_product_3d(n_ij, q);
                  moment_i = -c.lever_i * n_cross_q;
                  moment_j = -c.lever_j * n_cross_q;
                }

              if (torsion && c.k_t > 0)
                {
                  const Tensor<1, 3> d_omega = omega_i - omega_j;
                  const double       omega_t = d_omega * n_ij;
                  const double       y_t     = c.m0 - c.k_t * omega_t;
                  const double       m       = capped_force(y_t, c.m_max);
                  energy -= (capped_potential(c.m0, c.m_max) -
                             capped_potential(y_t, c.m_max)) /
                            c.k_t;
                  if (m_out)
                    (*m_out)[k] = m;
                  if (with_gradient)
                    {
                      moment_i += m * n_ij;
                      moment_j -= m * n_ij;
                      g += m * d_omega;
                    }
                }
              if (with_gradient)
                {
                  // Chain rule through n = r/|r|: dn/dr = (I - n n)/d.
                  force_t += (g - (g * n_ij) * n_ij) / d;
                  force_i += force_t;
                }
            }
          PairResult &result = pair_results[k];
          result.energy      = energy;
          if (with_gradient)
            {
              result.force      = force_i;
              result.rotation_i = (-1. / pack.radius[i]) * moment_i;
              result.rotation_j = (-1. / pack.radius[j]) * moment_j;
            }
        }
    };

    // Grain-wall contacts: the wall normal is fixed and walls move only
    // along it, so the tangential displacement is linear in theta.
    const auto wall_chunk = [&](const std::size_t begin,
                                const std::size_t end,
                                ChunkSums        &sums) {
      for (std::size_t k = begin; k < end; ++k)
        {
          const Contact     &c   = network.wall_contacts[k];
          const unsigned int i   = c.i, w = c.other;
          const unsigned int ax  = Walls::axis(w);
          const double       sgn = Walls::sign(w);
          const Tensor<1, 3> u_i = block(theta, 3 * i);
          const double       h =
            walls.overlap(w, pack.centre[i] + u_i, pack.radius[i]);
          double energy = hertz_energy(c.k_n, h) - hertz_energy(c.k_n, c.h0);
          Tensor<1, 3> gradient_i, moment_i;
          if (h > 0)
            {
              const double p = hertz_force(c.k_n, h);
              if (with_gradient)
                {
                  gradient_i[ax] -= sgn * p;
                  sums.max_p  = std::max(sums.max_p, p);
                  sums.max_dp = std::max(sums.max_dp, std::abs(p - c.p0));
                }
              if (state) // wall contacts are held by the grain's rank only
                {
                  ++state->n_contacts;
                  ++state->coordination[i];
                  grain_loads[7 * std::size_t(i) + w] += p;
                  grain_loads[7 * std::size_t(i) + 6] += p;
                  state->max_contact_force = std::max(state->max_contact_force, p);
                }
            }
          if (friction && c.p0 > 0 && c.k_s > 0)
            {
              Tensor<1, 3> n_w;
              n_w[ax]                    = sgn;
              const Tensor<1, 3> omega_i = block(theta, rot + 3 * i) / pack.radius[i];
              Tensor<1, 3>       u_s     = u_i - (u_i * n_w) * n_w -
                                 c.lever_i * dealii::cross_product_3d(omega_i, n_w);
              const Tensor<1, 3> y = c.q0 - c.k_s * u_s;
              const Tensor<1, 3> q = capped_force(y, c.q_max);
              energy -= (capped_potential(c.q0, c.q_max) - capped_potential(y, c.q_max)) /
                        c.k_s;
              if (state && h > 0 && is_sliding(y, c.q_max, c.q0, u_s))
                ++state->n_sliding;
              if (q_out)
                (*q_out)[n_pairs + k] = q;
              if (with_gradient)
                {
                  gradient_i -= q;
                  moment_i = -c.lever_i * dealii::cross_product_3d(n_w, q);
                }
              if (torsion && c.k_t > 0)
                {
                  const double omega_t = omega_i * n_w;
                  const double y_t     = c.m0 - c.k_t * omega_t;
                  const double m       = capped_force(y_t, c.m_max);
                  energy -= (capped_potential(c.m0, c.m_max) -
                             capped_potential(y_t, c.m_max)) /
                            c.k_t;
                  if (m_out)
                    (*m_out)[n_pairs + k] = m;
                  if (with_gradient)
                    moment_i += m * n_w;
                }
            }
          wall_results[k].energy = energy;
          if (with_gradient)
            {
              wall_results[k].gradient = gradient_i;
              wall_results[k].rotation = (-1. / pack.radius[i]) * moment_i;
            }
        }
    };

    const auto run_chunks = [&](const std::size_t begin, const std::size_t end) {
      for (std::size_t chunk = begin; chunk < end; ++chunk)
        if (chunk < n_pair_chunks)
          pair_chunk(chunk * chunk_size,
                     std::min((chunk + 1) * chunk_size, n_pairs),
                     chunk_sums[chunk]);
        else
          {
            const std::size_t w = chunk - n_pair_chunks;
            wall_chunk(w * chunk_size,
                       std::min((w + 1) * chunk_size, n_walls),
                       chunk_sums[chunk]);
          }
    };
    if (state == nullptr)
      dealii::parallel::apply_to_subranges(std::size_t(0), chunk_sums.size(), run_chunks, 1);
    else
      run_chunks(0, chunk_sums.size());

    double max_p = 0, max_dp = 0;
    for (const ChunkSums &sums : chunk_sums)
      {
        max_p  = std::max(max_p, sums.max_p);
        max_dp = std::max(max_dp, sums.max_dp);
      }

    // Each own grain gathers its contacts' contributions in contact order:
    // per grain [dPi/du, dPi/d(Omega R), its share of Pi] with a gradient,
    // else only the share of Pi.
    update_incidence();
    const unsigned int components = with_gradient ? 7 : 1;
    grain_values.resize(std::size_t(n) * components);
    const std::size_t                two_pairs = 2 * n_pairs;
    const std::vector<unsigned int> &owned     = partition.owned_grains();
    const auto gather = [&](const unsigned int begin, const unsigned int end) {
      for (unsigned int k = begin; k < end; ++k)
        {
          const unsigned int i = owned[k];
          Tensor<1, 3>       g_u, g_rot;
          double             energy = 0;
          for (unsigned int e = incidence_start[i]; e < incidence_start[i + 1]; ++e)
            {
              const std::size_t entry = incidence[e];
              if (entry < two_pairs)
                {
                  const PairResult &result = pair_results[entry / 2];
                  if (entry % 2 == 0)
                    {
                      energy += result.energy;
                      g_u -= result.force;
                      g_rot += result.rotation_i;
                    }
                  else
                    {
                      g_u += result.force;
                      g_rot += result.rotation_j;
                    }
                }
              else
                {
                  const WallResult &result = wall_results[entry - two_pairs];
                  energy += result.energy;
                  g_u += result.gradient;
                  g_rot += result.rotation;
                }
            }
          if (model.gravity) // weight, along -z
            {
              energy += pack.mass(i) * model.gravity_acceleration * theta[3 * i + 2];
              g_u[2] += pack.mass(i) * model.gravity_acceleration;
            }
          double *values = &grain_values[std::size_t(i) * components];
          if (with_gradient)
            for (unsigned int d = 0; d < 3; ++d)
              {
                values[d]     = g_u[d];
                values[3 + d] = g_rot[d];
              }
          values[components - 1] = energy;
        }
    };
    if (state == nullptr)
      dealii::parallel::apply_to_subranges(0u, static_cast<unsigned int>(owned.size()), gather, 64);
    else
      gather(0, owned.size());
    partition.gather(grain_values, components);

    double pi = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double *values = &grain_values[std::size_t(i) * components];
        pi += values[components - 1];
        if (with_gradient)
          for (unsigned int d = 0; d < 3; ++d)
            {
              (*gradient)[3 * i + d]       = values[d];
              (*gradient)[rot + 3 * i + d] = values[3 + d];
            }
      }
    if (with_gradient)
      {
        last_max_contact_force = partition.max(max_p);
        last_max_force_change  = partition.max(max_dp);
      }
    if (state)
      {
        state->n_contacts       = partition.sum(state->n_contacts);
        state->n_grain_contacts = partition.sum(state->n_grain_contacts);
        state->n_sliding        = partition.sum(state->n_sliding);
        state->max_contact_force = partition.max(state->max_contact_force);
        partition.sum(state->coordination);
        partition.gather(grain_loads, 7);
        double sum_p = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            for (unsigned int w = 0; w < 6; ++w)
              state->wall_force[w] += grain_loads[7 * std::size_t(i) + w];
            sum_p += grain_loads[7 * std::size_t(i) + 6];
          }
        if (state->n_contacts > 0)
          state->mean_normal_force = sum_p / state->n_contacts;
      }
    return pi;
  }

  double
  WorkFunctional::update_caps(const Vector<double> &theta,
                              ContactNetwork       &network_to_update) const
  {
    double     largest_change = 0, largest_cap = 0;
    const auto set = [&](Contact &c, const double h, const double r_star, const double mu) {
      if (!(c.p0 > 0 && c.k_s > 0))
        return;
      const double p     = hertz_force(c.k_n, h);
      const double a     = h > 0 ? std::sqrt(r_star * h) : 0.;
      const double q_max = mu * p;
      const double m_max = c.k_t > 0 ? torsion_cap(a, mu, p) : 0.;
      largest_change     = std::max(largest_change, std::abs(q_max - c.q_max));
      largest_cap        = std::max(largest_cap, q_max);
      c.q_max            = q_max;
      c.m_max            = m_max;
    };
    for (Contact &c : network_to_update.pairs)
      {
        const unsigned int i = c.i, j = c.other;
        const double       d = ((pack.centre[i] + block(theta, 3 * i)) -
                          (pack.centre[j] + block(theta, 3 * j)))
                           .norm();
        set(c,
            pack.radius[i] + pack.radius[j] - d,
            effective_radius(pack.radius[i], pack.radius[j]),
            model.friction);
      }
    for (Contact &c : network_to_update.wall_contacts)
      set(c,
          walls.overlap(c.other, pack.centre[c.i] + block(theta, 3 * c.i), pack.radius[c.i]),
          pack.radius[c.i],
          model.wall_friction);
    largest_change = network.get_partition().max(largest_change);
    largest_cap    = network.get_partition().max(largest_cap);
    return largest_cap > 0 ? largest_change / largest_cap : 0.;
  }

  void
  WorkFunctional::freeze_stick_slip(const Vector<double> &theta,
                                    ContactNetwork       &network_to_update) const
  {
    // |Q| = min(|y|, cap): below the cap, the trial force y sticks.
    const std::size_t         n_pairs = network.pairs.size();
    std::vector<Tensor<1, 3>> q(n_pairs + network.wall_contacts.size());
    std::vector<double>       m(q.size(), 0.);
    evaluate<false>(theta, nullptr, nullptr, &q, &m);
    constexpr double unlimited = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < q.size(); ++k)
      {
        Contact &c = k < n_pairs ? network_to_update.pairs[k] :
                                   network_to_update.wall_contacts[k - n_pairs];
        if (!(c.p0 > 0 && c.k_s > 0))
          continue;
        if (q[k].norm() < c.q_max)
          c.q_max = unlimited;
        if (c.k_t > 0 && std::abs(m[k]) < c.m_max)
          c.m_max = unlimited;
      }
  }

  void
  WorkFunctional::commit(const Vector<double> &theta,
                         Pack                 &pack_to_move,
                         ContactNetwork       &network_to_update,
                         Walls                &reference_walls) const
  {
    const std::size_t n_pairs = network.pairs.size();
    const std::size_t n_all   = n_pairs + network.wall_contacts.size();
    std::vector<Tensor<1, 3>> q(n_all);
    std::vector<double>       m(n_all, 0.);
    evaluate<false>(theta, nullptr, nullptr, &q, &m);
    for (std::size_t k = 0; k < n_pairs; ++k)
      {
        network_to_update.pairs[k].q0 = q[k];
        network_to_update.pairs[k].m0 = m[k];
      }
    for (std::size_t k = 0; k < network.wall_contacts.size(); ++k)
      {
        network_to_update.wall_contacts[k].q0 = q[n_pairs + k];
        network_to_update.wall_contacts[k].m0 = m[n_pairs + k];
      }
    for (unsigned int i = 0; i < pack_to_move.size(); ++i)
      pack_to_move.centre[i] += block(theta, 3 * i);
    reference_walls = walls;
    network_to_update.update_reference(pack_to_move, reference_walls, model);
  }

  template double
  WorkFunctional::evaluate<true>(const Vector<double> &,
                                 Vector<double> *,
                                 ContactState *,
                                 std::vector<Tensor<1, 3>> *,
                                 std::vector<double> *) const;
  template double
  WorkFunctional::evaluate<false>(const Vector<double> &,
                                  Vector<double> *,
                                  ContactState *,
                                  std::vector<Tensor<1, 3>> *,
                                  std::vector<double> *) const;
} // namespace sable::qusgm
