#include <sable/mpm/postprocess/statistics.h>

#include <iomanip>

namespace sable::mpm
{
  template <int dim>
  StatisticsFile<dim>::StatisticsFile(
    const std::string &                                       filename,
    const unsigned int                                        n_bodies,
    const bool                                                with_contact,
    const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
    const bool                                                write,
    const bool                                                append)
    : with_contact(with_contact)
  {
    if (!write)
      return;
    if (append)
      {
        file = std::make_unique<std::ofstream>(filename, std::ios::app);
        *file << std::setprecision(17);
        return;
      }
    file = std::make_unique<std::ofstream>(filename);
    const char *axes = "xyz";
    *file << "step,time,dt,particles,cells,kinetic_energy,strain_energy,gravity_energy,"
             "boundary_work";
    for (unsigned int d = 0; d < dim; ++d)
      *file << ",momentum_" << axes[d];
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        for (unsigned int d = 0; d < dim; ++d)
          *file << ",body" << b << '_' << axes[d];
        for (unsigned int d = 0; d < dim; ++d)
          *file << ",body" << b << "_v" << axes[d];
        if (dim == 2)
          *file << ",body" << b << "_omega";
        else
          for (unsigned int d = 0; d < 3; ++d)
            *file << ",body" << b << "_omega_" << axes[d];
      }
    if (with_contact)
      {
        *file << ",contact_heat";
        for (const auto &[a, b] : pairs)
          for (unsigned int d = 0; d < dim; ++d)
            *file << ",contact" << a << '_' << b << "_f" << axes[d];
      }
    *file << '\n' << std::setprecision(17);
  }

  template <int dim>
  void
  StatisticsFile<dim>::write_row(const unsigned int      step,
                                 const double            time,
                                 const double            dt,
                                 const double            boundary_work,
                                 const Statistics<dim> &s)
  {
    if (!file)
      return;
    *file << step << ',' << time << ',' << dt << ',' << s.n_particles << ',' << s.n_cells << ','
          << s.kinetic_energy << ','
          << s.strain_energy << ',' << s.gravity_energy << ','
          << boundary_work;
    for (unsigned int d = 0; d < dim; ++d)
      *file << ',' << s.momentum[d];
    for (unsigned int b = 0; b < s.body_mass.size(); ++b)
      {
        for (unsigned int d = 0; d < dim; ++d)
          *file << ',' << s.body_position[b][d];
        for (unsigned int d = 0; d < dim; ++d)
          *file << ',' << s.body_velocity[b][d];
        if (dim == 2)
          *file << ',' << s.body_angular_velocity[b][2];
        else
          for (unsigned int d = 0; d < 3; ++d)
            *file << ',' << s.body_angular_velocity[b][d];
      }
    if (with_contact)
      {
        *file << ',' << s.contact_heat;
        for (const auto &force : s.pair_forces)
          for (unsigned int d = 0; d < dim; ++d)
            *file << ',' << force[d];
      }
    *file << '\n';
    file->flush();
  }

  template class StatisticsFile<2>;
  template class StatisticsFile<3>;
} // namespace sable::mpm
