#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>

#include <fstream>

namespace sable
{
  void
  declare_common_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "mpm",
                      dealii::Patterns::Selection("mpm|qusgm"),
                      "Which model the scene runs: the explicit material "
                      "point method with frictional contact (mpm) or the "
                      "quasi-static granular model for sphere packs (qusgm).");
    prm.declare_entry("Dimension",
                      "2",
                      dealii::Patterns::Integer(2, 3),
                      "Space dimension of an MPM scene: 2 (plane strain) or "
                      "3. QuSGM packs are always three-dimensional.");
  }

  CommonParameters
  read_common_parameters(const std::string &filename)
  {
    {
      std::ifstream file(filename);
      if (!file)
        throw InputError("cannot read the parameter file '" + filename +
                         "': it does not exist or is not readable");
    }
    dealii::ParameterHandler prm;
    declare_common_parameters(prm);
    prm.parse_input(filename, "", /*skip_undefined=*/true);
    CommonParameters common;
    common.model = prm.get("Model") == "qusgm" ? Model::qusgm : Model::mpm;
    common.dimension = prm.get_integer("Dimension");
    return common;
  }
} // namespace sable
