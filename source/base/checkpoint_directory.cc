#include <deal.II/base/mpi.h>

#include <sable/base/checkpoint_directory.h>

#include <boost/crc.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sable
{
  namespace
  {
    namespace fs = std::filesystem;

    const char *const manifest_header = "sable checkpoint manifest 1";

    /// CRC-32 of a file.
    std::uint32_t
    file_checksum(const fs::path &path)
    {
      std::ifstream in(path, std::ios::binary);
      if (!in)
        throw std::runtime_error("cannot read '" + path.string() + "'");
      boost::crc_32_type crc;
      std::vector<char>  buffer(1 << 20);
      while (in)
        {
          in.read(buffer.data(), buffer.size());
          crc.process_bytes(buffer.data(), in.gcount());
        }
      return crc.checksum();
    }

    /// fsync a file or directory (best effort).
    void
    sync(const fs::path &path)
    {
      const int fd = ::open(path.c_str(), O_RDONLY);
      if (fd >= 0)
        {
          ::fsync(fd);
          ::close(fd);
        }
    }
  } // namespace


  void
  on_root(MPI_Comm communicator, const std::function<void()> &work)
  {
    std::string error;
    if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          work();
        }
      catch (const std::exception &e)
        {
          error = e.what();
          if (error.empty())
            error = "unknown error";
        }
    error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw std::runtime_error(error);
  }


  void
  write_manifest(const std::string &directory_name)
  {
    const fs::path        directory(directory_name);
    std::vector<fs::path> files;
    for (const auto &entry : fs::directory_iterator(directory))
      if (entry.is_regular_file() && entry.path().filename() != "manifest")
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::ostringstream text;
    text << manifest_header << '\n' << files.size() << '\n';
    for (const fs::path &file : files)
      {
        text << fs::file_size(file) << ' ' << std::hex << file_checksum(file) << std::dec << ' '
             << file.filename().string() << '\n';
        sync(file);
      }
    text << "end\n";
    {
      std::ofstream out(directory / "manifest");
      out << text.str();
      out.close();
      if (!out)
        throw std::runtime_error("cannot write '" + (directory / "manifest").string() + "'");
    }
    sync(directory / "manifest");
    sync(directory);
  }


  std::string
  checkpoint_problem(const std::string              &directory,
                     const std::vector<std::string> &required_files,
                     const bool                      verify_checksums)
  {
    const fs::path path(directory);
    if (!fs::is_directory(path))
      return "does not exist";
    std::ifstream manifest(path / "manifest");
    if (!manifest)
      return "has no manifest (the write did not finish)";
    std::string header;
    std::getline(manifest, header);
    unsigned int n_files = 0;
    if (header != manifest_header || !(manifest >> n_files))
      return "has an unreadable manifest";
    std::vector<std::string> listed;
    for (unsigned int i = 0; i < n_files; ++i)
      {
        std::uintmax_t size = 0;
        std::uint32_t  crc  = 0;
        std::string    name;
        if (!(manifest >> size >> std::hex >> crc >> std::dec >> name))
          return "has an unreadable manifest";
        const fs::path file = path / name;
        if (!fs::is_regular_file(file))
          return "misses the file " + name;
        if (fs::file_size(file) != size)
          return "has the file " + name + " of " + std::to_string(fs::file_size(file)) +
                 " bytes instead of " + std::to_string(size);
        if (verify_checksums && file_checksum(file) != crc)
          return "has the file " + name + " with a wrong checksum";
        listed.push_back(name);
      }
    std::string end;
    if (!(manifest >> end) || end != "end")
      return "has an unreadable manifest";
    for (const std::string &name : required_files)
      if (std::find(listed.begin(), listed.end(), name) == listed.end())
        return "misses the file " + name;
    return "";
  }


  std::string
  find_checkpoint(const std::string              &output_directory,
                  const std::vector<std::string> &required_files,
                  const std::string              &how_to_write,
                  MPI_Comm                        communicator,
                  std::ostream                   &log)
  {
    std::string chosen;
    on_root(communicator, [&]() {
      const fs::path           base = fs::path(output_directory) / checkpoint_name;
      std::vector<std::string> found;
      for (const std::string &candidate : {base.string(), base.string() + ".old"})
        {
          const std::string problem = checkpoint_problem(candidate, required_files);
          if (problem.empty())
            {
              chosen = candidate;
              break;
            }
          found.push_back("'" + candidate + "' " + problem);
        }
      if (chosen.empty())
        throw std::runtime_error("cannot resume: no complete checkpoint in the output directory '" +
                                 output_directory + "' (" + found[0] + "; " + found[1] +
                                 "). Checkpoints are written with " + how_to_write + ".");
      if (!found.empty())
        log << "Note: the checkpoint " << found[0] << "; resuming from '" << chosen
            << "' instead." << std::endl;
    });
    return dealii::Utilities::MPI::broadcast(communicator, chosen, 0);
  }


  void
  publish_checkpoint(const std::string              &tmp,
                     const std::string              &directory_name,
                     const std::vector<std::string> &required_files)
  {
    const fs::path directory(directory_name);
    const fs::path old = directory.string() + ".old";
    // an incomplete 'directory', left by an earlier failure, must not
    // replace a complete 'old' (sizes suffice to tell)
    if (checkpoint_problem(directory.string(), required_files, false).empty())
      {
        fs::remove_all(old);
        fs::rename(directory, old);
      }
    else
      fs::remove_all(directory);
    fs::rename(tmp, directory);
    sync(directory.parent_path().empty() ? fs::path(".") : directory.parent_path());
    fs::remove_all(old);
  }


  void
  keep_table_rows(const std::string &path, const std::function<bool(unsigned long)> &keep)
  {
    std::ifstream      in(path);
    std::ostringstream kept;
    std::string        line;
    if (std::getline(in, line))
      kept << line << '\n';
    while (std::getline(in, line))
      {
        if (line.empty())
          continue;
        if (keep(std::stoul(line.substr(0, line.find(',')))))
          kept << line << '\n';
      }
    in.close();
    const std::string tmp = path + ".tmp";
    {
      std::ofstream out(tmp);
      out << kept.str();
      out.close();
      if (!out)
        throw std::runtime_error("cannot write '" + tmp + "'");
    }
    fs::rename(tmp, path);
  }
} // namespace sable
