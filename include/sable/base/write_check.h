// Checks before a large write, so that a full disk or a file size limit is
// reported by sable with the path instead of aborting inside a library
// (p4est, MPI-IO) halfway through.
#ifndef sable_base_write_check_h
#define sable_base_write_check_h

#include <string>

namespace sable
{
  /**
   * Why @p bytes in all, the largest file @p largest_file bytes, cannot be
   * written into @p directory: fewer bytes free on its file system (statvfs)
   * or a smaller file size limit of the process (ulimit -f). An empty
   * string if neither. The sizes are estimates from below, so a write that
   * fits is never refused.
   */
  std::string
  write_problem(const std::string &directory, double bytes, double largest_file);
} // namespace sable

#endif
