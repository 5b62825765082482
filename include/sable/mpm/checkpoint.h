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
   * It is written and swapped in as sable/base/checkpoint_directory.h
   * describes.
   */

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
