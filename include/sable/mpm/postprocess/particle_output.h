#ifndef sable_mpm_postprocess_particle_output_h
#define sable_mpm_postprocess_particle_output_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/parameters.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/postprocess/stress_smoothing.h>

#include <string>
#include <tuple>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The material points as deal.II output patches, one point each, with
   * the fields of doc/mpm.md ("Particle fields"): id, body, mass, initial
   * volume, velocity, displacement (if the layout keeps the initial
   * position), F and the Cauchy stress as full 3 x 3 tensors (plane
   * strain: F_zz = 1, stress_zz as computed), pressure -tr(stress)/3, von
   * Mises stress sqrt(3/2 s:s) and the material history; with a
   * StressSmoothing also the smoothed stress (tensor), its pressure, von
   * Mises stress and in-plane principal stress difference
   * sigma_1 - sigma_2 = sqrt((s_xx - s_yy)^2 + 4 s_xy^2).
   *
   * In VTU, velocity and displacement are vectors and F and stress 9-
   * component tensors (row-major), which ParaView shows as such. deal.II
   * 9.4's HDF5 writer keeps only 3 components of any non-scalar field, so
   * there the tensors are written component by component as scalars
   * (stress_xx, stress_xy, ...). deal.II's patches hold single-precision
   * floats: id and body are written as floats (ids exact up to 2^24).
   */
  template <int dim>
  class ParticleOutput : public DataOutInterface<0, dim>
  {
  public:
    /// @p history_names: names of the layout's history slots (missing
    /// ones are called history_<i>); @p tensors: declare F and stress as
    /// tensors (VTU) rather than 9 scalars each (HDF5); @p smoothed: with
    /// the smoothed stress fields.
    ParticleOutput(const ParticleLayout<dim> &     layout,
                   const std::vector<std::string> &history_names,
                   const bool                      tensors,
                   const bool                      smoothed = false);

    /// One patch per locally owned point of @p particles; @p smoothing
    /// (computed for them) if the output has the smoothed fields.
    void
    build_patches(const Particles::ParticleHandler<dim> &particles,
                  const StressSmoothing<dim> *            smoothing = nullptr);

    /// Number of values per point (all components of all fields).
    unsigned int
    n_values() const
    {
      return names.size();
    }

  private:
    const std::vector<DataOutBase::Patch<0, dim>> &
    get_patches() const override
    {
      return patches;
    }

    std::vector<std::string>
    get_dataset_names() const override
    {
      return names;
    }

    std::vector<
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 DataComponentInterpretation::DataComponentInterpretation>>
    get_nonscalar_data_ranges() const override
    {
      return ranges;
    }

    const ParticleLayout<dim> layout;

    /// Component names, and where the first of each field sits.
    std::vector<std::string> names;
    unsigned int             velocity, displacement, deformation, stress, smoothed_stress;
    bool                     smoothed;

    std::vector<
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 DataComponentInterpretation::DataComponentInterpretation>>
      ranges;

    std::vector<DataOutBase::Patch<0, dim>> patches;
  };
} // namespace sable::mpm

#endif
