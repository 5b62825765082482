#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/mpm/mesh_refinement.h>
#include <sable/mpm/owned_cell_strip.h>

#include <algorithm>
#include <limits>

namespace sable::mpm
{
  template <int dim>
  MeshRefinement<dim>::MeshRefinement(
    const MeshRefinementParameters<dim> &                      parameters,
    const std::map<types::boundary_id, BoundaryParameters<dim>> &boundaries,
    const std::vector<BodyParameters<dim>> &                    bodies)
    : parameters(parameters)
    , boundaries(boundaries)
  {
    for (const auto &body : bodies)
      surface_bodies.push_back(body.refine_surface);
  }

  template <int dim>
  void
  MeshRefinement<dim>::refine_initial(
    parallel::distributed::Triangulation<dim> &triangulation,
    const std::vector<BodyParameters<dim>> &   bodies) const
  {
    if (!parameters.enabled())
      return;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && level(cell) < static_cast<int>(parameters.minimum_level))
        cell->set_refine_flag();
    // refining a cell to the minimum level may take several passes on a
    // grid that starts with mixed levels
    for (unsigned int pass = 0; pass < parameters.minimum_level; ++pass)
      {
        triangulation.execute_coarsening_and_refinement();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              level(cell) < static_cast<int>(parameters.minimum_level))
            cell->set_refine_flag();
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->clear_refine_flag();

    for (unsigned int pass = parameters.minimum_level; pass < parameters.maximum_level; ++pass)
      {
        std::vector<CellContent> contents = seeding_contents(triangulation, bodies);
        if (flag_cells(triangulation, contents).refine == 0)
          break;
        // nothing to coarsen yet: keep every cell the grid started with
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            cell->clear_coarsen_flag();
        triangulation.execute_coarsening_and_refinement();
      }
  }

  template <int dim>
  std::vector<typename MeshRefinement<dim>::CellContent>
  MeshRefinement<dim>::seeding_contents(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const std::vector<BodyParameters<dim>> &         bodies) const
  {
    std::vector<CellContent>  contents(triangulation.n_active_cells());
    const OwnedCellStrip<dim> cells(triangulation);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const BodyParameters<dim> &body  = bodies[b];
        const unsigned int         k     = body.particles_per_direction;
        unsigned int               n_sub = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n_sub *= k;
        cells.for_each_overlapping(body.bounding_box(), [&](const auto &c) {
          unsigned int inside = 0;
          for (unsigned int i = 0; i < n_sub; ++i)
            {
              const Point<dim> reference = seeding_point<dim>(i, k);
              Point<dim>       x;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = c.lower[d] + reference[d] * (c.upper[d] - c.lower[d]);
              inside += body.contains(x) ? 1 : 0;
            }
          contents[c.cell->active_cell_index()].add(b, inside);
        });
      }
    return contents;
  }

  template <int dim>
  typename MeshRefinement<dim>::FlagCount
  MeshRefinement<dim>::flag_cells(parallel::distributed::Triangulation<dim> &triangulation,
                                  std::vector<CellContent> &                 contents) const
  {
    using Criterion = typename MeshRefinementParameters<dim>::Criterion;
    contents.resize(triangulation.n_active_cells());
    GridTools::exchange_cell_data_to_ghosts<int, parallel::distributed::Triangulation<dim>>(
      triangulation,
      [&](const auto &cell) { return contents[cell->active_cell_index()].body; },
      [&](const auto &cell, const int body) { contents[cell->active_cell_index()].body = body; });

    // what meets at each vertex: for the surface criterion, bodies that do
    // not ask for surface refinement count as empty space
    struct VertexState
    {
      int  body     = no_body;
      bool several  = false; // two bodies meet here
      bool empty    = false; // a cell without material
      bool occupied = false; // a cell with material
    };
    const auto vertex_states = [&](const bool surface_view) {
      std::vector<VertexState> vertices(triangulation.n_vertices());
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          if (cell->is_artificial())
            continue;
          int body = contents[cell->active_cell_index()].body;
          if (surface_view && body >= 0 && !surface_bodies[body])
            body = no_body;
          for (const unsigned int v : cell->vertex_indices())
            {
              VertexState &s = vertices[cell->vertex_index(v)];
              if (body == no_body)
                s.empty = true;
              else
                {
                  s.occupied = true;
                  if (body == several_bodies || (s.body != no_body && s.body != body))
                    s.several = true;
                  s.body = body;
                }
            }
        }
      return vertices;
    };
    const std::vector<VertexState> vertices = vertex_states(false);
    const bool all_surfaces =
      std::find(surface_bodies.begin(), surface_bodies.end(), false) == surface_bodies.end();
    const std::vector<VertexState> surface_vertices =
      parameters.uses(Criterion::body_surface) && !all_surfaces ? vertex_states(true) : vertices;

    const auto at_wall = [&](const auto &cell) {
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f))
          {
            const auto it = boundaries.find(cell->face(f)->boundary_id());
            if (it != boundaries.end() && it->second.type == BoundaryType::friction)
              return true;
          }
      return false;
    };
    const unsigned int children = GeometryInfo<dim>::max_children_per_cell;

    enum Decision : char
    {
      coarsen,
      keep,
      refine
    };
    std::vector<char> decisions(triangulation.n_active_cells(), keep);
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const CellContent &content = contents[cell->active_cell_index()];
        bool surface = false, meeting = false;
        for (const unsigned int v : cell->vertex_indices())
          {
            const VertexState &s = surface_vertices[cell->vertex_index(v)];
            surface = surface || s.several || (s.empty && s.occupied);
            meeting = meeting || vertices[cell->vertex_index(v)].several;
          }
        bool refine_here = false, keep_here = false;
        if (parameters.uses(Criterion::body_surface))
          refine_here = refine_here || surface;
        if (parameters.uses(Criterion::contact))
          refine_here = refine_here || meeting || (content.body != no_body && at_wall(cell));
        if (parameters.uses(Criterion::region))
          {
            const auto corners = cell->bounding_box().get_boundary_points();
            bool       inside  = true;
            for (unsigned int d = 0; d < dim; ++d)
              inside = inside && corners.second[d] > parameters.region_lower_corner[d] &&
                       corners.first[d] < parameters.region_upper_corner[d];
            refine_here = refine_here || inside;
          }
        if (parameters.uses(Criterion::particle_count))
          {
            refine_here =
              refine_here || content.n_particles > parameters.maximum_particles_per_cell;
            // the parent would hold about 2^dim times as many points:
            // coarsening must not bring back a cell that is refined again
            keep_here = content.n_particles * children > parameters.maximum_particles_per_cell;
          }
        decisions[cell->active_cell_index()] = refine_here ? refine : keep_here ? keep : coarsen;
      }

    // refine below the maximum level; coarsen only whole families above the
    // minimum level, so that a flag always changes the grid
    unsigned long long n_refine = 0, n_coarsen = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const int cell_level = level(cell);
        // a cell's children hold at least one of its points per direction:
        // finer, a node may see one body only where two meet, and the
        // bodies pass through each other (a disk seeded two points per
        // coarse cell and dropped on a plane body sank in at four fine
        // cells per coarse one)
        double child_size = std::numeric_limits<double>::max();
        for (unsigned int d = 0; d < dim; ++d)
          child_size = std::min(child_size, 0.5 * cell->extent_in_direction(d));
        const bool points_allow =
          contents[cell->active_cell_index()].seeding_spacing <= child_size * (1 + 1e-6);
        if (decisions[cell->active_cell_index()] == refine &&
            cell_level < static_cast<int>(parameters.maximum_level) && points_allow)
          {
            cell->set_refine_flag();
            ++n_refine;
          }
        else if (decisions[cell->active_cell_index()] == coarsen &&
                 cell_level > static_cast<int>(parameters.minimum_level))
          {
            const auto parent         = cell->parent();
            bool       whole_family = true;
            for (unsigned int c = 0; c < parent->n_children(); ++c)
              {
                const auto child = parent->child(c);
                whole_family     = whole_family && child->is_active() &&
                               child->is_locally_owned() &&
                               decisions[child->active_cell_index()] == coarsen;
              }
            if (whole_family)
              {
                cell->set_coarsen_flag();
                ++n_coarsen;
              }
          }
      }
    const MPI_Comm communicator = triangulation.get_communicator();
    return {Utilities::MPI::sum(n_refine, communicator), Utilities::MPI::sum(n_coarsen, communicator)};
  }

  template class MeshRefinement<2>;
  template class MeshRefinement<3>;
} // namespace sable::mpm
