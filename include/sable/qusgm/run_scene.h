#ifndef sable_qusgm_run_scene_h
#define sable_qusgm_run_scene_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <sable/base/output_directory.h>
#include <sable/base/parameter_settings.h>

#include <string>

namespace sable::qusgm
{
  /// Declare every entry of a QuSGM parameter file (besides the common ones).
  void
  declare_parameters(dealii::ParameterHandler &prm);

  /**
   * Read, check and run the QuSGM scene in @p filename, with the entries of
   * @p settings (`--set`) changed after the file is read. @p mode says what
   * happens to an earlier run's results in the output directory (see
   * OutputDirectory): OutputMode::resume continues that run from its last
   * checkpoint.
   */
  void
  run_scene(const std::string &                  filename,
            MPI_Comm                             communicator,
            OutputMode                           mode     = OutputMode::fresh,
            const std::vector<ParameterSetting> &settings = {});
} // namespace sable::qusgm

#endif
