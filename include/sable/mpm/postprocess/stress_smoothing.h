#ifndef sable_mpm_postprocess_stress_smoothing_h
#define sable_mpm_postprocess_stress_smoothing_h

#include <deal.II/base/symmetric_tensor.h>

#include <sable/mpm/grid.h>
#include <sable/mpm/particle_cells.h>

#include <unordered_map>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * A smooth stress for output (Output/Smoothed stress output): each
   * body's point stresses projected onto the grid nodes,
   * sigma_i = sum_p N_i(x_p) V_p sigma_p / sum_p N_i(x_p) V_p, and
   * interpolated back to the body's points, sigma_s(x_p) = sum_i N_i(x_p)
   * sigma_i. Each body has its own nodal values (kept sparsely: one body
   * per node in arrays, others in a hash table), so that stress
   * is not averaged across a contact. A uniform stress comes back exactly,
   * a linear one exactly at points whose nodes hold only interior points;
   * the speckle at the scale of the points is filtered.
   *
   * The nodes of the locally owned cells see all their points when the
   * cell list holds the ghost cells' points (multi-body contact under
   * MPI); otherwise, under MPI, the nodes on rank boundaries see only
   * this rank's points.
   */
  template <int dim>
  class StressSmoothing
  {
  public:
    /// Smooth the stresses of the points of @p cells; the results of the
    /// locally owned points by their local index.
    void
    compute(const ParticleCells<dim> &cells,
            const Grid<dim> &         grid,
            const unsigned int        n_local_indices);

    /// The smoothed stress of the owned point of @p local_index.
    const SymmetricTensor<2, 3> &
    operator[](const unsigned int local_index) const
    {
      return smoothed[local_index];
    }

  private:
    /// V sum, and V sigma sums, of one body at one node
    struct Sums
    {
      double                volume = 0;
      SymmetricTensor<2, 3> volume_stress;
    };

    Sums &
    sums(const unsigned int node, const unsigned int body);

    std::vector<unsigned int>                       first_body;
    std::vector<Sums>                               first_sums;
    std::unordered_map<unsigned long long, Sums>     others;
    std::vector<SymmetricTensor<2, 3>>              smoothed;
  };
} // namespace sable::mpm

#endif
