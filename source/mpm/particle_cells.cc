#include <sable/mpm/particle_cells.h>

namespace sable::mpm
{
  template <int dim>
  void
  ParticleCells<dim>::rebuild(const Particles::ParticleHandler<dim> &particle_handler,
                              const Grid<dim> &                      grid,
                              const CellColouring<dim> &             colouring)
  {
    // forget the previous cells (only their slots, not every cell's; after
    // a mesh change their iterators may be gone, their indices are kept)
    slot.resize(grid.triangulation.n_active_cells(), numbers::invalid_unsigned_int);
    for (const Cell &c : cells)
      if (c.active_cell_index < slot.size())
        slot[c.active_cell_index] = numbers::invalid_unsigned_int;
    cells.clear();
    ++n_versions;

    // one jump per non-empty cell: a cell's range ends where the next
    // non-empty cell's particles begin
    const auto collect = [&](auto particle, const auto end, const bool owned) {
      while (particle != end)
        {
          const auto cell  = particle->get_surrounding_cell();
          const auto         range = particle_handler.particles_in_cell(cell);
          const unsigned int index = cell->active_cell_index();
          slot[index]              = cells.size();
          const auto [lower, upper] = cell_box<dim>(cell);
          cells.push_back({cell, index, &grid.cell_data(cell), range, owned, lower, upper});
          particle = range.end();
        }
    };
    collect(particle_handler.begin(), particle_handler.end(), true);
    n_owned_cells = cells.size();
    collect(particle_handler.begin_ghost(), particle_handler.end_ghost(), false);

    // the colouring's blocks, with their empty cells and empty blocks left
    // out: this walks every cell of the colouring (most of them empty in
    // a sparse scene), so the colours are filtered concurrently; each
    // writes only its own lists, which do not depend on the threads
    colours.resize(colouring.get_colours().size());
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(colours.size()),
      [&](const unsigned int first, const unsigned int end) {
        for (unsigned int k = first; k < end; ++k)
          {
            const auto &all    = colouring.get_colours()[k];
            Colour &    colour = colours[k];
            colour.cells.clear();
            colour.block_start.assign(1, 0);
            for (unsigned int b = 0; b + 1 < all.block_start.size(); ++b)
              {
                for (unsigned int c = all.block_start[b]; c < all.block_start[b + 1]; ++c)
                  if (const unsigned int s = slot[all.cell_indices[c]];
                      s != numbers::invalid_unsigned_int)
                    colour.cells.push_back(s);
                if (colour.cells.size() > colour.block_start.back())
                  colour.block_start.push_back(colour.cells.size());
              }
          }
      },
      1);
  }

  template <int dim>
  void
  ParticleCells<dim>::update_reference_locations() const
  {
    parallel::apply_to_subranges(
      0u,
      n_owned_cells,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int c = begin; c < end; ++c)
          {
            const Cell &cell = cells[c];
            for (auto &particle : cell.particles)
              particle.set_reference_location(cell.reference_location(particle.get_location()));
          }
      },
      16);
  }

  template class ParticleCells<2>;
  template class ParticleCells<3>;
} // namespace sable::mpm
