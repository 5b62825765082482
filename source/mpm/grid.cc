#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <sable/mpm/grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sable::mpm
{
  namespace
  {
    template <int dim>
    std::vector<GridTools::PeriodicFacePair<typename DoFHandler<dim>::cell_iterator>>
    coarse_periodic_faces(const Triangulation<dim> &triangulation,
                          const DoFHandler<dim> &   dof_handler)
    {
      // the coarse pairs add_periodicity() was given, each once (lower face
      // first); make_periodicity_constraints() descends to the active faces
      std::vector<GridTools::PeriodicFacePair<typename DoFHandler<dim>::cell_iterator>> pairs;
      for (const auto &[face, partner] : triangulation.get_periodic_face_map())
        if (face.first->level() == 0 && face.second % 2 == 0)
          {
            GridTools::PeriodicFacePair<typename DoFHandler<dim>::cell_iterator> pair;
            pair.cell[0] = typename DoFHandler<dim>::cell_iterator(
              &triangulation, 0, face.first->index(), &dof_handler);
            pair.cell[1] = typename DoFHandler<dim>::cell_iterator(
              &triangulation, 0, partner.first.first->index(), &dof_handler);
            pair.face_idx[0]  = face.second;
            pair.face_idx[1]  = partner.first.second;
            pair.orientation  = partner.second;
            pairs.push_back(pair);
          }
      return pairs;
    }
  } // namespace

  template <int dim>
  Grid<dim>::Grid(const parallel::distributed::Triangulation<dim> &triangulation,
                  const ShapeFunctions                             shape_functions)
    : triangulation(triangulation)
    , fe(1)
    , dof_handler(triangulation)
    , shape_functions(shape_functions)
  {}

  template <int dim>
  void
  Grid<dim>::setup()
  {
    dof_handler.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    node_partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      dof_handler.locally_owned_dofs(),
      relevant,
      triangulation.get_communicator());

    // hanging nodes: each constrained vertex is a weighted sum of
    // unconstrained nodes; on a periodic grid the vertices of one face of
    // each matched pair are their images on the other (close() resolves
    // chains of constraints)
    AffineConstraints<double> constraints;
    constraints.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    periodic = Periodicity<dim>::of(triangulation);
    if (periodic.any())
      DoFTools::make_periodicity_constraints<dim, dim, double>(
        coarse_periodic_faces(triangulation, dof_handler),
                                                               constraints);
    constraints.close();

    cells.assign(triangulation.n_active_cells(), CellData());
    hanging_cells.clear();
    gimp_cells.clear();
    candidate_nodes.clear();
    double h_min = std::numeric_limits<double>::max();
    Tensor<1, dim> huge;
    for (unsigned int d = 0; d < dim; ++d)
      huge[d] = std::numeric_limits<double>::max();
    spacing.assign(n_relevant_nodes(), huge);
    // summed over the owned cells, then over the ranks: a node's support may
    // reach cells beyond this rank's ghost layer (the fine cells of a
    // hanging vertex whose master it is)
    LinearAlgebra::distributed::Vector<double> volumes(node_partitioner);
    positions.assign(n_relevant_nodes(), Point<dim>());
    std::vector<types::global_dof_index> dofs(nodes_per_cell);
    // every node's position first: a folded cell's shifts need its masters'
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            positions[node_partitioner->global_to_local(dofs[v])] = cell->vertex(v);
        }
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          CellData &data = cells[cell->active_cell_index()];
          cell->get_dof_indices(dofs);
          bool hanging = false;
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              data.nodes[v] = node_partitioner->global_to_local(dofs[v]);
              hanging       = hanging || constraints.is_constrained(dofs[v]);
            }
          if (hanging)
            {
              data.hanging = hanging_cells.size();
              hanging_cells.push_back(fold_hanging_vertices(cell, dofs, constraints));
            }
          // each vertex's shape function integrates to a 2^dim-th of the
          // cell; a hanging vertex's goes to its masters by their weights
          const double share = cell->measure() / nodes_per_cell;
          if (cell->is_locally_owned() && hanging)
            {
              const HangingCell &folded = hanging_cells[data.hanging];
              for (unsigned int e = 0; e < folded.first[nodes_per_cell]; ++e)
                volumes.local_element(folded.nodes[folded.slot[e]]) += folded.weight[e] * share;
            }
          else if (cell->is_locally_owned())
            for (unsigned int v = 0; v < nodes_per_cell; ++v)
              volumes.local_element(data.nodes[v]) += share;
          const auto [nodes, n_nodes] = cell_nodes(data);
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double h = cell->extent_in_direction(d);
              data.inverse_h[d] = 1. / h;
              if (cell->is_locally_owned())
                h_min = std::min(h_min, h);
              for (unsigned int k = 0; k < n_nodes; ++k)
                spacing[nodes[k]][d] = std::min(spacing[nodes[k]][d], h);
            }
        }
    volumes.compress(VectorOperation::add);
    volumes.update_ghost_values();
    support_volumes.resize(n_relevant_nodes());
    for (unsigned int node = 0; node < n_relevant_nodes(); ++node)
      support_volumes[node] = volumes.local_element(node);
    min_cell_size = Utilities::MPI::min(h_min, triangulation.get_communicator());
    if (shape_functions == ShapeFunctions::gimp)
      setup_lattice();
  }

  template <int dim>
  void
  Grid<dim>::setup_lattice()
  {
    AssertThrow(Utilities::MPI::n_mpi_processes(triangulation.get_communicator()) == 1,
                ExcMessage("GIMP shape functions run on one MPI rank (threads are "
                           "allowed): a point reaches the nodes of the cells next to "
                           "its own, beyond the ghost layer of a distributed grid."));
    const auto first_cell = triangulation.begin_active();
    Tensor<1, dim> h;
    for (unsigned int d = 0; d < dim; ++d)
      {
        h[d]             = first_cell->extent_in_direction(d);
        lattice_cells[d] = static_cast<int>(std::lround(periodic.period(d) / h[d]));
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      for (unsigned int d = 0; d < dim; ++d)
        AssertThrow(std::abs(cell->extent_in_direction(d) - h[d]) <= 1e-10 * h[d],
                    ExcMessage("GIMP shape functions need a uniform grid: all cells "
                               "of one size, no local refinement."));

    const auto lattice_index = [&](const Point<dim> &x) {
      std::array<int, dim> index;
      for (unsigned int d = 0; d < dim; ++d)
        index[d] = static_cast<int>(std::lround((x[d] - periodic.lower[d]) / h[d]));
      return index;
    };
    const auto flat = [&](const std::array<int, dim> &index) {
      int f = 0;
      for (int d = dim - 1; d >= 0; --d)
        f = f * (lattice_cells[d] + 1) + index[d];
      return f;
    };
    int n_lattice = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_lattice *= lattice_cells[d] + 1;
    lattice_nodes.assign(n_lattice, numbers::invalid_unsigned_int);
    gimp_cells.assign(cells.size(), GimpCell());
    // each lattice point's node; on a periodic axis the upper face's
    // vertices are images of the lower face's and are never looked up
    for (const auto &cell : triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const CellData &data = cells[cell->active_cell_index()];
          gimp_cells[cell->active_cell_index()].lattice = lattice_index(cell->vertex(0));
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              const std::array<int, dim> index = lattice_index(cell->vertex(v));
              bool on_image_face = false;
              for (unsigned int d = 0; d < dim; ++d)
                on_image_face = on_image_face ||
                                (periodic.periodic[d] && index[d] == lattice_cells[d]);
              if (!on_image_face)
                lattice_nodes[flat(index)] = data.nodes[v];
            }
        }

    // the nodes a cell's points may reach: 4 per direction around it (once
    // each: on a periodic axis of 3 cells two of them are one node)
    std::array<int, dim> lower, upper;
    lower.fill(-1);
    upper.fill(2);
    std::vector<unsigned int> reach;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const CellData &data = cells[cell->active_cell_index()];
          reach.clear();
          nodes_in_reach(data, lower, upper, reach);
          std::sort(reach.begin(), reach.end());
          reach.erase(std::unique(reach.begin(), reach.end()), reach.end());
          AssertThrow(reach.empty() || reach.back() != numbers::invalid_unsigned_int,
                      ExcInternalError());
          GimpCell &g       = gimp_cells[cell->active_cell_index()];
          g.first_candidate = candidate_nodes.size();
          g.n_candidates    = reach.size();
          candidate_nodes.insert(candidate_nodes.end(), reach.begin(), reach.end());
        }
  }

  template <int dim>
  void
  Grid<dim>::widen_reach(const CellData &      data,
                         const Point<dim> &    xi,
                         const double          spacing,
                         std::array<int, dim> &lower,
                         std::array<int, dim> &upper) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      {
        // a node k has weight only if its hat's support (k - 1, k + 1)
        // meets the domain [xi - l, xi + l] (which only shrinks at faces)
        const double half = std::min(0.5 * spacing * data.inverse_h[d], 0.5);
        lower[d] = std::min(lower[d], std::max(-1, static_cast<int>(std::floor(xi[d] - half - 1e-9))));
        upper[d] = std::max(upper[d], std::min(2, static_cast<int>(std::ceil(xi[d] + half + 1e-9))));
      }
  }

  template <int dim>
  void
  Grid<dim>::nodes_in_reach(const CellData &            data,
                            const std::array<int, dim> &lower,
                            const std::array<int, dim> &upper,
                            std::vector<unsigned int> & nodes) const
  {
    const std::array<int, dim> &origin = gimp_cell(data).lattice;
    std::array<int, dim>        offset = lower;
    while (true)
      {
        int  flat   = 0;
        bool inside = true;
        for (int d = dim - 1; d >= 0; --d)
          {
            int i = origin[d] + offset[d];
            if (periodic.periodic[d])
              i = (i + lattice_cells[d]) % lattice_cells[d];
            else
              inside = inside && i >= 0 && i <= lattice_cells[d];
            flat = flat * (lattice_cells[d] + 1) + i;
          }
        if (inside)
          nodes.push_back(lattice_nodes[flat]);
        unsigned int d = 0;
        while (d < dim && offset[d] == upper[d])
          offset[d] = lower[d], ++d;
        if (d == dim)
          return;
        ++offset[d];
      }
  }

  template <int dim>
  typename Grid<dim>::HangingCell
  Grid<dim>::fold_hanging_vertices(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const std::vector<types::global_dof_index> &          dofs,
    const AffineConstraints<double> &                     constraints) const
  {
    HangingCell  folded;
    unsigned int n_entries = 0;
    const auto   slot      = [&](const types::global_dof_index dof, const Point<dim> &vertex) {
      const unsigned int   node  = node_partitioner->global_to_local(dof);
      const Tensor<1, dim> shift = periodic.image_shift(vertex, positions[node]);
      for (unsigned int k = 0; k < folded.n_nodes; ++k)
        if (folded.nodes[k] == node)
          {
            AssertThrow((folded.shift[k] - shift).norm() == 0.,
                        ExcMessage("A cell reaches one node across a periodic seam and "
                                   "directly: a periodic axis needs at least 3 cells."));
            return k;
          }
      AssertThrow(folded.n_nodes < max_nodes_per_cell,
                  ExcMessage("A cell's hanging vertices reach more nodes than a "
                             "2:1 balanced mesh allows."));
      folded.nodes[folded.n_nodes] = node;
      folded.shift[folded.n_nodes] = shift;
      folded.shifted               = folded.shifted || shift.norm() > 0.;
      return folded.n_nodes++;
    };
    unsigned int vertex  = 0;
    const auto   add     = [&](const types::global_dof_index dof, const double weight) {
      AssertThrow(n_entries < HangingCell::max_entries,
                  ExcMessage("A hanging vertex depends on more nodes than expected."));
      folded.slot[n_entries]   = slot(dof, cell->vertex(vertex));
      folded.weight[n_entries] = weight;
      ++n_entries;
    };
    const auto relevant = [&](const types::global_dof_index dof) {
      return node_partitioner->in_local_range(dof) || node_partitioner->is_ghost_entry(dof);
    };
    for (unsigned int v = 0; v < nodes_per_cell; ++v)
      {
        vertex              = v;
        folded.first[v]     = n_entries;
        const auto *entries = constraints.get_constraint_entries(dofs[v]);
        if (entries == nullptr)
          add(dofs[v], 1.);
        else
          for (const auto &[master, weight] : *entries)
            // a ghost cell's master may lie beyond this rank's nodes; no
            // local particle reads it, so its share is not needed here
            if (relevant(master))
              add(master, weight);
      }
    folded.first[nodes_per_cell] = n_entries;
    return folded;
  }

  template <int dim>
  std::shared_ptr<const Utilities::MPI::Partitioner>
  Grid<dim>::make_partitioner(const unsigned int n_components) const
  {
    const auto expand = [n_components](const IndexSet &set) {
      IndexSet expanded(set.size() * n_components);
      for (const auto index : set)
        expanded.add_range(index * n_components, (index + 1) * n_components);
      expanded.compress();
      return expanded;
    };
    return std::make_shared<Utilities::MPI::Partitioner>(
      expand(node_partitioner->locally_owned_range()),
      expand(node_partitioner->ghost_indices()),
      triangulation.get_communicator());
  }

  template class Grid<2>;
  template class Grid<3>;
} // namespace sable::mpm
