// Pack generation and preparation as in the paper's section 3.2.
#ifndef sable_qusgm_preparation_h
#define sable_qusgm_preparation_h

#include <sable/qusgm/pack.h>
#include <sable/qusgm/simulation.h>

#include <stdexcept>

namespace sable::qusgm
{
  /// Preparation could not compact the pack: the message says why and
  /// what to change; the increments so far are in the table.
  class PreparationError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  struct PackGenerationSettings
  {
    unsigned int n_grains        = 500;
    double       min_radius      = 0.07e-3;
    double       max_radius      = 0.13e-3;
    double       youngs_modulus  = 70e9;
    double       youngs_modulus_deviation = 0.1; ///< relative std. deviation
    double       poisson_ratio   = 0.2;
    double       density         = 2420;
    double       solid_fraction  = 0.3; ///< of the loose random pack
    unsigned int seed            = 1;
  };

  /**
   * A loose random polydisperse pack in a cube, by random sequential
   * addition of non-overlapping spheres (cell list, O(N)); radii uniform,
   * Young's moduli normal (truncated at +-3 deviations). @p walls gets the
   * cube.
   */
  Pack
  generate_loose_pack(const PackGenerationSettings &settings, Walls &walls);

  struct PreparationSettings
  {
    // (a) frictionless isotropic compaction with growth of grains that have
    // fewer than `min_coordination` contacts.
    double       target_confining_stress = 10e6;
    double       compaction_strain       = 4e-3; ///< largest step
    unsigned int min_coordination        = 4;
    double       max_growth              = 0.05; ///< per round, of radius
    unsigned int max_compaction_steps    = 2000;
    unsigned int max_growth_rounds       = 40;
    // (b) frictional uniaxial strain until the sliding ratio saturates.
    bool         friction_stage          = true;
    double       friction_strain         = 1e-4;
    unsigned int max_friction_steps      = 200;
    unsigned int saturation_window       = 5;
    double       saturation_tolerance    = 0.01;
  };

  /**
   * (a) Compact the pack isotropically without friction, growing grains
   * with too few contacts, until every grain has at least min_coordination
   * contacts and sigma_c reaches the target; (b) with the scene's friction,
   * apply uniaxial strain until the sliding ratio changes by less than the
   * tolerance over the window. Records stages "compaction", "growth" and
   * "activation" in the simulation's table.
   *
   * Throws PreparationError if a compaction or growth increment stops at
   * the minimiser's iteration limit, or if stage (a) does not reach the
   * target within max_compaction_steps (e.g. a pack without contacts),
   * instead of handing a pack that is not compacted to the load path.
   */
  void
  prepare_pack(Simulation                &simulation,
               const ContactModel        &frictional_model,
               const PreparationSettings &settings);
} // namespace sable::qusgm

#endif
