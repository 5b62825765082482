#include <deal.II/base/parallel.h>

#include <sable/mpm/stress_update.h>

#include <cmath>
#include <mutex>
#include <type_traits>

namespace sable::mpm
{
  template <int dim>
  typename StressUpdate<dim>::Failure
  StressUpdate<dim>::update(const ParticleCells<dim> &         cells,
                            const std::vector<Tensor<2, dim>> &velocity_gradients,
                            const double                       time_step,
                            const std::vector<double> *        cell_time_steps,
                            const bool                         midpoint_deformation) const
  {
    using Layout = ParticleLayout<dim>;
    // the stress components a material writes: in plane strain xx yy zz xy
    // (xz and yz stay zero), in 3D all six
    constexpr unsigned int n_written = dim == 2 ? 4 : 6;
    Failure                failure;
    std::mutex             failure_mutex;
    // the loop over the cells, compiled for each rule of F's update (the
    // default's without a test per point)
    const auto update_cells = [&](const unsigned int begin,
                                  const unsigned int end,
                                  const auto         midpoint) {
        Tensor<2, dim> identity;
        for (unsigned int d = 0; d < dim; ++d)
          identity[d][d] = 1.;
        MaterialPointBatch<dim> batch;
        Failure                 local;

        // the material update of the points from @p first on (consecutive
        // in their cell), then one finiteness test for the batch: x - x is
        // 0 for a finite x, NaN for NaN and infinity
        double     dt           = time_step;
        const auto finish_batch = [&](const unsigned int body, auto first) {
          if (batch.size() == 0)
            return;
          materials[body]->update_stresses(batch, dt);
          double residue = 0.;
          for (unsigned int p = 0; p < batch.size(); ++p)
            for (unsigned int c = 0; c < n_written; ++c)
              residue += batch.stress[p][c] - batch.stress[p][c];
          if (!std::isfinite(residue))
            for (unsigned int p = 0; p < batch.size(); ++p, ++first)
              {
                bool finite = true;
                for (unsigned int c = 0; c < n_written; ++c)
                  finite = finite && std::isfinite(batch.stress[p][c]);
                if (!finite && (!local.failed || first->get_id() < local.id))
                  local = {true, first->get_id(), first->get_location()};
              }
          batch.clear();
        };

        for (unsigned int c = begin; c < end; ++c)
          {
            if (cell_time_steps != nullptr)
              {
                dt = (*cell_time_steps)[c];
                if (dt == 0.)
                  continue;
              }
            const auto & particles = cells[c].particles;
            unsigned int body      = numbers::invalid_unsigned_int;
            auto         first     = particles.begin();
            for (auto particle = particles.begin(); particle != particles.end(); ++particle)
              {
                const auto         props = particle->get_properties();
                const unsigned int b     = static_cast<unsigned int>(props[Layout::body]);
                if (b != body)
                  {
                    finish_batch(body, first);
                    body  = b;
                    first = particle;
                  }
                const Tensor<2, dim> &L = velocity_gradients[particle->get_local_index()];
                Tensor<2, dim>        F = Layout::deformation_gradient(props);
                if constexpr (decltype(midpoint)::value)
                  F = invert(identity - 0.5 * dt * L) * (identity + 0.5 * dt * L) * F;
                else
                  F = (identity + dt * L) * F;
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int j = 0; j < dim; ++j)
                    props[Layout::deformation + i * dim + j] = F[i][j];
                batch.L.push_back(L);
                batch.F.push_back(F);
                batch.stress.push_back(&props[Layout::stress]);
                batch.history.push_back(layout.n_history > 0 ? &props[layout.history] : nullptr);
              }
            finish_batch(body, first);
          }
        if (local.failed)
          {
            std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure.failed || local.id < failure.id)
              failure = local;
          }
    };
    parallel::apply_to_subranges(
      0u,
      cells.n_owned(),
      [&](const unsigned int begin, const unsigned int end) {
        if (midpoint_deformation)
          update_cells(begin, end, std::true_type());
        else
          update_cells(begin, end, std::false_type());
      },
      16);
    return failure;
  }

  template class StressUpdate<2>;
  template class StressUpdate<3>;
} // namespace sable::mpm
