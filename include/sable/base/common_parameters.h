#ifndef sable_base_common_parameters_h
#define sable_base_common_parameters_h

#include <deal.II/base/parameter_handler.h>

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
   * `Model` (mpm | qusgm) and `Dimension` (2 | 3, MPM only).
   */
  void
  declare_common_parameters(dealii::ParameterHandler &prm);

  struct CommonParameters
  {
    Model        model     = Model::mpm;
    unsigned int dimension = 2;
  };

  /**
   * Read only the common entries of @p filename, skipping all others, so the
   * program can pick the model and the dimension before declaring the rest.
   * Throws if the file cannot be read or a common entry is invalid.
   */
  CommonParameters
  read_common_parameters(const std::string &filename);
} // namespace sable

#endif
