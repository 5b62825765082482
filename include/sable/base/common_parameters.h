#ifndef sable_base_common_parameters_h
#define sable_base_common_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <sable/base/parameter_settings.h>

#include <string>

namespace sable
{
  /// Which model a parameter file runs.
  enum class Model
  {
    mpm,
    qusgm
  };

  /**
   * The entries at the top level of every sable parameter file:
   * `Model` (mpm | qusgm), `Dimension` (2 | 3, MPM only) and `Threads`.
   */
  void
  declare_common_parameters(dealii::ParameterHandler &prm);

  struct CommonParameters
  {
    Model        model     = Model::mpm;
    unsigned int dimension = 2;
    /// Threads per MPI rank (0: one per core); see set_threads().
    unsigned int threads = 1;
  };

  /**
   * Limit deal.II's task scheduler (TBB) to @p threads threads per MPI rank
   * (0: as many as the machine has cores). Results do not depend on it:
   * every threaded loop in sable writes per item or reduces in a fixed
   * order.
   */
  void
  set_threads(const unsigned int threads);

  /**
   * Read only the common entries of @p filename, skipping all others, so the
   * program can pick the model and the dimension before declaring the rest.
   * @p settings (the command line's `--set`) apply to the common entries
   * and are otherwise left for the full read. Throws if the file cannot be
   * read or a common entry is invalid.
   */
  CommonParameters
  read_common_parameters(const std::string &                  filename,
                         const std::vector<ParameterSetting> &settings = {});
} // namespace sable

#endif
