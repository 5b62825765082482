#include <deal.II/base/multithread_info.h>

#include <sable/base/common_parameters.h>
#include <sable/base/input_error.h>
#include <sable/base/parameter_file.h>

#include <fstream>
#include <memory>

#ifdef DEAL_II_WITH_TBB
#  include <tbb/global_control.h>
#endif

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
    prm.declare_entry("Threads",
                      "1",
                      dealii::Patterns::Integer(0),
                      "Threads per MPI rank for the threaded loops (MPM "
                      "transfers, contact and stress update, QuSGM work "
                      "functional and vector operations); 0: one per core. The command line option "
                      "--threads N and the environment variable SABLE_THREADS "
                      "override it. Results do not depend on it.");
  }

  void
  set_threads(const unsigned int threads)
  {
    dealii::MultithreadInfo::set_thread_limit(
      threads == 0 ? dealii::numbers::invalid_unsigned_int : threads);
#ifdef DEAL_II_WITH_TBB
    // hold TBB's limit for the rest of the program (what deal.II's
    // MultithreadInfo reports, and what TBB really uses)
    static std::unique_ptr<tbb::global_control> limit;
    limit.reset();
    limit = std::make_unique<tbb::global_control>(
      tbb::global_control::max_allowed_parallelism,
      dealii::MultithreadInfo::n_threads());
#endif
  }

  CommonParameters
  read_common_parameters(const std::string &                  filename,
                         const std::vector<ParameterSetting> &settings)
  {
    {
      std::ifstream file(filename);
      if (!file)
        throw InputError("cannot read the parameter file '" + filename +
                         "': it does not exist or is not readable");
    }
    dealii::ParameterHandler prm;
    declare_common_parameters(prm);
    parse_parameter_file(prm, filename, /*skip_undefined=*/true);
    apply_parameter_settings(prm, settings, /*skip_undeclared=*/true);
    CommonParameters common;
    common.model = prm.get("Model") == "qusgm" ? Model::qusgm : Model::mpm;
    common.dimension = prm.get_integer("Dimension");
    common.threads   = prm.get_integer("Threads");
    return common;
  }
} // namespace sable
