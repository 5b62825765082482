#include <sable/mpm/periodicity.h>

#include <algorithm>

namespace sable::mpm
{
  template <int dim>
  Periodicity<dim>
  Periodicity<dim>::of(const parallel::distributed::Triangulation<dim> &triangulation)
  {
    Periodicity<dim> p;
    // the coarse vertices are on every rank, so the box is the same on all
    p.lower = triangulation.get_vertices()[0];
    p.upper = p.lower;
    for (const Point<dim> &v : triangulation.get_vertices())
      for (unsigned int d = 0; d < dim; ++d)
        {
          p.lower[d] = std::min(p.lower[d], v[d]);
          p.upper[d] = std::max(p.upper[d], v[d]);
        }
    // faces 2d and 2d + 1 of a box cell are its faces normal to axis d
    for (const auto &[face, partner] : triangulation.get_periodic_face_map())
      p.periodic[face.second / 2] = true;
    return p;
  }

  template struct Periodicity<2>;
  template struct Periodicity<3>;
} // namespace sable::mpm
