#include <deal.II/base/parallel.h>

#include <sable/mpm/particle_rebinning.h>

#include <algorithm>
#include <map>
#include <mutex>

namespace sable::mpm
{
  template <int dim>
  typename ParticleRebinning<dim>::CellIterator
  ParticleRebinning<dim>::find_cell(const CellIterator &    old_cell,
                                    const Point<dim> &      x,
                                    const Periodicity<dim> &periodicity)
  {
    // each pass crosses one face; a point moves less than a cell per step,
    // so it crosses at most one face per direction (and coarser cells cut
    // the walk short)
    typename Triangulation<dim>::cell_iterator current = old_cell;
    for (unsigned int crossing = 0; crossing <= dim; ++crossing)
      {
        // the image of x next to the current cell (across a periodic seam)
        Point<dim> near = x;
        if (periodicity.any())
          near += periodicity.image_shift(x, current->center());
        const auto [lower, upper] = cell_box<dim>(current);
        unsigned int face         = numbers::invalid_unsigned_int;
        for (unsigned int d = 0; d < dim && face == numbers::invalid_unsigned_int; ++d)
          if (near[d] < lower[d])
            face = 2 * d;
          else if (near[d] > upper[d])
            face = 2 * d + 1;
        if (face == numbers::invalid_unsigned_int)
          return current;

        if (!current->at_boundary(face))
          current = current->neighbor(face);
        else if (current->has_periodic_neighbor(face))
          current = current->periodic_neighbor(face);
        else
          return {}; // it left the grid

        // a finer neighbour: down to the child that holds the point (the
        // children of a hypercube are numbered lexicographically)
        while (current->has_children())
          {
            near = x;
            if (periodicity.any())
              near += periodicity.image_shift(x, current->center());
            const Point<dim> centre = current->center();
            unsigned int     child  = 0;
            for (unsigned int d = 0; d < dim; ++d)
              if (near[d] > centre[d])
                child |= 1u << d;
            current = current->child(child);
          }
      }
    return {};
  }

  template <int dim>
  bool
  ParticleRebinning<dim>::rebin(Particles::ParticleHandler<dim> &particle_handler,
                                const ParticleCells<dim> &       cells,
                                const Periodicity<dim> &         periodicity,
                                const std::size_t                max_moves)
  {
    // the points that stayed: their reference locations; the others are
    // listed, per range of cells, with their cell's index
    std::map<unsigned int, std::vector<Leaving>> leaving_per_range;
    std::mutex                                   mutex;
    parallel::apply_to_subranges(
      0u,
      cells.n_owned(),
      [&](const unsigned int begin, const unsigned int end) {
        std::vector<Leaving> left;
        for (unsigned int c = begin; c < end; ++c)
          {
            const auto &cell = cells[c];
            for (auto particle = cell.particles.begin(); particle != cell.particles.end();
                 ++particle)
              {
                const Point<dim> &x = particle->get_location();
                if (cell.contains(x))
                  particle->set_reference_location(cell.reference_location(x));
                else
                  left.emplace_back(cell.active_cell_index, particle);
              }
          }
        if (!left.empty())
          {
            std::lock_guard<std::mutex> lock(mutex);
            leaving_per_range.emplace(begin, std::move(left));
          }
      },
      16);
    // in the order the sort moves them: by cell index, and within a cell
    // in the container's order (whatever the threads)
    leaving.clear();
    for (const auto &range : leaving_per_range)
      leaving.insert(leaving.end(), range.second.begin(), range.second.end());
    if (leaving.size() > max_moves)
      return false;
    std::stable_sort(leaving.begin(), leaving.end(), [](const Leaving &a, const Leaving &b) {
      return a.first < b.first;
    });

    destination.resize(leaving.size());
    for (unsigned int i = 0; i < leaving.size(); ++i)
      {
        const ParticleIterator &particle = leaving[i].second;
        destination[i] =
          find_cell(particle->get_surrounding_cell(), particle->get_location(), periodicity);
        if (destination[i].state() != IteratorState::valid)
          return false;
      }

    // insert all, then remove the old copies, a cell's last first, so that
    // the removals do not disturb the points still to be removed
    for (unsigned int i = 0; i < leaving.size(); ++i)
      {
        const ParticleIterator &particle = leaving[i].second;
        const auto              view     = particle->get_properties();
        properties.assign(view.begin(), view.end());
        const Point<dim> x        = particle->get_location();
        const auto [lower, upper] = cell_box<dim>(destination[i]);
        particle_handler.insert_particle(x,
                                         reference_location_in_box(x, lower, upper),
                                         particle->get_id(),
                                         destination[i],
                                         make_array_view(properties));
      }
    for (auto entry = leaving.rbegin(); entry != leaving.rend(); ++entry)
      particle_handler.remove_particle(entry->second);
    n_moved += leaving.size();
    return true;
  }

  template class ParticleRebinning<2>;
  template class ParticleRebinning<3>;
} // namespace sable::mpm
