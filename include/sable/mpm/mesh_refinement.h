#ifndef sable_mpm_mesh_refinement_h
#define sable_mpm_mesh_refinement_h

#include <deal.II/distributed/tria.h>

#include <sable/mpm/parameters.h>

#include <algorithm>
#include <map>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Chooses where the background grid is refined and coarsened
   * (Mesh refinement subsection; doc/mpm.md, "Adaptive meshes").
   *
   * The criteria look at what each cell holds: no body, one body, or
   * several, and how many material points. A vertex where cells of
   * different content meet lies on a body's surface; one where two bodies
   * meet is a contact vertex. Cells touching such vertices (on both sides
   * of the surface) are refined up to the maximum level; cells no
   * criterion asks for are coarsened down to the minimum level. Cell
   * contents are exchanged with the ghost cells first, so every rank
   * flags its cells as one rank would.
   *
   * Before the bodies are seeded, refine_initial() judges the cells by the
   * bodies' seeding points (the points seeding would create), so bodies
   * are seeded on the refined grid; afterwards flag_cells() judges them by
   * the material points.
   */
  template <int dim>
  class MeshRefinement
  {
  public:
    /// Cell content: an index >= 0 is the one body present.
    static constexpr int no_body       = -1;
    static constexpr int several_bodies = -2;

    /// What one locally owned cell holds.
    struct CellContent
    {
      int          body        = no_body;
      unsigned int n_particles = 0;
      /// the largest spacing its points were seeded at (0: points still to
      /// be seeded on the cell)
      double seeding_spacing = 0;

      void
      add(const unsigned int body_index, const unsigned int count = 1, const double spacing = 0)
      {
        if (count == 0)
          return;
        n_particles += count;
        seeding_spacing = std::max(seeding_spacing, spacing);
        if (body == no_body)
          body = body_index;
        else if (body != static_cast<int>(body_index))
          body = several_bodies;
      }
    };

    MeshRefinement(const MeshRefinementParameters<dim> &                      parameters,
                   const std::map<types::boundary_id, BoundaryParameters<dim>> &boundaries,
                   const std::vector<BodyParameters<dim>> &                    bodies);

    /**
     * The level of the grid's base cells (the Subdivisions cells of a
     * scene, see make_grid()): 'Minimum level' and 'Maximum level' count
     * from it. Default 0: from the coarse mesh.
     */
    void
    set_base_level(const unsigned int level)
    {
      base_level = level;
    }

    /// Refine globally to the minimum level, then where the criteria ask
    /// (judged by the bodies' seeding points) up to the maximum level.
    void
    refine_initial(parallel::distributed::Triangulation<dim> &triangulation,
                   const std::vector<BodyParameters<dim>> &   bodies) const;

    /// Cells flagged on all ranks.
    struct FlagCount
    {
      unsigned long long refine  = 0;
      unsigned long long coarsen = 0;
    };

    /**
     * Set refine and coarsen flags on the locally owned cells from their
     * contents (indexed by active cell index; only owned cells are read).
     * Returns the numbers of flagged cells over all ranks.
     */
    FlagCount
    flag_cells(parallel::distributed::Triangulation<dim> &triangulation,
               std::vector<CellContent> &                 contents) const;

  private:
    /// The contents of the owned cells judged by the seeding points.
    std::vector<CellContent>
    seeding_contents(const parallel::distributed::Triangulation<dim> &triangulation,
                     const std::vector<BodyParameters<dim>> &         bodies) const;

    const MeshRefinementParameters<dim>                         parameters;
    const std::map<types::boundary_id, BoundaryParameters<dim>> boundaries;
    /// per body: whether the body surface criterion looks at it
    std::vector<bool> surface_bodies;
    unsigned int      base_level = 0;

    /// A cell's level counted from the base level.
    template <class Iterator>
    int
    level(const Iterator &cell) const
    {
      return cell->level() - static_cast<int>(base_level);
    }
  };
} // namespace sable::mpm

#endif
