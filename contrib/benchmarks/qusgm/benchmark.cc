// QuSGM benchmark: the cost of one uniaxial-strain increment against the
// number of grains, and the error in the increment's stress change (so in
// K and G) against wall time for both minimisers, their stopping tests and
// the increment size. See doc/benchmarks.md for how to run it.
//
//   qusgm_benchmark scaling <cache dir> N1 [N2 ...]
//   qusgm_benchmark accuracy <cache dir> N
//   qusgm_benchmark validation <cache dir> N [sigma_c of stage (a) in Pa]
//   qusgm_benchmark dem <cache dir> N
//   qusgm_benchmark threads <cache dir> N [max threads = 2]
//   mpirun -np P qusgm_benchmark ranks <cache dir> N
//
// threads: the time of one evaluation of Pi and grad Pi (mean of 200, at
// the affine guess of a uniaxial increment of 1e-4) and of one increment
// (L-BFGS, force test 1e-4) with 1, 2, ... threads, and whether the
// results are bit-identical to the one-thread results
// (contrib/benchmarks/scaling/run.sh runs it).
//
// ranks: the same two timings with the grains distributed over the P ranks
// (one thread each), and Pi, |grad Pi| and the increment's stress change
// printed to 17 digits, for comparison with a run on another rank count.
//
// validation: from the compacted pack, for mu = 0.3, 0.5 and 0, friction
// activation by uniaxial strain until the sliding ratio saturates, then
// uniaxial-strain increments of 1e-4 to sigma_c = 25 MPa; one
// increments.csv per mu in <cache dir>/validation_mu<mu>.csv.
//
// Packs are generated and compacted without friction to 4 MPa (the
// paper's stage (a)), cached in <cache dir>, then friction is activated by
// five uniaxial increments of 1e-4 before anything is timed.
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <sable/base/common_parameters.h>

#include <sable/qusgm/load_path.h>
#include <sable/qusgm/preparation.h>
#include <sable/qusgm/simulation.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>

using namespace sable::qusgm;

namespace
{
  dealii::ConditionalOStream quiet(std::cout, false);

  ContactModel
  friction_model()
  {
    ContactModel m;
    m.friction      = 0.3;
    m.wall_friction = 0.3;
    m.torsion       = true;
    return m;
  }

  MinimizerSettings
  lbfgs(const double force_tolerance)
  {
    MinimizerSettings s;
    s.method             = MinimizerSettings::Method::lbfgs;
    s.sub_increments     = 1;
    s.energy_tolerance   = 0;
    s.gradient_tolerance = 0;
    s.force_tolerance    = force_tolerance;
    s.max_iterations     = 100000;
    return s;
  }

  MinimizerSettings
  nlcg_paper(const double eps1, const double eps2)
  {
    MinimizerSettings s;
    s.method                       = MinimizerSettings::Method::nlcg;
    s.sub_increments               = 10;
    s.iterations_per_sub_increment = 10;
    s.steepest_descent_restart     = 10;
    s.energy_tolerance             = eps1;
    s.gradient_tolerance           = eps2;
    s.force_tolerance              = 0;
    s.max_iterations               = 100000;
    return s;
  }

  // A pack of n grains after the paper's stage (a), from the cache or made.
  Simulation
  prepared(const unsigned int n, const std::string &cache,
           const bool activate = true, const double target = 4e6)
  {
    namespace fs = std::filesystem;
    fs::create_directories(cache);
    const std::string suffix =
      std::to_string(n) +
      (target == 4e6 ? "" : "_" + std::to_string(int(target / 1e3)) + "kPa");
    const std::string pack_file  = cache + "/pack_" + suffix + ".csv";
    const std::string walls_file = cache + "/walls_" + suffix + ".txt";
    Pack  pack;
    Walls walls;
    if (fs::exists(pack_file) && fs::exists(walls_file))
      {
        pack = read_pack(pack_file, GrainDefaults{70e9, 0.2, 2420});
        pack.sort_spatially();
        std::ifstream in(walls_file);
        for (double &x : walls.position)
          in >> x;
      }
    else
      {
        const auto             start = std::chrono::steady_clock::now();
        PackGenerationSettings g;
        g.n_grains = n;
        g.seed     = n;
        pack       = generate_loose_pack(g, walls);
        ContactModel smooth = friction_model();
        Simulation   sim(pack, walls, smooth, lbfgs(1e-5), quiet);
        PreparationSettings p;
        p.target_confining_stress = target;
        p.friction_stage          = false;
        prepare_pack(sim, smooth, p);
        write_pack(sim.pack, pack_file);
        std::ofstream out(walls_file);
        out << std::setprecision(17);
        for (const double x : sim.walls.position)
          out << x << '\n';
        std::cout << "# prepared " << n << " grains in "
                  << std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - start)
                       .count()
                  << " s (" << sim.n_increments << " increments)" << std::endl;
        pack  = sim.pack;
        walls = sim.walls;
      }
    Simulation sim(pack, walls, friction_model(), lbfgs(1e-5), quiet);
    sim.radii_changed();
    if (activate)
      for (unsigned int k = 0; k < 5; ++k)
        sim.strain_step({{0, 0, 1e-4}}, "activation");
    return sim;
  }

  struct Outcome
  {
    std::array<double, 3> d_stress;
    double                k, g, seconds;
    IncrementResult       result;
  };

  Outcome
  run(const Simulation &start, const MinimizerSettings &s, const double d_eps)
  {
    Simulation sim = start;
    sim.settings   = s;
    const auto before = sim.last.macroscopic.stress;
    const auto t0     = std::chrono::steady_clock::now();
    const IncrementRecord &r = sim.strain_step({{0, 0, d_eps}}, "benchmark");
    Outcome o;
    o.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (unsigned int a = 0; a < 3; ++a)
      o.d_stress[a] = r.macroscopic.stress[a] - before[a];
    o.k      = r.bulk_modulus;
    o.g      = r.shear_modulus;
    o.result = r.result;
    return o;
  }

  double
  stress_error(const Outcome &o, const Outcome &ref)
  {
    double e = 0, scale = 0;
    for (unsigned int a = 0; a < 3; ++a)
      {
        e     = std::max(e, std::abs(o.d_stress[a] - ref.d_stress[a]));
        scale = std::max(scale, std::abs(ref.d_stress[a]));
      }
    return e / scale;
  }

  // Dynamic relaxation of the same increment, as a DEM code would do it:
  // explicit central differences with the same contact forces (-grad Pi),
  // translational masses m and rotational ones (2/5) m for Omega R,
  // Cundall's local damping 0.7, time step 0.2 sqrt(m_min / (2 k_max)). The walls
  // jump to their new position with the affine guess at t = 0, as for the
  // minimisers. Returns the wall time and steps until the stress change is
  // within @p tolerance of the reference at two checks 100 steps apart.
  std::pair<double, unsigned int>
  dem_relax(const Simulation &start, const double d_eps,
            const Outcome &ref, const double tolerance)
  {
    Simulation         sim = start;
    const unsigned int n   = sim.pack.size();
    const auto         t0  = std::chrono::steady_clock::now();
    ContactNetwork    &network = sim.network;
    WorkFunctional     f(sim.pack, network, sim.model);
    Walls              walls = sim.walls;
    const auto move = LoadPath::wall_moves({{0, 0, d_eps}}, sim.undeformed_lengths);
    dealii::Vector<double> theta(6 * n), v(6 * n), g(6 * n), mass(6 * n);
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < n; ++i)
        {
          const double x = sim.pack.centre[i][a];
          theta[3 * i + a] =
            move[a] + (move[a + 3] - move[a]) * (x - walls.position[a]) / walls.length(a);
        }
    for (unsigned int w = 0; w < 6; ++w)
      walls.position[w] += move[w];
    f.set_walls(walls);
    double m_min = 1e300;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double m = sim.pack.mass(i);
        m_min          = std::min(m_min, 0.4 * m);
        for (unsigned int d = 0; d < 3; ++d)
          {
            mass[3 * i + d]         = m;
            mass[3 * n + 3 * i + d] = 0.4 * m;
          }
      }
    // Stiffest contact: dP/dh = 1.5 k_n sqrt(h); k*_s is below it.
    const ContactState s0 = f.state(theta);
    double k_max = 0;
    for (const Contact &c : network.pairs)
      k_max = std::max(k_max, 1.5 * c.k_n * std::sqrt(std::max(c.h0, 0.)));
    for (const Contact &c : network.wall_contacts)
      k_max = std::max(k_max, 1.5 * c.k_n * std::sqrt(std::max(c.h0, 0.)));
    const double dt = 0.2 * std::sqrt(m_min / (2 * k_max));
    std::vector<Point<3>> x;
    unsigned int good = 0;
    for (unsigned int step = 1; step <= 400000; ++step)
      {
        f.value_and_gradient(theta, g);
        for (unsigned int k = 0; k < 6 * n; ++k)
          {
            const double force = -g[k];
            const double damped =
              force - 0.7 * std::abs(force) * (v[k] > 0 ? 1. : v[k] < 0 ? -1. : 0.);
            v[k] += dt * damped / mass[k];
            theta[k] += dt * v[k];
          }
        if (step % 20 == 0)
          {
            f.positions(theta, x);
            if (network.needs_rebuild(x, walls))
              network.build(sim.pack, sim.walls, x, walls, sim.model,
                            sim.settings.skin * sim.pack.mean_radius());
          }
        if (step % 100 == 0)
          {
            const ContactState s = f.state(theta);
            double e = 0, scale = 0;
            for (unsigned int a = 0; a < 3; ++a)
              {
                const double sigma =
                  0.5 * (s.wall_force[a] + s.wall_force[a + 3]) / walls.area(a);
                e = std::max(e, std::abs(sigma - start.last.macroscopic.stress[a] -
                                         ref.d_stress[a]));
                scale = std::max(scale, std::abs(ref.d_stress[a]));
              }
            good = e < tolerance * scale ? good + 1 : 0;
            if (good == 2)
              return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                        .count(),
                      step};
          }
      }
    (void)s0;
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            400000};
  }

  // The state Pi and grad Pi are timed at: the walls of @p f moved by a
  // uniaxial increment of 1e-4, the grains by the affine guess.
  void
  affine_guess(const Simulation &sim, WorkFunctional &f, dealii::Vector<double> &theta)
  {
    const unsigned int n     = sim.pack.size();
    Walls              walls = sim.walls;
    const auto move = LoadPath::wall_moves({{0, 0, 1e-4}}, sim.undeformed_lengths);
    theta.reinit(6 * n);
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < n; ++i)
        theta[3 * i + a] = move[a] + (move[a + 3] - move[a]) *
                                       (sim.pack.centre[i][a] - walls.position[a]) /
                                       walls.length(a);
    for (unsigned int w = 0; w < 6; ++w)
      walls.position[w] += move[w];
    f.set_walls(walls);
  }

  // Threads: evaluations and one increment with 1 .. max_threads threads.
  void
  thread_scaling(const Simulation &start, const unsigned int max_threads)
  {
    const unsigned int n = start.pack.size();
    std::cout << "threads,contacts,evaluation_ms,evaluation_speedup,increment_s,"
                 "increment_speedup,iterations,pi_difference,gradient_difference,"
                 "stress_change_difference"
              << std::endl;
    double                 pi_1 = 0, evaluation_1 = 0, increment_1 = 0;
    dealii::Vector<double> gradient_1;
    std::array<double, 3>  d_stress_1{};
    for (unsigned int threads = 1; threads <= max_threads; ++threads)
      {
        sable::set_threads(threads);
        Simulation     sim = start;
        WorkFunctional f(sim.pack, sim.network, sim.model);
        dealii::Vector<double> theta, gradient(6 * n);
        affine_guess(sim, f, theta);
        double pi = f.value_and_gradient(theta, gradient); // warm-up
        const unsigned int repeats = 200;
        const auto         t0      = std::chrono::steady_clock::now();
        for (unsigned int k = 0; k < repeats; ++k)
          pi = f.value_and_gradient(theta, gradient);
        const double evaluation =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
          repeats;
        const Outcome o = run(start, lbfgs(1e-4), 1e-4);
        if (threads == 1)
          {
            pi_1 = pi, evaluation_1 = evaluation, increment_1 = o.seconds;
            gradient_1 = gradient, d_stress_1 = o.d_stress;
          }
        double g_diff = 0, s_diff = 0;
        for (unsigned int k = 0; k < gradient.size(); ++k)
          g_diff = std::max(g_diff, std::abs(gradient[k] - gradient_1[k]));
        for (unsigned int a = 0; a < 3; ++a)
          s_diff = std::max(s_diff, std::abs(o.d_stress[a] - d_stress_1[a]));
        std::cout << dealii::MultithreadInfo::n_threads() << ','
                  << sim.network.pairs.size() + sim.network.wall_contacts.size() << ','
                  << 1e3 * evaluation << ',' << evaluation_1 / evaluation << ','
                  << o.seconds << ',' << increment_1 / o.seconds << ','
                  << o.result.iterations << ',' << std::abs(pi - pi_1) << ',' << g_diff
                  << ',' << s_diff << std::endl;
      }
  }

  // Ranks: the grains of @p start distributed over MPI_COMM_WORLD.
  void
  rank_scaling(Simulation start)
  {
    const unsigned int n = start.pack.size();
    start.set_communicator(MPI_COMM_WORLD);
    WorkFunctional f(start.pack, start.network, start.model);
    dealii::Vector<double> theta, gradient(6 * n);
    affine_guess(start, f, theta);
    double pi = f.value_and_gradient(theta, gradient); // warm-up
    MPI_Barrier(MPI_COMM_WORLD);
    const unsigned int repeats = 200;
    const auto         t0      = std::chrono::steady_clock::now();
    for (unsigned int k = 0; k < repeats; ++k)
      pi = f.value_and_gradient(theta, gradient);
    const double evaluation =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / repeats;
    MPI_Barrier(MPI_COMM_WORLD);
    const Outcome o = run(start, lbfgs(1e-4), 1e-4);
    const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    unsigned int       held  = start.network.pairs.size() + start.network.wall_contacts.size();
    const unsigned int most  = dealii::Utilities::MPI::max(held, MPI_COMM_WORLD);
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << "ranks,contacts_on_busiest_rank,evaluation_ms,increment_s,iterations,"
                   "evaluations,pi,gradient_norm,stress_change_z\n"
                << ranks << ',' << most << ',' << 1e3 * evaluation << ',' << o.seconds << ','
                << o.result.iterations << ',' << o.result.evaluations << ','
                << std::setprecision(17) << pi << ','
                << gradient.l2_norm() << ',' << o.d_stress[2] << std::endl;
  }

  void
  print(const std::string &name, const Outcome &o, const Outcome &ref,
        const unsigned int n, const double d_eps)
  {
    std::cout << n << ',' << d_eps << ',' << name << ',' << o.seconds << ','
              << o.result.iterations << ',' << o.result.evaluations << ','
              << o.result.residual / o.result.max_contact_force << ','
              << stress_error(o, ref) << ',' << std::abs(o.k / ref.k - 1) << ','
              << std::abs(o.g / ref.g - 1) << ',' << o.result.stopped_by
              << std::endl;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc,
                                              argv,
                                              dealii::numbers::invalid_unsigned_int);
  sable::set_threads(1);
  if (argc < 4)
    {
      std::cerr << "Usage: qusgm_benchmark scaling|accuracy|validation|dem|threads|ranks <cache dir> N...\n";
      return 1;
    }
  const std::string mode = argv[1], cache = argv[2];
  if (mode == "ranks")
    {
      rank_scaling(prepared(std::stoi(argv[3]), cache));
      return 0;
    }
  if (mode == "threads")
    {
      const Simulation start = prepared(std::stoi(argv[3]), cache);
      thread_scaling(start, argc > 4 ? std::stoi(argv[4]) : 2);
      return 0;
    }
  std::cout << "grains,strain_increment,method,seconds,iterations,evaluations,"
               "relative_residual,stress_change_error,bulk_modulus_error,"
               "shear_modulus_error,stopped_by"
            << std::endl;
  if (mode == "dem")
    {
      const unsigned int n     = std::stoi(argv[3]);
      const Simulation   start = prepared(n, cache);
      const Outcome      ref   = run(start, lbfgs(1e-9), 1e-4);
      const auto [seconds, steps] = dem_relax(start, 1e-4, ref, 1e-3);
      std::cout << n << ",0.0001,dynamic relaxation (DEM-like) to 1e-3," << seconds
                << ',' << steps << ",,,,,," << std::endl;
      for (const double f : {1e-3, 1e-4})
        for (const bool predictor : {false, true})
          {
            MinimizerSettings s = lbfgs(f);
            s.predictor         = predictor;
            print("lbfgs force " + std::to_string(f) + (predictor ? " predictor" : ""),
                  run(start, s, 1e-4), ref, n, 1e-4);
          }
      return 0;
    }
  if (mode == "validation")
    {
      const unsigned int n      = std::stoi(argv[3]);
      const double       target = argc > 4 ? std::stod(argv[4]) : 4e6;
      const std::vector<double> mus =
        argc > 4 ? std::vector<double>{0.3} : std::vector<double>{0.3, 0.5, 0.};
      for (const double mu : mus)
        {
          Simulation sim = prepared(n, cache, false, target);
          // The stage (a) pack carries no history: record from here.
          sim.open_table(cache + "/validation_mu" + std::to_string(mu).substr(0, 3) +
                         (argc > 4 ? "_" + std::string(argv[4]) : "") + ".csv");
          sim.settings.predictor = true;
          ContactModel model  = friction_model();
          model.friction      = mu;
          model.wall_friction = mu;
          sim.set_model(model);
          PreparationSettings p;
          p.max_compaction_steps = 0;
          p.max_friction_steps   = 150;
          p.saturation_window    = 10;
          prepare_pack(sim, model, p);
          if (mu == 0)
            for (unsigned int k = 0; k < 30; ++k)
              sim.strain_step({{0, 0, 1e-4}}, "activation");
          unsigned int k = 0;
          while (sim.last.macroscopic.confining_stress < 25e6 && k++ < 400)
            sim.strain_step({{0, 0, 1e-4}}, "test");
          std::cout << "# mu = " << mu << ": " << sim.n_increments
                    << " increments, sigma_c " << sim.last.macroscopic.confining_stress
                    << ", sliding " << sim.last.macroscopic.sliding_ratio << std::endl;
        }
      return 0;
    }
  for (int arg = 3; arg < argc; ++arg)
    {
      const unsigned int n     = std::stoi(argv[arg]);
      const Simulation   start = prepared(n, cache);
      std::cout << "# " << n << " grains: sigma_c "
                << start.last.macroscopic.confining_stress * 1e-6
                << " MPa, coordination " << start.last.macroscopic.coordination
                << ", sliding ratio " << start.last.macroscopic.sliding_ratio
                << std::endl;
      if (mode == "scaling")
        {
          const Outcome ref = run(start, lbfgs(1e-9), 1e-4);
          print("reference lbfgs 1e-9", ref, ref, n, 1e-4);
          print("nlcg paper 1e-11/1e-13", run(start, nlcg_paper(1e-11, 1e-13), 1e-4),
                ref, n, 1e-4);
          print("lbfgs force 1e-4", run(start, lbfgs(1e-4), 1e-4), ref, n, 1e-4);
          MinimizerSettings p = lbfgs(1e-4);
          p.predictor         = true;
          print("lbfgs force 1e-4 predictor", run(start, p, 1e-4), ref, n, 1e-4);
        }
      else
        for (const double d_eps : {5e-5, 1e-4, 5e-4})
          {
            const Outcome ref = run(start, lbfgs(1e-10), d_eps);
            print("reference lbfgs 1e-10", ref, ref, n, d_eps);
            for (const auto &[e1, e2] : {std::pair{1e-9, 1e-11}, std::pair{1e-11, 1e-13},
                                         std::pair{1e-13, 1e-15}})
              {
                std::ostringstream name;
                name << "nlcg paper " << e1 << '/' << e2;
                print(name.str(), run(start, nlcg_paper(e1, e2), d_eps), ref, n, d_eps);
              }
            for (const double f : {1e-3, 1e-4, 1e-5, 1e-6})
              {
                std::ostringstream name;
                name << "nlcg force " << f;
                MinimizerSettings s = nlcg_paper(0, 0);
                s.force_tolerance   = f;
                print(name.str(), run(start, s, d_eps), ref, n, d_eps);
              }
            for (const double f : {1e-3, 1e-4, 1e-5, 1e-6})
              {
                std::ostringstream name;
                name << "lbfgs force " << f;
                print(name.str(), run(start, lbfgs(f), d_eps), ref, n, d_eps);
              }
            for (const double f : {1e-1, 1e-2, 1e-3})
              {
                std::ostringstream name;
                name << "lbfgs increment force " << f;
                MinimizerSettings s         = lbfgs(0);
                s.increment_force_tolerance = f;
                print(name.str(), run(start, s, d_eps), ref, n, d_eps);
              }
          }
    }
  return 0;
}
