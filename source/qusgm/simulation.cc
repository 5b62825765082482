#include <deal.II/base/mpi.h>

#include <sable/qusgm/load_path.h>
#include <sable/qusgm/simulation.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace sable::qusgm
{
  Simulation::Simulation(const Pack                 &pack,
                         const Walls                &walls,
                         const ContactModel         &model,
                         const MinimizerSettings    &settings,
                         dealii::ConditionalOStream &out,
                         dealii::TimerOutput        *timer,
                         const MPI_Comm              communicator)
    : pack(pack)
    , walls(walls)
    , model(model)
    , settings(settings)
    , communicator(communicator)
    , out(out)
    , timer(timer)
  {
    network.set_communicator(communicator);
    reset_undeformed();
    // The stress the pack starts from, so the first increment has moduli.
    last.macroscopic = measure(walls, undeformed_lengths, current_state(), pack, axis);
  }

  void
  Simulation::set_communicator(const MPI_Comm new_communicator)
  {
    communicator = new_communicator;
    network.set_communicator(communicator);
    network.build(pack, walls, pack.centre, walls, model, settings.skin * pack.mean_radius());
  }

  void
  Simulation::set_model(const ContactModel &new_model)
  {
    model = new_model;
    network.update_reference(pack, walls, model);
    last_theta.reinit(0);
  }

  void
  Simulation::open_table(const std::string &filename, const bool append)
  {
    table = std::make_shared<IncrementTable>(filename, append);
  }

  void
  Simulation::reset_undeformed()
  {
    for (unsigned int a = 0; a < 3; ++a)
      undeformed_lengths[a] = walls.length(a);
  }

  void
  Simulation::radii_changed()
  {
    last_theta.reinit(0);
    network = ContactNetwork();
    network.set_communicator(communicator);
    network.build(pack,
                  walls,
                  pack.centre,
                  walls,
                  model,
                  settings.skin * pack.mean_radius());
  }

  ContactState
  Simulation::current_state() const
  {
    ContactNetwork copy = network;
    copy.build(pack, walls, pack.centre, walls, model,
               settings.skin * pack.mean_radius());
    WorkFunctional functional(pack, copy, model);
    functional.set_walls(walls);
    return functional.state(Vector<double>(6 * pack.size()));
  }

  void
  Simulation::set_progress(const unsigned int k, const unsigned int n)
  {
    if (progress_n != n || k < progress_first || progress_n == 0)
      {
        progress_first = k;
        progress_start = std::chrono::steady_clock::now();
      }
    progress_k = k;
    progress_n = n;
  }

  PackState
  Simulation::pack_state() const
  {
    PackState state;
    state.pack               = pack;
    state.walls              = walls;
    state.undeformed_lengths = undeformed_lengths;
    state.wall_force         = current_state().wall_force;
    const unsigned int n     = pack.size();
    for (const bool wall : {false, true})
      for (const Contact &c : network.gather_on_root(wall ? network.wall_contacts : network.pairs, n))
        if (c.p0 > 0)
          {
            ContactLoad load;
            load.i                = c.i;
            load.other            = c.other;
            load.wall             = wall;
            load.tangential_force = c.q0;
            load.torsional_couple = c.m0;
            load.normal_force     = c.p0;
            load.overlap          = c.h0;
            state.contacts.push_back(load);
          }
    return state;
  }

  void
  Simulation::set_pack_state(const PackState &state)
  {
    undeformed_lengths = state.undeformed_lengths;
    last_theta.reinit(0);
    network.set_reference_loads(pack, walls, model, settings.skin * pack.mean_radius(),
                                state.contacts);
    last.macroscopic = measure(walls, undeformed_lengths, current_state(), pack, axis);
  }

  const IncrementRecord &
  Simulation::strain_step(const std::array<double, 3> &d_strain,
                          const std::string           &stage)
  {
    return step(LoadPath::wall_moves(d_strain, undeformed_lengths), stage);
  }

  const IncrementRecord &
  Simulation::step(const std::array<double, 6> &wall_moves,
                   const std::string           &stage)
  {
    const auto start = std::chrono::steady_clock::now();
    std::array<double, 3> length_before, stress_before = last.macroscopic.stress;
    for (unsigned int a = 0; a < 3; ++a)
      length_before[a] = walls.length(a);

    IncrementRecord record;
    {
      std::unique_ptr<dealii::TimerOutput::Scope> scope;
      if (timer)
        scope = std::make_unique<dealii::TimerOutput::Scope>(*timer, "equilibrium (" + stage + ")");
      IncrementSolver solver(pack, walls, network, model, settings);
      // Predictor: if the walls repeat the last move (up to a positive
      // factor), start from the last solution times that factor.
      Vector<double> guess;
      if (settings.predictor && last_theta.size() == 6 * pack.size())
        {
          double dot = 0, previous = 0, current = 0;
          for (unsigned int w = 0; w < 6; ++w)
            {
              dot += wall_moves[w] * last_moves[w];
              previous += last_moves[w] * last_moves[w];
              current += wall_moves[w] * wall_moves[w];
            }
          if (previous > 0 && dot > 0 &&
              std::abs(dot * dot - previous * current) <= 1e-12 * previous * current)
            {
              guess = last_theta;
              guess *= dot / previous;
            }
        }
      record.result = solver.apply(wall_moves, iteration_log,
                                   guess.size() ? &guess : nullptr);
      last_theta = solver.solution();
      last_moves = wall_moves;
      record.macroscopic =
        measure(walls, undeformed_lengths, solver.state(), pack, axis);
    }
    // Moduli of this interval: strain increments relative to the box
    // before the increment.
    std::array<double, 3> d_stress, d_strain;
    for (unsigned int a = 0; a < 3; ++a)
      {
        d_strain[a] = (length_before[a] - walls.length(a)) / length_before[a];
        d_stress[a] = record.macroscopic.stress[a] - stress_before[a];
      }
    const auto moduli    = fit_moduli(d_stress, d_strain);
    record.bulk_modulus  = moduli.first;
    record.shear_modulus = moduli.second;
    record.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    have_previous = true;
    ++n_increments;
    last = record;
    if (table)
      table->write(n_increments,
                   stage,
                   record.macroscopic,
                   record.bulk_modulus,
                   record.shear_modulus,
                   record.result,
                   record.wall_time);
    // a row that cannot be written (a full disk) stops the run on every
    // rank (rank 0 writes the table; a program without MPI has one)
    std::string problem = table ? table->problem() : std::string();
    if (dealii::Utilities::MPI::job_supports_mpi())
      problem = dealii::Utilities::MPI::broadcast(communicator, problem, 0);
    if (!problem.empty())
      throw std::runtime_error(problem);

    // The progress line; an undefined value is shown as "-".
    const auto &m     = record.macroscopic;
    const auto  fixed = [](const double value, const int width, const int digits) {
      std::ostringstream text;
      text << std::fixed << std::setprecision(digits) << std::setw(width);
      if (std::isfinite(value))
        text << value;
      else
        text << "-";
      return text.str();
    };
    out << std::setw(5) << n_increments << ' ' << std::left << std::setw(12) << stage
        << std::right << " sigma_c " << fixed(m.confining_stress * 1e-6, 8, 3) << " MPa"
        << "  sigma_d " << fixed(m.deviatoric_stress * 1e-6, 8, 3) << " MPa"
        << "  K " << fixed(record.bulk_modulus * 1e-9, 7, 3) << " GPa"
        << "  G " << fixed(record.shear_modulus * 1e-9, 7, 3) << " GPa"
        << "  Z " << fixed(m.coordination, 0, 2) << "  sliding "
        << fixed(m.sliding_ratio, 0, 3) << "  it " << record.result.iterations
        << std::scientific << std::setprecision(1) << "  res/F "
        << record.result.residual / std::max(record.result.max_contact_force, 1e-300)
        << std::defaultfloat << "  " << fixed(record.wall_time, 0, 2) << " s";
    if (progress_n > 0 && progress_k >= progress_first)
      {
        // Time left from the mean time per increment of the load path so far.
        const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - progress_start)
            .count();
        const double left =
          elapsed / (progress_k - progress_first + 1) * (progress_n - progress_k);
        std::ostringstream estimate;
        if (left < 120)
          estimate << std::fixed << std::setprecision(0) << left << " s";
        else if (left < 7200)
          estimate << std::fixed << std::setprecision(1) << left / 60 << " min";
        else
          estimate << std::fixed << std::setprecision(1) << left / 3600 << " h";
        out << "  [" << progress_k << '/' << progress_n << ", about " << estimate.str()
            << " left]";
      }
    if (!record.result.converged)
      out << "  (not converged: " << record.result.stopped_by << ")";
    out << std::endl;
    return last;
  }
} // namespace sable::qusgm
