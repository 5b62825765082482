// Equilibrium of one load increment: the walls move, the grains follow by
// minimising the work functional (SPEC Part C, Appendix A of the paper).
#ifndef sable_qusgm_minimizer_h
#define sable_qusgm_minimizer_h

#include <sable/qusgm/contact_network.h>
#include <sable/qusgm/pack.h>
#include <sable/qusgm/work_functional.h>

#include <array>
#include <ostream>
#include <string>

namespace sable::qusgm
{
  struct MinimizerSettings
  {
    enum class Method
    {
      nlcg,  ///< the paper's Fletcher-Reeves CG with Brent line search
      lbfgs  ///< limited-memory BFGS with a weak-Wolfe line search
    };
    Method       method                   = Method::nlcg;
    unsigned int steepest_descent_restart = 10;   ///< k_SD
    unsigned int sub_increments           = 10;   ///< wall sub-increments
    unsigned int iterations_per_sub_increment = 10; ///< k_inc
    unsigned int max_iterations           = 20000; ///< k_max
    double       energy_tolerance         = 1e-11; ///< epsilon_1
    double       gradient_tolerance       = 1e-13; ///< epsilon_2
    /// Stop when the largest residual force or moment/R is this fraction of
    /// the largest contact force (0: test off).
    double force_tolerance = 0;
    /// Stop when it is this fraction of the largest change of a contact
    /// force in this increment (0: test off).
    double increment_force_tolerance = 0;
    double displacement_cap = 0.01; ///< per-iteration move / grain radius
    unsigned int line_search_bits = 24;  ///< Brent accuracy, bits of alpha
    unsigned int lbfgs_history    = 8;
    double       skin             = 0.3; ///< cell-list skin / mean radius
    /// Start from the previous increment's solution, scaled, when the walls
    /// repeat its move (else, and with sub-increments, the affine guess).
    bool predictor = false;
    /// Stop, unconverged ("stagnation"), when this many iterations after the
    /// last wall sub-increment brought no progress: neither a largest
    /// residual below 0.99 times the lowest so far nor a Pi below the lowest
    /// so far by 1e-12 |Pi| (0: never).
    unsigned int stagnation_window = 100;
  };

  struct IncrementResult
  {
    unsigned int iterations  = 0;
    unsigned int evaluations = 0;
    unsigned int rebuilds    = 0;
    double       value       = 0; ///< Pi at the end
    double       gradient_norm = 0;
    double       residual      = 0; ///< max |F_i|, |M_i|/R_i
    double       max_contact_force = 0;
    bool         converged         = false;
    /// the test that stopped the minimiser: force, increment force,
    /// gradient, energy, zero gradient (converged); iteration limit,
    /// stagnation, line search stalled (not converged)
    std::string  stopped_by;
    /// the last iteration that made progress (see stagnation_window)
    unsigned int last_progress = 0;
  };

  /**
   * Drives one load increment: moves the walls in sub-increments with the
   * affine guess for the grains, minimises Pi, and on return has committed
   * the equilibrium as the next reference configuration.
   */
  class IncrementSolver
  {
  public:
    IncrementSolver(Pack                    &pack,
                    Walls                   &reference_walls,
                    ContactNetwork          &network,
                    const ContactModel      &model,
                    const MinimizerSettings &settings);

    /**
     * Apply the wall moves @p wall_displacement (change of each wall's
     * coordinate) and find the equilibrium. With @p log, one line per
     * iteration: iteration, Pi, |grad Pi|, step, active and sliding contacts.
     */
    IncrementResult
    apply(const std::array<double, 6> &wall_displacement,
          std::ostream                *log   = nullptr,
          const Vector<double>        *guess = nullptr);

    /// The displacements and rotations of the last increment.
    const Vector<double> &
    solution() const
    {
      return last_solution;
    }

    /// Loads of the last equilibrium (before commit, so per-increment data
    /// such as sliding refers to that increment).
    const ContactState &
    state() const
    {
      return last_state;
    }

    const MinimizerSettings &
    get_settings() const
    {
      return settings;
    }

    MinimizerSettings &
    get_settings()
    {
      return settings;
    }

  private:
    void
    move_walls(const std::array<double, 6> &delta, Vector<double> &theta);

    void
    maybe_rebuild(const Vector<double> &theta, IncrementResult &result);

    double
    max_step(const Vector<double> &direction) const;

    Pack              &pack;
    Walls             &reference_walls;
    ContactNetwork    &network;
    ContactModel       model;
    MinimizerSettings  settings;
    WorkFunctional     functional;
    Walls              walls;
    ContactState       last_state;
    Vector<double>     last_solution;
    std::vector<Point<3>> positions;
  };
} // namespace sable::qusgm

#endif
