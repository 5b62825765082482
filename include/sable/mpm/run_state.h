#ifndef sable_mpm_run_state_h
#define sable_mpm_run_state_h

#include <algorithm>
#include <array>

namespace sable::mpm
{
  /**
   * Where a run is and what it has accumulated: time and step, the signal
   * speed for the next time step, the energy bookkeeping of the energy
   * guard, the output schedule and the adaptation schedule. Everything a
   * checkpoint must restore beyond the mesh and the material points is
   * here or in the output series and the contact sums, and serialize()
   * is the one list of it.
   */
  struct RunState
  {
    double       time        = 0;
    double       time_step   = 0;
    unsigned int step_number = 0;
    /// largest c + |v| over the points, for the next time step
    double max_signal_speed = 0;

    /// work done by moving walls so far
    double boundary_work = 0;
    /// impulse the bodies of prescribed velocity gave the others so far
    std::array<double, 3> driver_impulse = {{0, 0, 0}};
    /// kinetic + strain energy and gravitational energy at the start
    double initial_energy         = 0;
    double initial_gravity_energy = 0;
    /// 1e-14 sum m c^2: energies below it are round-off
    double energy_floor = 0;
    /// the gravitational energy of all the mass over one cell height: the
    /// energy a discretisation resolves, below which a drift is not judged
    double resolved_energy = 0;
    /// the largest release of gravitational energy so far
    double largest_gravity_release = 0;

    double       next_output_time = 0;
    unsigned int output_counter   = 0;
    /// whether an uninterrupted run writes a row of statistics.csv at
    /// step_number (a stopped run also writes its last step)
    bool statistics_row_due = false;

    unsigned int adaptations_without_change = 0;
    /// how far the fastest point travelled since the last adaptation
    double travel_since_adaptation = 0;

    /**
     * The energy a scene can hold: the initial energy plus the largest
     * release of gravitational energy so far and the work of moving walls
     * (a body rising again after a bounce gives no new energy). Call with
     * the current gravitational energy.
     */
    double
    energy_budget(const double gravity_energy)
    {
      largest_gravity_release =
        std::max(largest_gravity_release, initial_gravity_energy - gravity_energy);
      return energy_scale(gravity_energy);
    }

    /// energy_budget() without recording the release: the scale of the
    /// energy balance.
    double
    energy_scale(const double gravity_energy) const
    {
      return initial_energy +
             std::max(largest_gravity_release, initial_gravity_energy - gravity_energy) +
             std::max(boundary_work, 0.) + energy_floor;
    }

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &time &time_step &step_number &max_signal_speed;
      ar &boundary_work &driver_impulse &initial_energy &initial_gravity_energy &energy_floor &
        largest_gravity_release &resolved_energy;
      ar &next_output_time &output_counter &statistics_row_due;
      ar &adaptations_without_change &travel_since_adaptation;
    }
  };
} // namespace sable::mpm

#endif
