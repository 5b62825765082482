#include <sable/base/input_error.h>
#include <sable/qusgm/run_scene.h>

namespace sable::qusgm
{
  void
  declare_parameters(dealii::ParameterHandler &)
  {}

  void
  run_scene(const std::string &, MPI_Comm)
  {
    throw InputError("'Model = qusgm': the quasi-static granular model is "
                     "not available in this build");
  }
} // namespace sable::qusgm
