#include <deal.II/base/symmetric_tensor.h>

#include <sable/mpm/contact/separating_plane.h>

#include <algorithm>
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
    /// of a contact node). Looser, the normal jitters from step to step by
    /// the tolerance, and a settling pile's disks crept into each other
    /// (half a point spacing at 1e-3 and 1e-2, doc/validation.md).
    constexpr double       turn_tolerance = 1e-4;
    constexpr unsigned int max_iterations = 30;
  } // namespace

  template <int dim>
  Tensor<1, dim>
  separating_normal(const std::vector<NodeSample<dim>> &inside,
                    const std::vector<NodeSample<dim>> &outside,
                    const Point<dim> &                  origin,
                    const Tensor<1, dim> &              cell_size)
  {
    double inside_weight = 0, outside_weight = 0;
    for (const NodeSample<dim> &s : inside)
      inside_weight += s.weight;
    for (const NodeSample<dim> &s : outside)
      outside_weight += s.weight;
    if (!(inside_weight > 0) || !(outside_weight > 0))
      return Tensor<1, dim>();

    // each point in cell units, its label (1 inside) and its scaled
    // weight; kept per thread, as the fits run node after node
    struct Row
    {
      Tensor<1, dim> xi;
      double         label, weight;
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
            row.xi[d] = (s.location[d] - origin[d]) / cell_size[d];
          row.label  = label;
          row.weight = 0.5 * s.weight / total;
          rows.push_back(row);
        }
    };
    add_rows(inside, 1., inside_weight);
    add_rows(outside, 0., outside_weight);

    // the objective at (beta, c); each row's f and exp(-|f|) go to @p at,
    // from which the gradient there needs no exponential of its own
    struct Evaluation
    {
      double f, decay;
    };
    thread_local std::vector<Evaluation> current, trial_evaluation;
    const auto objective = [&](const Tensor<1, dim> &beta, const double c, std::vector<Evaluation> &at) {
      at.resize(rows.size());
      double value = 0;
      for (unsigned int i = 0; i < rows.size(); ++i)
        {
          const Row &  row = rows[i];
          const double f   = beta * row.xi + c;
          // log(1 + exp(f)) without overflow
          const double decay = std::exp(-std::abs(f));
          value += row.weight * (std::max(f, 0.) + std::log1p(decay) - row.label * f);
          at[i] = {f, decay};
        }
      return value + 0.5 * ridge_penalty * beta.norm_square();
    };
    const auto direction_of = [](const Tensor<1, dim> &beta) {
      const double norm = beta.norm();
      return norm > 0 ? Tensor<1, dim>(beta / norm) : beta;
    };

    Tensor<1, dim> beta;
    double         c     = 0;
    double         value = objective(beta, c, current);
    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        // gradient and Hessian, split into the parts of beta and of c:
        // [A b; b^T d] (A with the penalty)
        Tensor<1, dim>          gradient_beta, b;
        double                  gradient_c = 0, d = 0;
        SymmetricTensor<2, dim> A;
        for (unsigned int i = 0; i < rows.size(); ++i)
          {
            const Row &row        = rows[i];
            const auto [f, decay] = current[i];
            // the logistic function 1/(1 + exp(-f)) from exp(-|f|)
            const double p = f >= 0 ? 1. / (1. + decay) : decay / (1. + decay);
            const double r = row.weight * (p - row.label);
            const double h = row.weight * p * (1. - p);
            gradient_beta += r * row.xi;
            gradient_c += r;
            A += h * symmetrize(outer_product(row.xi, row.xi));
            b += h * row.xi;
            d += h;
          }
        gradient_beta += ridge_penalty * beta;
        A += ridge_penalty * unit_symmetric_tensor<dim>();
        // the offset has no penalty; a trace keeps d positive
        d += 1e-12;
        // the Newton step with c eliminated (Schur complement)
        const Tensor<1, dim> step_beta =
          invert(A - symmetrize(outer_product(b, b)) / d) * (gradient_beta - (gradient_c / d) * b);
        const double step_c = (gradient_c - b * step_beta) / d;

        // backtracking: the objective is convex, so a short enough step
        // along the Newton direction descends
        const double   slope  = gradient_beta * step_beta + gradient_c * step_c;
        double         length = 1;
        Tensor<1, dim> trial_beta;
        double         trial_c = c, trial_value = value;
        for (unsigned int halving = 0; halving < 20; ++halving, length *= 0.5)
          {
            trial_beta  = beta - length * step_beta;
            trial_c     = c - length * step_c;
            trial_value = objective(trial_beta, trial_c, trial_evaluation);
            if (trial_value <= value - 1e-4 * length * slope)
              break;
          }
        const Tensor<1, dim> before = direction_of(beta);
        beta                        = trial_beta;
        c                           = trial_c;
        value                       = trial_value;
        std::swap(current, trial_evaluation);
        if (iteration > 0 && (direction_of(beta) - before).norm() < turn_tolerance)
          break;
      }

    // f grows into @p inside: the outward normal is -grad f in real space
    Tensor<1, dim> normal;
    for (unsigned int d = 0; d < dim; ++d)
      normal[d] = -beta[d] / cell_size[d];
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
