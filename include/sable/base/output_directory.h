// The output directory of a run: refused if it holds an earlier run's
// results (unless --overwrite or --resume), and locked against a second
// run writing into it at the same time. Shared by the MPM and QuSGM runs.
#ifndef sable_base_output_directory_h
#define sable_base_output_directory_h

#include <deal.II/base/mpi.h>

#include <ostream>
#include <string>
#include <vector>

namespace sable
{
  /// How a run treats the results already in its output directory.
  enum class OutputMode
  {
    fresh,     ///< refuse to start if there are any
    overwrite, ///< remove them first (--overwrite)
    resume     ///< continue them from the checkpoint (--resume)
  };

  /// Name of the lock file in the output directory.
  inline const char *const lock_file_name = "sable.lock";

  /**
   * Whether a file or directory called @p name (no path) is one sable
   * writes into an output directory: statistics.csv, increments.csv,
   * iterations.log, the particle, contact node, grid, grain and contact
   * series, the checkpoint and the QuSGM states. --overwrite removes
   * these and nothing else.
   */
  bool
  is_sable_output(const std::string &name);

  /// The names in @p directory that is_sable_output() accepts: the tables,
  /// the checkpoint, then the others, each alphabetically.
  std::vector<std::string>
  sable_outputs(const std::string &directory);

  /**
   * Holds the output directory of a run for its lifetime. The constructor
   * (collective; rank 0 does the work) checks, in this order and before
   * changing anything, that no other living sable process holds the lock
   * file `sable.lock` (a lock of a dead process on this host is taken over
   * with a note to @p log), and for OutputMode::fresh that the directory
   * holds no sable outputs; then it creates the directory and the lock
   * file (with the process id and host name), and for
   * OutputMode::overwrite removes the earlier outputs. With
   * OutputMode::resume and no directory it does nothing (there is no
   * checkpoint to resume from either). A refusal is an InputError naming
   * the directory and the ways out; a directory that cannot be created or
   * written into, a std::runtime_error naming the path. The destructor
   * removes the lock file, on normal exit and when an exception unwinds.
   */
  class OutputDirectory
  {
  public:
    OutputDirectory(const std::string &directory,
                    OutputMode         mode,
                    MPI_Comm           communicator,
                    std::ostream      &log);
    ~OutputDirectory();

    OutputDirectory(const OutputDirectory &) = delete;
    OutputDirectory &
    operator=(const OutputDirectory &) = delete;

  private:
    /// Remove our lock file, if any.
    void
    release();

    /// The lock file this process created (rank 0), else empty.
    std::string lock_file;
    /// Its contents, to remove only our own lock.
    std::string lock_text;
  };
} // namespace sable

#endif
