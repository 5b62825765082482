// StatisticsFile::first_not_finite(), which the run guard uses to stop a run
// whose statistics row holds a NaN or an infinity in any column (not only
// the energies the energy guard reads): a row of finite values passes; a
// NaN in a pair-force column, an infinity in contact_heat and a NaN in a
// body's rotation are each named; a body without points (its position and
// velocity 0/0) is not a failure. 2D and 3D.

#include <deal.II/base/mpi.h>

#include <sable/mpm/postprocess/statistics.h>

#include <limits>
#include <string>

#include "test_support.h"

using namespace dealii;
using sable_tests::check;

namespace
{
  template <int dim>
  void
  run_case()
  {
    using namespace sable::mpm;
    const std::string label = std::to_string(dim) + "D: ";
    const double      nan   = std::numeric_limits<double>::quiet_NaN();
    // two bodies, contact, one reported pair; nothing written
    const StatisticsFile<dim> file("unused.csv", {0, 1}, true, false, {{0, 1}}, true, false);
    Statistics<dim>           s;
    s.energy_drift          = 0.;
    s.body_mass             = {1., 2.};
    s.body_position         = {Point<dim>(), Point<dim>()};
    s.body_velocity         = {Tensor<1, dim>(), Tensor<1, dim>()};
    s.body_angular_velocity = {Tensor<1, 3>(), Tensor<1, 3>()};
    s.pair_forces           = {Tensor<1, dim>()};
    s.pair_moments          = {{{Tensor<1, 3>(), Tensor<1, 3>()}}};
    const auto first = [&](const Statistics<dim> &row) {
      return file.first_not_finite(10, 0.5, 1e-3, 0., row);
    };
    check(label + "a finite row passes", first(s).empty());

    Statistics<dim> t = s;
    t.pair_forces[0][1] = nan;
    check(label + "NaN pair force named (" + first(t) + ")", first(t) == "contact0_1_fy");
    t = s;
    t.pair_moments[0][1][2] = nan;
    const std::string moment = dim == 2 ? "contact0_1_mb" : "contact0_1_mb_z";
    check(label + "NaN pair moment named (" + first(t) + ")", first(t) == moment);
    t = s;
    t.contact_heat = std::numeric_limits<double>::infinity();
    check(label + "infinite contact heat named (" + first(t) + ")", first(t) == "contact_heat");
    t = s;
    t.body_angular_velocity[0][2] = nan;
    const std::string omega = dim == 2 ? "body0_omega" : "body0_omega_z";
    check(label + "NaN rotation named (" + first(t) + ")", first(t) == omega);
    t = s;
    t.body_mass[1]        = 0.;
    t.body_position[1][0] = nan;
    t.body_velocity[1][0] = nan;
    check(label + "a body without points is not a failure", first(t).empty());
    t.body_mass[1] = 2.;
    check(label + "the same NaN position with points is named (" + first(t) + ")",
          first(t) == "body1_x");
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run_case<2>();
  run_case<3>();
  return sable_tests::exit_code();
}
