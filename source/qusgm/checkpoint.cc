// Checkpoint and restart of a QuSGM run (see sable/qusgm/checkpoint.h).
#include <deal.II/base/mpi.h>

#include <sable/base/checkpoint_directory.h>
#include <sable/qusgm/checkpoint.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace sable::qusgm
{
  namespace
  {
    namespace fs = std::filesystem;

    const char *const              state_file     = "qusgm.state";
    const std::vector<std::string> required_files = {state_file};
    /// 2: the scene's entries in the progress (1: without)
    constexpr unsigned int         format         = 2;

    /// Everything of a Simulation that the next increment depends on.
    struct SavedSimulation
    {
      unsigned int          format   = qusgm::format;
      unsigned int          n_grains = 0;
      Pack                  pack;
      Walls                 walls;
      ContactModel          model;
      std::array<double, 3> undeformed_lengths{};
      MacroscopicState      last_macroscopic;
      double                last_bulk_modulus = 0, last_shear_modulus = 0;
      unsigned int          n_increments  = 0;
      unsigned int          axis          = 2;
      bool                  have_previous = false;
      Vector<double>        last_theta;
      std::array<double, 6> last_moves{};
      std::vector<Contact>  pairs, wall_contacts; ///< all of them, by key

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &format;
        // an older format is reported by load_state(), not misread
        if (format != qusgm::format)
          return;
        ar &n_grains &pack &walls &model;
        for (double &x : undeformed_lengths)
          ar &x;
        ar &last_macroscopic &last_bulk_modulus &last_shear_modulus &n_increments &axis
          &have_previous &last_theta;
        for (double &x : last_moves)
          ar &x;
        ar &pairs &wall_contacts;
      }
    };

  } // namespace


  std::string
  Simulation::save_state() const
  {
    SavedSimulation saved;
    saved.n_grains           = pack.size();
    saved.pack               = pack;
    saved.walls              = walls;
    saved.model              = model;
    saved.undeformed_lengths = undeformed_lengths;
    saved.last_macroscopic   = last.macroscopic;
    saved.last_bulk_modulus  = last.bulk_modulus;
    saved.last_shear_modulus = last.shear_modulus;
    saved.n_increments       = n_increments;
    saved.axis               = axis;
    saved.have_previous      = have_previous;
    saved.last_theta         = last_theta;
    saved.last_moves         = last_moves;
    saved.pairs              = network.gather_on_root(network.pairs, pack.size());
    saved.wall_contacts      = network.gather_on_root(network.wall_contacts, pack.size());
    if (dealii::Utilities::MPI::this_mpi_process(communicator) != 0)
      return "";
    std::ostringstream bytes;
    {
      boost::archive::binary_oarchive archive(bytes);
      archive << saved;
    }
    return bytes.str();
  }


  void
  Simulation::load_state(const std::string &bytes)
  {
    SavedSimulation saved;
    {
      std::istringstream               in(bytes);
      boost::archive::binary_iarchive archive(in);
      archive >> saved;
    }
    if (saved.format != format)
      throw std::runtime_error("its checkpoint format is " + std::to_string(saved.format) +
                               ", written by an earlier version of sable; this version reads "
                               "format " + std::to_string(format) +
                               " only. Start the run again (with --overwrite), or resume it "
                               "with the version that wrote the checkpoint.");
    if (saved.n_grains != saved.pack.size())
      throw std::runtime_error("its state is damaged (" + std::to_string(saved.n_grains) +
                               " grains announced, " + std::to_string(saved.pack.size()) +
                               " read)");
    if (saved.n_grains != pack.size())
      throw std::runtime_error("it holds a pack of " + std::to_string(saved.n_grains) +
                               " grains, the parameter file gives " +
                               std::to_string(pack.size()));
    pack               = saved.pack;
    walls              = saved.walls;
    model              = saved.model;
    undeformed_lengths = saved.undeformed_lengths;
    last.macroscopic   = saved.last_macroscopic;
    last.bulk_modulus  = saved.last_bulk_modulus;
    last.shear_modulus = saved.last_shear_modulus;
    n_increments       = saved.n_increments;
    axis               = saved.axis;
    have_previous      = saved.have_previous;
    last_theta         = saved.last_theta;
    last_moves         = saved.last_moves;
    // Every contact with its history; build() keeps those of this rank's
    // grains and adds the (open, history-free) ones now within the skin.
    network = ContactNetwork();
    network.set_communicator(communicator);
    network.pairs         = std::move(saved.pairs);
    network.wall_contacts = std::move(saved.wall_contacts);
    network.build(pack, walls, pack.centre, walls, model, settings.skin * pack.mean_radius());
  }


  void
  save_checkpoint(const Simulation  &simulation,
                  const RunProgress &progress,
                  const std::string &output_directory,
                  const MPI_Comm     communicator)
  {
    const std::string state = simulation.save_state();
    const fs::path    directory = fs::path(output_directory) / checkpoint_name;
    const fs::path    tmp       = directory.string() + ".tmp";
    on_root(communicator, [&]() {
      fs::remove_all(tmp);
      fs::create_directories(tmp);
      {
        std::ofstream out(tmp / state_file, std::ios::binary);
        {
          boost::archive::binary_oarchive archive(out);
          archive << state << progress;
        }
        out.close();
        if (!out)
          throw std::runtime_error("cannot write '" + (tmp / state_file).string() + "'");
      }
      write_manifest(tmp.string());
      publish_checkpoint(tmp.string(), directory.string(), required_files);
    });
  }


  bool
  may_change_on_resume(const std::string &name)
  {
    return name == "Threads" || name == "Output directory" ||
           name == "Load path/Number of increments" || name.rfind("Output/", 0) == 0;
  }


  std::string
  find_checkpoint(const std::string &output_directory,
                  const MPI_Comm     communicator,
                  std::ostream      &log)
  {
    return sable::find_checkpoint(output_directory,
                                  required_files,
                                  "'Output/Checkpoint interval' > 0",
                                  communicator,
                                  log);
  }


  RunProgress
  load_checkpoint(Simulation &simulation, const std::string &directory)
  {
    std::string state;
    RunProgress progress;
    try
      {
        std::ifstream                   in(fs::path(directory) / state_file, std::ios::binary);
        boost::archive::binary_iarchive archive(in);
        // the state first: it tells an older format
        archive >> state;
        simulation.load_state(state);
        archive >> progress;
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error("cannot resume from '" + directory + "': " + e.what());
      }
    return progress;
  }
} // namespace sable::qusgm
