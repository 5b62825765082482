#ifndef sable_mpm_grid_h
#define sable_mpm_grid_h

#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <sable/mpm/periodicity.h>
#include <sable/mpm/q1_shape.h>

#include <array>
#include <utility>
#include <memory>
#include <vector>

namespace dealii
{
  template <typename number>
  class AffineConstraints;
}

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
   *
   * On a locally refined mesh a cell's vertex may be a hanging node, whose
   * value is fixed by the nodes of the coarser neighbour (the constraints
   * of AffineConstraints / DoFTools::make_hanging_node_constraints). Such a
   * cell carries a small table that folds its vertex shape functions into
   * the unconstrained nodes, N_k = sum_v w_vk N_v, so that transfers
   * scatter to and gather from unconstrained nodes only: no hanging node
   * holds data, P2G and G2P use the same weights (exact transposes), and
   * the folded functions keep the partition of unity and sum_k grad N_k = 0.
   *
   * On a periodic grid (faces matched with add_periodicity() before
   * refinement) the vertices of the upper faces are constrained to their
   * images on the lower faces in the same way: a cell at the upper face
   * folds its shape functions onto nodes one period away, and its table
   * carries for each node the shift (whole periods) that brings a point of
   * the cell next to that node, for sums weighted by position.
   */
  template <int dim>
  class Grid
  {
  public:
    static constexpr unsigned int nodes_per_cell = 1u << dim;
    /// Most unconstrained nodes a cell's folded shape functions reach: the
    /// vertices of its parent's children (2:1 balanced mesh).
    static constexpr unsigned int max_nodes_per_cell = dim == 2 ? 9 : 27;

    struct CellData
    {
      /// the vertices' nodes (constrained ones included)
      std::array<unsigned int, nodes_per_cell> nodes;
      Tensor<1, dim>                           inverse_h;
      /// index into the table of cells with hanging vertices, or
      /// numbers::invalid_unsigned_int
      unsigned int hanging = numbers::invalid_unsigned_int;
    };

    /// The folding of a cell with hanging vertices, sparse: vertex v
    /// contributes weight[e] of its shape function to node slot[e] for
    /// e in [first[v], first[v + 1]).
    struct HangingCell
    {
      static constexpr unsigned int max_entries = 8 * nodes_per_cell;

      unsigned int                                 n_nodes = 0;
      std::array<unsigned int, max_nodes_per_cell> nodes;
      std::array<unsigned char, nodes_per_cell + 1> first;
      std::array<unsigned char, max_entries>        slot;
      std::array<double, max_entries>               weight;
      /// per node: the whole periods a point of the cell is moved by to lie
      /// next to the node (nonzero only across a periodic seam)
      bool                                          shifted = false;
      std::array<Tensor<1, dim>, max_nodes_per_cell> shift;
    };

    /// Shape functions of one cell at one point, on unconstrained nodes.
    struct Shape
    {
      unsigned int          n_nodes = 0;
      const unsigned int *  nodes   = nullptr;
      const double *        values  = nullptr;
      const Tensor<1, dim> *gradients = nullptr;
      /// per node, the image shift of the point (see HangingCell::shift), or
      /// nullptr where no node lies across a periodic seam
      const Tensor<1, dim> *shifts = nullptr;

      /// A point at @p x as node @p k sees it: its image next to the node.
      Point<dim>
      image_for_node(const Point<dim> &x, const unsigned int k) const
      {
        return shifts == nullptr ? x : x + shifts[k];
      }

      Q1Shape<dim>                                   vertex;
      std::array<double, max_nodes_per_cell>         folded_values;
      std::array<Tensor<1, dim>, max_nodes_per_cell> folded_gradients;
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

    /// The unconstrained nodes a cell's shape functions reach.
    std::pair<const unsigned int *, unsigned int>
    cell_nodes(const CellData &data) const
    {
      if (data.hanging == numbers::invalid_unsigned_int)
        return {data.nodes.data(), nodes_per_cell};
      const HangingCell &h = hanging_cells[data.hanging];
      return {h.nodes.data(), h.n_nodes};
    }

    /// Evaluate the cell's shape functions at reference point @p xi.
    inline void
    evaluate(const CellData &data, const Point<dim> &xi, Shape &shape) const
    {
      shape.vertex.evaluate(xi, data.inverse_h);
      if (data.hanging == numbers::invalid_unsigned_int)
        {
          shape.n_nodes   = nodes_per_cell;
          shape.nodes     = data.nodes.data();
          shape.values    = shape.vertex.values.data();
          shape.gradients = shape.vertex.gradients.data();
          shape.shifts    = nullptr;
          return;
        }
      const HangingCell &h = hanging_cells[data.hanging];
      shape.n_nodes        = h.n_nodes;
      shape.nodes          = h.nodes.data();
      shape.shifts         = h.shifted ? h.shift.data() : nullptr;
      for (unsigned int k = 0; k < h.n_nodes; ++k)
        {
          shape.folded_values[k]    = 0.;
          shape.folded_gradients[k] = Tensor<1, dim>();
        }
      for (unsigned int v = 0; v < nodes_per_cell; ++v)
        for (unsigned int e = h.first[v]; e < h.first[v + 1]; ++e)
          {
            shape.folded_values[h.slot[e]] += h.weight[e] * shape.vertex.values[v];
            shape.folded_gradients[h.slot[e]] += h.weight[e] * shape.vertex.gradients[v];
          }
      shape.values    = shape.folded_values.data();
      shape.gradients = shape.folded_gradients.data();
    }

    /// Number of cells with hanging vertices on this rank (owned and ghost).
    unsigned int
    n_hanging_cells() const
    {
      return hanging_cells.size();
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

    /// The periodic axes and the box (read off the triangulation in setup()).
    const Periodicity<dim> &
    periodicity() const
    {
      return periodic;
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
    HangingCell
    fold_hanging_vertices(const typename DoFHandler<dim>::active_cell_iterator &cell,
                          const std::vector<types::global_dof_index> &         dofs,
                          const AffineConstraints<double> &                    constraints) const;

    FE_Q<dim>              fe;
    MappingCartesian<dim>  mapping;
    DoFHandler<dim>        dof_handler;
    std::shared_ptr<const Utilities::MPI::Partitioner> node_partitioner;
    std::vector<CellData> cells;
    std::vector<HangingCell> hanging_cells;
    std::vector<Tensor<1, dim>> spacing;
    std::vector<Point<dim>>     positions;
    Periodicity<dim>            periodic;
    double                min_cell_size = 0.;
  };
} // namespace sable::mpm

#endif
