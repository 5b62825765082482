// Q1Shape<dim> (the hand-written tensor-product linear shape functions the
// particle transfers use) against deal.II's FE_Q<dim>(1):
//  - values at ~100 random reference points equal FE_Q<dim>(1).shape_value;
//  - gradients on an anisotropic axis-aligned cell [x0, x0 + h] equal the
//    physical gradients FEValues (MappingCartesian) computes there, i.e.
//    the reference gradient divided by h_d;
//  - partition of unity sum_v N_v = 1 and sum_v grad N_v = 0.
// Tolerance 1e-14: both sides are a handful of products of numbers in
// [0, 1] and 1/h_d, so they agree to a few ulp; a wrong vertex ordering or
// factor gives O(1) errors.

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <sable/mpm/q1_shape.h>

#include <random>
#include <string>
#include <vector>

#include "test_support.h"

using namespace dealii;
using sable_tests::check_relative;

template <int dim>
void
test(std::mt19937 &rng)
{
  const std::string name = std::to_string(dim) + "D: ";
  std::uniform_real_distribution<double> unit(0., 1.);

  const unsigned int      n_points = 100;
  std::vector<Point<dim>> points(n_points);
  for (auto &p : points)
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = unit(rng);
  // the vertices themselves, where N_v(x_w) = delta_vw must hold
  for (unsigned int v = 0; v < (1u << dim); ++v)
    {
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = (v >> d) & 1u;
      points.push_back(p);
    }

  // an anisotropic cell away from the origin
  const double h_values[3] = {0.37, 2.9, 0.0625};
  Point<dim>   x0, x1;
  Tensor<1, dim> h, inverse_h;
  for (unsigned int d = 0; d < dim; ++d)
    {
      h[d]         = h_values[d];
      x0[d]        = -1.3 + 0.7 * d;
      x1[d]        = x0[d] + h[d];
      inverse_h[d] = 1. / h[d];
    }
  Triangulation<dim> triangulation;
  GridGenerator::hyper_rectangle(triangulation, x0, x1);

  const FE_Q<dim>       fe(1);
  MappingCartesian<dim> mapping;
  const Quadrature<dim> quadrature(points);
  FEValues<dim>         fe_values(mapping, fe, quadrature,
                          update_values | update_gradients |
                            update_quadrature_points);
  fe_values.reinit(triangulation.begin_active());

  double gradient_scale = 0;
  for (unsigned int d = 0; d < dim; ++d)
    gradient_scale = std::max(gradient_scale, inverse_h[d]);

  double max_value_error = 0, max_fe_values_value_error = 0,
         max_gradient_error = 0, max_reference_gradient_error = 0,
         max_unity_error = 0, max_gradient_sum = 0, max_location_error = 0;
  sable::mpm::Q1Shape<dim> shape;
  for (unsigned int q = 0; q < points.size(); ++q)
    {
      const Point<dim> &xi = points[q];
      shape.evaluate(xi, inverse_h);
      // the mapped point is x0 + h * xi (checks the FEValues set-up)
      for (unsigned int d = 0; d < dim; ++d)
        max_location_error =
          std::max(max_location_error,
                   std::abs(fe_values.quadrature_point(q)[d] -
                            (x0[d] + h[d] * xi[d])));
      double         sum = 0;
      Tensor<1, dim> gradient_sum;
      for (unsigned int v = 0; v < fe.n_dofs_per_cell(); ++v)
        {
          max_value_error = std::max(max_value_error,
                                     std::abs(shape.values[v] -
                                              fe.shape_value(v, xi)));
          max_fe_values_value_error =
            std::max(max_fe_values_value_error,
                     std::abs(shape.values[v] - fe_values.shape_value(v, q)));
          const Tensor<1, dim> reference_gradient = fe.shape_grad(v, xi);
          for (unsigned int d = 0; d < dim; ++d)
            {
              max_reference_gradient_error =
                std::max(max_reference_gradient_error,
                         std::abs(shape.gradients[v][d] -
                                  reference_gradient[d] / h[d]));
              max_gradient_error =
                std::max(max_gradient_error,
                         std::abs(shape.gradients[v][d] -
                                  fe_values.shape_grad(v, q)[d]));
            }
          sum += shape.values[v];
          gradient_sum += shape.gradients[v];
        }
      max_unity_error  = std::max(max_unity_error, std::abs(sum - 1.));
      max_gradient_sum = std::max(max_gradient_sum, gradient_sum.norm());
    }

  check_relative(name + "FEValues maps the reference points to x0 + h xi "
                   "(max error / cell diameter)",
                 max_location_error, 0., 1e-14, h.norm());
  check_relative(name + "max |N_v - FE_Q(1).shape_value| at " +
                   std::to_string(points.size()) + " points",
                 max_value_error, 0., 1e-14, 1.);
  check_relative(name + "max |N_v - FEValues.shape_value| on the cell",
                 max_fe_values_value_error, 0., 1e-14, 1.);
  check_relative(name + "max |grad N_v - FE_Q(1).shape_grad / h_d|",
                 max_reference_gradient_error, 0., 1e-14, gradient_scale);
  check_relative(name + "max |grad N_v - FEValues.shape_grad| on the "
                   "anisotropic cell",
                 max_gradient_error, 0., 1e-14, gradient_scale);
  check_relative(name + "partition of unity: max |sum_v N_v - 1|",
                 max_unity_error, 0., 1e-14, 1.);
  check_relative(name + "max |sum_v grad N_v|", max_gradient_sum, 0., 1e-14,
                 gradient_scale);
}

int
main()
{
  std::mt19937 rng(20240611);
  test<2>(rng);
  test<3>(rng);
  return sable_tests::exit_code();
}
