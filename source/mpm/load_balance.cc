#include <deal.II/base/mpi.h>

#include <sable/mpm/load_balance.h>

#include <ostream>

namespace sable::mpm
{
  template <int dim>
  void
  LoadBalance<dim>::connect(parallel::distributed::Triangulation<dim> &triangulation,
                            const Particles::ParticleHandler<dim> &    particle_handler)
  {
    disconnect();
    connection = triangulation.signals.weight.connect(
      [&particle_handler](const typename Triangulation<dim>::cell_iterator &cell,
                          const typename Triangulation<dim>::CellStatus     status) {
        return cell_weight(particle_handler, cell, status);
      });
  }

  template <int dim>
  unsigned int
  LoadBalance<dim>::cell_weight(const Particles::ParticleHandler<dim> &            particle_handler,
                                const typename Triangulation<dim>::cell_iterator &cell,
                                const typename Triangulation<dim>::CellStatus     status)
  {
    unsigned int n_particles = 0;
    switch (status)
      {
        case Triangulation<dim>::CELL_PERSIST:
          n_particles = particle_handler.n_particles_in_cell(cell);
          break;
        case Triangulation<dim>::CELL_REFINE:
          // called for each future child with the parent: an equal share
          n_particles =
            particle_handler.n_particles_in_cell(cell) / GeometryInfo<dim>::max_children_per_cell;
          break;
        case Triangulation<dim>::CELL_COARSEN:
          for (const auto &child : cell->child_iterators())
            n_particles += particle_handler.n_particles_in_cell(child);
          break;
        default:
          Assert(false, ExcInternalError());
      }
    return cell_cost + particle_cost * n_particles;
  }

  template <int dim>
  std::pair<unsigned long long, unsigned long long>
  LoadBalance<dim>::particles_per_rank(const Particles::ParticleHandler<dim> &particle_handler,
                                       const MPI_Comm                         communicator)
  {
    const unsigned long long local = particle_handler.n_locally_owned_particles();
    return {Utilities::MPI::min(local, communicator), Utilities::MPI::max(local, communicator)};
  }

  template <int dim>
  void
  LoadBalance<dim>::print(const ConditionalOStream &                       out,
                          const parallel::distributed::Triangulation<dim> &triangulation,
                          const Particles::ParticleHandler<dim> &          particle_handler,
                          const unsigned long long                         ghost_nodes)
  {
    const MPI_Comm communicator = triangulation.get_communicator();
    const auto [fewest, most]   = particles_per_rank(particle_handler, communicator);
    const unsigned long long cells     = triangulation.n_locally_owned_active_cells();
    const unsigned long long particles = particle_handler.n_locally_owned_particles();
    const unsigned long long work      = cell_cost * cells + particle_cost * particles;
    // every rank takes part in the reductions; rank 0's stream prints
    const unsigned long long min_cells = Utilities::MPI::min(cells, communicator);
    const unsigned long long max_cells = Utilities::MPI::max(cells, communicator);
    const unsigned long long min_ghost = Utilities::MPI::min(ghost_nodes, communicator);
    const unsigned long long max_ghost = Utilities::MPI::max(ghost_nodes, communicator);
    const unsigned long long min_work  = Utilities::MPI::min(work, communicator);
    const unsigned long long max_work  = Utilities::MPI::max(work, communicator);
    out << "particles per rank: " << fewest << " .. " << most << "; cells per rank: " << min_cells
        << " .. " << max_cells << "; ghost nodes per rank: " << min_ghost << " .. " << max_ghost
        << "; work per rank (" << cell_cost << " per cell + " << particle_cost
        << " per material point): " << min_work << " .. " << max_work << std::endl;
  }

  template class LoadBalance<2>;
  template class LoadBalance<3>;
} // namespace sable::mpm
