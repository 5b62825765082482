#ifndef sable_mpm_checkpoint_h
#define sable_mpm_checkpoint_h

#include <deal.II/base/mpi.h>

#include <ostream>
#include <string>

namespace sable::mpm
{
  /**
   * Checkpoints of an MPM run (Simulator::save_checkpoint(),
   * Simulator::resume()). A checkpoint is a directory holding
   *
   * - `triangulation*`: the mesh (with its refinement) and the material
   *   points with all their properties, written by
   *   parallel::distributed::Triangulation::save() after
   *   ParticleHandler::prepare_for_serialization();
   * - `simulator.state`: the simulator's own state (time, step, time-step
   *   bookkeeping, energy check, output series, contact heat, ...), a
   *   boost text archive written by rank 0;
   * - `manifest`: written last, the size and CRC-32 of every other file.
   *
   * A checkpoint is written into `<name>.tmp`; then the previous `<name>` is
   * renamed to `<name>.old`, `<name>.tmp` to `<name>`, and `<name>.old` is
   * removed. Whatever moment a run is stopped at, `<name>` or `<name>.old`
   * holds a complete checkpoint; find_checkpoint() picks it.
   */

  /// Directory name of the checkpoint inside the output directory.
  inline const char *const checkpoint_name = "checkpoint";

  /**
   * What is wrong with the checkpoint in @p directory (missing, no
   * manifest, a file missing, of the wrong size or, with
   * @p verify_checksums, with the wrong checksum), or an empty string if it
   * is complete. Checksums mean reading every file.
   */
  std::string
  checkpoint_problem(const std::string &directory, const bool verify_checksums = true);

  /**
   * The checkpoint to resume the run in @p output_directory from:
   * `<output_directory>/checkpoint`, or `checkpoint.old` if the former is
   * missing or incomplete (a note goes to @p log on rank 0). Collective.
   * Throws std::runtime_error naming the directory and what was found if
   * neither is usable.
   */
  std::string
  find_checkpoint(const std::string &output_directory,
                  MPI_Comm           communicator,
                  std::ostream &     log);
} // namespace sable::mpm

#endif
