#include <deal.II/base/mpi.h>

#include <sable/mpm/bodies/clipped_seeding.h>
#include <sable/mpm/bodies/conforming_seeding.h>
#include <sable/mpm/owned_cell_strip.h>
#include <sable/mpm/periodicity.h>
#include <sable/mpm/q1_shape.h>
#include <sable/mpm/seeding.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace sable::mpm
{
  namespace
  {
    /// How deep, in seeding cells, points carry their surface's normal:
    /// every point in the reach of a node up to a cell inside the surface;
    /// and within what distance of a face of another direction they carry
    /// none (near an edge or a corner the face is ambiguous; a block's
    /// edge zones two cells wide left the sides of a cube six cells wide
    /// on a wedge to the staircase's mass gradient).
    constexpr double surface_layer = 2.;
    constexpr double edge_margin   = 1.;
  } // namespace

  template <int dim>
  void
  seed_bodies(const parallel::distributed::Triangulation<dim> &triangulation,
              const std::vector<BodyParameters<dim>> &         bodies,
              const std::vector<std::unique_ptr<Material>> &   materials,
              const ParticleLayout<dim> &                      layout,
              const Tensor<1, dim> &                           gravity,
              Particles::ParticleHandler<dim> &                particle_handler)
  {
    const OwnedCellStrip<dim> owned_cells(triangulation);
    const Periodicity<dim>    periodicity = Periodicity<dim>::of(triangulation);
    // the grid's bounds (the coarse vertices are on every rank)
    Point<dim> grid_lower = triangulation.get_vertices()[0];
    Point<dim> grid_upper = grid_lower;
    for (const Point<dim> &v : triangulation.get_vertices())
      for (unsigned int d = 0; d < dim; ++d)
        {
          grid_lower[d] = std::min(grid_lower[d], v[d]);
          grid_upper[d] = std::max(grid_upper[d], v[d]);
        }
    types::particle_index     next_id = 0;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const BodyParameters<dim> &body     = bodies[b];
        const Material &           material = *materials[b];
        const unsigned int         k        = body.particles_per_direction;
        const auto                 box      = body.bounding_box();
        const Point<dim>           top      = body.top_point(gravity);
        const Point<dim>           centre   = body.centre();

        std::vector<double> properties(layout.n_properties(), 0.);
        unsigned int        n_sub = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n_sub *= k;

        // the shifts by whole periods that bring part of the body into the
        // grid: a body crossing a periodic face is seeded wrapped, its
        // points at x + shift
        std::vector<Tensor<1, dim>> shifts = periodicity.image_shifts();
        shifts.erase(std::remove_if(shifts.begin(),
                                    shifts.end(),
                                    [&](const Tensor<1, dim> &shift) {
                                      for (unsigned int d = 0; d < dim; ++d)
                                        if (shift[d] != 0 &&
                                            (box.first[d] + shift[d] >= periodicity.upper[d] ||
                                             box.second[d] + shift[d] <= periodicity.lower[d]))
                                          return true;
                                      return false;
                                    }),
                     shifts.end());
        const auto shifted = [](const std::pair<Point<dim>, Point<dim>> &b,
                                const Tensor<1, dim> &                  shift) {
          return std::make_pair(b.first + shift, b.second + shift);
        };

        // one material point at x in cell (at @p reference in its unit
        // cell), at x_body in the body's frame (x less the image shift)
        const auto add_point = [&](const auto &      cell,
                                   const Point<dim> &x,
                                   const Point<dim> &x_body,
                                   const Point<dim> &reference,
                                   const double      volume,
                                   const Tensor<1, dim> *velocity) {
          std::fill(properties.begin(), properties.end(), 0.);
          properties[layout.mass]           = material.density() * volume;
          properties[layout.initial_volume] = volume;
          properties[layout.body]           = b;
          // v = v0 + omega x (x - c), unless the points file gives v
          Tensor<1, 3> r, omega_cross_r;
          for (unsigned int d = 0; d < dim; ++d)
            r[d] = x_body[d] - centre[d];
          omega_cross_r = cross_product_3d(body.angular_velocity, r);
          for (unsigned int d = 0; d < dim; ++d)
            properties[layout.velocity + d] =
              velocity ? (*velocity)[d] : body.velocity[d] + omega_cross_r[d];
          // the affine transfers start from the spin's velocity gradient
          if (layout.affine_stored && velocity == nullptr)
            layout.set_affine(properties, spin_velocity_gradient<dim>(body.angular_velocity));
          for (unsigned int d = 0; d < dim; ++d)
            properties[layout.deformation + d * dim + d] = 1.;
          if (body.lithostatic_stress)
            {
              // p = rho g . (x - x_top) >= 0, sigma = -p I
              const double pressure =
                material.density() * (gravity * (x_body - top));
              for (unsigned int d = 0; d < 3; ++d)
                properties[layout.stress + d] = -pressure;
            }
          if (layout.initial_position_stored)
            for (unsigned int d = 0; d < dim; ++d)
              properties[layout.initial_position() + d] = x[d];
          // the face the points within two cells of it (four layers at two
          // points per cell direction) lie under: its normal, and the vector
          // to it where the contact locates faces (to_surface_stored implies
          // surface_normal_stored)
          if (layout.surface_normal_stored)
            {
              const double         cell = k * ParticleLayout<dim>::spacing_of_volume(volume);
              const FaceBelow<dim> face =
                body.face_below(x_body, surface_layer * cell, edge_margin * cell);
              for (unsigned int d = 0; d < dim; ++d)
                properties[layout.surface_normal() + d] = face.normal[d];
              // a disk's or sphere's points carry their vector to its
              // circle without a normal (the mass gradient gives a round
              // body's normal)
              if (layout.to_surface_stored)
                {
                  const Tensor<1, dim> to_surface =
                    body.shape == BodyParameters<dim>::Shape::disk ?
                      body.to_round_surface(x_body, surface_layer * cell) :
                      face.depth * face.normal;
                  for (unsigned int d = 0; d < dim; ++d)
                    properties[layout.to_surface() + d] = to_surface[d];
                }
            }
          particle_handler.insert_particle(x, reference, next_id++, cell,
                                            make_array_view(properties));
        };

        // the lattice of one owned cell: its k^dim sub-cell centres that
        // the body, moved by @p shift, holds (all of them where
        // @p whole_cell)
        const auto seed_cell_lattice = [&](const auto &           strip_cell,
                                           const Tensor<1, dim> &shift,
                                           const bool            whole_cell) {
          const Point<dim> lower      = strip_cell.lower;
          const Point<dim> upper      = strip_cell.upper;
          const double     sub_volume = strip_cell.cell->measure() / n_sub;
          for (unsigned int i = 0; i < n_sub; ++i)
            {
              const Point<dim> reference = seeding_point<dim>(i, k);
              Point<dim>       x;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = lower[d] + reference[d] * (upper[d] - lower[d]);
              if (whole_cell || body.contains(x - shift))
                add_point(strip_cell.cell, x, x - shift, reference, sub_volume, nullptr);
            }
        };

        // each point of a cloud, moved by @p shift, in the one owned cell
        // holding it (cells half open, closed at the grid's upper bounds);
        // points sorted by x to find a cell's in a slab. With
        // @p lattice_in_whole_cells, a cell the cloud's points fill
        // whole (their volumes sum to the cell's) and larger than
        // @p smallest gets the lattice of its own size instead: a clipped
        // body on an adapted grid keeps the fine spacing where its surface
        // cuts the cells and the cells' own inside
        const auto seed_cloud = [&](const PointCloud<dim> &cloud,
                                    const Tensor<1, dim> & shift,
                                    const bool             lattice_in_whole_cells = false,
                                    const Tensor<1, dim> & smallest = Tensor<1, dim>()) {
            std::vector<unsigned int> order(cloud.positions.size());
            std::iota(order.begin(), order.end(), 0u);
            std::sort(order.begin(), order.end(), [&](const unsigned int i, const unsigned int j) {
              return cloud.positions[i][0] < cloud.positions[j][0];
            });
            owned_cells.for_each_overlapping(shifted(box, shift), [&](const auto &strip_cell) {
              const Point<dim> lower = strip_cell.lower - shift;
              const Point<dim> upper = strip_cell.upper - shift;
              const auto inside = [&](const Point<dim> &x) {
                for (unsigned int d = 0; d < dim; ++d)
                  if (x[d] < lower[d] || x[d] > upper[d] ||
                      (x[d] == upper[d] && upper[d] < grid_upper[d]))
                    return false;
                return true;
              };
              auto i = std::lower_bound(order.begin(), order.end(), lower[0],
                                        [&](const unsigned int p, const double value) {
                                          return cloud.positions[p][0] < value;
                                        });
              const auto coarser = [&]() {
                for (unsigned int d = 0; d < dim; ++d)
                  if (upper[d] - lower[d] > smallest[d] * (1 + 1e-9))
                    return true;
                return false;
              };
              if (lattice_in_whole_cells && coarser())
                {
                  const double measure = strip_cell.cell->measure();
                  double       filled  = 0;
                  for (auto j = i; j != order.end() && cloud.positions[*j][0] <= upper[0]; ++j)
                    if (inside(cloud.positions[*j]))
                      filled += cloud.volumes[*j];
                  if (std::abs(filled - measure) <= 1e-10 * measure)
                    {
                      seed_cell_lattice(strip_cell, shift, true);
                      return;
                    }
                }
              for (; i != order.end() && cloud.positions[*i][0] <= upper[0]; ++i)
                {
                  const Point<dim> &x = cloud.positions[*i];
                  if (!inside(x))
                    continue;
                  Point<dim> reference;
                  for (unsigned int d = 0; d < dim; ++d)
                    reference[d] = (x[d] - lower[d]) / (upper[d] - lower[d]);
                  add_point(strip_cell.cell, x + shift, x, reference, cloud.volumes[*i],
                            cloud.velocities.empty() ? nullptr : &cloud.velocities[*i]);
                }
            });
        };

        if (body.shape == BodyParameters<dim>::Shape::points)
          {
            for (const Tensor<1, dim> &shift : shifts)
              seed_cloud(body.cloud, shift);
            continue;
          }
        if (body.seeding_used() != BodyParameters<dim>::Seeding::lattice)
          {
            // the smallest cell the body overlaps (its extent per
            // direction), on every rank
            Tensor<1, dim> smallest;
            for (unsigned int d = 0; d < dim; ++d)
              smallest[d] = std::numeric_limits<double>::max();
            for (const Tensor<1, dim> &shift : shifts)
              owned_cells.for_each_overlapping(shifted(box, shift), [&](const auto &strip_cell) {
                for (unsigned int d = 0; d < dim; ++d)
                  smallest[d] = std::min(smallest[d], strip_cell.upper[d] - strip_cell.lower[d]);
              });
            for (unsigned int d = 0; d < dim; ++d)
              smallest[d] = Utilities::MPI::min(smallest[d], triangulation.get_communicator());
            double spacing = smallest[0];
            for (unsigned int d = 1; d < dim; ++d)
              spacing = std::min(spacing, smallest[d]);
            // clipped: the lattice of those cells, aligned with the grid
            const PointCloud<dim> cloud =
              body.seeding_used() == BodyParameters<dim>::Seeding::conforming ?
                conforming_ball_points(body.center, body.radius, spacing / k) :
                clipped_ball_points(body.center, body.radius, grid_lower, smallest, k);
            const bool clipped = body.seeding_used() == BodyParameters<dim>::Seeding::clipped;
            for (const Tensor<1, dim> &shift : shifts)
              seed_cloud(cloud, shift, clipped, smallest);
            continue;
          }

        for (const Tensor<1, dim> &shift : shifts)
          owned_cells.for_each_overlapping(shifted(box, shift), [&](const auto &strip_cell) {
            seed_cell_lattice(strip_cell, shift, false);
          });
      }
    // ids unique over all ranks: offset by the points of the lower ranks
    const MPI_Comm              communicator = triangulation.get_communicator();
    types::particle_index       offset       = 0;
    const types::particle_index local = particle_handler.n_locally_owned_particles();
    MPI_Exscan(&local, &offset, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      offset = 0;
    for (auto &particle : particle_handler)
      particle.set_id(particle.get_id() + offset);
    particle_handler.update_cached_numbers();
  }

#define SABLE_INSTANTIATE(dim)                                                              \
  template void seed_bodies<dim>(const parallel::distributed::Triangulation<dim> &,         \
                                 const std::vector<BodyParameters<dim>> &,                  \
                                 const std::vector<std::unique_ptr<Material>> &,            \
                                 const ParticleLayout<dim> &,                               \
                                 const Tensor<1, dim> &,                                    \
                                 Particles::ParticleHandler<dim> &);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
