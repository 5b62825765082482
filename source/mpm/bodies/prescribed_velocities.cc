#include <sable/mpm/bodies/prescribed_velocities.h>

namespace sable::mpm
{
  template <int dim>
  PrescribedVelocities<dim>::PrescribedVelocities(const std::vector<BodyParameters<dim>> &bodies)
  {
    for (const auto &body : bodies)
      {
        prescribed.push_back(body.prescribed);
        velocities.push_back(body.prescribed_velocity);
        start_times.push_back(body.prescribed_start_time);
        n_prescribed += body.prescribed;
      }
    update(0.);
  }

  template <int dim>
  bool
  PrescribedVelocities<dim>::update(const double time)
  {
    current.resize(velocities.size());
    bool changed = false;
    for (unsigned int b = 0; b < velocities.size(); ++b)
      {
        const Tensor<1, dim> v = time >= start_times[b] ? velocities[b] : Tensor<1, dim>();
        changed |= v != current[b];
        current[b] = v;
      }
    return changed;
  }

  template class PrescribedVelocities<2>;
  template class PrescribedVelocities<3>;
} // namespace sable::mpm
