#include <deal.II/base/parallel.h>

#include <sable/qusgm/minimizer.h>

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <iomanip>
#include <limits>

namespace sable::qusgm
{
  namespace
  {
    /**
     * Scalar product in fixed blocks of 4096 entries, threaded over the
     * blocks and summed in block order, so the result does not depend on
     * the number of threads (deal.II's Vector reductions split by it).
     */
    double
    dot(const Vector<double> &a, const Vector<double> &b)
    {
      constexpr std::size_t block    = 4096;
      const std::size_t     n        = a.size();
      const std::size_t     n_blocks = (n + block - 1) / block;
      std::vector<double>   partial(n_blocks, 0.);
      const auto            sum_blocks = [&](const std::size_t begin, const std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
          {
            double sum = 0;
            for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i)
              sum += a[i] * b[i];
            partial[k] = sum;
          }
      };
      if (n_blocks > 1)
        dealii::parallel::apply_to_subranges(std::size_t(0), n_blocks, sum_blocks, 1);
      else
        sum_blocks(0, n_blocks);
      double sum = 0;
      for (const double p : partial)
        sum += p;
      return sum;
    }
  } // namespace

  IncrementSolver::IncrementSolver(Pack                    &pack,
                                   Walls                   &reference_walls,
                                   ContactNetwork          &network,
                                   const ContactModel      &model,
                                   const MinimizerSettings &settings)
    : pack(pack)
    , reference_walls(reference_walls)
    , network(network)
    , model(model)
    , settings(settings)
    , functional(pack, network, model)
  {}

  void
  IncrementSolver::move_walls(const std::array<double, 6> &delta,
                              Vector<double>              &theta)
  {
    // Affine guess: the field that carries the old walls onto the new ones
    // (the paper's eq. A1 for symmetric wall moves).
    for (unsigned int a = 0; a < 3; ++a)
      {
        const double lower = walls.position[a], length = walls.length(a);
        if (delta[a] == 0 && delta[a + 3] == 0)
          continue;
        for (unsigned int i = 0; i < pack.size(); ++i)
          {
            const double x = pack.centre[i][a] + theta[3 * i + a];
            theta[3 * i + a] +=
              delta[a] + (delta[a + 3] - delta[a]) * (x - lower) / length;
          }
      }
    for (unsigned int w = 0; w < 6; ++w)
      walls.position[w] += delta[w];
    functional.set_walls(walls);
  }

  void
  IncrementSolver::maybe_rebuild(const Vector<double> &theta,
                                 IncrementResult      &result)
  {
    functional.positions(theta, positions);
    const double cap_motion =
      settings.displacement_cap * pack.max_radius() * 2.;
    if (network.needs_rebuild(positions, walls, cap_motion))
      {
        network.build(pack,
                      reference_walls,
                      positions,
                      walls,
                      model,
                      settings.skin * pack.mean_radius());
        ++result.rebuilds;
      }
  }

  double
  IncrementSolver::max_step(const Vector<double> &direction) const
  {
    const unsigned int n     = pack.size();
    double             ratio = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        double m = 0;
        for (unsigned int part = 0; part < 2; ++part)
          {
            const unsigned int o = part * 3 * n + 3 * i;
            m                    = std::max(m,
                         direction[o] * direction[o] +
                           direction[o + 1] * direction[o + 1] +
                           direction[o + 2] * direction[o + 2]);
          }
        ratio = std::max(ratio, std::sqrt(m) / pack.radius[i]);
      }
    return ratio > 0 ? settings.displacement_cap / ratio :
                       std::numeric_limits<double>::max();
  }

  IncrementResult
  IncrementSolver::apply(const std::array<double, 6> &wall_displacement,
                         std::ostream                *log,
                         const Vector<double>        *guess)
  {
    IncrementResult    result;
    const unsigned int n = pack.size();
    const unsigned int evaluations_before = functional.n_evaluations;
    walls                                 = reference_walls;
    functional.set_walls(walls);
    Vector<double> theta(6 * n), gradient(6 * n), previous_gradient(6 * n),
      direction(6 * n), trial(6 * n), trial_gradient(6 * n);

    const unsigned int n_sub = std::max(1u, settings.sub_increments);
    std::array<double, 6> sub_delta;
    for (unsigned int w = 0; w < 6; ++w)
      sub_delta[w] = wall_displacement[w] / n_sub;
    bool any_motion = false;
    for (unsigned int w = 0; w < 6; ++w)
      any_motion |= wall_displacement[w] != 0;
    unsigned int applied = 0;
    if (any_motion && guess && n_sub == 1 && guess->size() == theta.size())
      {
        // Predictor: the walls move at once, the grains as in the guess.
        for (unsigned int w = 0; w < 6; ++w)
          walls.position[w] += sub_delta[w];
        functional.set_walls(walls);
        theta = *guess;
        ++applied;
      }
    else if (any_motion)
      {
        move_walls(sub_delta, theta);
        ++applied;
      }
    else
      applied = n_sub;
    maybe_rebuild(theta, result);
    if (model.frictional() && model.stick_slip == ContactModel::StickSlip::per_increment)
      functional.freeze_stick_slip(theta, network);

    // Scale of the paper's gradient test: N (E R^2)^2.
    const double e_r2 = pack.mean_youngs_modulus() * std::pow(pack.mean_radius(), 2);
    const double gradient_scale = n * e_r2 * e_r2;

    if (log)
      *log << "# iteration pi gradient_norm step active_contacts sliding_contacts\n";

    // With caps from the current normal load, equilibrium and caps are
    // found in turn: solve, set the caps to mu P at the solution, solve
    // again from there, until no cap changes by more than 1e-3 of the
    // largest.
    const bool   update_caps = model.frictional() &&
                             model.friction_cap == ContactModel::FrictionCap::current;
    constexpr unsigned int max_cap_passes  = 20;
    unsigned int           first_iteration = 0;
    double                 value           = 0;
    for (unsigned int pass = 0;; ++pass)
      {
        result.converged = false;
        result.stopped_by.clear();
        value = functional.value_and_gradient(theta, gradient);
        double previous_value = value;
        bool   restart        = true;
        std::deque<std::pair<Vector<double>, Vector<double>>> memory;
        unsigned int since_sub_increment = 0;
        double       step                = 0;
        bool         tracking_progress   = false;
        double       best_residual = 0, best_value = 0;

        for (unsigned int k = first_iteration;; ++k)
          {
            // Wall sub-increment every k_inc iterations.
            if (applied < n_sub &&
                since_sub_increment >= settings.iterations_per_sub_increment)
              {
                move_walls(sub_delta, theta);
                ++applied;
                since_sub_increment = 0;
                maybe_rebuild(theta, result);
                value   = functional.value_and_gradient(theta, gradient);
                restart = true;
                memory.clear();
              }
            ++since_sub_increment;

            const double g2       = dot(gradient, gradient);
            const double residual = WorkFunctional::max_residual(gradient);
            if (log)
              {
                const ContactState s = functional.state(theta);
                *log << k << ' ' << std::setprecision(12) << value << ' '
                     << std::sqrt(g2) << ' ' << step << ' ' << s.n_contacts << ' '
                     << s.n_sliding << '\n';
              }

            // Stopping tests, once the walls have reached their target.
            if (applied == n_sub)
              {
                // Progress: a new lowest residual (by 1%) or Pi (beyond round-off).
                if (!tracking_progress || residual < 0.99 * best_residual ||
                    value < best_value - 1e-12 * std::abs(best_value))
                  {
                    best_residual        = tracking_progress ? std::min(best_residual, residual) :
                                                               residual;
                    best_value           = tracking_progress ? std::min(best_value, value) : value;
                    tracking_progress    = true;
                    result.last_progress = k;
                  }
                std::string reason;
                if (settings.force_tolerance > 0 &&
                    residual <=
                      settings.force_tolerance * functional.last_max_contact_force)
                  reason = "force";
                else if (settings.increment_force_tolerance > 0 &&
                         residual <= settings.increment_force_tolerance *
                                       functional.last_max_force_change)
                  reason = "increment force";
                else if (settings.gradient_tolerance > 0 &&
                         g2 < settings.gradient_tolerance * gradient_scale)
                  reason = "gradient";
                else if (settings.energy_tolerance > 0 && k > 0 &&
                         since_sub_increment > 1 && !restart &&
                         previous_value - value <
                           settings.energy_tolerance * std::abs(previous_value))
                  reason = "energy";
                else if (g2 == 0)
                  reason = "zero gradient";
                if (!reason.empty())
                  {
                    result.converged  = true;
                    result.stopped_by = reason;
                    result.iterations = k;
                    break;
                  }
                if (k >= settings.max_iterations)
                  {
                    result.stopped_by = "iteration limit";
                    result.iterations = k;
                    break;
                  }
                if (settings.stagnation_window > 0 &&
                    k >= result.last_progress + settings.stagnation_window)
                  {
                    result.stopped_by = "stagnation";
                    result.iterations = k;
                    break;
                  }
              }

            // Search direction.
            bool steepest =
              restart || (settings.method == MinimizerSettings::Method::nlcg &&
                          settings.steepest_descent_restart > 0 &&
                          k % settings.steepest_descent_restart == 0);
            if (settings.method == MinimizerSettings::Method::nlcg)
              {
                if (steepest)
                  direction.equ(-1., gradient);
                else
                  {
                    const double beta = g2 / dot(previous_gradient, previous_gradient);
                    direction *= beta;
                    direction.add(-1., gradient);
                  }
              }
            else
              {
                // L-BFGS two-loop recursion.
                direction.equ(-1., gradient);
                std::vector<double> alpha(memory.size());
                for (int m = int(memory.size()) - 1; m >= 0; --m)
                  {
                    const auto &[s, y] = memory[m];
                    alpha[m]           = dot(s, direction) / dot(s, y);
                    direction.add(-alpha[m], y);
                  }
                if (!memory.empty())
                  {
                    const auto &[s, y] = memory.back();
                    direction *= dot(s, y) / dot(y, y);
                  }
                for (unsigned int m = 0; m < memory.size(); ++m)
                  {
                    const auto  &[s, y] = memory[m];
                    const double b      = dot(y, direction) / dot(s, y);
                    direction.add(alpha[m] - b, s);
                  }
              }
            double slope = dot(direction, gradient);
            if (!(slope < 0))
              {
                direction.equ(-1., gradient);
                slope = -g2;
                memory.clear();
                steepest = true;
              }
            const double alpha_max = max_step(direction);

            previous_gradient = gradient;
            previous_value    = value;
            double alpha      = 0;
            if (settings.method == MinimizerSettings::Method::nlcg)
              {
                // Exact minimisation along the direction on [0, alpha_max].
                auto phi = [&](const double a) {
                  trial = theta;
                  trial.add(a, direction);
                  return functional.value(trial);
                };
                std::uintmax_t max_iter = 100;
                const auto     best     = boost::math::tools::brent_find_minima(
                  phi, 0., alpha_max, int(settings.line_search_bits), max_iter);
                alpha = best.first;
                if (!(best.second < value))
                  {
                    // Near the minimum Pi is flat to round-off along the line;
                    // find the zero of the directional derivative instead on
                    // [0, alpha_max].
                    alpha = 0;
                    auto dphi = [&](const double a) {
                      trial = theta;
                      trial.add(a, direction);
                      functional.value_and_gradient(trial, trial_gradient);
                      return dot(trial_gradient, direction);
                    };
                    const double d_hi = dphi(alpha_max);
                    if (d_hi <= 0)
                      alpha = alpha_max;
                    else
                      {
                        // TOMS 748 on the bracket [0, alpha_max] (slope < 0 <
                        // d_hi); a derivative below 1e-6 |slope| counts as its
                        // zero. The answer is the step with the smallest
                        // |derivative| evaluated.
                        double best_d = std::numeric_limits<double>::infinity();
                        auto   root   = [&](const double a) {
                          const double d = dphi(a);
                          if (std::abs(d) < best_d)
                            {
                              best_d = std::abs(d);
                              alpha  = a;
                            }
                          return std::abs(d) < 1e-6 * std::abs(slope) ? 0. : d;
                        };
                        const auto bracket_closed = [](const double a, const double b) {
                          return b - a <= 4 * std::numeric_limits<double>::epsilon() * b;
                        };
                        std::uintmax_t evaluations = 60;
                        boost::math::tools::toms748_solve(
                          root, 0., alpha_max, slope, d_hi, bracket_closed, evaluations);
                      }
                  }
                if (alpha > 0)
                  {
                    theta.add(alpha, direction);
                    maybe_rebuild(theta, result);
                    value = functional.value_and_gradient(theta, gradient);
                  }
              }
            else
              {
                // Weak Wolfe conditions by bisection (Lewis & Overton).
                const double c1 = 1e-4, c2 = 0.9;
                double       lo = 0, hi = std::numeric_limits<double>::infinity();
                double a = memory.empty() ? alpha_max : std::min(1., alpha_max);
                double best_alpha = 0, best_value = value;
                for (unsigned int ls = 0; ls < 50; ++ls)
                  {
                    trial = theta;
                    trial.add(a, direction);
                    const double f = functional.value_and_gradient(trial, trial_gradient);
                    if (f < best_value)
                      {
                        best_value = f;
                        best_alpha = a;
                      }
                    const double d = dot(trial_gradient, direction);
                    // Hager-Zhang's approximate Armijo condition takes over
                    // where Pi is flat to round-off.
                    const bool decrease =
                      f <= value + c1 * a * slope ||
                      (std::abs(f - value) <= 1e-12 * std::abs(value) &&
                       d <= (2 * c1 - 1) * slope);
                    if (!decrease)
                      hi = a;
                    else if (d < c2 * slope && a < alpha_max)
                      lo = a;
                    else
                      {
                        best_alpha = a;
                        best_value = std::min(f, best_value);
                        break;
                      }
                    a = std::isfinite(hi) ? 0.5 * (lo + hi) : std::min(2. * a, alpha_max);
                  }
                alpha = best_alpha;
                if (alpha > 0)
                  {
                    theta.add(alpha, direction);
                    const double f = functional.value_and_gradient(theta, trial_gradient);
                    // Curvature pair for the inverse-Hessian model.
                    Vector<double> s(direction);
                    s *= alpha;
                    Vector<double> y(trial_gradient);
                    y -= gradient;
                    if (dot(s, y) > 1e-12 * std::sqrt(dot(s, s) * dot(y, y)))
                      {
                        memory.emplace_back(std::move(s), std::move(y));
                        if (memory.size() > settings.lbfgs_history)
                          memory.pop_front();
                      }
                    value    = f;
                    gradient = trial_gradient;
                    functional.positions(theta, positions);
                    if (network.needs_rebuild(positions, walls,
                                              settings.displacement_cap *
                                                pack.max_radius() * 2.))
                      {
                        maybe_rebuild(theta, result);
                        value = functional.value_and_gradient(theta, gradient);
                      }
                  }
              }
            step = alpha;
            if (alpha == 0)
              {
                if (steepest)
                  {
                    // No descent even along -grad: converged to round-off.
                    result.converged  = false;
                    result.stopped_by = "line search stalled";
                    result.iterations = k;
                    if (applied == n_sub)
                      break;
                  }
                restart = true;
                memory.clear();
                continue;
              }
            restart = false;
          }

        if (!update_caps || !result.converged || pass + 1 >= max_cap_passes ||
            functional.update_caps(theta, network) <= 1e-3)
          break;
        first_iteration = result.iterations + 1;
      }

    last_state               = functional.state(theta);
    result.value             = value;
    result.gradient_norm     = std::sqrt(dot(gradient, gradient));
    result.residual          = last_state.max_residual;
    result.max_contact_force = last_state.max_contact_force;
    result.evaluations       = functional.n_evaluations - evaluations_before;
    last_solution            = theta;
    functional.commit(theta, pack, network, reference_walls);
    return result;
  }
} // namespace sable::qusgm
