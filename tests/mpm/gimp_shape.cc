// The uniform GIMP shape functions of sable::mpm::Grid
// (Grid/Shape functions = gimp), in 2D and 3D, on a box grid and on one
// periodic along y:
//  - one direction against an independent quadrature: the weight of each
//    node is the mean of its hat function over the point's domain computed with 20,000 midpoints per domain
//    (error ~1e-9, tolerance 1e-7), its half-length shrunk to the distance
//    to the grid's face where that is smaller; a point whose domain lies inside one
//    cell gets the linear weights at its centre (1e-12: a difference of two
//    integrals of order 1, divided by the domain's width 2l >= 0.01), and
//    so does a point 1e-10 cells from a face of the grid (1e-9), whose
//    domain has shrunk to that distance: walls there hold the points;
//  - partition of unity sum_k N_k = 1 and sum_k grad N_k = 0 at 300 random
//    points with random seeding spacings in (0, h], next to the faces too
//    (1e-13: sums of a few dozen products of numbers in [0, 1]);
//  - gradients equal the central differences of the values as the point
//    moves (step 1e-6 h; the weights are piecewise quadratic, so the
//    difference is exact up to round-off ~1e-10 / h and the kinks of the
//    hat function inside the difference interval, which shift it by at
//    most the step: tolerance 1e-5 / h);
//  - continuity across a cell face: a point 1e-9 h either side of a face,
//    evaluated in either cell, gets the same weight from every node (1e-8)
//    and the same gradient (1e-6 / h), where the linear functions' gradient
//    jumps by 1/h (checked, so the comparison can fail);
//  - every node a point reaches is among Grid::cell_nodes() of its cell
//    (the colouring of the threaded scatter relies on it), and across the
//    periodic seam the point's image (Shape::image_for_node) lies within
//    1.5 cells of the node.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_tools.h>

#include <sable/mpm/grid.h>
#include <sable/mpm/parameters.h>
#include <sable/mpm/run_scene.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "test_support.h"

using namespace dealii;
using sable_tests::check;
using sable_tests::check_relative;

namespace
{
  void
  test_one_direction()
  {
    using sable::mpm::gimp_weights_1d;
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> unit(0., 1.);
    double                                 error = 0, error_inside = 0;
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double xi    = unit(rng);
        const double l     = 0.005 + 0.495 * unit(rng);
        // a face of the grid at the cell's lower vertex, its upper one or
        // far away
        const double lower = i % 3 == 0 ? 0. : -10.;
        const double upper = i % 3 == 1 ? 1. : 10.;
        const auto   w     = gimp_weights_1d(xi, l, lower, upper);
        const double half = std::min({l, xi - lower, upper - xi});
        const double a = xi - half, b = xi + half;
        const int    first = xi < 0.5 ? -1 : 0;
        const unsigned int n = 20000;
        for (int k = 0; k < 3; ++k)
          {
            double sum = 0;
            for (unsigned int q = 0; q < n; ++q)
              {
                const double x = a + (q + 0.5) * (b - a) / n;
                sum += std::max(0., 1. - std::abs(x - (first + k)));
              }
            error = std::max(error, std::abs(w.value[k] - sum / n));
          }
        if (xi - l >= 0 && xi + l <= 1)
          for (int k = 0; k < 3; ++k)
            error_inside = std::max(error_inside,
                                    std::abs(w.value[k] -
                                             std::max(0., 1. - std::abs(xi - (first + k)))));
      }
    check_relative("1D: GIMP weights = mean of the hat over the domain", error, 0., 1e-7, 1.);
    // a point 1e-10 cells from a face of the grid: the domain has shrunk
    // to 1e-10, so the weights are the linear ones to ~1e-10
    double error_at_face = 0;
    for (const double xi : {1e-10, 1. - 1e-10})
      {
        const auto w     = gimp_weights_1d(xi, 0.4, xi < 0.5 ? 0. : -5., xi < 0.5 ? 5. : 1.);
        const int  first = xi < 0.5 ? -1 : 0;
        for (int k = 0; k < 3; ++k)
          error_at_face = std::max(
            error_at_face, std::abs(w.value[k] - std::max(0., 1. - std::abs(xi - (first + k)))));
      }
    check_relative("1D: at a face of the grid the weights are the linear ones",
                   error_at_face, 0., 1e-9, 1.);
    check_relative("1D: a domain inside one cell gives the linear weights at its centre",
                   error_inside, 0., 1e-12, 1.);
  }

  template <int dim>
  void
  test_grid(const bool periodic_y)
  {
    using namespace sable::mpm;
    const std::string   name = std::to_string(dim) + "D" + (periodic_y ? ", periodic y: " : ": ");
    GridParameters<dim> parameters;
    const unsigned int  n_cells = dim == 2 ? 6 : 4;
    for (unsigned int d = 0; d < dim; ++d)
      {
        parameters.lower_corner[d] = -0.3 * d;
        parameters.upper_corner[d] = parameters.lower_corner[d] + 1. + 0.5 * d;
      }
    parameters.subdivisions.assign(dim, n_cells);
    for (unsigned int f = 0; f < 2 * dim; ++f)
      parameters.face_ids.push_back(f);
    parameters.periodic[1] = periodic_y;
    parallel::distributed::Triangulation<dim> triangulation(MPI_COMM_WORLD);
    make_grid(parameters, triangulation);
    Grid<dim> grid(triangulation, ShapeFunctions::gimp);
    grid.setup();
    Tensor<1, dim> h;
    for (unsigned int d = 0; d < dim; ++d)
      h[d] = triangulation.begin_active()->extent_in_direction(d);
    const double h_max = *std::max_element(&h[0], &h[0] + dim);

    // the shape functions at a physical point, evaluated in a given cell
    // or the one holding it, as node -> (value, gradient)
    using Values = std::map<unsigned int, std::pair<double, Tensor<1, dim>>>;
    const auto evaluate = [&](const Point<dim> &x, const double spacing, int cell_hint = -1) {
      auto found = GridTools::find_active_cell_around_point(grid.get_mapping(), triangulation, x);
      if (cell_hint >= 0)
        for (const auto &cell : triangulation.active_cell_iterators())
          if (static_cast<int>(cell->active_cell_index()) == cell_hint)
            found = {cell, grid.get_mapping().transform_real_to_unit_cell(cell, x)};
      typename Grid<dim>::Shape shape;
      const auto &data = grid.cell_data(found.first);
      grid.evaluate(data, found.second, std::pow(spacing, dim), shape);
      Values values;
      const auto [candidates, n_candidates] = grid.cell_nodes(data);
      bool in_candidates = true, images_near = true;
      for (unsigned int k = 0; k < shape.n_nodes; ++k)
        {
          values[shape.nodes[k]] = {shape.values[k], shape.gradients[k]};
          in_candidates = in_candidates && std::find(candidates, candidates + n_candidates,
                                                     shape.nodes[k]) != candidates + n_candidates;
          const Point<dim> image = shape.image_for_node(x, k);
          for (unsigned int d = 0; d < dim; ++d)
            images_near = images_near &&
                          std::abs(image[d] - grid.node_positions()[shape.nodes[k]][d]) <=
                            1.5 * h[d] + 1e-12;
        }
      return std::make_tuple(values, in_candidates, images_near, found.first->active_cell_index());
    };

    std::mt19937                           rng(dim + 10 * periodic_y);
    std::uniform_real_distribution<double> unit(0., 1.);
    double pu_error = 0, gradient_sum = 0, fd_error = 0;
    bool   all_in_candidates = true, all_images_near = true, reached_across_seam = false;
    for (unsigned int i = 0; i < 300; ++i)
      {
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          {
            // a third of the points within half a cell of a face
            const double extent = parameters.upper_corner[d] - parameters.lower_corner[d];
            const double u      = unit(rng);
            x[d] = i % 3 != 0 ? parameters.lower_corner[d] + u * extent :
                   u < 0.5    ? parameters.lower_corner[d] + u * h[d] :
                                parameters.upper_corner[d] - (1 - u) * h[d];
          }
        const double spacing = h_max * (0.05 + 0.95 * unit(rng));
        const auto [values, in_candidates, images_near, cell] = evaluate(x, spacing);
        all_in_candidates = all_in_candidates && in_candidates;
        all_images_near   = all_images_near && images_near;
        double         sum = 0;
        Tensor<1, dim> gradient;
        for (const auto &[node, vg] : values)
          {
            sum += vg.first;
            gradient += vg.second;
            if (periodic_y && std::abs(grid.node_positions()[node][1] - x[1]) > 2 * h[1])
              reached_across_seam = true;
          }
        pu_error     = std::max(pu_error, std::abs(sum - 1.));
        gradient_sum = std::max(gradient_sum, gradient.norm() * h_max);
        // central differences, in the same cell
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double step = 1e-6 * h[d];
            Point<dim>   plus = x, minus = x;
            plus[d] += step;
            minus[d] -= step;
            const Values vp = std::get<0>(evaluate(plus, spacing, cell));
            const Values vm = std::get<0>(evaluate(minus, spacing, cell));
            for (const auto &[node, vg] : values)
              {
                const double fp = vp.count(node) ? vp.at(node).first : 0.;
                const double fm = vm.count(node) ? vm.at(node).first : 0.;
                fd_error = std::max(fd_error, std::abs((fp - fm) / (2 * step) - vg.second[d]) * h[d]);
              }
          }
      }
    check_relative(name + "partition of unity, max |sum N - 1|", pu_error, 0., 1e-13, 1.);
    check_relative(name + "max |sum grad N| h", gradient_sum, 0., 1e-13, 1.);
    check_relative(name + "gradients = central differences of the values, max error x h",
                   fd_error, 0., 1e-5, 1.);
    check(name + "every node a point reaches is one of its cell's Grid::cell_nodes()",
          all_in_candidates);
    check(name + "the point's image lies within 1.5 cells of every node it reaches",
          all_images_near);
    if (periodic_y)
      check(name + "points next to the seam reach nodes on its other side", reached_across_seam);

    // continuity across an interior face normal to x, evaluated in either
    // cell: the point 1e-9 h left and right of the face
    Point<dim> face;
    for (unsigned int d = 0; d < dim; ++d)
      face[d] = parameters.lower_corner[d] + (d == 0 ? 2. : 1.37) * h[d];
    const double spacing = 0.5 * h_max;
    double       jump_value = 0, jump_gradient = 0;
    Point<dim> left = face, right = face;
    left[0] -= 1e-9 * h[0];
    right[0] += 1e-9 * h[0];
    const auto [vl, il, nl, cl] = evaluate(left, spacing);
    const auto [vr, ir, nr, cr] = evaluate(right, spacing);
    check(name + "the two points lie in different cells", cl != cr);
    std::map<unsigned int, bool> nodes;
    for (const auto &[node, vg] : vl)
      nodes[node] = true;
    for (const auto &[node, vg] : vr)
      nodes[node] = true;
    for (const auto &[node, unused] : nodes)
      {
        (void)unused;
        const auto l = vl.count(node) ? vl.at(node) : std::pair<double, Tensor<1, dim>>();
        const auto r = vr.count(node) ? vr.at(node) : std::pair<double, Tensor<1, dim>>();
        jump_value    = std::max(jump_value, std::abs(l.first - r.first));
        jump_gradient = std::max(jump_gradient, (l.second - r.second).norm() * h[0]);
      }
    check_relative(name + "weights continuous across a cell face", jump_value, 0., 1e-8, 1.);
    check_relative(name + "gradients continuous across a cell face (x h)", jump_gradient, 0., 1e-6, 1.);

    // the linear functions' gradient jumps there (the test can fail)
    Grid<dim> linear(triangulation, ShapeFunctions::linear);
    linear.setup();
    double linear_jump = 0;
    std::map<unsigned int, Tensor<1, dim>> gl, gr;
    for (const auto &[point, target] : {std::make_pair(left, &gl), std::make_pair(right, &gr)})
      {
        const auto found =
          GridTools::find_active_cell_around_point(linear.get_mapping(), triangulation, point);
        typename Grid<dim>::Shape shape;
        linear.evaluate(linear.cell_data(found.first), found.second, 0., shape);
        for (unsigned int k = 0; k < shape.n_nodes; ++k)
          (*target)[shape.nodes[k]] = shape.gradients[k];
      }
    for (const auto &[node, g] : gl)
      linear_jump = std::max(linear_jump,
                             ((gr.count(node) ? gr.at(node) : Tensor<1, dim>()) - g).norm() * h[0]);
    check(name + "the linear functions' gradient jumps by " + std::to_string(linear_jump) +
            " / h there (> 0.1)",
          linear_jump > 0.1);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_one_direction();
  test_grid<2>(false);
  test_grid<2>(true);
  test_grid<3>(false);
  test_grid<3>(true);
  return sable_tests::exit_code();
}
