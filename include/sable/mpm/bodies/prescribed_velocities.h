#ifndef sable_mpm_bodies_prescribed_velocities_h
#define sable_mpm_bodies_prescribed_velocities_h

#include <deal.II/base/tensor.h>

#include <sable/mpm/bodies/body_parameters.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The bodies of prescribed velocity (rigid drivers such as a loading pin,
   * 'Body k/Prescribed velocity') and their velocity in the current step:
   * the prescribed one from the body's start time on, zero before. The
   * grid-to-particle pass gives their points this velocity (and no strain
   * rate); the multi-body contact sets their nodal velocities to it.
   */
  template <int dim>
  class PrescribedVelocities
  {
  public:
    PrescribedVelocities() = default;

    explicit PrescribedVelocities(const std::vector<BodyParameters<dim>> &bodies);

    /// The velocities of the step that starts at @p time; whether any
    /// changed.
    bool
    update(const double time);

    /// Whether any body is a driver.
    bool
    any() const
    {
      return n_prescribed > 0;
    }

    /// The number of bodies, drivers or not.
    unsigned int
    n_bodies() const
    {
      return prescribed.size();
    }

    bool
    is_prescribed(const unsigned int body) const
    {
      return body < prescribed.size() && prescribed[body];
    }

    /// This step's velocity of a prescribed @p body.
    const Tensor<1, dim> &
    velocity(const unsigned int body) const
    {
      return current[body];
    }

  private:
    std::vector<bool>           prescribed;
    std::vector<Tensor<1, dim>> velocities;
    std::vector<double>         start_times;
    std::vector<Tensor<1, dim>> current;
    unsigned int                n_prescribed = 0;
  };
} // namespace sable::mpm

#endif
