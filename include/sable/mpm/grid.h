#ifndef sable_mpm_grid_h
#define sable_mpm_grid_h

#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <array>
#include <memory>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * The background grid: FE_Q<dim>(1) nodes on the user's distributed
   * triangulation of axis-aligned cells, with what the particle transfers
   * need cached once per mesh change: for each locally owned and ghost cell
   * its nodes as indices into the rank's locally relevant node range and
   * its inverse extents, and for each node the smallest adjacent cell size
   * per direction.
   */
  template <int dim>
  class Grid
  {
  public:
    static constexpr unsigned int nodes_per_cell = 1u << dim;

    struct CellData
    {
      std::array<unsigned int, nodes_per_cell> nodes;
      Tensor<1, dim>                           inverse_h;
    };

    explicit Grid(const parallel::distributed::Triangulation<dim> &triangulation);

    /// Distribute nodes and rebuild the caches (after any mesh change).
    void
    setup();

    const CellData &
    cell_data(const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return cells[cell->active_cell_index()];
    }

    /// Locally owned plus ghost nodes of this rank.
    unsigned int
    n_relevant_nodes() const
    {
      return node_partitioner->locally_owned_size() +
             node_partitioner->n_ghost_indices();
    }

    /// Partitioner of nodal data with @p n_components values per node,
    /// stored node by node (local index = node * n_components + component).
    std::shared_ptr<const Utilities::MPI::Partitioner>
    make_partitioner(const unsigned int n_components) const;

    /// Per relevant node, the smallest extent per direction of its cells.
    const std::vector<Tensor<1, dim>> &
    node_spacing() const
    {
      return spacing;
    }

    /// Position of each relevant node.
    const std::vector<Point<dim>> &
    node_positions() const
    {
      return positions;
    }

    /// Smallest cell extent over the whole grid (all ranks).
    double
    minimum_cell_size() const
    {
      return min_cell_size;
    }

    const DoFHandler<dim> &
    get_dof_handler() const
    {
      return dof_handler;
    }

    const Mapping<dim> &
    get_mapping() const
    {
      return mapping;
    }

    /// Local node index of a global node (dof) index.
    unsigned int
    local_index(const types::global_dof_index index) const
    {
      return node_partitioner->global_to_local(index);
    }

    const parallel::distributed::Triangulation<dim> &triangulation;

  private:
    FE_Q<dim>              fe;
    MappingCartesian<dim>  mapping;
    DoFHandler<dim>        dof_handler;
    std::shared_ptr<const Utilities::MPI::Partitioner> node_partitioner;
    std::vector<CellData> cells;
    std::vector<Tensor<1, dim>> spacing;
    std::vector<Point<dim>>     positions;
    double                min_cell_size = 0.;
  };
} // namespace sable::mpm

#endif
