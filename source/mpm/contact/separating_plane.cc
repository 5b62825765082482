#include <sable/mpm/contact/separating_plane.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace sable::mpm
{
  namespace
  {
    /// Ridge penalty on beta, in cell units with each cloud weighing 1/2.
    /// Clouds that do not overlap have no finite best plane; the penalty
    /// stops |beta| near 30 per cell, where the fitted plane has turned to
    /// within a few degrees of the widest gap between them (the limit of a
    /// vanishing penalty): a block's corner on a plane 3 degrees, two faces
    /// ending flush 0.
    constexpr double ridge_penalty = 1e-6;

    /// Newton's method stops when the normal turns less than this (radians)
    /// in one step, or after max_iterations (twelve suffice for the clouds
    /// of a contact node).
    constexpr double       turn_tolerance = 1e-4;
    constexpr unsigned int max_iterations = 30;

    /// Solve A x = b in place for a symmetric positive definite A (Cholesky).
    template <unsigned int n>
    std::array<double, n>
    solve_spd(std::array<std::array<double, n>, n> A, std::array<double, n> b)
    {
      for (unsigned int j = 0; j < n; ++j)
        {
          double d = A[j][j];
          for (unsigned int k = 0; k < j; ++k)
            d -= A[j][k] * A[j][k];
          A[j][j] = std::sqrt(std::max(d, 1e-300));
          for (unsigned int i = j + 1; i < n; ++i)
            {
              double s = A[i][j];
              for (unsigned int k = 0; k < j; ++k)
                s -= A[i][k] * A[j][k];
              A[i][j] = s / A[j][j];
            }
        }
      for (unsigned int i = 0; i < n; ++i)
        {
          for (unsigned int k = 0; k < i; ++k)
            b[i] -= A[i][k] * b[k];
          b[i] /= A[i][i];
        }
      for (unsigned int i = n; i-- > 0;)
        {
          for (unsigned int k = i + 1; k < n; ++k)
            b[i] -= A[k][i] * b[k];
          b[i] /= A[i][i];
        }
      return b;
    }
  } // namespace

  template <int dim>
  Tensor<1, dim>
  separating_normal(const std::vector<NodeSample<dim>> &inside,
                    const std::vector<NodeSample<dim>> &outside,
                    const Point<dim> &                  origin,
                    const Tensor<1, dim> &              cell_size)
  {
    constexpr unsigned int n = dim + 1;
    using Vector             = std::array<double, n>;
    using Matrix             = std::array<Vector, n>;

    double inside_weight = 0, outside_weight = 0;
    for (const NodeSample<dim> &s : inside)
      inside_weight += s.weight;
    for (const NodeSample<dim> &s : outside)
      outside_weight += s.weight;
    if (!(inside_weight > 0) || !(outside_weight > 0))
      return Tensor<1, dim>();

    // each point as (xi, 1), its label (1 inside) and its scaled weight;
    // kept per thread, as the fits run node after node
    struct Row
    {
      Vector z;
      double label, weight;
    };
    thread_local std::vector<Row> rows;
    rows.clear();
    const auto add_rows = [&](const std::vector<NodeSample<dim>> &cloud,
                              const double                        label,
                              const double                        total) {
      for (const NodeSample<dim> &s : cloud)
        {
          Row row;
          for (unsigned int d = 0; d < dim; ++d)
            row.z[d] = (s.location[d] - origin[d]) / cell_size[d];
          row.z[dim] = 1;
          row.label  = label;
          row.weight = 0.5 * s.weight / total;
          rows.push_back(row);
        }
    };
    add_rows(inside, 1., inside_weight);
    add_rows(outside, 0., outside_weight);

    // the objective at theta; each row's f and exp(-|f|) go to @p at,
    // from which the gradient at theta needs no exponential of its own
    struct Evaluation
    {
      double f, decay;
    };
    thread_local std::vector<Evaluation> current, trial_evaluation;
    const auto objective = [&](const Vector &theta, std::vector<Evaluation> &at) {
      at.resize(rows.size());
      double value = 0;
      for (unsigned int i = 0; i < rows.size(); ++i)
        {
          const Row &row = rows[i];
          double     f   = 0;
          for (unsigned int k = 0; k < n; ++k)
            f += theta[k] * row.z[k];
          // log(1 + exp(f)) without overflow
          const double decay = std::exp(-std::abs(f));
          value += row.weight * (std::max(f, 0.) + std::log1p(decay) - row.label * f);
          at[i] = {f, decay};
        }
      for (unsigned int d = 0; d < dim; ++d)
        value += 0.5 * ridge_penalty * theta[d] * theta[d];
      return value;
    };
    const auto direction_of = [](const Vector &theta) {
      Tensor<1, dim> beta;
      for (unsigned int d = 0; d < dim; ++d)
        beta[d] = theta[d];
      const double norm = beta.norm();
      return norm > 0 ? Tensor<1, dim>(beta / norm) : beta;
    };

    Vector theta{};
    double value = objective(theta, current);
    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        Vector gradient{};
        Matrix hessian{};
        for (unsigned int i = 0; i < rows.size(); ++i)
          {
            const Row &row        = rows[i];
            const auto [f, decay] = current[i];
            // the logistic function 1/(1 + exp(-f)) from exp(-|f|)
            const double p = f >= 0 ? 1. / (1. + decay) : decay / (1. + decay);
            const double r = row.weight * (p - row.label);
            const double h = row.weight * p * (1. - p);
            for (unsigned int a = 0; a < n; ++a)
              {
                gradient[a] += r * row.z[a];
                for (unsigned int b = 0; b <= a; ++b)
                  hessian[a][b] += h * row.z[a] * row.z[b];
              }
          }
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int b = 0; b < a; ++b)
            hessian[b][a] = hessian[a][b];
        for (unsigned int d = 0; d < dim; ++d)
          {
            gradient[d] += ridge_penalty * theta[d];
            hessian[d][d] += ridge_penalty;
          }
        // the offset has no penalty; a trace keeps its pivot positive
        hessian[dim][dim] += 1e-12;
        const Vector step = solve_spd<n>(hessian, gradient);

        // backtracking: the objective is convex, so a short enough step
        // along the Newton direction descends
        double slope = 0;
        for (unsigned int k = 0; k < n; ++k)
          slope += gradient[k] * step[k];
        double length = 1;
        Vector trial;
        double trial_value = value;
        for (unsigned int halving = 0; halving < 20; ++halving, length *= 0.5)
          {
            for (unsigned int k = 0; k < n; ++k)
              trial[k] = theta[k] - length * step[k];
            trial_value = objective(trial, trial_evaluation);
            if (trial_value <= value - 1e-4 * length * slope)
              break;
          }
        const Tensor<1, dim> before = direction_of(theta);
        theta                       = trial;
        value                       = trial_value;
        std::swap(current, trial_evaluation);
        if (iteration > 0 && (direction_of(theta) - before).norm() < turn_tolerance)
          break;
      }

    // f grows into @p inside: the outward normal is -grad f in real space
    Tensor<1, dim> normal;
    for (unsigned int d = 0; d < dim; ++d)
      normal[d] = -theta[d] / cell_size[d];
    const double norm = normal.norm();
    return norm > 0 ? Tensor<1, dim>(normal / norm) : Tensor<1, dim>();
  }

  template Tensor<1, 2>
  separating_normal(const std::vector<NodeSample<2>> &,
                    const std::vector<NodeSample<2>> &,
                    const Point<2> &,
                    const Tensor<1, 2> &);
  template Tensor<1, 3>
  separating_normal(const std::vector<NodeSample<3>> &,
                    const std::vector<NodeSample<3>> &,
                    const Point<3> &,
                    const Tensor<1, 3> &);
} // namespace sable::mpm
