#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/base/output_directory.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace sable
{
  namespace
  {
    namespace fs = std::filesystem;

    std::string
    host_name()
    {
      char name[256] = {};
      if (::gethostname(name, sizeof(name) - 1) != 0)
        return "unknown";
      return name;
    }

    /// The holder of a lock file: process id and host, "pid host".
    struct LockHolder
    {
      long        pid = 0;
      std::string host;

      /// A process of this host that no longer exists.
      bool
      is_dead_here() const
      {
        return pid > 0 && host == host_name() && ::kill(pid, 0) != 0 && errno == ESRCH;
      }
    };

    LockHolder
    read_lock(const fs::path &file)
    {
      LockHolder    holder;
      std::ifstream in(file);
      in >> holder.pid >> holder.host;
      return holder;
    }

    std::string
    in_use_message(const std::string &directory, const fs::path &file, const LockHolder &holder)
    {
      std::ostringstream message;
      message << "the output directory '" << directory
              << "' is in use by another sable run (process " << holder.pid << " on host '"
              << holder.host << "', lock file '" << file.string()
              << "'). Wait for that run to end, or choose another 'Output directory'"
                 " (--set \"Output directory=...\"); if no such run exists, remove the lock file.";
      return message.str();
    }

    std::string
    list(const std::vector<std::string> &names)
    {
      std::string text;
      for (unsigned int i = 0; i < names.size() && i < 5; ++i)
        text += (i ? ", " : "") + names[i];
      if (names.size() > 5)
        text += ", ... (" + std::to_string(names.size()) + " in all)";
      return text;
    }
  } // namespace


  bool
  is_sable_output(const std::string &name)
  {
    static const std::regex pattern(
      "(statistics|increments)\\.csv(\\.tmp)?|iterations\\.log|"
      "checkpoint(\\.old|\\.tmp)?|final_state|prepared_state|"
      "(particles|contact_nodes|grid)(\\.pvd|\\.xdmf|_[0-9]+[.0-9]*(vtu|pvtu|h5))|"
      "(grains|contacts)(\\.pvd|-[0-9]+[.0-9]*(vtu|pvtu))");
    return std::regex_match(name, pattern);
  }


  std::vector<std::string>
  sable_outputs(const std::string &directory)
  {
    std::vector<std::string> names;
    std::error_code          error;
    for (const auto &entry : fs::directory_iterator(directory, error))
      if (is_sable_output(entry.path().filename().string()))
        names.push_back(entry.path().filename().string());
    // the tables and the checkpoint first: they say most about the run
    const auto rank = [](const std::string &name) {
      return name.find(".csv") != std::string::npos ? 0 : name.rfind("checkpoint", 0) == 0 ? 1 : 2;
    };
    std::sort(names.begin(), names.end(), [&](const std::string &a, const std::string &b) {
      return std::make_pair(rank(a), a) < std::make_pair(rank(b), b);
    });
    return names;
  }


  OutputDirectory::OutputDirectory(const std::string &directory,
                                   const OutputMode   mode,
                                   MPI_Comm           communicator,
                                   std::ostream      &log)
  {
    // rank 0 works; its error, 'I' (input) or 'E' (environment) first,
    // is thrown on every rank
    std::string error;
    if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          const fs::path path(directory);
          const fs::path file = path / lock_file_name;
          if (!(mode == OutputMode::resume && !fs::exists(path)))
            {
              // 1. nobody else writes here
              bool take_over = false;
              if (fs::exists(file))
                {
                  const LockHolder holder = read_lock(file);
                  if (!holder.is_dead_here())
                    throw InputError(in_use_message(directory, file, holder));
                  take_over = true;
                  log << "Note: taking over the lock file '" << file.string()
                      << "' of process " << holder.pid
                      << ", which no longer runs (an earlier run was killed)." << std::endl;
                }

              // 2. no earlier results, unless they are to go
              const std::vector<std::string> earlier = sable_outputs(directory);
              if (mode == OutputMode::fresh && !earlier.empty())
                throw InputError("the output directory '" + directory +
                                 "' holds the results of an earlier run (" + list(earlier) +
                                 "). Start with --overwrite to remove them first (only sable's own "
                                 "outputs, no other files), with --resume to continue that run "
                                 "from its checkpoint, or choose another 'Output directory'.");

              // 3. the directory and our lock
              std::error_code ec;
              fs::create_directories(path, ec);
              if (ec || !fs::is_directory(path))
                throw std::runtime_error("cannot create the output directory '" + directory +
                                         "': " + (ec ? ec.message() : "a file of that name exists"));
              if (take_over)
                fs::remove(file);
              const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
              if (fd < 0 && errno == EEXIST)
                throw InputError(in_use_message(directory, file, read_lock(file)));
              if (fd < 0)
                throw std::runtime_error("cannot write into the output directory '" + directory +
                                         "' (creating '" + file.string() +
                                         "'): " + std::strerror(errno));
              lock_text = std::to_string(::getpid()) + " " + host_name() + "\n";
              const bool written =
                ::write(fd, lock_text.data(), lock_text.size()) ==
                static_cast<ssize_t>(lock_text.size());
              const int write_errno = errno;
              ::close(fd);
              lock_file = file.string();
              if (!written)
                throw std::runtime_error("cannot write into the output directory '" + directory +
                                         "' (writing '" + file.string() +
                                         "'): " + std::strerror(write_errno));

              // 4. the earlier results go
              if (mode == OutputMode::overwrite && !earlier.empty())
                {
                  for (const std::string &name : earlier)
                    fs::remove_all(path / name);
                  log << "Note: --overwrite removed the earlier outputs in '" << directory
                      << "' (" << list(earlier) << ")." << std::endl;
                }
            }
        }
      catch (const InputError &e)
        {
          error = std::string("I") + e.what();
        }
      catch (const std::exception &e)
        {
          error = std::string("E") + e.what();
        }
    error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
    if (error.empty())
      return;
    // a lock taken before the error is released (no destructor runs)
    release();
    if (error[0] == 'I')
      throw InputError(error.substr(1));
    throw std::runtime_error(error.substr(1));
  }


  OutputDirectory::~OutputDirectory()
  {
    release();
  }


  void
  OutputDirectory::release()
  {
    if (lock_file.empty())
      return;
    // only our own lock (a user may have removed it and started another run)
    std::ifstream     in(lock_file);
    std::stringstream text;
    text << in.rdbuf();
    in.close();
    if (text.str() == lock_text)
      ::unlink(lock_file.c_str());
    lock_file.clear();
  }
} // namespace sable
