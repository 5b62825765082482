#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <sable/mpm/bodies/clipped_seeding.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

  template <int dim>
  PointCloud<dim>
  clipped_ball_points(const Point<dim> &    centre,
                      const double          radius,
                      const Point<dim> &    origin,
                      const Tensor<1, dim> &cell,
                      const unsigned int    k)
  {
    const auto depth   = [&](const Point<dim> &x) { return radius - x.distance(centre); };
    double     spacing = std::numeric_limits<double>::max();
    double     sub_volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        spacing = std::min(spacing, cell[d] / k);
        sub_volume *= cell[d] / k;
      }
    // no point shallower than a quarter spacing: walls and bodies read the
    // surface from the nodes' mass centroids as if it were flat, which on a
    // round body puts it a little high, and a point at the surface of a
    // disk on a friction wall was pushed through it (A1 at 16 cells per
    // diameter, 3 points per cell direction)
    const double least_depth = 0.25 * spacing;
    // no point under a quarter of a sub-cell's volume: FLIP's velocity
    // updates from nodes that little mass reaches sent such points off at
    // up to 240 m/s in a settling pile (6 cells per diameter)
    const double least_volume = 0.25 * sub_volume;
    // @p from joins @p into at their common centroid (and is left empty)
    const auto join = [](BallPart<dim> &into, BallPart<dim> &from) {
      const double volume = into.volume + from.volume;
      into.centroid = Point<dim>((into.volume * into.centroid + from.volume * from.centroid) / volume);
      into.volume   = volume;
      from.volume   = 0;
    };

    // the cells the ball's bounding box overlaps, numbered along x first
    std::array<int, dim> first, count;
    unsigned int         n_cells = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        first[d] = static_cast<int>(std::floor((centre[d] - radius - origin[d]) / cell[d]));
        count[d] = static_cast<int>(std::floor((centre[d] + radius - origin[d]) / cell[d])) - first[d] + 1;
        n_cells *= count[d];
      }
    const auto cell_index = [&](unsigned int c) {
      std::array<int, dim> index;
      for (unsigned int d = 0; d < dim; ++d)
        {
          index[d] = c % count[d];
          c /= count[d];
        }
      return index;
    };
    unsigned int n_sub = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_sub *= k;

    // each cell's parts; a part shallower than the least depth joins the
    // deepest part of its cell, moved in along the radius if that one is
    // still shallower (a cell the surface barely enters)
    std::vector<BallPart<dim>> points;
    // the points of cell c: cell_begin[c] .. cell_begin[c + 1]
    std::vector<unsigned int>  cell_begin(n_cells + 1, 0);
    std::vector<BallPart<dim>> parts(n_sub);
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const std::array<int, dim> index = cell_index(c);
        unsigned int               deepest = n_sub;
        for (unsigned int i = 0; i < n_sub; ++i)
          {
            Point<dim>   sub_lower, sub_upper;
            unsigned int sub = i;
            for (unsigned int d = 0; d < dim; ++d)
              {
                sub_lower[d] = origin[d] + (first[d] + index[d]) * cell[d] + (sub % k) * cell[d] / k;
                sub_upper[d] = sub_lower[d] + cell[d] / k;
                sub /= k;
              }
            parts[i] = ball_part_in_box(centre, radius, sub_lower, sub_upper);
            // a whole sub-cell keeps the lattice's point, its centre
            if (parts[i].volume >= sub_volume * (1 - 1e-12))
              parts[i] = {sub_volume, Point<dim>(0.5 * (sub_lower + sub_upper))};
            if (parts[i].volume > 0 &&
                (deepest == n_sub || depth(parts[i].centroid) > depth(parts[deepest].centroid)))
              deepest = i;
          }
        if (deepest < n_sub)
          {
            for (unsigned int i = 0; i < n_sub; ++i)
              if (i != deepest && parts[i].volume > 0 && depth(parts[i].centroid) < least_depth)
                join(parts[deepest], parts[i]);
            BallPart<dim> &joined = parts[deepest];
            if (depth(joined.centroid) < least_depth)
              {
                const Tensor<1, dim> out = joined.centroid - centre;
                joined.centroid          = centre + (radius - least_depth) / out.norm() * out;
              }
            for (const BallPart<dim> &part : parts)
              if (part.volume > 0)
                points.push_back(part);
          }
        cell_begin[c + 1] = points.size();
      }

    // a point under the least volume joins the nearest larger point of its
    // cell or the cells beside it
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int p = cell_begin[c]; p < cell_begin[c + 1]; ++p)
        {
          if (points[p].volume >= least_volume)
            continue;
          const std::array<int, dim> index    = cell_index(c);
          unsigned int               nearest  = numbers::invalid_unsigned_int;
          double                     distance = std::numeric_limits<double>::max();
          for (unsigned int n = 0; n < Utilities::pow(3u, dim); ++n)
            {
              unsigned int neighbour = 0, stride = 1, code = n;
              bool         inside    = true;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const int j = index[d] + static_cast<int>(code % 3) - 1;
                  code /= 3;
                  inside = inside && j >= 0 && j < count[d];
                  neighbour += std::max(j, 0) * stride;
                  stride *= count[d];
                }
              if (!inside)
                continue;
              for (unsigned int q = cell_begin[neighbour]; q < cell_begin[neighbour + 1]; ++q)
                if (points[q].volume >= least_volume &&
                    points[q].centroid.distance(points[p].centroid) < distance)
                  {
                    nearest  = q;
                    distance = points[q].centroid.distance(points[p].centroid);
                  }
            }
          if (nearest != numbers::invalid_unsigned_int)
            join(points[nearest], points[p]);
        }

    PointCloud<dim> cloud;
    for (const BallPart<dim> &point : points)
      if (point.volume > 0)
        {
          cloud.positions.push_back(point.centroid);
          cloud.volumes.push_back(point.volume);
        }
    return cloud;
  }

  template BallPart<2>
  ball_part_in_box<2>(const Point<2> &, const double, const Point<2> &, const Point<2> &);
  template BallPart<3>
  ball_part_in_box<3>(const Point<3> &, const double, const Point<3> &, const Point<3> &);
  template PointCloud<2>
  clipped_ball_points<2>(const Point<2> &, const double, const Point<2> &, const Tensor<1, 2> &,
                         const unsigned int);
  template PointCloud<3>
  clipped_ball_points<3>(const Point<3> &, const double, const Point<3> &, const Tensor<1, 3> &,
                         const unsigned int);
} // namespace sable::mpm
