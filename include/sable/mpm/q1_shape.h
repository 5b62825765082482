#ifndef sable_mpm_q1_shape_h
#define sable_mpm_q1_shape_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Values and gradients of the 2^dim tensor-product linear (FE_Q<dim>(1))
   * shape functions of an axis-aligned cell at a point given in reference
   * coordinates. Vertex v has coordinate 1 in direction d if bit d of v is
   * set, the numbering of deal.II's vertices and of FE_Q(1)'s dofs.
   * Evaluating this directly is what makes particle transfers cheap: no
   * FEValues object is built per particle (tests/mpm/q1_shape.cc compares
   * with FE_Q<dim>(1)).
   */
  template <int dim>
  struct Q1Shape
  {
    static constexpr unsigned int n_nodes = 1u << dim;

    std::array<double, n_nodes>         values;
    std::array<Tensor<1, dim>, n_nodes> gradients;

    /// @p inverse_h holds 1/h_d, the inverse cell extents.
    inline void
    evaluate(const Point<dim> &xi, const Tensor<1, dim> &inverse_h)
    {
      // one-dimensional factors and their derivatives for each direction
      double phi[dim][2], dphi[dim][2];
      for (unsigned int d = 0; d < dim; ++d)
        {
          phi[d][0]  = 1. - xi[d];
          phi[d][1]  = xi[d];
          dphi[d][0] = -inverse_h[d];
          dphi[d][1] = inverse_h[d];
        }
      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          const unsigned int b0 = v & 1u, b1 = (v >> 1) & 1u;
          if constexpr (dim == 2)
            {
              values[v]       = phi[0][b0] * phi[1][b1];
              gradients[v][0] = dphi[0][b0] * phi[1][b1];
              gradients[v][1] = phi[0][b0] * dphi[1][b1];
            }
          else
            {
              const unsigned int b2 = (v >> 2) & 1u;
              values[v] = phi[0][b0] * phi[1][b1] * phi[2][b2];
              gradients[v][0] = dphi[0][b0] * phi[1][b1] * phi[2][b2];
              gradients[v][1] = phi[0][b0] * dphi[1][b1] * phi[2][b2];
              gradients[v][2] = phi[0][b0] * phi[1][b1] * dphi[2][b2];
            }
        }
    }
  };
} // namespace sable::mpm

#endif
