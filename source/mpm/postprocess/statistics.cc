#include <deal.II/base/mpi.h>

#include <sable/mpm/postprocess/statistics.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <iomanip>

namespace sable::mpm
{
  template <int dim>
  StatisticsFile<dim>::StatisticsFile(
    const std::string &                                       filename,
    const std::vector<unsigned int> &                         bodies,
    const bool                                                with_contact,
    const bool                                                with_drivers,
    const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
    const bool                                                with_pair_moments,
    const bool                                                write,
    const bool                                                append,
    MPI_Comm                                                  communicator)
    : filename(filename)
    , communicator(communicator)
  {
    // the columns: name and value, in the order of the file
    const auto add = [this](const std::string &                name,
                            std::function<double(const Row &)> value,
                            const unsigned int body = numbers::invalid_unsigned_int) {
      columns.push_back({name, std::move(value), body});
    };
    const std::string axes = "xyz";
    add("step", [](const Row &r) { return r.step; });
    add("time", [](const Row &r) { return r.time; });
    add("dt", [](const Row &r) { return r.dt; });
    add("particles", [](const Row &r) { return r.statistics.n_particles; });
    add("cells", [](const Row &r) { return r.statistics.n_cells; });
    add("kinetic_energy", [](const Row &r) { return r.statistics.kinetic_energy; });
    add("strain_energy", [](const Row &r) { return r.statistics.strain_energy; });
    add("gravity_energy", [](const Row &r) { return r.statistics.gravity_energy; });
    add("boundary_work", [](const Row &r) { return r.boundary_work; });
    add("plastic_work", [](const Row &r) { return r.statistics.plastic_work; });
    add("wall_heat", [](const Row &r) { return r.statistics.wall_heat; });
    add("impact_loss", [](const Row &r) { return r.statistics.impact_loss; });
    add("energy_drift", [](const Row &r) { return r.statistics.energy_drift; });
    for (unsigned int d = 0; d < dim; ++d)
      add("momentum_" + axes.substr(d, 1), [d](const Row &r) { return r.statistics.momentum[d]; });
    if (with_drivers)
      for (unsigned int d = 0; d < dim; ++d)
        add("driver_impulse_" + axes.substr(d, 1),
            [d](const Row &r) { return r.statistics.driver_impulse[d]; });
    for (const unsigned int b : bodies)
      {
        const std::string body = "body" + std::to_string(b);
        for (unsigned int d = 0; d < dim; ++d)
          add(body + "_" + axes.substr(d, 1),
              [b, d](const Row &r) { return r.statistics.body_position[b][d]; },
              b);
        for (unsigned int d = 0; d < dim; ++d)
          add(body + "_v" + axes.substr(d, 1),
              [b, d](const Row &r) { return r.statistics.body_velocity[b][d]; },
              b);
        // 2D: the rotation about z only
        for (unsigned int d = (dim == 2 ? 2 : 0); d < 3; ++d)
          add(body + (dim == 2 ? "_omega" : "_omega_" + axes.substr(d, 1)),
              [b, d](const Row &r) { return r.statistics.body_angular_velocity[b][d]; },
              b);
      }
    if (with_contact)
      {
        add("contact_heat", [](const Row &r) { return r.statistics.contact_heat; });
        for (unsigned int i = 0; i < pairs.size(); ++i)
          {
            const std::string pair =
              "contact" + std::to_string(pairs[i].first) + "_" + std::to_string(pairs[i].second);
            for (unsigned int d = 0; d < dim; ++d)
              add(pair + "_f" + axes.substr(d, 1),
                  [i, d](const Row &r) { return r.statistics.pair_forces[i][d]; });
            // the moments on the first (a) and the second (b) body, each
            // about its centre of mass; 2D: about z only
            if (with_pair_moments)
              for (unsigned int body = 0; body < 2; ++body)
                for (unsigned int d = (dim == 2 ? 2 : 0); d < 3; ++d)
                  add(pair + "_m" + (body == 0 ? "a" : "b") +
                        (dim == 2 ? "" : "_" + axes.substr(d, 1)),
                      [i, body, d](const Row &r) {
                        return r.statistics.pair_moments[i][body][d];
                      });
          }
      }

    if (!write)
      return;
    file = std::make_unique<std::ofstream>(filename, append ? std::ios::app : std::ios::out);
    // reported by the first write_row(), on every rank
    if (!*file)
      failure = "cannot write '" + filename + "': " + std::strerror(errno);
    if (!append)
      for (unsigned int c = 0; c < columns.size(); ++c)
        *file << (c ? "," : "") << columns[c].name << (c + 1 == columns.size() ? "\n" : "");
    *file << std::setprecision(17);
  }

  template <int dim>
  void
  StatisticsFile<dim>::write_row(const unsigned int      step,
                                 const double            time,
                                 const double            dt,
                                 const double            boundary_work,
                                 const Statistics<dim> &s)
  {
    std::string error = failure;
    if (file && error.empty())
      {
        const Row row{static_cast<double>(step), time, dt, boundary_work, s};
        for (unsigned int c = 0; c < columns.size(); ++c)
          *file << (c ? "," : "") << columns[c].value(row);
        *file << '\n';
        file->flush();
        if (!*file)
          error = "cannot write '" + filename + "' (step " + std::to_string(step) +
                  "): " + std::strerror(errno) + "; the rows up to the step before are complete";
      }
    error = Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw std::runtime_error(error);
  }

  template <int dim>
  std::string
  StatisticsFile<dim>::first_not_finite(const unsigned int     step,
                                        const double           time,
                                        const double           dt,
                                        const double           boundary_work,
                                        const Statistics<dim> &s) const
  {
    const Row row{static_cast<double>(step), time, dt, boundary_work, s};
    for (const Column &column : columns)
      if (!std::isfinite(column.value(row)) &&
          !(column.body != numbers::invalid_unsigned_int && column.body < s.body_mass.size() &&
            s.body_mass[column.body] == 0))
        return column.name;
    return "";
  }

  namespace
  {
    /// Per body, along each periodic axis, the mass-weighted circular mean
    /// of its points' positions (the angle 2 pi (x - lower) / period): a
    /// point of the body within half a period of all its points, whichever
    /// side of the seam they are on (collective).
    template <int dim>
    std::vector<Point<dim>>
    circular_mean_positions(const Particles::ParticleHandler<dim> &particle_handler,
                            const ParticleLayout<dim> &            layout,
                            const unsigned int                     n_bodies,
                            const Periodicity<dim> &               periodicity,
                            const MPI_Comm                         communicator)
    {
      std::vector<double> sums(n_bodies * 2 * dim, 0.);
      for (const auto &particle : particle_handler)
        {
          const auto         props = particle.get_properties();
          const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
          for (unsigned int d = 0; d < dim; ++d)
            if (periodicity.periodic[d])
              {
                const double angle = 2. * numbers::PI *
                                     (particle.get_location()[d] - periodicity.lower[d]) /
                                     periodicity.period(d);
                sums[(body * dim + d) * 2] += props[layout.mass] * std::cos(angle);
                sums[(body * dim + d) * 2 + 1] += props[layout.mass] * std::sin(angle);
              }
        }
      Utilities::MPI::sum(sums, communicator, sums);
      std::vector<Point<dim>> means(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
        for (unsigned int d = 0; d < dim; ++d)
          if (periodicity.periodic[d])
            means[b][d] = periodicity.lower[d] +
                          std::atan2(sums[(b * dim + d) * 2 + 1], sums[(b * dim + d) * 2]) /
                            (2. * numbers::PI) * periodicity.period(d);
      return means;
    }
  } // namespace

  template <int dim>
  Statistics<dim>
  compute_statistics(const Triangulation<dim> &                    triangulation,
                     const Particles::ParticleHandler<dim> &       particle_handler,
                     const ParticleLayout<dim> &                   layout,
                     const std::vector<std::unique_ptr<Material>> &materials,
                     const Tensor<1, dim> &                        gravity,
                     const BardenhagenContact<dim> *               contact,
                     const Periodicity<dim> &                      periodicity,
                     const double                                  time_step)
  {
    const bool periodic = periodicity.any();
    const MPI_Comm communicator = triangulation.get_communicator();
    const unsigned int n_bodies = materials.size();
    const std::vector<Point<dim>> body_references =
      periodic ? circular_mean_positions(particle_handler, layout, n_bodies, periodicity, communicator) :
                 std::vector<Point<dim>>();
    // kinetic, strain, gravity, plastic work, momentum (dim), then per
    // body: mass, m x (dim), m v (dim), angular momentum about the origin
    // (3), inertia tensor about the origin (9)
    constexpr unsigned int n_global = 4 + dim;
    constexpr unsigned int per_body = 1 + 2 * dim + 3 + 9;
    const unsigned int     n_values = n_global + n_bodies * per_body;
    std::vector<double>    sums(n_values, 0.);
    for (const auto &particle : particle_handler)
      {
        const auto         props = particle.get_properties();
        const unsigned int body  = static_cast<unsigned int>(props[layout.body]);
        const double       mass  = props[layout.mass];
        const Point<dim>   x =
          periodic ? particle.get_location() +
                       periodicity.image_shift(particle.get_location(), body_references[body]) :
                     particle.get_location();
        double             v2    = 0;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += props[layout.velocity + d] * props[layout.velocity + d];
        sums[0] += 0.5 * mass * v2;
        sums[1] += props[layout.initial_volume] *
                   materials[body]->strain_energy_density(
                     ParticleLayout<dim>::stress_tensor(props),
                     embed_in_3d<dim>(ParticleLayout<dim>::deformation_gradient(props), 1.));
        sums[2] -= mass * (gravity * x);
        sums[3] += props[layout.initial_volume] *
                   materials[body]->plastic_work_density(props.data() + layout.history);
        double *const body_sums = &sums[n_global + body * per_body];
        body_sums[0] += mass;
        Tensor<1, 3> r, v;
        for (unsigned int d = 0; d < dim; ++d)
          {
            sums[4 + d] += mass * props[layout.velocity + d];
            body_sums[1 + d] += mass * x[d];
            body_sums[1 + dim + d] += mass * props[layout.velocity + d];
            r[d] = x[d];
            v[d] = props[layout.velocity + d];
          }
        const Tensor<1, 3> angular = mass * cross_product_3d(r, v);
        for (unsigned int d = 0; d < 3; ++d)
          body_sums[1 + 2 * dim + d] += angular[d];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            body_sums[4 + 2 * dim + 3 * i + j] += mass * ((i == j ? r * r : 0.) - r[i] * r[j]);
      }
    Utilities::MPI::sum(sums, communicator, sums);

    Statistics<dim> s;
    s.kinetic_energy = sums[0];
    s.strain_energy  = sums[1];
    s.gravity_energy = sums[2];
    s.plastic_work   = sums[3];
    for (unsigned int d = 0; d < dim; ++d)
      s.momentum[d] = sums[4 + d];
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const double *const body_sums = &sums[n_global + b * per_body];
        const double        mass      = body_sums[0];
        s.body_mass.push_back(mass);
        Point<dim>     x;
        Tensor<1, dim> v;
        Tensor<1, 3>   x3, v3, angular;
        Tensor<2, 3>   inertia;
        for (unsigned int d = 0; d < dim; ++d)
          {
            x[d] = x3[d] = body_sums[1 + d] / mass;
            v[d] = v3[d] = body_sums[1 + dim + d] / mass;
          }
        if (periodic)
          periodicity.wrap(x);
        s.body_position.push_back(x);
        s.body_velocity.push_back(v);
        // shift angular momentum and inertia to the centre of mass:
        // L_c = L_o - M x_c x v_c, I_c = I_o - M (|x_c|^2 1 - x_c x_c)
        for (unsigned int i = 0; i < 3; ++i)
          {
            angular[i] = body_sums[1 + 2 * dim + i];
            for (unsigned int j = 0; j < 3; ++j)
              inertia[i][j] = body_sums[4 + 2 * dim + 3 * i + j] -
                              mass * ((i == j ? x3 * x3 : 0.) - x3[i] * x3[j]);
          }
        angular -= mass * cross_product_3d(x3, v3);
        Tensor<1, 3> omega;
        if (dim == 2)
          omega[2] = inertia[2][2] > 0 ? angular[2] / inertia[2][2] : 0.;
        else if (determinant(inertia) > 0)
          omega = invert(inertia) * angular;
        s.body_angular_velocity.push_back(omega);
      }
    s.n_particles = particle_handler.n_global_particles();
    s.n_cells     = triangulation.n_global_active_cells();
    if (contact != nullptr)
      {
        s.contact_heat = Utilities::MPI::sum(contact->frictional_heat, communicator);
        for (const auto &force : contact->pair_forces)
          s.pair_forces.push_back(Utilities::MPI::sum(force, communicator));
        // M_a = sum (x_i - x_a) x f_i = M_O - x_a x F on the first body,
        // and -(M_O - x_b x F) on the second, about where the centres were
        // when the forces acted: a step of @p time_step before, less the
        // step's move (the mean of the points' moves is the body's
        // velocity times the step, as the transfers keep momentum)
        if (!periodic)
          for (unsigned int i = 0; i < contact->pair_moments.size(); ++i)
            {
              const Tensor<1, 3> moment = Utilities::MPI::sum(contact->pair_moments[i], communicator);
              const auto [a, b]         = contact->get_reported_pairs()[i];
              Tensor<1, 3> force, x_a, x_b;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  force[d] = s.pair_forces[i][d];
                  x_a[d]   = s.body_position[a][d] - time_step * s.body_velocity[a][d];
                  x_b[d]   = s.body_position[b][d] - time_step * s.body_velocity[b][d];
                }
              s.pair_moments.push_back({{moment - cross_product_3d(x_a, force),
                                         -(moment - cross_product_3d(x_b, force))}});
            }
      }
    return s;
  }

  template class StatisticsFile<2>;
  template class StatisticsFile<3>;
#define SABLE_INSTANTIATE(dim)                                                              \
  template Statistics<dim> compute_statistics<dim>(const Triangulation<dim> &, const Particles::ParticleHandler<dim> &, \
                                                   const ParticleLayout<dim> &,             \
                                                   const std::vector<std::unique_ptr<Material>> &, \
                                                   const Tensor<1, dim> &,                  \
                                                   const BardenhagenContact<dim> *,         \
                                                   const Periodicity<dim> &,                \
                                                   const double);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
