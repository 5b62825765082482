#ifndef sable_mpm_grid_h
#define sable_mpm_grid_h

#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <sable/mpm/gimp_shape.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/periodicity.h>
#include <sable/mpm/q1_shape.h>

#include <array>
#include <cmath>
#include <limits>
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
   *
   * With ShapeFunctions::gimp the grid must be uniform (no refinement) and
   * on one MPI rank: the nodes form a lattice, and a point reaches the
   * three nodes per direction nearest to it, which may be vertices of the
   * neighbouring cells (or, across a periodic seam, their images).
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
      std::array<unsigned int, max_nodes_per_cell>   stencil_nodes;
      /// GIMP: the last point volume seen and its seeding spacing (the
      /// points of a cell mostly share one; a root per point costs)
      double last_volume  = -1.;
      double last_spacing = 0.;
      std::array<Tensor<1, dim>, max_nodes_per_cell> stencil_shifts;
      std::array<double, max_nodes_per_cell>         folded_values;
      std::array<Tensor<1, dim>, max_nodes_per_cell> folded_gradients;
    };

    explicit Grid(const parallel::distributed::Triangulation<dim> &triangulation,
                  const ShapeFunctions shape_functions = ShapeFunctions::linear);

    ShapeFunctions
    get_shape_functions() const
    {
      return shape_functions;
    }

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
      if (!gimp_cells.empty())
        {
          const GimpCell &g = gimp_cell(data);
          return {candidate_nodes.data() + g.first_candidate, g.n_candidates};
        }
      if (data.hanging == numbers::invalid_unsigned_int)
        return {data.nodes.data(), nodes_per_cell};
      const HangingCell &h = hanging_cells[data.hanging];
      return {h.nodes.data(), h.n_nodes};
    }

    /// GIMP: widen the box [@p lower, @p upper] of node offsets from the
    /// cell's vertex 0 (per direction, within -1 to 2) to hold every node
    /// that a point at @p xi with seeding spacing @p spacing reaches with a
    /// nonzero weight (with a margin: the box may hold a few more).
    void
    widen_reach(const CellData &      data,
                const Point<dim> &    xi,
                const double          spacing,
                std::array<int, dim> &lower,
                std::array<int, dim> &upper) const;

    /// GIMP: append to @p nodes the nodes of the box of offsets [@p lower,
    /// @p upper] from the cell's vertex 0 (see widen_reach()).
    void
    nodes_in_reach(const CellData &            data,
                   const std::array<int, dim> &lower,
                   const std::array<int, dim> &upper,
                   std::vector<unsigned int> & nodes) const;

    /// Evaluate the cell's shape functions at reference point @p xi for a
    /// point of initial volume @p point_volume (which sets its GIMP domain).
    inline void
    evaluate(const CellData &  data,
             const Point<dim> &xi,
             const double      point_volume,
             Shape &           shape) const
    {
      if (shape_functions == ShapeFunctions::gimp)
        {
          evaluate_gimp(data, xi, point_volume, shape);
          return;
        }
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

    /// Per relevant node, the integral of its shape function: the volume
    /// its support holds (summed over all ranks).
    const std::vector<double> &
    node_support_volumes() const
    {
      return support_volumes;
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
    inline void
    evaluate_gimp(const CellData &  data,
                  const Point<dim> &xi,
                  const double      point_volume,
                  Shape &           shape) const;

    /// The lattice of nodes of a uniform grid and each cell's candidates.
    void
    setup_lattice();

    /// GIMP, per cell: the lattice index of its vertex 0, and where the
    /// nodes its points may reach (4 per direction) start in
    /// candidate_nodes. Kept apart from CellData, which the linear
    /// functions' transfers read, so that they do not carry it.
    struct GimpCell
    {
      std::array<int, dim> lattice{};
      unsigned int         first_candidate = 0;
      unsigned int         n_candidates    = 0;
    };

    /// The GIMP data of the cell whose CellData is @p data (an element of
    /// cells, so its position there is its active cell index).
    const GimpCell &
    gimp_cell(const CellData &data) const
    {
      return gimp_cells[&data - cells.data()];
    }

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
    std::vector<double>         support_volumes;
    std::vector<Point<dim>>     positions;
    Periodicity<dim>            periodic;
    double                min_cell_size = 0.;

    const ShapeFunctions shape_functions;
    /// GIMP: cells per direction, and the node at each lattice point
    /// (x fastest; numbers::invalid_unsigned_int where constrained)
    std::array<int, dim>      lattice_cells{};
    std::vector<unsigned int> lattice_nodes;
    std::vector<GimpCell>     gimp_cells;
    std::vector<unsigned int> candidate_nodes;
  };

  template <int dim>
  inline void
  Grid<dim>::evaluate_gimp(const CellData &  data,
                           const Point<dim> &xi,
                           const double      point_volume,
                           Shape &           shape) const
  {
    if (point_volume != shape.last_volume)
      {
        shape.last_volume  = point_volume;
        shape.last_spacing = ParticleLayout<dim>::spacing_of_volume(point_volume);
      }
    const double   spacing = shape.last_spacing;
    const GimpCell &cell   = gimp_cell(data);
    // per direction: the lattice index, the image shift, the weight and its
    // derivative of the (at most three) nodes that reach the point
    int          index[dim][3];
    double       shift[dim][3], value[dim][3], derivative[dim][3];
    unsigned int n[dim];
    bool         shifted = false;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double infinity = std::numeric_limits<double>::infinity();
        const double half     = std::min(0.5 * spacing * data.inverse_h[d], 0.5);
        const GimpWeights1D w = gimp_weights_1d(
          xi[d],
          half,
          periodic.periodic[d] ? -infinity : -double(cell.lattice[d]),
          periodic.periodic[d] ? infinity : double(lattice_cells[d] - cell.lattice[d]));
        const int first = cell.lattice[d] + first_gimp_node(xi[d]);
        n[d]            = 0;
        for (int k = 0; k < 3; ++k)
          if (w.value[k] != 0. || w.derivative[k] != 0.)
            {
              int    i = first + k;
              double s = 0;
              if (periodic.periodic[d])
                {
                  // the node's image inside the lattice; the point moves
                  // the other way to lie next to it
                  if (i < 0)
                    i += lattice_cells[d], s = periodic.period(d);
                  else if (i >= lattice_cells[d])
                    i -= lattice_cells[d], s = -periodic.period(d);
                  shifted = shifted || s != 0.;
                }
              index[d][n[d]]      = i;
              shift[d][n[d]]      = s;
              value[d][n[d]]      = w.value[k];
              derivative[d][n[d]] = w.derivative[k] * data.inverse_h[d];
              ++n[d];
            }
      }
    const int    stride_y = lattice_cells[0] + 1;
    const int    stride_z = stride_y * (dim == 3 ? lattice_cells[1] + 1 : 1);
    unsigned int k        = 0;
    for (unsigned int c = 0; c < (dim == 3 ? n[dim - 1] : 1u); ++c)
      for (unsigned int b = 0; b < n[1]; ++b)
        for (unsigned int a = 0; a < n[0]; ++a, ++k)
          {
            int    flat = index[0][a] + stride_y * index[1][b];
            double v    = value[0][a] * value[1][b];
            Tensor<1, dim> g;
            g[0] = derivative[0][a] * value[1][b];
            g[1] = value[0][a] * derivative[1][b];
            if constexpr (dim == 3)
              {
                flat += stride_z * index[2][c];
                g[0] *= value[2][c];
                g[1] *= value[2][c];
                g[2] = v * derivative[2][c];
                v *= value[2][c];
              }
            shape.stencil_nodes[k]    = lattice_nodes[flat];
            shape.folded_values[k]    = v;
            shape.folded_gradients[k] = g;
            if (shifted)
              {
                shape.stencil_shifts[k][0] = shift[0][a];
                shape.stencil_shifts[k][1] = shift[1][b];
                if constexpr (dim == 3)
                  shape.stencil_shifts[k][2] = shift[2][c];
              }
          }
    shape.n_nodes   = k;
    shape.nodes     = shape.stencil_nodes.data();
    shape.values    = shape.folded_values.data();
    shape.gradients = shape.folded_gradients.data();
    shape.shifts    = shifted ? shape.stencil_shifts.data() : nullptr;
  }
} // namespace sable::mpm

#endif
