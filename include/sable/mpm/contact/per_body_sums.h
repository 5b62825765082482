#ifndef sable_mpm_contact_per_body_sums_h
#define sable_mpm_contact_per_body_sums_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <sable/mpm/particle_cells.h>
#include <sable/mpm/particle_layout.h>

#include <vector>

namespace sable::mpm
{
  /// Per body, @p n_entries sums over its points in the owned cells on
  /// all ranks: @p add(properties, location, sums) adds a point's shares;
  /// the points of bodies not @p wanted are skipped.
  template <int dim, typename AddPoint>
  std::vector<double>
  sum_per_body(const ParticleCells<dim> &cells,
               const std::vector<bool> & wanted,
               const unsigned int        n_entries,
               const MPI_Comm            communicator,
               const AddPoint &          add)
  {
    std::vector<double> sums(wanted.size() * n_entries, 0.);
    for (unsigned int c = 0; c < cells.n_owned(); ++c)
      for (const auto &particle : cells[c].particles)
        {
          const auto         props = particle.get_properties();
          const unsigned int body  = static_cast<unsigned int>(props[ParticleLayout<dim>::body]);
          if (wanted[body])
            add(props, particle.get_location(), &sums[body * n_entries]);
        }
    Utilities::MPI::sum(sums, communicator, sums);
    return sums;
  }

  /// The centre of mass of each body @p wanted, over its points on all
  /// ranks (the origin for the others and for bodies without points).
  template <int dim>
  std::vector<Point<dim>>
  centres_of_mass(const ParticleCells<dim> &cells,
                  const std::vector<bool> & wanted,
                  const MPI_Comm            communicator)
  {
    // per body: sum m x and sum m
    const auto add_point = [](const auto &props, const auto &x, double *sum) {
      const double mass = props[ParticleLayout<dim>::mass];
      for (unsigned int d = 0; d < dim; ++d)
        sum[d] += mass * x[d];
      sum[dim] += mass;
    };
    const std::vector<double> sums =
      sum_per_body<dim>(cells, wanted, dim + 1, communicator, add_point);
    std::vector<Point<dim>> centres(wanted.size());
    for (unsigned int b = 0; b < wanted.size(); ++b)
      if (sums[b * (dim + 1) + dim] > 0)
        for (unsigned int d = 0; d < dim; ++d)
          centres[b][d] = sums[b * (dim + 1) + d] / sums[b * (dim + 1) + dim];
    return centres;
  }
} // namespace sable::mpm

#endif
