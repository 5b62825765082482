#ifndef sable_qusgm_run_scene_h
#define sable_qusgm_run_scene_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <sable/base/parameter_settings.h>

#include <string>

namespace sable::qusgm
{
  /// Declare every entry of a QuSGM parameter file (besides the common ones).
  void
  declare_parameters(dealii::ParameterHandler &prm);

  /**
   * Read, check and run the QuSGM scene in @p filename, with the entries of
   * @p settings (`--set`) changed after the file is read; with @p resume,
   * continue from the last checkpoint in its output directory.
   */
  void
  run_scene(const std::string &                  filename,
            MPI_Comm                             communicator,
            bool                                 resume   = false,
            const std::vector<ParameterSetting> &settings = {});
} // namespace sable::qusgm

#endif
