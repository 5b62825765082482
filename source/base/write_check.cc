#include <sable/base/write_check.h>

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <iomanip>
#include <sstream>

namespace sable
{
  std::string
  write_problem(const std::string &directory, const double bytes, const double largest_file)
  {
    std::ostringstream problem;
    problem << std::setprecision(3);
    struct statvfs file_system;
    if (::statvfs(directory.c_str(), &file_system) == 0)
      {
        const double free = double(file_system.f_bavail) * file_system.f_frsize;
        if (free < bytes)
          {
            problem << "its file system has " << free << " bytes free, the files need at least "
                    << bytes << " (the disk is full)";
            return problem.str();
          }
      }
    struct rlimit limit;
    if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
        double(limit.rlim_cur) < largest_file)
      problem << "files are limited to " << double(limit.rlim_cur)
              << " bytes (ulimit -f), the largest needs at least " << largest_file;
    return problem.str();
  }
} // namespace sable
