// Checkpoint and restart of a QuSGM run.
#ifndef sable_qusgm_checkpoint_h
#define sable_qusgm_checkpoint_h

#include <deal.II/base/mpi.h>

#include <sable/qusgm/simulation.h>

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace sable::qusgm
{
  /**
   * Where a run is, besides the Simulation: how many increments of the load
   * path are done and the VTU series written so far.
   */
  struct RunProgress
  {
    unsigned int load_increments = 0; ///< done (0: the pack is prepared)
    std::vector<std::pair<double, std::string>> grain_files, contact_files;
    /// The scene's entries (sable::parameter_entries()), compared on resume.
    std::vector<std::pair<std::string, std::string>> scene_entries;

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &load_increments &grain_files &contact_files &scene_entries;
    }
  };

  /// Whether the entry @p name ("Subsection/Entry") may have another value
  /// when a QuSGM run is resumed: the number of increments of the load
  /// path, the Output entries, threads and the output directory.
  bool
  may_change_on_resume(const std::string &name);

  /**
   * Write `<output_directory>/checkpoint`: the file `qusgm.state` (a
   * boost binary archive of Simulation::save_state() and @p progress) and
   * a manifest, swapped in atomically as sable/base/checkpoint_directory.h
   * describes. Collective; rank 0 writes.
   *
   * A checkpoint is taken between increments, so the state is the last
   * equilibrium with the contacts' reference loads: what the next increment
   * starts from. A run resumed from it continues bit for bit as if it had
   * not stopped, on any number of ranks.
   */
  void
  save_checkpoint(const Simulation  &simulation,
                  const RunProgress &progress,
                  const std::string &output_directory,
                  MPI_Comm           communicator);

  /// The checkpoint of the run in @p output_directory (see
  /// sable::find_checkpoint()). Collective.
  std::string
  find_checkpoint(const std::string &output_directory, MPI_Comm communicator, std::ostream &log);

  /**
   * Restore @p simulation from the checkpoint @p directory and return the
   * progress. Throws std::runtime_error naming the directory if it is of an
   * older format or does not belong to a pack of @p simulation's number of
   * grains.
   */
  RunProgress
  load_checkpoint(Simulation &simulation, const std::string &directory);
} // namespace sable::qusgm

#endif
