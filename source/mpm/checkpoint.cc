// Checkpoint and restart of the MPM simulator (see sable/mpm/checkpoint.h).
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/mpm/checkpoint.h>
#include <sable/mpm/postprocess/grid_output.h>
#include <sable/mpm/simulator.h>

#include <boost/archive/text_iarchive.hpp>
#include <boost/archive/text_oarchive.hpp>
#include <boost/crc.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace sable::mpm
{
  namespace
  {
    namespace fs = std::filesystem;

    const char *const manifest_header = "sable checkpoint manifest 1";
    const char *const state_file      = "simulator.state";
    const char *const mesh_file       = "triangulation";

    /// Run @p work on rank 0; an exception there is thrown on every rank.
    void
    on_root(MPI_Comm communicator, const std::function<void()> &work)
    {
      std::string error;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
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
      error = Utilities::MPI::broadcast(communicator, error, 0);
      if (!error.empty())
        throw std::runtime_error(error);
    }

    void
    require(const bool condition, const std::string &message)
    {
      if (!condition)
        throw std::runtime_error(message);
    }

    /// CRC-32 of a file; also flushes it to the disk.
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

    /// The manifest of every regular file in @p directory, written last.
    void
    write_manifest(const fs::path &directory)
    {
      std::vector<fs::path> files;
      for (const auto &entry : fs::directory_iterator(directory))
        if (entry.is_regular_file() && entry.path().filename() != "manifest")
          files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      std::ostringstream text;
      text << manifest_header << '\n' << files.size() << '\n';
      for (const fs::path &file : files)
        {
          text << fs::file_size(file) << ' ' << std::hex << file_checksum(file) << std::dec
               << ' ' << file.filename().string() << '\n';
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

    /// Everything of the Simulator that is not in the mesh or the particles.
    template <int dim>
    struct SavedState
    {
      /// 2: with the grid output series
      unsigned int          format         = 2;
      unsigned int          dimension      = dim;
      unsigned int          n_bodies       = 0;
      unsigned int          n_properties   = 0;
      unsigned int          n_coarse_cells = 0;
      unsigned int          n_ranks        = 0;
      std::vector<double>   grid_box;
      unsigned long long    n_particles  = 0;
      unsigned int          step_number  = 0;
      double                time         = 0;
      double                time_step    = 0;
      double                max_signal_speed        = 0;
      double                boundary_work           = 0;
      double                initial_energy          = 0;
      double                initial_gravity_energy  = 0;
      double                energy_floor            = 0;
      double                largest_gravity_release = 0;
      double                next_output_time        = 0;
      unsigned int          output_counter          = 0;
      unsigned int          adaptations_without_change = 0;
      double                travel_since_adaptation    = 0;
      bool                  with_contact            = false;
      double                frictional_heat         = 0;
      double                momentum_defect         = 0;
      double                momentum_correction     = 0;
      std::vector<Tensor<1, dim>>                 pair_forces;
      std::vector<std::pair<double, std::string>> particle_files;
      std::vector<std::pair<double, std::string>> contact_node_files;
      std::vector<XDMFEntry>                      xdmf_entries;
      std::vector<std::pair<double, std::string>> grid_files;
      std::vector<XDMFEntry>                      grid_xdmf_entries;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &format &dimension &n_bodies &n_properties &n_coarse_cells &n_ranks &grid_box;
        ar &n_particles &step_number &time &time_step &max_signal_speed &boundary_work;
        ar &initial_energy &initial_gravity_energy &energy_floor &largest_gravity_release;
        ar &next_output_time &output_counter &adaptations_without_change &travel_since_adaptation;
        ar &with_contact &frictional_heat &momentum_defect &momentum_correction &pair_forces;
        ar &particle_files &contact_node_files &xdmf_entries;
        // format is read first, so a format 1 checkpoint loads without these
        if (format >= 2)
          ar &grid_files &grid_xdmf_entries;
      }
    };

    template <int dim>
    std::vector<double>
    grid_box(const Triangulation<dim> &triangulation)
    {
      const auto corners =
        GridTools::compute_bounding_box(triangulation).get_boundary_points();
      std::vector<double> box;
      for (unsigned int d = 0; d < dim; ++d)
        box.push_back(corners.first[d]);
      for (unsigned int d = 0; d < dim; ++d)
        box.push_back(corners.second[d]);
      return box;
    }

    /**
     * Keep the rows of statistics.csv an uninterrupted run has up to
     * @p step: those before it, and the row of @p step itself if the
     * statistics interval asks for it or the run ends there (a stopped run
     * also writes its last step).
     */
    void
    truncate_statistics(const fs::path &   path,
                        const unsigned int step,
                        const unsigned int interval,
                        const bool         ends_here)
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
          const unsigned long row_step = std::stoul(line.substr(0, line.find(',')));
          if (row_step < step || (row_step == step && (step % interval == 0 || ends_here)))
            kept << line << '\n';
        }
      in.close();
      const fs::path tmp = path.string() + ".tmp";
      {
        std::ofstream out(tmp);
        out << kept.str();
        out.close();
        if (!out)
          throw std::runtime_error("cannot write '" + tmp.string() + "'");
      }
      fs::rename(tmp, path);
    }
  } // namespace


  std::string
  checkpoint_problem(const std::string &directory, const bool verify_checksums)
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
    bool has_state = false, has_mesh = false;
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
        has_state = has_state || name == state_file;
        has_mesh  = has_mesh || name == mesh_file;
      }
    std::string end;
    if (!(manifest >> end) || end != "end")
      return "has an unreadable manifest";
    if (!has_state || !has_mesh)
      return "misses the simulator state or the mesh";
    return "";
  }


  std::string
  find_checkpoint(const std::string &output_directory,
                  MPI_Comm           communicator,
                  std::ostream &     log)
  {
    std::string chosen;
    on_root(communicator, [&]() {
      const fs::path           base = fs::path(output_directory) / checkpoint_name;
      std::vector<std::string> found;
      for (const std::string &candidate : {base.string(), base.string() + ".old"})
        {
          const std::string problem = checkpoint_problem(candidate);
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
                                 "). Checkpoints are written with 'Output/Checkpoint "
                                 "interval' > 0.");
      if (!found.empty())
        log << "Note: the checkpoint " << found[0] << "; resuming from '" << chosen
            << "' instead." << std::endl;
    });
    return Utilities::MPI::broadcast(communicator, chosen, 0);
  }


  template <int dim>
  void
  Simulator<dim>::save_checkpoint(const std::string &directory_name)
  {
    AssertThrow(initialized, ExcMessage("save_checkpoint() needs an initialized Simulator."));
    AssertThrow(!directory_name.empty() || !parameters.output_directory.empty(),
                ExcMessage("save_checkpoint() needs a directory when the output directory is "
                           "empty."));
    TimerOutput::Scope scope(timer, "checkpoint");
    const fs::path directory =
      directory_name.empty() ? fs::path(parameters.output_directory) / checkpoint_name :
                               fs::path(directory_name);
    const fs::path tmp = directory.string() + ".tmp";
    const fs::path old = directory.string() + ".old";
    on_root(communicator, [&]() {
      fs::remove_all(tmp);
      fs::create_directories(tmp);
    });

    particle_handler->prepare_for_serialization();
    triangulation.save((tmp / mesh_file).string());

    SavedState<dim> state;
    state.n_bodies                = parameters.bodies.size();
    state.n_properties            = layout.n_properties();
    state.n_coarse_cells          = triangulation.n_cells(0);
    state.n_ranks                 = Utilities::MPI::n_mpi_processes(communicator);
    state.grid_box                = grid_box(triangulation);
    state.n_particles             = particle_handler->n_global_particles();
    state.step_number             = step_number;
    state.time                    = time;
    state.time_step               = time_step;
    state.max_signal_speed        = max_signal_speed;
    state.boundary_work           = boundary_work;
    state.initial_energy          = initial_energy;
    state.initial_gravity_energy  = initial_gravity_energy;
    state.energy_floor            = energy_floor;
    state.largest_gravity_release = largest_gravity_release;
    state.next_output_time        = next_output_time;
    state.output_counter          = output_counter;
    state.adaptations_without_change = adaptations_without_change;
    state.travel_since_adaptation    = travel_since_adaptation;
    state.particle_files          = particle_series.files;
    state.contact_node_files      = contact_node_files;
    state.xdmf_entries            = particle_series.xdmf_entries;
    if (grid_output)
      {
        state.grid_files        = grid_output->series.files;
        state.grid_xdmf_entries = grid_output->series.xdmf_entries;
      }
    if (contact)
      {
        // per-rank sums, kept on rank 0 after a restart
        state.with_contact        = true;
        state.frictional_heat     = Utilities::MPI::sum(contact->frictional_heat, communicator);
        state.momentum_defect     = Utilities::MPI::sum(contact->momentum_defect, communicator);
        state.momentum_correction = Utilities::MPI::sum(contact->momentum_correction, communicator);
        for (const auto &force : contact->pair_forces)
          state.pair_forces.push_back(Utilities::MPI::sum(force, communicator));
      }

    // all ranks are done with the mesh files before rank 0 seals the set
    MPI_Barrier(communicator);
    on_root(communicator, [&]() {
      {
        std::ofstream out(tmp / state_file);
        {
          boost::archive::text_oarchive archive(out);
          archive << state;
        }
        out.close();
        if (!out)
          throw std::runtime_error("cannot write '" + (tmp / state_file).string() + "'");
      }
      write_manifest(tmp);
      // the set is complete: swap it in, keeping the previous complete one
      // until then (an incomplete 'directory', left by an earlier failure,
      // must not replace a complete 'old'; sizes suffice to tell)
      if (checkpoint_problem(directory.string(), false).empty())
        {
          fs::remove_all(old);
          fs::rename(directory, old);
        }
      else
        fs::remove_all(directory);
      fs::rename(tmp, directory);
      sync(directory.parent_path().empty() ? fs::path(".") : directory.parent_path());
      fs::remove_all(old);
    });
  }


  template <int dim>
  void
  Simulator<dim>::resume(const std::string &directory)
  {
    AssertThrow(!initialized,
                ExcMessage("resume() replaces initialize(): call it once, on a new Simulator."));
    TimerOutput::Scope scope(timer, "initialize");
    const fs::path path(directory);

    SavedState<dim> state;
    {
      std::ifstream in(path / state_file);
      try
        {
          boost::archive::text_iarchive archive(in);
          archive >> state;
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("cannot read the simulator state '" +
                                   (path / state_file).string() + "': " + e.what());
        }
    }

    setup_models();
    create_particle_handler();
    const auto mismatch = [&](const std::string &what,
                              const std::string &saved,
                              const std::string &now) {
      return "cannot resume from '" + directory + "': it holds a scene with " + what + " " +
             saved + ", the parameter file gives " + now;
    };
    require((state.format == 1 || state.format == 2) && state.dimension == dim,
            mismatch("format/dimension",
                     std::to_string(state.format) + "/" + std::to_string(state.dimension),
                     "1 or 2/" + std::to_string(dim)));
    require(state.n_bodies == parameters.bodies.size(),
            mismatch("'Number of bodies' =",
                     std::to_string(state.n_bodies),
                     std::to_string(parameters.bodies.size())));
    require(state.n_properties == layout.n_properties(),
            mismatch("material-point properties:",
                     std::to_string(state.n_properties),
                     std::to_string(layout.n_properties())));
    AssertThrow(triangulation.n_levels() == 1,
                ExcMessage("resume() needs the unrefined coarse mesh of the saved run."));
    {
      const std::vector<double> box = grid_box(triangulation);
      bool                      same = box.size() == state.grid_box.size() &&
                  triangulation.n_cells(0) == state.n_coarse_cells;
      for (unsigned int i = 0; same && i < box.size(); ++i)
        same = std::abs(box[i] - state.grid_box[i]) <=
               1e-12 * (1. + std::abs(state.grid_box[i]));
      std::ostringstream saved, now;
      saved << state.n_coarse_cells << " cells in [";
      now << triangulation.n_cells(0) << " cells in [";
      for (unsigned int i = 0; i < box.size(); ++i)
        {
          saved << (i ? ", " : "") << state.grid_box[i];
          now << (i ? ", " : "") << box[i];
        }
      saved << "]";
      now << "]";
      require(same, mismatch("a coarse grid of", saved.str(), now.str()));
    }

    // the mesh with its refinement, and the material points
    triangulation.load((path / mesh_file).string());
    particle_handler->deserialize();
    setup_after_mesh_change();
    require(particle_handler->n_global_particles() == state.n_particles,
            "cannot resume from '" + directory + "': it should hold " +
              std::to_string(state.n_particles) + " material points, " +
              std::to_string(particle_handler->n_global_particles()) + " were read");

    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    step_number             = state.step_number;
    time                    = state.time;
    time_step               = state.time_step;
    max_signal_speed        = state.max_signal_speed;
    boundary_work           = state.boundary_work;
    initial_energy          = state.initial_energy;
    initial_gravity_energy  = state.initial_gravity_energy;
    energy_floor            = state.energy_floor;
    largest_gravity_release = state.largest_gravity_release;
    next_output_time        = state.next_output_time;
    output_counter          = state.output_counter;
    adaptations_without_change = state.adaptations_without_change;
    travel_since_adaptation    = state.travel_since_adaptation;
    particle_series.files        = state.particle_files;
    contact_node_files           = state.contact_node_files;
    particle_series.xdmf_entries = state.xdmf_entries;
    if (grid_output)
      {
        grid_output->series.files        = state.grid_files;
        grid_output->series.xdmf_entries = state.grid_xdmf_entries;
      }
    if (contact && state.with_contact)
      {
        // the sums over ranks continue on rank 0
        contact->frictional_heat     = root ? state.frictional_heat : 0.;
        contact->momentum_defect     = root ? state.momentum_defect : 0.;
        contact->momentum_correction = root ? state.momentum_correction : 0.;
        if (state.pair_forces.size() == contact->pair_forces.size())
          for (unsigned int i = 0; i < state.pair_forces.size(); ++i)
            contact->pair_forces[i] = root ? state.pair_forces[i] : Tensor<1, dim>();
      }

    // statistics.csv: the rows up to the checkpoint, then this run's
    bool append = false;
    if (!parameters.output_directory.empty())
      {
        on_root(communicator, [&]() {
          const fs::path file = fs::path(parameters.output_directory) / "statistics.csv";
          if (fs::exists(file))
            {
              truncate_statistics(file, step_number, parameters.statistics_interval, finished());
              append = true;
            }
        });
        append = Utilities::MPI::broadcast(communicator, append, 0);
      }
    setup_output(append);

    pcout << "sable MPM " << dim << "D: resumed from " << directory << " at step "
          << step_number << ", t = " << time << ": " << triangulation.n_global_active_cells()
          << " cells, " << particle_handler->n_global_particles() << " material points, "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s)" << std::endl;
    initialized = true;
  }

  template void Simulator<2>::save_checkpoint(const std::string &);
  template void Simulator<3>::save_checkpoint(const std::string &);
  template void Simulator<2>::resume(const std::string &);
  template void Simulator<3>::resume(const std::string &);
} // namespace sable::mpm
