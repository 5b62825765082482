// The state of a QuSGM run (pack, walls, contacts, history) and one load
// increment with its macroscopic record: shared by pack preparation, the
// load paths and the scene runner.
#ifndef sable_qusgm_simulation_h
#define sable_qusgm_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <sable/qusgm/contact_network.h>
#include <sable/qusgm/macroscopic.h>
#include <sable/qusgm/minimizer.h>
#include <sable/qusgm/pack.h>

#include <sable/qusgm/pack_io.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>

namespace sable::qusgm
{
  struct IncrementRecord
  {
    MacroscopicState macroscopic;
    /// Hooke fit of this increment's stress and strain changes (NaN where
    /// undefined, see fit_moduli())
    double           bulk_modulus  = 0;
    double           shear_modulus = 0;
    IncrementResult  result;
    double           wall_time = 0;
  };

  class Simulation
  {
  public:
    /**
     * With a @p communicator of more than one rank, the grains are
     * distributed over its ranks (see GrainPartition); every rank then
     * calls every member function, in the same order. Only the caller
     * decides which rank writes the table and the logs.
     *
     * The stress of the configuration given is measured at once, so that
     * the first increment has moduli (its stress change is from there).
     */
    Simulation(const Pack              &pack,
               const Walls             &walls,
               const ContactModel      &model,
               const MinimizerSettings &settings,
               dealii::ConditionalOStream &out,
               dealii::TimerOutput        *timer        = nullptr,
               MPI_Comm                    communicator = MPI_COMM_SELF);

    /// Distribute the grains over the ranks of @p communicator from now on
    /// (keeping the contacts' history).
    void
    set_communicator(MPI_Comm communicator);

    /// Switch contact model (e.g. frictionless preparation to friction).
    void
    set_model(const ContactModel &model);

    /// Write a row per increment to @p filename from now on (with
    /// @p append, after the rows it has).
    void
    open_table(const std::string &filename, bool append = false);

    /**
     * The state a run continues from: pack, walls, contact model, every
     * contact with its reference loads, and what the next increment takes
     * from the last one. Collective; the bytes are returned on rank 0 only
     * (see sable/qusgm/checkpoint.h).
     */
    std::string
    save_state() const;

    /// Continue from the bytes of save_state() (on every rank).
    void
    load_state(const std::string &bytes);

    /**
     * The state for files (write_state()): grains, walls, the box of zero
     * strain, the wall forces, and every closed contact with its reference
     * loads. Collective; the contacts are complete on rank 0 only.
     */
    PackState
    pack_state() const;

    /**
     * Continue from a state read from files: the box of zero strain and
     * the contacts' reference loads of @p state (whose pack and walls this
     * simulation was made with). See ContactNetwork::set_reference_loads().
     */
    void
    set_pack_state(const PackState &state);

    /**
     * Increment @p k of @p n of the load path comes next: the progress line
     * shows "k/n" and an estimate of the time left (from the mean time of
     * the increments since the first call).
     */
    void
    set_progress(unsigned int k, unsigned int n);

    /// Apply wall moves, reach equilibrium, record, print a progress line.
    const IncrementRecord &
    step(const std::array<double, 6> &wall_moves, const std::string &stage);

    /// Apply strain increments (compression positive) relative to the
    /// undeformed box.
    const IncrementRecord &
    strain_step(const std::array<double, 3> &d_strain, const std::string &stage);

    /// Take the current box as undeformed (zero strain).
    void
    reset_undeformed();

    /// Rebuild contacts after radii changed.
    void
    radii_changed();

    /// Equilibrium state of the current reference (no wall motion).
    ContactState
    current_state() const;

    Pack                  pack;
    Walls                 walls;
    ContactNetwork        network;
    ContactModel          model;
    MinimizerSettings     settings;
    std::array<double, 3> undeformed_lengths;
    IncrementRecord       last;
    unsigned int          n_increments = 0;
    unsigned int          axis         = 2; ///< axial direction of the load path
    std::ostream         *iteration_log = nullptr;

  private:
    MPI_Comm                         communicator;
    dealii::ConditionalOStream      &out;
    dealii::TimerOutput             *timer;
    std::shared_ptr<IncrementTable>  table; // shared by copies
    bool                             have_previous = false; // kept for old checkpoints
    // The last increment's solution and wall moves, for the predictor.
    Vector<double>                   last_theta;
    std::array<double, 6>            last_moves{};
    // Progress through the load path for the console.
    unsigned int                          progress_k = 0, progress_n = 0, progress_first = 0;
    std::chrono::steady_clock::time_point progress_start;
  };
} // namespace sable::qusgm

#endif
