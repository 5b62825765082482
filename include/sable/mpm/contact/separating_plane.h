#ifndef sable_mpm_contact_separating_plane_h
#define sable_mpm_contact_separating_plane_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// One material point as a contact node sees it: its location (the
  /// image nearest the node on a periodic grid) and its weight m_p N_i(x_p).
  template <int dim>
  struct NodeSample
  {
    Point<dim> location;
    double     weight;
  };

  /**
   * The plane that best separates two point clouds near a contact node, by
   * weighted logistic regression (Nairn, Hammerquist & Smith 2020): the
   * probability that a point at x belongs to @p inside is modelled as
   * 1/(1 + exp(-(beta . xi + c))), xi = (x - @p origin)/@p cell_size per
   * direction, and beta, c maximise the weighted likelihood of the two
   * clouds, each cloud's weights scaled to the same total (so the heavier
   * body does not pull the plane), with a small ridge penalty on beta that
   * keeps it finite when the clouds do not overlap. Newton's method with
   * a backtracking line search from beta = 0.
   *
   * Returns the plane's unit normal pointing out of @p inside; zero if
   * either cloud has no weight.
   */
  template <int dim>
  Tensor<1, dim>
  separating_normal(const std::vector<NodeSample<dim>> &inside,
                    const std::vector<NodeSample<dim>> &outside,
                    const Point<dim> &                  origin,
                    const Tensor<1, dim> &              cell_size);
} // namespace sable::mpm

#endif
