#include <sable/base/input_error.h>
#include <sable/qusgm/contact_laws.h>
#include <sable/qusgm/load_path.h>
#include <sable/qusgm/preparation.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>

namespace sable::qusgm
{
  Pack
  generate_loose_pack(const PackGenerationSettings &s, Walls &walls)
  {
    check_input(s.n_grains > 1, "Pack/Number of grains", s.n_grains, ">= 2 (a pack)");
    check_input(s.min_radius > 0, "Pack/Minimum radius", s.min_radius, "> 0");
    check_input(s.max_radius >= s.min_radius,
                "Pack/Maximum radius",
                s.max_radius,
                ">= Minimum radius");
    check_input(s.solid_fraction > 0 && s.solid_fraction <= 0.35,
                "Pack/Initial solid fraction",
                s.solid_fraction,
                "0 < phi <= 0.35 (random sequential addition)");
    std::mt19937                           rng(s.seed);
    std::uniform_real_distribution<double> uniform(0., 1.);
    std::normal_distribution<double>       normal(0., 1.);

    std::vector<double> radii(s.n_grains), moduli(s.n_grains);
    double              volume = 0;
    for (unsigned int i = 0; i < s.n_grains; ++i)
      {
        radii[i] = s.min_radius + (s.max_radius - s.min_radius) * uniform(rng);
        const double z = std::max(-3., std::min(3., normal(rng)));
        moduli[i] = s.youngs_modulus * (1. + s.youngs_modulus_deviation * z);
        volume += 4. / 3. * M_PI * std::pow(radii[i], 3);
      }
    // Place the large grains first: random sequential addition jams less.
    std::vector<unsigned int> order(s.n_grains);
    for (unsigned int i = 0; i < s.n_grains; ++i)
      order[i] = i;
    std::sort(order.begin(), order.end(), [&](unsigned int a, unsigned int b) {
      return radii[a] > radii[b];
    });

    const double side = std::cbrt(volume / s.solid_fraction);
    for (unsigned int a = 0; a < 3; ++a)
      {
        walls.position[a]     = 0;
        walls.position[a + 3] = side;
      }
    const double       cell = 2. * s.max_radius;
    const unsigned int nc   = std::max(1u, static_cast<unsigned int>(side / cell));
    std::vector<std::vector<unsigned int>> cells(nc * nc * nc);
    auto index = [&](const double x) {
      return std::min(nc - 1, static_cast<unsigned int>(std::max(0., x) / side * nc));
    };

    Pack pack;
    for (const unsigned int g : order)
      {
        const double r = radii[g];
        bool         placed = false;
        for (unsigned int attempt = 0; attempt < 100000 && !placed; ++attempt)
          {
            Point<3> x;
            for (unsigned int a = 0; a < 3; ++a)
              x[a] = r + (side - 2 * r) * uniform(rng);
            const unsigned int cx = index(x[0]), cy = index(x[1]), cz = index(x[2]);
            bool free = true;
            for (int dz = -1; dz <= 1 && free; ++dz)
              for (int dy = -1; dy <= 1 && free; ++dy)
                for (int dx = -1; dx <= 1 && free; ++dx)
                  {
                    const int ix = int(cx) + dx, iy = int(cy) + dy, iz = int(cz) + dz;
                    if (ix < 0 || iy < 0 || iz < 0 || ix >= int(nc) ||
                        iy >= int(nc) || iz >= int(nc))
                      continue;
                    for (const unsigned int j : cells[ix + nc * (iy + nc * iz)])
                      if ((pack.centre[j] - x).norm() < r + pack.radius[j])
                        {
                          free = false;
                          break;
                        }
                  }
            if (free)
              {
                cells[cx + nc * (cy + nc * cz)].push_back(pack.size());
                pack.add_grain(x, r, moduli[g], s.poisson_ratio, s.density);
                placed = true;
              }
          }
        check_input(placed,
                    "Pack/Initial solid fraction",
                    s.solid_fraction,
                    "a value at which random sequential addition can place "
                    "every grain (try a lower one)");
      }
    pack.sort_spatially();
    std::iota(pack.id.begin(), pack.id.end(), std::uint64_t(0));
    return pack;
  }

  namespace
  {
    // Grow grains with fewer than the required contacts towards their
    // next neighbour (or wall) so that they touch it. Each rank grows its
    // own grains (their contacts are all in its network) and the new radii
    // go to every rank. Returns how many grains grew.
    unsigned int
    grow_grains(Simulation &sim, const PreparationSettings &settings,
                const ContactState &state)
    {
      Pack                 &pack      = sim.pack;
      const unsigned int    n         = pack.size();
      const GrainPartition &partition = sim.network.get_partition();
      // Surface gaps to candidate neighbours, per grain.
      std::vector<std::vector<double>> gaps(n);
      for (const Contact &c : sim.network.pairs)
        {
          const double gap = (pack.centre[c.i] - pack.centre[c.other]).norm() -
                             pack.radius[c.i] - pack.radius[c.other];
          gaps[c.i].push_back(gap);
          gaps[c.other].push_back(gap);
        }
      for (const Contact &c : sim.network.wall_contacts)
        gaps[c.i].push_back(
          -sim.walls.overlap(c.other, pack.centre[c.i], pack.radius[c.i]));
      // Mean overlap of the loaded contacts (each pair counted from both
      // grains): grown grains press as hard. Summed per grain, then over
      // the grains in order, so that any number of ranks gives one answer.
      std::vector<double> overlaps(2 * std::size_t(n), 0.);
      for (const unsigned int i : partition.owned_grains())
        for (const double x : gaps[i])
          if (x < 0)
            {
              overlaps[2 * i] -= x;
              overlaps[2 * i + 1] += 1;
            }
      partition.gather(overlaps, 2);
      double mean_overlap = 0, n_overlaps = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          mean_overlap += overlaps[2 * i];
          n_overlaps += overlaps[2 * i + 1];
        }
      mean_overlap = n_overlaps > 0 ? mean_overlap / n_overlaps : 0.;

      unsigned int grown = 0;
      for (const unsigned int i : partition.owned_grains())
        if (state.coordination[i] < settings.min_coordination)
          {
            std::vector<double> &g = gaps[i];
            std::sort(g.begin(), g.end());
            const unsigned int k    = settings.min_coordination - 1;
            const double       next = k < g.size() ? g[k] : 0.2 * pack.radius[i];
            const double growth = std::min(std::max(next, 0.) + mean_overlap,
                                           settings.max_growth * pack.radius[i]);
            pack.radius[i] += growth;
            ++grown;
          }
      partition.gather(pack.radius, 1);
      return partition.sum(grown);
    }
  } // namespace

  void
  prepare_pack(Simulation                &sim,
               const ContactModel        &frictional_model,
               const PreparationSettings &settings)
  {
    // (a) Frictionless isotropic compaction.
    ContactModel smooth  = frictional_model;
    smooth.friction      = 0;
    smooth.wall_friction = 0;
    sim.set_model(smooth);

    // An increment of stage (a) that ends unconverged at the iteration
    // limit leaves a pack out of equilibrium: stop rather than go on.
    const auto check_converged = [&](const IncrementRecord &record) {
      if (record.result.stopped_by != "iteration limit")
        return;
      std::ostringstream message;
      message << "preparation could not compact the pack: increment "
              << sim.n_increments << " (" << (record.macroscopic.n_contacts ? "" : "no contacts, ")
              << "sigma_c = " << record.macroscopic.confining_stress
              << " Pa) stopped unconverged at 'Minimizer/Maximum iterations' = "
              << sim.settings.max_iterations << " (largest residual / contact force "
              << record.result.residual / std::max(record.result.max_contact_force, 1e-300)
              << "). Allow more iterations or smaller steps ('Preparation/Compaction "
                 "strain increment'); increments.csv holds the increments so far";
      throw PreparationError(message.str());
    };
    bool         reached = false;
    bool         jammed = false;
    unsigned int rounds = 0;
    const double target = settings.target_confining_stress;
    const double tolerance = 0.05; // on sigma_c at the end of stage (a)
    for (unsigned int k = 0; k < settings.max_compaction_steps; ++k)
      {
        const ContactState state   = sim.current_state();
        const double       sigma_c = sim.last.macroscopic.confining_stress;
        unsigned int       n_below = 0;
        for (const unsigned int c : state.coordination)
          n_below += c < settings.min_coordination;
        const bool growth_done =
          n_below == 0 || rounds >= settings.max_growth_rounds;
        if (growth_done && std::abs(sigma_c - target) <= tolerance * target)
          {
            reached = true;
            break;
          }

        if (!jammed && sigma_c > 1e-3 * target)
          {
            // Stresses appear: this box is the undeformed one.
            jammed = true;
            sim.reset_undeformed();
          }
        if (jammed && !growth_done && sigma_c >= 0.5 * target)
          {
            ++rounds;
            grow_grains(sim, settings, state);
            sim.radii_changed();
            check_converged(sim.step({}, "growth"));
            continue;
          }
        // Strain step: coarse while loose; once loaded, sized from the last
        // tangent bulk modulus towards the target (negative: unload, which
        // is elastic without friction).
        double step = settings.compaction_strain;
        if (jammed && std::isfinite(sim.last.bulk_modulus) &&
            sim.last.bulk_modulus > 0)
          {
            step = 0.8 * (target - sigma_c) / (3. * sim.last.bulk_modulus);
            step = std::max(-settings.compaction_strain,
                            std::min(settings.compaction_strain, step));
          }
        else if (jammed && sigma_c > target)
          step = -0.1 * settings.compaction_strain;
        std::array<double, 3> d_strain;
        d_strain.fill(step);
        std::array<double, 3> lengths;
        for (unsigned int a = 0; a < 3; ++a)
          lengths[a] = sim.walls.length(a);
        check_converged(sim.step(LoadPath::wall_moves(d_strain, lengths), "compaction"));
      }
    if (!reached)
      {
        std::ostringstream message;
        message << "preparation could not compact the pack: after "
                << settings.max_compaction_steps
                << " increments ('Preparation/Maximum compaction increments') sigma_c = "
                << sim.last.macroscopic.confining_stress << " Pa with "
                << sim.last.macroscopic.n_contacts
                << " contacts (none: the walls have not reached the grains), target "
                << target << " Pa +- 5%. Allow more increments, larger ones "
                << "('Compaction strain increment') or a lower target; increments.csv "
                << "holds the increments so far";
        throw PreparationError(message.str());
      }

    // (b) Frictional uniaxial strain until the sliding ratio saturates.
    sim.set_model(frictional_model);
    if (!settings.friction_stage || !frictional_model.frictional())
      return;
    std::vector<double> history;
    for (unsigned int k = 0; k < settings.max_friction_steps; ++k)
      {
        std::array<double, 3> d_strain{};
        d_strain[sim.axis] = settings.friction_strain;
        const double ratio = sim.strain_step(d_strain, "activation").macroscopic.sliding_ratio;
        history.push_back(std::isfinite(ratio) ? ratio : 0.); // no contacts: none slide
        const unsigned int w = settings.saturation_window;
        if (history.size() > w)
          {
            const auto   begin = history.end() - w - 1;
            const double lo    = *std::min_element(begin, history.end());
            const double hi    = *std::max_element(begin, history.end());
            if (hi - lo < settings.saturation_tolerance && hi > 0)
              break;
          }
      }
  }
} // namespace sable::qusgm
