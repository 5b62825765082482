#include <sable/mpm/bodies/clipped_seeding.h>

#include <algorithm>
#include <cmath>

namespace sable::mpm
{
  namespace
  {
    template <int dim>
    void
    add_ball_part(const Point<dim> &centre,
                  const double      radius_square,
                  const Point<dim> &lower,
                  const Point<dim> &upper,
                  const unsigned int levels_left,
                  double &          volume,
                  Tensor<1, dim> &  moment)
    {
      // the box's nearest and farthest points from the centre
      double nearest = 0, farthest = 0, box_volume = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double outside = std::max({0., lower[d] - centre[d], centre[d] - upper[d]});
          const double reach = std::max(std::abs(centre[d] - lower[d]), std::abs(upper[d] - centre[d]));
          nearest += outside * outside;
          farthest += reach * reach;
          box_volume *= upper[d] - lower[d];
        }
      if (nearest >= radius_square)
        return;
      const Point<dim> middle = 0.5 * (lower + upper);
      if (farthest <= radius_square || levels_left == 0)
        {
          if (farthest > radius_square && (middle - centre).norm_square() >= radius_square)
            return;
          volume += box_volume;
          moment += box_volume * middle;
          return;
        }
      for (unsigned int child = 0; child < (1u << dim); ++child)
        {
          Point<dim> child_lower, child_upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const bool upper_half = (child >> d) & 1u;
              child_lower[d]        = upper_half ? middle[d] : lower[d];
              child_upper[d]        = upper_half ? upper[d] : middle[d];
            }
          add_ball_part(centre, radius_square, child_lower, child_upper, levels_left - 1, volume, moment);
        }
    }
  } // namespace

  template <int dim>
  BallPart<dim>
  ball_part_in_box(const Point<dim> &centre,
                   const double      radius,
                   const Point<dim> &lower,
                   const Point<dim> &upper)
  {
    double         volume = 0;
    Tensor<1, dim> moment;
    add_ball_part(centre, radius * radius, lower, upper, dim == 2 ? 8 : 5, volume, moment);
    BallPart<dim> part;
    part.volume = volume;
    if (volume > 0)
      part.centroid = Point<dim>(moment / volume);
    return part;
  }

  template BallPart<2>
  ball_part_in_box<2>(const Point<2> &, const double, const Point<2> &, const Point<2> &);
  template BallPart<3>
  ball_part_in_box<3>(const Point<3> &, const double, const Point<3> &, const Point<3> &);
} // namespace sable::mpm
