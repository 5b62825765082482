#include <deal.II/base/parallel.h>

#include <sable/mpm/stress_update.h>

#include <cmath>
#include <mutex>

namespace sable::mpm
{
  template <int dim>
  typename StressUpdate<dim>::Failure
  StressUpdate<dim>::update(const ParticleCells<dim> &         cells,
                            const std::vector<Tensor<2, dim>> &velocity_gradients,
                            const double                       time_step) const
  {
    using Layout = ParticleLayout<dim>;
    Failure    failure;
    std::mutex failure_mutex;
    parallel::apply_to_subranges(
      0u,
      cells.n_owned(),
      [&](const unsigned int begin, const unsigned int end) {
        Tensor<2, dim> identity;
        for (unsigned int d = 0; d < dim; ++d)
          identity[d][d] = 1.;
        MaterialPointBatch                                 batch;
        std::vector<SymmetricTensor<2, 3>>                 stresses;
        std::vector<typename Particles::ParticleIterator<dim>> points;
        Failure                                            local;

        // the batch's stresses back into the points' properties, with one
        // finiteness check per batch
        const auto finish_batch = [&](const unsigned int body) {
          if (batch.size() == 0)
            return;
          materials[body]->update_stresses(batch, time_step);
          bool finite = true;
          for (unsigned int p = 0; p < batch.size(); ++p)
            {
              const auto props = points[p]->get_properties();
              for (unsigned int c = 0; c < 6; ++c)
                {
                  props[Layout::stress + c] = stresses[p].access_raw_entry(c);
                  finite = finite && std::isfinite(stresses[p].access_raw_entry(c));
                }
            }
          if (!finite)
            for (unsigned int p = 0; p < batch.size(); ++p)
              {
                bool point_finite = true;
                for (unsigned int c = 0; c < 6; ++c)
                  point_finite = point_finite && std::isfinite(stresses[p].access_raw_entry(c));
                if (!point_finite && (!local.failed || points[p]->get_id() < local.id))
                  local = {true, points[p]->get_id(), points[p]->get_location()};
              }
          batch.clear();
          points.clear();
        };

        for (unsigned int c = begin; c < end; ++c)
          {
            const auto & particles = cells[c].particles;
            unsigned int body      = numbers::invalid_unsigned_int;
            // sized for the cell before pointers into it are taken
            stresses.resize(std::distance(particles.begin(), particles.end()));
            for (auto particle = particles.begin(); particle != particles.end(); ++particle)
              {
                const auto         props = particle->get_properties();
                const unsigned int b     = static_cast<unsigned int>(props[Layout::body]);
                if (b != body)
                  {
                    finish_batch(body);
                    body = b;
                  }
                const Tensor<2, dim> L = velocity_gradients[particle->get_local_index()];
                Tensor<2, dim>       F = Layout::deformation_gradient(props);
                F                      = (identity + time_step * L) * F;
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int j = 0; j < dim; ++j)
                    props[Layout::deformation + i * dim + j] = F[i][j];
                const unsigned int p = batch.size();
                stresses[p]          = Layout::stress_tensor(props);
                batch.L.push_back(embed_in_3d<dim>(L, 0.));
                batch.F.push_back(embed_in_3d<dim>(F, 1.));
                batch.stress.push_back(&stresses[p]);
                batch.history.push_back(layout.n_history > 0 ? &props[layout.history] : nullptr);
                points.push_back(particle);
              }
            finish_batch(body);
          }
        if (local.failed)
          {
            std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure.failed || local.id < failure.id)
              failure = local;
          }
      },
      16);
    return failure;
  }

  template class StressUpdate<2>;
  template class StressUpdate<3>;
} // namespace sable::mpm
