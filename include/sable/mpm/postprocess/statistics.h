#ifndef sable_mpm_postprocess_statistics_h
#define sable_mpm_postprocess_statistics_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// Global sums over all particles at one instant.
  template <int dim>
  struct Statistics
  {
    double                      kinetic_energy = 0;
    double                      strain_energy  = 0;
    /// -sum_p m_p g . x_p
    double                      gravity_energy = 0;
    Tensor<1, dim>              momentum;
    std::vector<double>         body_mass;
    std::vector<Point<dim>>     body_position;
    std::vector<Tensor<1, dim>> body_velocity;
    unsigned long long          n_particles = 0;
  };

  /**
   * statistics.csv: one row per recorded step (DESIGN.md, output
   * conventions). Only rank 0 writes; every value with 17 significant
   * digits so runs can be compared to round-off.
   */
  template <int dim>
  class StatisticsFile
  {
  public:
    StatisticsFile(const std::string &filename,
                   const unsigned int n_bodies,
                   const bool         write);

    void
    write_row(const unsigned int       step,
              const double             time,
              const double             dt,
              const double             boundary_work,
              const Statistics<dim> &  statistics);

  private:
    std::unique_ptr<std::ofstream> file;
  };
} // namespace sable::mpm

#endif
