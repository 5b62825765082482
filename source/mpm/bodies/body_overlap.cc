#include <sable/base/input_error.h>
#include <sable/base/significant_digits.h>
#include <sable/mpm/bodies/body_overlap.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    /// The bodies with a shape, listed in the boxes of a uniform grid that
    /// their bounding boxes overlap: a point meets only the bodies of its
    /// box (a pack of 10,000 grains would otherwise test each point 10,000
    /// times).
    template <int dim>
    class BodyBins
    {
    public:
      explicit BodyBins(const std::vector<BodyParameters<dim>> &bodies)
      {
        std::vector<unsigned int> shaped;
        std::vector<double>       sizes;
        for (unsigned int b = 0; b < bodies.size(); ++b)
          if (bodies[b].shape != BodyParameters<dim>::Shape::points)
            {
              const auto box     = bodies[b].bounding_box();
              double     largest = 0;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lower[d] = shaped.empty() ? box.first[d] : std::min(lower[d], box.first[d]);
                  upper[d] = shaped.empty() ? box.second[d] : std::max(upper[d], box.second[d]);
                  largest  = std::max(largest, box.second[d] - box.first[d]);
                }
              shaped.push_back(b);
              sizes.push_back(largest);
            }
        if (shaped.empty())
          return;
        // boxes the size of the median body, at most four per body (a few
        // small bodies beside a large one would otherwise fill millions of
        // boxes with the large one)
        std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
        size                   = std::max(sizes[sizes.size() / 2], 1e-12);
        const double max_boxes = std::max(64., 4. * shaped.size());
        for (;; size *= 2)
          {
            double n_boxes = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                count[d] = static_cast<unsigned int>(std::ceil((upper[d] - lower[d]) / size)) + 1;
                n_boxes *= count[d];
              }
            if (n_boxes <= max_boxes)
              break;
          }
        std::size_t n_boxes = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n_boxes *= count[d];
        boxes.resize(n_boxes);
        for (const unsigned int b : shaped)
          {
            const auto                    box = bodies[b].bounding_box();
            std::array<unsigned int, dim> first, last;
            for (unsigned int d = 0; d < dim; ++d)
              {
                first[d] = index(box.first[d], d);
                last[d]  = index(box.second[d], d);
              }
            std::array<unsigned int, dim> i = first;
            for (;;)
              {
                boxes[flat(i)].push_back(b);
                unsigned int d = 0;
                while (d < dim && ++i[d] > last[d])
                  i[d] = first[d], ++d;
                if (d == dim)
                  break;
              }
          }
      }

      /// The bodies whose bounding boxes may hold @p x.
      const std::vector<unsigned int> &
      near(const Point<dim> &x) const
      {
        static const std::vector<unsigned int> none;
        if (boxes.empty())
          return none;
        std::array<unsigned int, dim> i;
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (x[d] < lower[d] || x[d] > upper[d])
              return none;
            i[d] = index(x[d], d);
          }
        return boxes[flat(i)];
      }

    private:
      unsigned int
      index(const double x, const unsigned int d) const
      {
        const double i = std::floor((x - lower[d]) / size);
        return static_cast<unsigned int>(std::clamp(i, 0., count[d] - 1.));
      }

      std::size_t
      flat(const std::array<unsigned int, dim> &i) const
      {
        std::size_t f = 0;
        for (int d = dim - 1; d >= 0; --d)
          f = f * count[d] + i[d];
        return f;
      }

      Point<dim>                             lower, upper;
      double                                 size = 1;
      std::array<unsigned int, dim>          count{};
      std::vector<std::vector<unsigned int>> boxes;
    };

  } // namespace

  template <int dim>
  void
  check_bodies_apart(const std::vector<BodyParameters<dim>> &bodies,
                     const Particles::ParticleHandler<dim> & particle_handler,
                     const ParticleLayout<dim> &             layout,
                     const Periodicity<dim> &                periodicity,
                     const MPI_Comm                          communicator)
  {
    // one body has nothing to overlap (the same on every rank)
    if (bodies.size() < 2)
      return;
    const BodyBins<dim>               bins(bodies);
    const std::vector<Tensor<1, dim>> shifts = periodicity.image_shifts();

    // the point lying deepest inside another body, in its own spacings:
    // {depth / spacing, body, other body, depth, spacing, location}; ties
    // go to the smaller bodies' indices and location, so that any number
    // of ranks reports the same point
    using Offence = std::array<double, 5 + dim>;
    const auto worse = [](const Offence &a, const Offence &b) {
      if (a[0] != b[0])
        return a[0] > b[0];
      return std::lexicographical_compare(a.begin() + 1, a.end(), b.begin() + 1, b.end());
    };
    Offence worst{};
    for (const auto &particle : particle_handler)
      {
        const auto         props   = particle.get_properties();
        const unsigned int body    = static_cast<unsigned int>(props[layout.body]);
        const double       spacing = layout.seeding_spacing(props);
        for (const Tensor<1, dim> &shift : shifts)
          {
            const Point<dim> image = particle.get_location() + shift;
            for (const unsigned int other : bins.near(image))
              {
                if (other == body)
                  continue;
                const double depth = bodies[other].depth_inside(image);
                if (depth <= 0.25 * spacing)
                  continue;
                Offence offence{{depth / spacing, double(body), double(other), depth, spacing}};
                for (unsigned int d = 0; d < dim; ++d)
                  offence[5 + d] = particle.get_location()[d];
                if (worse(offence, worst))
                  worst = offence;
              }
          }
      }

    const std::vector<Offence> all = Utilities::MPI::all_gather(communicator, worst);
    for (const Offence &offence : all)
      if (worse(offence, worst))
        worst = offence;
    if (worst[0] == 0)
      return;

    const unsigned int a = static_cast<unsigned int>(worst[1]);
    const unsigned int b = static_cast<unsigned int>(worst[2]);
    std::ostringstream message;
    message << "invalid input: " << bodies[std::min(a, b)].label(std::min(a, b)) << " and "
            << bodies[std::max(a, b)].label(std::max(a, b)) << " overlap: the material point at (";
    for (unsigned int d = 0; d < dim; ++d)
      message << (d > 0 ? ", " : "") << significant_digits(worst[5 + d], 6);
    message << ") of " << bodies[a].label(a) << " lies " << significant_digits(worst[3])
            << " inside " << bodies[b].label(b) << " (" << significant_digits(worst[0])
            << " point spacings of " << significant_digits(worst[4])
            << "); allowed: bodies that touch or lie apart, no material point of one more "
               "than a quarter of its spacing inside another (such a point puts mass there "
               "twice, and contact would start from surfaces already through each other)";
    throw InputError(message.str());
  }

#define SABLE_INSTANTIATE(dim)                                                              \
  template void check_bodies_apart<dim>(const std::vector<BodyParameters<dim>> &,           \
                                        const Particles::ParticleHandler<dim> &,            \
                                        const ParticleLayout<dim> &,                        \
                                        const Periodicity<dim> &,                           \
                                        const MPI_Comm);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
