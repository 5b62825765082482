#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <sable/mpm/contact/bardenhagen_contact.h>
#include <sable/mpm/contact/coulomb.h>

#include <cmath>
#include <map>
#include <tuple>

/*
 * A disk touching a flat face touches it at a point (used in 2D), which lies
 * between nodes. Corrected node by node, its weight goes to the node
 * nearest that point (the nodes beside it see the surface curve away),
 * up to half a cell off the point: a pivot under the centre, off which a
 * disk at rest rolls like an inverted pendulum, and a moment that spins a
 * sliding disk up (doc/mpm.md, "Detection"). Here the nodes within a cell
 * of the point share one impulse instead, in proportion to their masses
 * but tilted so that its line passes through the point; friction acts on
 * the velocity at the point itself.
 */
namespace sable::mpm
{
  namespace
  {
    using PairSums = std::map<std::pair<unsigned int, unsigned int>, std::vector<double>>;

    /// Add each pair's sums over all ranks, in rank order (the same on
    /// every rank); a pair that a rank lacks counts as zeros.
    void
    sum_over_ranks(PairSums &sums, const unsigned int n_values, const MPI_Comm communicator)
    {
      if (Utilities::MPI::n_mpi_processes(communicator) == 1)
        return;
      std::vector<double> local;
      for (const auto &[pair, values] : sums)
        {
          local.insert(local.end(), {double(pair.first), double(pair.second)});
          local.insert(local.end(), values.begin(), values.end());
        }
      sums.clear();
      for (const std::vector<double> &part : Utilities::MPI::all_gather(communicator, local))
        for (std::size_t i = 0; i + 2 + n_values <= part.size(); i += 2 + n_values)
          {
            auto &values = sums[{static_cast<unsigned int>(part[i]),
                                 static_cast<unsigned int>(part[i + 1])}];
            values.resize(n_values, 0.);
            for (unsigned int k = 0; k < n_values; ++k)
              values[k] += part[i + 2 + k];
          }
    }

    /// dim - 1 unit vectors spanning the plane normal to @p n.
    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangents_of(const Tensor<1, dim> &n)
    {
      std::array<Tensor<1, dim>, dim - 1> t;
      if constexpr (dim == 2)
        t[0] = Tensor<1, dim>({n[1], -n[0]});
      else
        {
          Tensor<1, dim> seed;
          seed[std::abs(n[0]) < 0.9 ? 0 : 1] = 1;
          t[0] = seed - (seed * n) * n;
          t[0] /= t[0].norm();
          t[1] = cross_product_3d(n, t[0]);
        }
      return t;
    }
  } // namespace

  template <int dim>
  bool
  BardenhagenContact<dim>::round_against_face(const typename BodyFields<dim>::Record &a,
                                              const typename BodyFields<dim>::Record &b) const
  {
    return std::isfinite(body_surface_radii[a.body]) != std::isfinite(body_surface_radii[b.body]);
  }

  template <int dim>
  void
  BardenhagenContact<dim>::find_contact_points(const BodyFields<dim> &             fields,
                                               const std::vector<Tensor<1, dim>> &spacing,
                                               const std::vector<Point<dim>> &    positions,
                                               const unsigned int                 n_owned_nodes,
                                               const MPI_Comm                     communicator)
  {
    using Record = typename BodyFields<dim>::Record;
    // unmark the last step's nodes (all of them after a mesh change)
    if (contact_point_nodes.size() != positions.size())
      contact_point_nodes.assign(positions.size(), 0);
    else
      for (const ContactPoint &point : contact_points)
        for (const auto &node : point.nodes)
          contact_point_nodes[node.node] = 0;
    contact_points.clear();

    // the two-body nodes of each (round, flat) pair, and its records
    const auto for_each_pair_node = [&](const auto &visit) {
      for (const unsigned int node : fields.get_contact_nodes())
        {
          const auto [begin, end] = fields.node_records(node);
          if (end - begin != 2 || !round_against_face(begin[0], begin[1]) ||
              begin[0].mass <= 0 || begin[1].mass <= 0)
            continue;
          const bool first_round = std::isfinite(body_surface_radii[begin[0].body]);
          visit(node, first_round ? begin[0] : begin[1], first_round ? begin[1] : begin[0]);
        }
    };

    // 1. each pair's round body's centre, from every record that knows its
    // surface (its points' mean end less the radius along their mean
    // vector to it), and the face under the flat records; the owned nodes'
    // sums, then all ranks'
    constexpr unsigned int n_first = 3 * dim + 3;
    PairSums               first;
    for_each_pair_node([&](const unsigned int node, const Record &round, const Record &flat) {
      // (a driven body's records carry its masses scaled, its surface not)
      const double flat_mass = unscaled_mass(flat);
      if (node >= n_owned_nodes || !on_one_face(flat) || flat.mass_on_surface < 0.9 * flat_mass ||
          round.mass_on_surface < 0.9 * round.mass)
        return;
      const Tensor<1, dim> end    = round.mass_surface_point / round.mass_on_surface;
      const Tensor<1, dim> inward = end - round.mass_position / round.mass;
      if (inward.norm() == 0)
        return;
      const Tensor<1, dim> centre = end - body_surface_radii[round.body] * inward / inward.norm();
      const Tensor<1, dim> face   = flat.mass_surface_point / flat.mass_on_surface;
      std::vector<double> &sum    = first[{round.body, flat.body}];
      sum.resize(n_first, 0.);
      for (unsigned int d = 0; d < dim; ++d)
        {
          sum[d] += round.mass * centre[d];
          sum[dim + d] += flat.mass * face[d];
          sum[2 * dim + d] += flat.mass_surface_normal[d];
        }
      sum[3 * dim] += round.mass;
      sum[3 * dim + 1] += flat.mass_surface;
      sum[3 * dim + 2] += flat.mass;
    });
    sum_over_ranks(first, n_first, communicator);

    for (const auto &[pair, sum] : first)
      {
        // one face: the flat records' normals agree
        Tensor<1, dim> centre, face, normal;
        for (unsigned int d = 0; d < dim; ++d)
          {
            centre[d] = sum[d] / sum[3 * dim];
            face[d]   = sum[dim + d] / sum[3 * dim + 2];
            normal[d] = sum[2 * dim + d];
          }
        if (normal.norm() < (1 - 1e-4) * sum[3 * dim + 1])
          continue;
        normal /= normal.norm();
        ContactPoint point;
        point.round  = pair.first;
        point.flat   = pair.second;
        point.normal = normal;
        point.point  = centre - body_surface_radii[pair.first] * normal;
        point.gap    = (point.point - face) * normal;
        point.compressed = false;
        point.cell       = 0;
        contact_points.push_back(point);
      }

    // 2. the pair's nodes within a cell of the point, with their linear
    // weights there; a patch wider than that (the surfaces meet at a node
    // beyond) leaves the pair to the nodes. Per point: the weights' sum,
    // the normal traction, whether the patch is wide, and per body the
    // moments sum m, sum m d, sum m d d^T of its records' masses over their
    // offsets d across the normal (for the shares)
    constexpr unsigned int n_moments = dim * dim;
    constexpr unsigned int n_second  = 3 + 2 * n_moments;
    std::map<std::pair<unsigned int, unsigned int>, unsigned int> index;
    for (unsigned int i = 0; i < contact_points.size(); ++i)
      index[{contact_points[i].round, contact_points[i].flat}] = i;
    PairSums second;
    for (const ContactPoint &point : contact_points)
      second[{point.round, point.flat}].assign(n_second, 0.);
    for_each_pair_node([&](const unsigned int node, const Record &round, const Record &flat) {
      const auto found = index.find({round.body, flat.body});
      if (found == index.end())
        return;
      ContactPoint &       point  = contact_points[found->second];
      std::vector<double> &sum    = second[{round.body, flat.body}];
      const bool           owned  = node < n_owned_nodes;
      const Tensor<1, dim> offset = positions[node] - Point<dim>(point.point);
      double               weight = 1;
      for (unsigned int d = 0; d < dim; ++d)
        weight *= std::max(1 - std::abs(offset[d]) / spacing[node][d], 0.);
      if (weight <= 0)
        {
          // beyond the cell: do the surfaces meet here?
          if (owned)
            {
              const SurfaceGap gap = surface_gap(flat, round, point.normal, spacing[node]);
              if (gap.separation <= gap.touching)
                sum[2] = 1;
            }
          return;
        }
      if (point.nodes.empty())
        {
          double cell = 0;
          for (unsigned int d = 0; d < dim; ++d)
            cell += std::pow(point.normal[d] * spacing[node][d], 2);
          point.cell = std::sqrt(cell);
        }
      point.nodes.push_back({node, weight, 0., 0., owned});
      if (!owned)
        return;
      sum[0] += weight;
      for (const Record *r : {&round, &flat})
        sum[1] += point.normal * (r->mass_stress * point.normal);
      const auto tangents = tangents_of(point.normal);
      for (unsigned int body = 0; body < 2; ++body)
        {
          const double           mass = body == 0 ? round.mass : flat.mass;
          std::array<double, dim> row;
          row[0] = 1;
          for (unsigned int t = 0; t + 1 < dim; ++t)
            row[t + 1] = offset * tangents[t] / point.cell;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              sum[3 + body * n_moments + i * dim + j] += mass * row[i] * row[j];
        }
    });
    sum_over_ranks(second, n_second, communicator);

    std::vector<ContactPoint> kept;
    for (ContactPoint &point : contact_points)
      {
        const std::vector<double> &sum = second[{point.round, point.flat}];
        if (sum[0] <= 0 || sum[2] > 0 || point.nodes.empty())
          continue;
        point.compressed = use_traction && sum[1] < 0;
        // each body's shares m_k (alpha + beta . d_k): sum 1, and
        // sum m_k d_k (...) = 0, so that the impulse's line passes through
        // the point (a record with little mass takes little)
        const auto       tangents = tangents_of(point.normal);
        bool             solvable = true;
        std::array<Vector<double>, 2> coefficients;
        for (unsigned int body = 0; body < 2; ++body)
          {
            FullMatrix<double> moments(dim, dim);
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                moments(i, j) = sum[3 + body * n_moments + i * dim + j];
            // the offsets span no direction across the normal (the nodes
            // in one line): no tilt moves the impulse's line onto the point
            if (!(std::abs(moments.determinant()) > 1e-8 * std::pow(moments(0, 0), dim)))
              {
                solvable = false;
                break;
              }
            FullMatrix<double> inverse(dim, dim);
            inverse.invert(moments);
            Vector<double> unit(dim);
            unit(0) = 1;
            coefficients[body].reinit(dim);
            inverse.vmult(coefficients[body], unit);
          }
        if (!solvable)
          continue;
        for (typename ContactPoint::Node &node : point.nodes)
          {
            node.weight /= sum[0];
            const Tensor<1, dim> offset = positions[node.node] - Point<dim>(point.point);
            for (unsigned int body = 0; body < 2; ++body)
              {
                double share = coefficients[body](0);
                for (unsigned int t = 0; t + 1 < dim; ++t)
                  share += coefficients[body](t + 1) * (offset * tangents[t]) / point.cell;
                const Record &r = fields.record(node.node, body == 0 ? point.round : point.flat);
                (body == 0 ? node.round_share : node.flat_share) = r.mass * share;
              }
            contact_point_nodes[node.node] = 1;
          }
        kept.push_back(std::move(point));
      }
    contact_points = std::move(kept);
  }

  template <int dim>
  void
  BardenhagenContact<dim>::act_at_contact_points(BodyFields<dim> & fields,
                                                 const double      dt,
                                                 const bool        record_forces,
                                                 const MPI_Comm    communicator)
  {
    using Record = typename BodyFields<dim>::Record;
    // per point, over the owned nodes: the relative velocity weighted by
    // the normal shares, and by the linear weights (the velocity at the
    // point), with the compliances each weighting gives and their cross term
    constexpr unsigned int n_sums = 2 * dim + 3;
    PairSums               sums;
    for (const ContactPoint &point : contact_points)
      {
        std::vector<double> &sum = sums[{point.round, point.flat}];
        sum.assign(n_sums, 0.);
        for (const auto &node : point.nodes)
          if (node.owned)
            {
              const Record &r = fields.record(node.node, point.round);
              const Record &f = fields.record(node.node, point.flat);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  sum[d] += node.round_share * r.new_velocity[d] - node.flat_share * f.new_velocity[d];
                  sum[dim + d] += node.weight * (r.new_velocity[d] - f.new_velocity[d]);
                }
              sum[2 * dim] += node.round_share * node.round_share / r.mass +
                              node.flat_share * node.flat_share / f.mass;
              sum[2 * dim + 1] += node.weight * node.weight * (1 / r.mass + 1 / f.mass);
              sum[2 * dim + 2] += node.weight * (node.round_share / r.mass + node.flat_share / f.mass);
            }
      }
    sum_over_ranks(sums, n_sums, communicator);

    for (ContactPoint &point : contact_points)
      {
        const std::vector<double> &sum = sums[{point.round, point.flat}];
        Tensor<1, dim>             shared, at_point;
        for (unsigned int d = 0; d < dim; ++d)
          {
            shared[d]   = sum[d];
            at_point[d] = sum[dim + d];
          }
        const Tensor<1, dim> &n        = point.normal;
        const double          approach = -(shared * n);
        // the surfaces meet within the step, and approach (or, with the
        // 2001 rule, press on each other)
        if (point.gap - dt * std::max(approach, 0.) > touching_tolerance * point.cell ||
            (approach <= 0 && !point.compressed) || sum[2 * dim] <= 0)
          continue;
        const double normal_impulse = approach / sum[2 * dim];
        // the slip at the point once the normal impulse has acted;
        // friction up to mu times the pressing part of it
        const Tensor<1, dim> slip_velocity = at_point + normal_impulse * sum[2 * dim + 2] * n;
        const Tensor<1, dim> slip          = slip_velocity - (slip_velocity * n) * n;
        const double         slip_speed    = slip.norm();
        const double         mu            = friction_between_bodies(point.round, point.flat);
        double               friction      = 0;
        Tensor<1, dim>       friction_direction;
        if (slip_speed > 0 && sum[2 * dim + 1] > 0)
          {
            const double stick = slip_speed / sum[2 * dim + 1];
            friction_direction = -slip / slip_speed;
            // the momentum update: mu times the pressing part of its
            // normal impulse. MUSL's remap pass (no forces recorded) corrects
            // the same step again: the step's two friction impulses together
            // stay within mu times its two normal impulses (its own is
            // small, the approach having been stopped already)
            friction =
              record_forces ?
                std::min(stick, mu * std::max(normal_impulse, 0.)) :
                stick * fraction_within_cap(point.first_friction,
                                            stick * friction_direction,
                                            mu * std::max(point.first_normal_impulse +
                                                            normal_impulse,
                                                          0.));
          }
        if (record_forces)
          {
            point.first_normal_impulse = normal_impulse;
            point.first_friction       = friction * friction_direction;
          }
        double owned_weight = 0;
        for (const auto &node : point.nodes)
          {
            Record &             r = fields.record(node.node, point.round);
            Record &             f = fields.record(node.node, point.flat);
            const Tensor<1, dim> on_round =
              normal_impulse * node.round_share * n + friction * node.weight * friction_direction;
            const Tensor<1, dim> on_flat =
              normal_impulse * node.flat_share * n + friction * node.weight * friction_direction;
            r.new_velocity += on_round / r.mass;
            f.new_velocity -= on_flat / f.mass;
            if (!record_forces)
              continue;
            r.normal         = -n;
            f.normal         = n;
            r.contact_force  = on_round / dt;
            f.contact_force  = -on_flat / dt;
            r.friction_force = friction * node.weight * friction_direction / dt;
            f.friction_force = -r.friction_force;
            r.state = f.state = friction > 0 && friction * sum[2 * dim + 1] < slip_speed ? 2 : 1;
            if (node.owned)
              {
                owned_weight += node.weight;
                momentum_correction += on_round.norm() + on_flat.norm();
              }
          }
        if (!record_forces)
          continue;
        // this rank's part of the point's force, moment and heat
        // (frictional work: the friction impulse times the slip left)
        if (heat_at_nodes)
          frictional_heat +=
            owned_weight * friction * (slip_speed - friction * sum[2 * dim + 1]);
        const Tensor<1, dim> force =
          owned_weight * (normal_impulse * n + friction * friction_direction) / dt;
        for (const auto &[a, b, sign] : {std::tuple<unsigned int, unsigned int, double>(point.round, point.flat, 1.),
                                         std::tuple<unsigned int, unsigned int, double>(point.flat, point.round, -1.)})
          {
            const unsigned int p = pair_index(a, b);
            if (p == BodyFields<dim>::invalid)
              continue;
            pair_forces[p] += sign * force;
            Tensor<1, 3> x3, f3;
            for (unsigned int d = 0; d < dim; ++d)
              {
                x3[d] = point.point[d];
                f3[d] = sign * force[d];
              }
            pair_moments[p] += cross_product_3d(x3, f3);
          }
      }
  }

#define SABLE_INSTANTIATE(dim)                                                              \
  template bool BardenhagenContact<dim>::round_against_face(                                \
    const typename BodyFields<dim>::Record &, const typename BodyFields<dim>::Record &) const; \
  template void BardenhagenContact<dim>::find_contact_points(const BodyFields<dim> &,       \
                                                             const std::vector<Tensor<1, dim>> &, \
                                                             const std::vector<Point<dim>> &,     \
                                                             const unsigned int,                  \
                                                             const MPI_Comm);                     \
  template void BardenhagenContact<dim>::act_at_contact_points(BodyFields<dim> &,           \
                                                               const double,                \
                                                               const bool,                  \
                                                               const MPI_Comm);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
