#ifndef sable_mpm_load_balance_h
#define sable_mpm_load_balance_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <boost/signals2/connection.hpp>

#include <utility>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The partition of the grid over MPI ranks by work: p4est cell weights
   * (a cell costs cell_cost, each material point in it particle_cost more)
   * used at every repartition and adaptation once connect() was called.
   */
  template <int dim>
  class LoadBalance
  {
  public:
    /**
     * From the 2D step time on one core (doc/benchmarks.md, eight
     * measurements on a shared machine: 0.03-0.24 us per cell, 0.24-0.68 us
     * per material point per step, ratio 1.6-26, median 6.5): 100 : 600.
     */
    static constexpr unsigned int cell_cost     = 100;
    static constexpr unsigned int particle_cost = 600;

    ~LoadBalance()
    {
      disconnect();
    }

    /// Weigh the cells of @p triangulation by the points of
    /// @p particle_handler from now on (both must outlive the connection).
    void
    connect(parallel::distributed::Triangulation<dim> &triangulation,
            const Particles::ParticleHandler<dim> &    particle_handler);

    void
    disconnect()
    {
      connection.disconnect();
    }

    /// The weight of @p cell in the coming repartition.
    static unsigned int
    cell_weight(const Particles::ParticleHandler<dim> &            particle_handler,
                const typename Triangulation<dim>::cell_iterator &cell,
                const typename Triangulation<dim>::CellStatus     status);

    /// Material points per rank: fewest, most.
    static std::pair<unsigned long long, unsigned long long>
    particles_per_rank(const Particles::ParticleHandler<dim> &particle_handler,
                       const MPI_Comm                         communicator);

    /// One console line: points, cells, ghost nodes and work per rank.
    static void
    print(const ConditionalOStream &                       out,
          const parallel::distributed::Triangulation<dim> &triangulation,
          const Particles::ParticleHandler<dim> &          particle_handler,
          const unsigned long long                         ghost_nodes);

  private:
    boost::signals2::connection connection;
  };
} // namespace sable::mpm

#endif
