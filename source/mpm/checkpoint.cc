// Checkpoint and restart of the MPM simulator (see sable/mpm/checkpoint.h).
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/base/checkpoint_directory.h>
#include <sable/base/parameter_file.h>
#include <sable/base/write_check.h>
#include <sable/mpm/checkpoint.h>
#include <sable/mpm/run_state.h>
#include <sable/mpm/postprocess/grid_output.h>
#include <sable/mpm/simulator.h>

#include <boost/archive/text_iarchive.hpp>
#include <boost/archive/text_oarchive.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

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

    const char *const state_file = "simulator.state";
    const char *const mesh_file  = "triangulation";
    const std::vector<std::string> required_files = {state_file, mesh_file};

    void
    require(const bool condition, const std::string &message)
    {
      if (!condition)
        throw std::runtime_error(message);
    }

    /// Everything of the Simulator that is not in the mesh or the particles.
    template <int dim>
    struct SavedState
    {
      /// 11: the corrections' loss (impact_loss); 10: the points' vectors
      /// to their face (with face normals); 9: the
      /// contact pairs' pulling impulses; 8: the reported pairs'
      /// moments; 7: whether the last step's
      /// statistics row is due; 6: the scene's
      /// entries, compared on resume (5: the friction heat of the walls; 4: the run
      /// state as one RunState, the contact nodes as an output series;
      /// 3: the grid's base level and the grid output series; 1 and 2 have
      /// a coarse mesh of every subdivision cell)
      static constexpr unsigned int current_format = 11;
      unsigned int          format         = current_format;
      unsigned int          dimension      = dim;
      unsigned int          n_bodies       = 0;
      unsigned int          n_properties   = 0;
      unsigned int          n_coarse_cells = 0;
      unsigned int          n_ranks        = 0;
      unsigned int          base_level     = 0;
      std::vector<double>   grid_box;
      unsigned long long    n_particles  = 0;
      RunState              run;
      double                wall_heat        = 0;
      double                correction_loss  = 0;
      bool                  with_contact            = false;
      double                frictional_heat         = 0;
      double                momentum_defect         = 0;
      double                momentum_correction     = 0;
      std::vector<Tensor<1, dim>>                 pair_forces;
      std::vector<Tensor<1, 3>>                   pair_moments;
      std::vector<double>                         pulling_impulses;
      std::vector<std::pair<double, std::string>> particle_files;
      std::vector<std::pair<double, std::string>> contact_node_files;
      std::vector<XDMFEntry>                      contact_node_xdmf_entries;
      std::vector<XDMFEntry>                      xdmf_entries;
      std::vector<std::pair<double, std::string>> grid_files;
      std::vector<XDMFEntry>                      grid_xdmf_entries;
      std::vector<std::pair<std::string, std::string>> scene_entries;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &format;
        // an older format is reported by resume(), not misread
        if (format != current_format)
          return;
        ar &dimension &n_bodies &n_properties &n_coarse_cells &n_ranks &base_level &grid_box;
        ar &n_particles &run &wall_heat &correction_loss;
        ar &with_contact &frictional_heat &momentum_defect &momentum_correction;
        ar &pair_forces &pair_moments &pulling_impulses;
        ar &particle_files &contact_node_files &contact_node_xdmf_entries &xdmf_entries;
        ar &grid_files &grid_xdmf_entries;
        ar &scene_entries;
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
     * statistics schedule asks for it (@p row_due) or the run ends there (a
     * stopped run also writes its last step).
     */
    void
    truncate_statistics(const fs::path &   path,
                        const unsigned int step,
                        const bool         row_due,
                        const bool         ends_here)
    {
      keep_table_rows(path.string(), [&](const unsigned long row_step) {
        return row_step < step || (row_step == step && (row_due || ends_here));
      });
    }
  } // namespace


  std::string
  find_checkpoint(const std::string &output_directory,
                  MPI_Comm           communicator,
                  std::ostream &     log)
  {
    return sable::find_checkpoint(output_directory,
                                  required_files,
                                  "'Output/Checkpoint interval' > 0",
                                  communicator,
                                  log);
  }


  template <int dim>
  void
  Simulator<dim>::save_checkpoint(const std::string &directory_name)
  {
    AssertThrow(initialized, ExcMessage("save_checkpoint() needs an initialized Simulator."));
    AssertThrow(!directory_name.empty() || !parameters.output_directory.empty(),
                ExcMessage("save_checkpoint() needs a directory when the output directory is "
                           "empty."));
    put_particles_in_order();
    TimerOutput::Scope scope(timer, "checkpoint");
    const fs::path directory =
      directory_name.empty() ? fs::path(parameters.output_directory) / checkpoint_name :
                               fs::path(directory_name);
    const fs::path tmp = directory.string() + ".tmp";
    // the material points' properties, the bulk of the checkpoint, at least
    const double bytes =
      double(particle_handler->n_global_particles()) * layout.n_properties() * sizeof(double);
    on_root(communicator, [&]() {
      // p4est aborts the program on a failed write: check first
      const fs::path parent  = directory.parent_path().empty() ? "." : directory.parent_path();
      std::string    problem = fs::is_directory(parent) ? write_problem(parent.string(), bytes, bytes) : "";
      if (problem.empty())
        {
          std::error_code error;
          fs::remove_all(tmp, error);
          if (!error)
            fs::create_directories(tmp, error);
          if (error)
            problem = error.message();
        }
      if (!problem.empty())
        throw std::runtime_error("cannot write the checkpoint '" + tmp.string() + "': " + problem +
                                 ". The previous checkpoint, if any, is kept.");
    });

    particle_handler->prepare_for_serialization();
    triangulation.save((tmp / mesh_file).string());

    SavedState<dim> state;
    state.n_bodies                = parameters.bodies.size();
    state.n_properties            = layout.n_properties();
    state.n_coarse_cells          = triangulation.n_cells(0);
    state.n_ranks                 = Utilities::MPI::n_mpi_processes(communicator);
    state.base_level              = base_level;
    state.grid_box                = grid_box(triangulation);
    state.n_particles             = particle_handler->n_global_particles();
    state.run                     = this->state;
    state.wall_heat = Utilities::MPI::sum(boundary_conditions.frictional_heat, communicator);
    state.correction_loss = Utilities::MPI::sum(correction_loss, communicator);
    state.scene_entries           = parameters.scene_entries;
    state.particle_files          = particle_series.files;
    state.contact_node_files        = contact_node_series.files;
    state.contact_node_xdmf_entries = contact_node_series.xdmf_entries;
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
        state.frictional_heat     = Utilities::MPI::sum(contact->get_model().frictional_heat, communicator);
        state.momentum_defect     = Utilities::MPI::sum(contact->get_model().momentum_defect, communicator);
        state.momentum_correction = Utilities::MPI::sum(contact->get_model().momentum_correction, communicator);
        for (const auto &force : contact->get_model().pair_forces)
          state.pair_forces.push_back(Utilities::MPI::sum(force, communicator));
        for (const auto &moment : contact->get_model().pair_moments)
          state.pair_moments.push_back(Utilities::MPI::sum(moment, communicator));
        // the same on every rank
        state.pulling_impulses = contact->get_model().get_pulling_impulses();
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
      write_manifest(tmp.string());
      publish_checkpoint(tmp.string(), directory.string(), required_files);
    });
  }


  template <int dim>
  void
  Simulator<dim>::resume(const std::string &directory)
  {
    AssertThrow(!seeded && !initialized,
                ExcMessage("resume() replaces seed() and initialize(): call it once, on a new "
                           "Simulator."));
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
    require(state.format == SavedState<dim>::current_format,
            "cannot resume from '" + directory + "': its checkpoint format is " +
              std::to_string(state.format) + ", written by an earlier version of sable; this "
              "version reads format " + std::to_string(SavedState<dim>::current_format) +
              " only. Start the run again (with --overwrite), or resume it with the version "
              "that wrote the checkpoint.");
    require(state.dimension == dim,
            mismatch("Dimension =", std::to_string(state.dimension), std::to_string(dim)));
    if (!state.scene_entries.empty() && !parameters.scene_entries.empty())
      {
        const std::string differences =
          entry_differences(state.scene_entries, parameters.scene_entries, may_change_on_resume);
        require(differences.empty(),
                "cannot resume from '" + directory +
                  "': the scene differs from the one the checkpoint was written with:" +
                  differences +
                  "\nOnly the time limits (Time/End time, Time/Maximum number of steps, "
                  "Time/CFL number), the Output entries besides the Output format and "
                  "Displacement output, Threads "
                  "and Solver/Balance particles across ranks may change on resume. Give these "
                  "entries their earlier values, or start the run again with --overwrite.");
      }
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

    base_level = state.base_level;
    if (mesh_refinement)
      mesh_refinement->set_base_level(base_level);
    // the mesh with its refinement, and the material points
    triangulation.load((path / mesh_file).string());
    particle_handler->deserialize();
    // the loaded mesh is split by cells only (and maybe over another
    // number of ranks): balance the material points again
    if (parallel && parameters.balance_particles)
      {
        connect_cell_weights();
        rebalance();
      }
    else
      setup_after_mesh_change();
    require(particle_handler->n_global_particles() == state.n_particles,
            "cannot resume from '" + directory + "': it should hold " +
              std::to_string(state.n_particles) + " material points, " +
              std::to_string(particle_handler->n_global_particles()) + " were read");

    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    this->state                  = state.run;
    // the sums over ranks continue on rank 0
    boundary_conditions.frictional_heat = root ? state.wall_heat : 0.;
    correction_loss                     = root ? state.correction_loss : 0.;
    particle_series.files        = state.particle_files;
    contact_node_series.files        = state.contact_node_files;
    contact_node_series.xdmf_entries = state.contact_node_xdmf_entries;
    particle_series.xdmf_entries = state.xdmf_entries;
    if (grid_output)
      {
        grid_output->series.files        = state.grid_files;
        grid_output->series.xdmf_entries = state.grid_xdmf_entries;
      }
    if (contact && state.with_contact)
      {
        // the sums over ranks continue on rank 0
        contact->get_model().frictional_heat     = root ? state.frictional_heat : 0.;
        contact->get_model().momentum_defect     = root ? state.momentum_defect : 0.;
        contact->get_model().momentum_correction = root ? state.momentum_correction : 0.;
        if (state.pair_forces.size() == contact->get_model().pair_forces.size())
          for (unsigned int i = 0; i < state.pair_forces.size(); ++i)
            contact->get_model().pair_forces[i] = root ? state.pair_forces[i] : Tensor<1, dim>();
        if (state.pair_moments.size() == contact->get_model().pair_moments.size())
          for (unsigned int i = 0; i < state.pair_moments.size(); ++i)
            contact->get_model().pair_moments[i] = root ? state.pair_moments[i] : Tensor<1, 3>();
        contact->get_model().set_pulling_impulses(state.pulling_impulses);
      }

    // statistics.csv: the rows up to the checkpoint, then this run's
    bool append = false;
    if (!parameters.output_directory.empty())
      {
        on_root(communicator, [&]() {
          const fs::path file = fs::path(parameters.output_directory) / "statistics.csv";
          if (fs::exists(file))
            {
              truncate_statistics(file, this->state.step_number, this->state.statistics_row_due, finished());
              append = true;
            }
        });
        append = Utilities::MPI::broadcast(communicator, append, 0);
      }
    setup_output(append);
    set_contact_body_shapes();

    pcout << "sable MPM " << dim << "D: resumed from " << directory << " at step "
          << this->state.step_number << ", t = " << this->state.time << ": " << triangulation.n_global_active_cells()
          << " cells, " << particle_handler->n_global_particles() << " material points, "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s)" << std::endl;
    if (parallel)
      print_balance();
    initialized = true;
  }

  template void Simulator<2>::save_checkpoint(const std::string &);
  template void Simulator<3>::save_checkpoint(const std::string &);
  template void Simulator<2>::resume(const std::string &);
  template void Simulator<3>::resume(const std::string &);
} // namespace sable::mpm
