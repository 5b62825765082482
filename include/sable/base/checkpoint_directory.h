// Checkpoint directories that are either complete or ignored: a manifest
// with the size and CRC-32 of every file, written last, and an atomic swap
// with the previous checkpoint. Shared by the MPM and QuSGM checkpoints.
#ifndef sable_base_checkpoint_directory_h
#define sable_base_checkpoint_directory_h

#include <deal.II/base/mpi.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace sable
{
  /**
   * A checkpoint is written into `<name>.tmp`; write_manifest() seals it;
   * publish_checkpoint() renames the previous `<name>` to `<name>.old`,
   * `<name>.tmp` to `<name>`, and removes `<name>.old`. Whatever moment a
   * run is stopped at, `<name>` or `<name>.old` holds a complete
   * checkpoint; find_checkpoint() picks it.
   */

  /// Directory name of a checkpoint inside the output directory.
  inline const char *const checkpoint_name = "checkpoint";

  /// Run @p work on rank 0; an exception there is thrown on every rank.
  void
  on_root(MPI_Comm communicator, const std::function<void()> &work);

  /// Write the manifest of every regular file in @p directory (last).
  void
  write_manifest(const std::string &directory);

  /**
   * What is wrong with the checkpoint in @p directory (missing, no
   * manifest, a file missing, of the wrong size or, with
   * @p verify_checksums, with the wrong checksum, or one of
   * @p required_files not listed), or an empty string if it is complete.
   * Checksums mean reading every file.
   */
  std::string
  checkpoint_problem(const std::string              &directory,
                     const std::vector<std::string> &required_files,
                     bool                            verify_checksums = true);

  /**
   * The checkpoint to resume the run in @p output_directory from:
   * `<output_directory>/checkpoint`, or `checkpoint.old` if the former is
   * missing or incomplete (a note goes to @p log on rank 0). Collective.
   * Throws std::runtime_error naming the directory, what was found and
   * @p how_to_write (the parameter that writes checkpoints) if neither is
   * usable.
   */
  std::string
  find_checkpoint(const std::string              &output_directory,
                  const std::vector<std::string> &required_files,
                  const std::string              &how_to_write,
                  MPI_Comm                        communicator,
                  std::ostream                   &log);

  /**
   * Make the sealed @p tmp the checkpoint @p directory, keeping the
   * previous complete one as `<directory>.old` until then. Rank 0 only.
   */
  void
  publish_checkpoint(const std::string              &tmp,
                     const std::string              &directory,
                     const std::vector<std::string> &required_files);

  /**
   * Keep the header and the rows of the CSV file @p path whose first
   * column (an integer) @p keep accepts, replacing the file atomically.
   */
  void
  keep_table_rows(const std::string                           &path,
                  const std::function<bool(unsigned long)>    &keep);
} // namespace sable

#endif
