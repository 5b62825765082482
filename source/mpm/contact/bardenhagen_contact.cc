#include <deal.II/base/parallel.h>

#include <sable/mpm/contact/bardenhagen_contact.h>
#include <sable/mpm/surface_offset.h>
#include <sable/mpm/contact/coulomb.h>

#include <algorithm>

#include <cmath>
#include <limits>
#include <tuple>

namespace sable::mpm
{
  template <int dim>
  BardenhagenContact<dim>::BardenhagenContact(
    const ContactParameters &        parameters,
    const std::vector<unsigned int> &body_groups)
    : parameters(parameters)
    , body_groups(body_groups)
    , use_traction(parameters.model == ContactParameters::Model::bardenhagen_2001)
    , cap_friction(use_traction && parameters.any_finite_friction())
  {
    const unsigned int n = body_groups.size();
    pair_forces.assign(parameters.reported_pairs.size(), Tensor<1, dim>());
    pair_moments.assign(parameters.reported_pairs.size(), Tensor<1, 3>());
    // a dense table is fine for the few bodies whose pairs are reported;
    // with many bodies and no reported pairs it stays empty
    if (!parameters.reported_pairs.empty())
      {
        reported_pair_index.assign(n * n, BodyFields<dim>::invalid);
        for (unsigned int i = 0; i < parameters.reported_pairs.size(); ++i)
          {
            const auto [a, b] = parameters.reported_pairs[i];
            reported_pair_index[a * n + b] = i;
          }
      }
  }

  template <int dim>
  unsigned int
  BardenhagenContact<dim>::pair_index(const unsigned int a,
                                      const unsigned int b) const
  {
    if (reported_pair_index.empty())
      return BodyFields<dim>::invalid;
    return reported_pair_index[a * body_groups.size() + b];
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply(BodyFields<dim> &                  fields,
                                 const std::vector<Tensor<1, dim>> &spacing,
                                 const double                       dt,
                                 const unsigned int                 n_owned_nodes,
                                 const bool                         record_forces,
                                 const MPI_Comm                     communicator,
                                 const std::vector<Point<dim>> *    node_positions,
                                 const std::vector<Tensor<1, dim>> *fitted_normals,
                                 const Geometry                     geometry,
                                 const std::vector<double> *        support_volumes)
  {
    pass_fields   = &fields;
    pass_fitted   = fitted_normals;
    pass_geometry = geometry;
    // Each node changes only its own records, so the chunks of nodes run in
    // parallel; what each node adds to the sums is kept and added node by
    // node at the end, the same way for any number of threads.
    // Only the 2001 release pulls: then the friction of a pair is capped by
    // its net normal impulse, which the first pass measures while it
    // corrects uncapped; the nodes where a capped pair's friction acted are
    // then corrected again from the velocities they had, which gives what a
    // measuring pass followed by a correcting pass would.
    friction_scale.clear();
    const unsigned int n_chunks =
      (fields.get_contact_nodes().size() + chunk_size - 1) / chunk_size;
    chunk_results.resize(n_chunks);
    const auto for_each_chunk = [&](const auto &work) {
      parallel::apply_to_subranges(
        0u,
        n_chunks,
        [&](const unsigned int first_chunk, const unsigned int last_chunk) {
          Scratch scratch;
          for (unsigned int chunk = first_chunk; chunk < last_chunk; ++chunk)
            work(chunk, scratch);
        },
        1);
    };
    // round bodies touching faces at points: found in the momentum update,
    // kept for MUSL's remap pass, which scatters the same masses. Only in 2D:
    // a sphere meeting a plate at a point rolled no better (A3 at R/4 -8.2%
    // against -4.3% located, the same at R/8), so spheres keep the located
    // surfaces
    const bool with_points =
      dim == 2 && round_and_flat_bodies &&
      parameters.round_surfaces == ContactParameters::RoundSurfaces::contact_point &&
      parameters.detection == ContactParameters::Detection::surface_position &&
      node_positions != nullptr;
    if (with_points && record_forces)
      find_contact_points(fields, spacing, *node_positions, n_owned_nodes, communicator);
    else if (!with_points)
      {
        contact_points.clear();
        contact_point_nodes.clear();
      }
    const Pass pass{fields, spacing, support_volumes, dt, n_owned_nodes, record_forces};
    for_each_chunk([&](const unsigned int chunk, Scratch &scratch) {
      apply_to_chunk(pass, cap_friction, chunk, scratch);
    });
    if (cap_friction)
      {
        compute_friction_scales(communicator, record_forces);
        if (!friction_scale.empty())
          for_each_chunk([&](const unsigned int chunk, Scratch &scratch) {
            redo_capped_nodes(pass, chunk, scratch);
          });
      }

    if (record_forces)
      {
        for (auto &f : pair_forces)
          f = 0;
        for (auto &m : pair_moments)
          m = 0;
      }
    const unsigned int n_reported = pair_forces.size();
    for (unsigned int chunk = 0; chunk < n_chunks; ++chunk)
      {
        const ChunkResults &results = chunk_results[chunk];
        for (unsigned int i = 0; i < results.node_totals.size(); ++i)
          {
            frictional_heat += results.node_totals[i].frictional_heat;
            momentum_defect += results.node_totals[i].momentum_defect;
            momentum_correction += results.node_totals[i].momentum_correction;
            if (!record_forces)
              continue;
            for (unsigned int p = 0; p < n_reported; ++p)
              {
                const Tensor<1, dim> &force = results.node_pair_forces[i * n_reported + p];
                pair_forces[p] += force;
                if (node_positions != nullptr)
                  {
                    const Point<dim> &x =
                      (*node_positions)[fields.get_contact_nodes()[chunk * chunk_size + i]];
                    Tensor<1, 3> x3, f3;
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        x3[d] = x[d];
                        f3[d] = force[d];
                      }
                    pair_moments[p] += cross_product_3d(x3, f3);
                  }
              }
          }
      }
    if (with_points)
      act_at_contact_points(fields, dt, record_forces, communicator);
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply_to_initial(BodyFields<dim> &                  fields,
                                            const std::vector<Tensor<1, dim>> &spacing,
                                            const double                       dt,
                                            const unsigned int                 n_owned_nodes,
                                            const MPI_Comm                     communicator,
                                            const std::vector<Point<dim>> *    node_positions,
                                            const std::vector<Tensor<1, dim>> *fitted_normals,
                                            const std::vector<double> *        support_volumes)
  {
    const PairTable<double>           pulled              = pulling_impulse;
    const double                      heat                = frictional_heat;
    const double                      defect              = momentum_defect;
    const double                      correction          = momentum_correction;
    const std::vector<Tensor<1, dim>> forces              = pair_forces;
    const std::vector<Tensor<1, 3>>   moments             = pair_moments;
    apply(fields,
          spacing,
          dt,
          n_owned_nodes,
          true,
          communicator,
          node_positions,
          fitted_normals,
          Geometry::compute,
          support_volumes);
    pulling_impulse     = pulled;
    frictional_heat     = heat;
    momentum_defect     = defect;
    momentum_correction = correction;
    pair_forces         = forces;
    pair_moments        = moments;
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply_to_chunk(const Pass &       pass,
                                          const bool         measure,
                                          const unsigned int chunk,
                                          Scratch &          scratch)
  {
    const std::vector<unsigned int> &nodes   = pass.fields.get_contact_nodes();
    const unsigned int               first   = chunk * chunk_size;
    const unsigned int               n_nodes =
      std::min<unsigned int>(first + chunk_size, nodes.size()) - first;
    ChunkResults &results = chunk_results[chunk];
    if (pass_geometry == Geometry::keep)
      {
        results.geometry_offsets.resize(n_nodes);
        unsigned int n_pairs = 0;
        for (unsigned int i = 0; i < n_nodes; ++i)
          {
            results.geometry_offsets[i] = n_pairs;
            const auto [begin, end]     = pass.fields.node_records(nodes[first + i]);
            n_pairs += n_kept_pairs(end - begin);
          }
        results.geometry.assign(n_pairs, PairGeometry());
      }
    Assert(pass_geometry != Geometry::reuse || results.geometry_offsets.size() == n_nodes,
           ExcMessage("Geometry::reuse needs the contact nodes of the last apply() with keep."));
    results.node_totals.resize(n_nodes);
    results.node_pair_forces.resize(n_nodes * pair_forces.size());
    results.pair_impulses.clear();
    if (measure)
      {
        results.saved_velocities.clear();
        results.saved_offsets.resize(n_nodes);
        for (unsigned int i = 0; i < n_nodes; ++i)
          {
            results.saved_offsets[i] = results.saved_velocities.size();
            const auto [begin, end]  = pass.fields.node_records(nodes[first + i]);
            for (auto r = begin; r != end; ++r)
              results.saved_velocities.push_back(r->new_velocity);
          }
      }
    for (unsigned int i = 0; i < n_nodes; ++i)
      apply_to_node(pass, measure, chunk, i, scratch);
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply_to_node(const Pass &       pass,
                                         const bool         measure,
                                         const unsigned int chunk,
                                         const unsigned int index,
                                         Scratch &          scratch)
  {
    const unsigned int node   = pass.fields.get_contact_nodes()[chunk * chunk_size + index];
    NodeSums &         sums   = scratch.sums;
    sums.frictional_heat = sums.momentum_defect = sums.momentum_correction = 0;
    sums.pair_forces.assign(pair_forces.size(), Tensor<1, dim>());
    sums.pair_impulses.clear();
    const auto [begin, end] = pass.fields.node_records(node);
    ChunkResults &results   = chunk_results[chunk];
    scratch.node            = node;
    scratch.support_volume  = pass.support_volumes != nullptr ? (*pass.support_volumes)[node] : 0.;
    apply_at_node(begin,
                  end,
                  pass.spacing[node],
                  pass.dt,
                  node < pass.n_owned_nodes,
                  pass.record_forces,
                  measure,
                  pass_geometry == Geometry::compute ?
                    nullptr :
                    results.geometry.data() + results.geometry_offsets[index],
                  scratch,
                  sums);

    results.node_totals[index] = {sums.frictional_heat,
                                  sums.momentum_defect,
                                  sums.momentum_correction};
    std::copy(sums.pair_forces.begin(),
              sums.pair_forces.end(),
              results.node_pair_forces.begin() + index * pair_forces.size());
    for (PairImpulse impulse : sums.pair_impulses)
      {
        impulse.node = index;
        results.pair_impulses.push_back(impulse);
      }
  }

  template <int dim>
  void
  BardenhagenContact<dim>::redo_capped_nodes(const Pass &       pass,
                                             const unsigned int chunk,
                                             Scratch &          scratch)
  {
    // the impulses come node by node
    ChunkResults &results = chunk_results[chunk];
    auto &        redo    = scratch.nodes_to_redo;
    redo.clear();
    for (const PairImpulse &impulse : results.pair_impulses)
      if (impulse.friction > 0 && (redo.empty() || redo.back() != impulse.node) &&
          friction_scale.find(impulse.pair) != nullptr)
        redo.push_back(impulse.node);

    const std::vector<unsigned int> &nodes = pass.fields.get_contact_nodes();
    for (const unsigned int index : redo)
      {
        auto saved = results.saved_velocities.cbegin() + results.saved_offsets[index];
        const auto [begin, end] = pass.fields.node_records(nodes[chunk * chunk_size + index]);
        for (auto r = begin; r != end; ++r)
          r->new_velocity = *saved++;
        apply_to_node(pass, false, chunk, index, scratch);
      }
  }

  template <int dim>
  void
  BardenhagenContact<dim>::keep_pulling_impulse(const unsigned int body_a,
                                                const unsigned int body_b,
                                                const bool         momentum_measure,
                                                const bool         owned,
                                                NodeSums &         sums) const
  {
    // a pair that shares a node without acting there is still in contact:
    // an empty impulse keeps its entry (read only where it has one)
    if (momentum_measure && !pulling_impulse.empty())
      {
        const std::pair<unsigned int, unsigned int> pair(std::min(body_a, body_b),
                                                         std::max(body_a, body_b));
        if (pulling_impulse.find(pair) != nullptr)
          sums.pair_impulses.push_back({pair, 0., 0., owned});
      }
  }

  template <int dim>
  void
  BardenhagenContact<dim>::compute_friction_scales(const MPI_Comm communicator,
                                                   const bool     momentum_update)
  {
    // per pair: net normal impulse, friction impulse (chunk by chunk, so
    // the sums do not depend on the threads; each pair's sum is formed in
    // the same order whatever the order of the pairs)
    auto &totals = pair_totals;
    totals.clear();
    for (const ChunkResults &results : chunk_results)
      for (const PairImpulse &impulse : results.pair_impulses)
        if (impulse.owned)
          {
            auto &total = totals[impulse.pair];
            total.first += impulse.normal;
            total.second += impulse.friction;
          }
    if (Utilities::MPI::n_mpi_processes(communicator) > 1)
      {
        // every rank's pairs to every rank, added in rank order
        std::vector<double> local;
        totals.for_each([&](const auto &pair, const auto &total) {
          local.insert(local.end(), {double(pair.first), double(pair.second), total.first, total.second});
        });
        totals.clear();
        for (const std::vector<double> &part : Utilities::MPI::all_gather(communicator, local))
          for (unsigned int i = 0; i + 3 < part.size(); i += 4)
            {
              auto &total = totals[{static_cast<unsigned int>(part[i]),
                                    static_cast<unsigned int>(part[i + 1])}];
              total.first += part[i + 2];
              total.second += part[i + 3];
            }
      }
    // the momentum update offsets a pair's pulling impulse of earlier
    // steps first: over time its friction stays within mu times its net
    // normal impulse (a block sliding on a staircase face was pulled back
    // in a quarter of the steps, and its friction, mu times the
    // compressive steps' impulse, was 4% above mu times its weight)
    if (momentum_update)
      next_pulling_impulse.clear();
    totals.for_each([&](const auto &pair, const auto &total) {
      const double mu = friction_between_bodies(pair.first, pair.second);
      double pulled = 0;
      if (momentum_update)
        {
          const double *const earlier = pulling_impulse.find(pair);
          pulled                      = earlier != nullptr ? *earlier : 0.;
          if (pulled - total.first > 0)
            next_pulling_impulse[pair] = pulled - total.first;
        }
      const double allowed = mu * std::max(total.first - pulled, 0.);
      if (total.second > allowed)
        friction_scale[pair] = allowed / total.second;
    });
    if (momentum_update)
      std::swap(pulling_impulse, next_pulling_impulse);
  }

  template <int dim>
  unsigned int
  BardenhagenContact<dim>::n_kept_pairs(const unsigned int n) const
  {
    // the 'centre of mass' treatment of nodes of three or more bodies
    // keeps nothing
    if (n == 2)
      return 1;
    if (n > 2 && parameters.multi_body_nodes == ContactParameters::MultiBodyNodes::pairwise)
      return n * (n - 1) / 2;
    return 0;
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply_at_node(typename BodyFields<dim>::Record *begin,
                                         typename BodyFields<dim>::Record *end,
                                         const Tensor<1, dim> &            spacing,
                                         const double                      dt,
                                         const bool                        owned,
                                         const bool                        record_forces,
                                         const bool                        measure,
                                         PairGeometry *                    geometry,
                                         Scratch &                         scratch,
                                         NodeSums &                        sums) const
  {
    using Record = typename BodyFields<dim>::Record;
    const unsigned int n = end - begin;
    auto &normal            = scratch.normal;
    auto &change            = scratch.change;
    auto &own               = scratch.own;
    auto &tangential_speed  = scratch.tangential_speed;
    auto &tangential_change = scratch.tangential_change;
    auto &friction          = scratch.friction;
    double total_mass = 0;
    for (const Record *r = begin; r != end; ++r)
      total_mass += r->mass;
    if (total_mass <= 0)
      return;
    // pairwise nodes need neither the bodies' combined normals nor the
    // centre of mass
    if (n > 2 && parameters.multi_body_nodes == ContactParameters::MultiBodyNodes::pairwise)
      {
        apply_pairwise_at_node(
          begin, end, spacing, dt, owned, record_forces, measure, geometry, scratch, sums);
        return;
      }
    normal.resize(n);
    change.resize(n);
    friction.resize(n);
    tangential_speed.resize(n);
    tangential_change.resize(n);
    Tensor<1, dim> total_momentum;
    for (const Record *r = begin; r != end; ++r)
      total_momentum += r->mass * r->new_velocity;
    const Tensor<1, dim> centre_of_mass_velocity = total_momentum / total_mass;

    // a round body against a face whose contact point took this node
    if (n == 2 && at_contact_point(scratch.node) && round_against_face(begin[0], begin[1]))
      return;
    // a two-body node's geometry from an earlier pass (Geometry::reuse)
    const bool reuse = n == 2 && geometry != nullptr && pass_geometry == Geometry::reuse;
    // outward unit normals: sum_p m_p grad N_i(x_p) points from the
    // body's particles towards the node, out of the body (it is minus
    // the gradient of the body's mass density)
    if (!reuse)
      for (unsigned int a = 0; a < n; ++a)
        normal[a] = begin[a].outward_direction();
    const bool release_by_approach_only =
      n == 2 && !reuse && approach_only_at_edge(normal[0], normal[1]);
    if (n == 2)
      {
        const Tensor<1, dim> common =
          reuse ? geometry->normal : pair_normal(begin[0], begin[1], normal[0], normal[1]);
        if (geometry != nullptr)
          geometry->normal = common;
        if (common.norm_square() == 0)
          return;
        normal[0] = common;
        normal[1] = -common;
      }
    else
      {
        own = normal;
        for (unsigned int a = 0; a < n; ++a)
          {
            // minus the mass-weighted mean of the others' directions
            Tensor<1, dim> others;
            for (unsigned int b = 0; b < n; ++b)
              if (b != a)
                others += begin[b].mass * own[b];
            others /= std::max(total_mass - begin[a].mass,
                               std::numeric_limits<double>::min());
            const double   own_weight =
              parameters.normals != ContactParameters::Normals::average ?
                begin[a].mass / std::max(total_mass - begin[a].mass,
                                         std::numeric_limits<double>::min()) :
                1.;
            Tensor<1, dim> combined = own_weight * own[a] - others;
            // a fitted plane separates the body from all the others
            if (pass_fitted != nullptr && fitted_normal(begin[a]).norm_square() > 0)
              combined = fitted_normal(begin[a]);
            const double norm = combined.norm();
            normal[a] = norm > 0 ? combined / norm : Tensor<1, dim>();
          }
      }

    // release logic: one decision per node at two-body nodes, so that
    // both bodies change together and momentum is kept
    const auto traction = [&](const unsigned int a) {
      return begin[a].mass > 0 ?
               normal[a] * (begin[a].mass_stress * normal[a]) / begin[a].mass :
               0.;
    };
    bool node_acts = false;
    if (n == 2)
      {
        const double approach =
          (begin[0].new_velocity - centre_of_mass_velocity) * normal[0];
        if (!reuse)
          {
            double mean_traction = 0;
            if (use_traction && !release_by_approach_only)
              mean_traction = (begin[0].mass * traction(0) + begin[1].mass * traction(1)) /
                              total_mass;
            if (geometry != nullptr)
              geometry->compressed = mean_traction < 0;
            node_acts = approach > 0 || mean_traction < 0;
          }
        else
          node_acts = approach > 0 || geometry->compressed;
        if (node_acts && begin[0].mass > 0 && begin[1].mass > 0 &&
            parameters.detection == ContactParameters::Detection::surface_position)
          node_acts = surfaces_meet(
            pair_gap(begin[0], begin[1], normal[0], spacing, scratch.support_volume, geometry),
            (begin[0].new_velocity - begin[1].new_velocity) * normal[0],
            dt);
      }

    double rate = 0;
    for (unsigned int a = 0; a < n; ++a)
      {
        const Record &r = begin[a];
        change[a]           = 0;
        friction[a]         = 0;
        tangential_speed[a] = tangential_change[a] = 0;
        const Tensor<1, dim> dv = r.new_velocity - centre_of_mass_velocity;
        const double         dv_n = dv * normal[a];
        const bool acts = n == 2 ? node_acts :
                                   (dv_n > 0 || (use_traction && traction(a) < 0));
        if (n == 2 && a == 0 && !acts)
          keep_pulling_impulse(begin[0].body, begin[1].body, measure && record_forces, owned, sums);
        if (!acts || r.mass <= 0)
          continue;
        // friction with the heaviest other body at the node
        unsigned int other = a == 0 ? 1 : 0;
        for (unsigned int b = 0; b < n; ++b)
          if (b != a && begin[b].mass > begin[other].mass)
            other = b;
        const double mu = friction_between_bodies(r.body, begin[other].body);
        const CoulombCorrection<dim> correction = coulomb_correction(dv, normal[a], mu);
        change[a]                               = correction.change;
        friction[a]                             = correction.friction;
        tangential_speed[a]                     = correction.tangential_speed;
        tangential_change[a]                    = correction.tangential_change;
        if (cap_friction && std::isfinite(mu))
          {
            // the pair's normal impulses, pulling ones included, and its
            // friction impulses
            const std::pair<unsigned int, unsigned int> pair(
              std::min(r.body, begin[other].body), std::max(r.body, begin[other].body));
            if (measure)
              sums.pair_impulses.push_back(
                {pair, r.mass * dv_n, r.mass * correction.tangential_change, owned});
            const double *const capped =
              correction.tangential_change > 0 ? friction_scale.find(pair) : nullptr;
            if (capped != nullptr)
              {
                // the normal part stays, the friction part shrinks
                const Tensor<1, dim> normal_part = -dv_n * normal[a];
                change[a] = normal_part + *capped * (correction.change - normal_part);
                friction[a] *= *capped;
                tangential_change[a] *= *capped;
              }
          }
        // the cell-collapse rate of paper 002 section 2.2
        const double mass_ratio = std::max(r.mass / std::max(total_mass - r.mass,
                                                             std::numeric_limits<double>::min()),
                                           1.);
        for (unsigned int d = 0; d < dim; ++d)
          rate = std::max(rate, mass_ratio * std::abs(change[a][d]) / spacing[d]);
      }

    double scale = 1;
    if (parameters.impulse_scaling > 0 && rate * dt > parameters.impulse_scaling)
      scale = parameters.impulse_scaling / (rate * dt);

    Tensor<1, dim> defect;
    for (unsigned int a = 0; a < n; ++a)
      {
        Record &r = begin[a];
        r.new_velocity += scale * change[a];
        if (record_forces)
          {
            r.normal        = normal[a];
            r.contact_force  = r.mass * scale * change[a] / dt;
            // static friction does no work: only a slipping body's counts
            r.friction_force = tangential_change[a] < tangential_speed[a] ?
                                 Tensor<1, dim>(r.mass * scale * friction[a] / dt) :
                                 Tensor<1, dim>();
            r.state          = change[a].norm() == 0 ? 0 :
                               tangential_change[a] < tangential_speed[a] ? 2 : 1;
          }
        if (!owned)
          continue;
        defect += r.mass * scale * change[a];
        sums.momentum_correction += r.mass * scale * change[a].norm();
        // frictional work (Nairn, Bardenhagen & Smith 2018): the
        // tangential impulse m tau times the slip speed left after it,
        // |dv_t| - tau (zero while sticking); at a two-body node the sum
        // over both bodies is the impulse times the relative slip speed
        // (only in the pass whose changes reach the particles). The normal
        // impulse does no work: it leaves no relative normal velocity, or
        // (impulse scaling) only an approach that the bodies' stresses
        // then take up.
        const double tau = scale * tangential_change[a];
        if (record_forces && heat_at_nodes)
          sums.frictional_heat += r.mass * tau * (tangential_speed[a] - tau);
        if (record_forces && n >= 2)
          for (unsigned int b = 0; b < n; ++b)
            if (b != a)
              {
                const unsigned int index = pair_index(r.body, begin[b].body);
                if (index == BodyFields<dim>::invalid)
                  continue;
                // split among the other bodies by their mass, summed
                // rather than taken as total - own: a body's tiny share
                // at a node (a GIMP weight of 1e-20) would leave 0 / 0
                double others = 0;
                for (unsigned int c = 0; c < n; ++c)
                  if (c != a)
                    others += begin[c].mass;
                const double share = others > 0 ? begin[b].mass / others : 0.;
                sums.pair_forces[index] += share * r.mass * scale * change[a] / dt;
              }
      }
    if (owned)
      sums.momentum_defect += defect.norm();
  }

  template <int dim>
  Tensor<1, dim>
  BardenhagenContact<dim>::pair_normal(const typename BodyFields<dim>::Record &a,
                                       const typename BodyFields<dim>::Record &b,
                                       const Tensor<1, dim> &                  normal_a,
                                       const Tensor<1, dim> &                  normal_b) const
  {
    // two round bodies with 'Round pair normals = line of centres': the
    // line between their centres, the normal of rigid disks or spheres in
    // contact, the same at every node of the pair (their mass gradients
    // tilt from node to node at a coarse contact; the fitted planes less
    // so, at the cost of a fit per node)
    if (!body_centres.empty() && std::isfinite(body_surface_radii[a.body]) &&
        std::isfinite(body_surface_radii[b.body]))
      {
        const Tensor<1, dim> line = body_centres[b.body] - body_centres[a.body];
        const double         norm = line.norm();
        if (norm > 0)
          return line / norm;
      }
    Tensor<1, dim> common;
    // the fitted planes' normals where both bodies have one (for two
    // bodies they are opposite; at nodes of more, each body's plane
    // separates it from all the others), with 'fitted at edges' only
    // where the bodies meet at an edge; else the flatter body's or the
    // heavier one's at the node (or a blend, as 'Contact/Normals' says)
    const bool fitted = pass_fitted != nullptr && fitted_normal(a).norm_square() > 0 &&
                        fitted_normal(b).norm_square() > 0 &&
                        (parameters.normals != ContactParameters::Normals::fitted_at_edges ||
                         meet_at_edge(normal_a, normal_b));
    if (fitted)
      common = fitted_normal(a) - fitted_normal(b);
    else if (parameters.normals == ContactParameters::Normals::largest_mass ||
             parameters.normals == ContactParameters::Normals::flatter_body ||
             parameters.normals == ContactParameters::Normals::logistic_regression ||
             parameters.normals == ContactParameters::Normals::fitted_at_edges)
      {
        // one body's normal: the flatter body's for the whole interface
        // or the heavier one's at the node, whose surface the node
        // resolves better (a flat plane's, not a block corner's);
        // but bodies whose outward directions are less than 120 degrees
        // apart do not face each other there (faces in contact are 180
        // degrees apart, a corner on a face 135): their faces end at the
        // node, edge to edge (the flush ends of stacked blocks), and either
        // body's direction leans along its end face and would stop the
        // bodies sliding along their interface; the difference of the two
        // keeps what they do not share, the interface's normal.
        // With 'flatter body', each body's surface normal where its points
        // carry it: a face inclined to the grid is a staircase of points,
        // whose mass gradient tilts from node to node (a block on a 30
        // degree wedge barely slid)
        const bool surfaces = parameters.normals == ContactParameters::Normals::flatter_body &&
                              !body_volumes.empty();
        const Tensor<1, dim> face_normal_a = surfaces ? face_normal(a) : Tensor<1, dim>();
        const Tensor<1, dim> face_normal_b = surfaces ? face_normal(b) : Tensor<1, dim>();
        const bool           face_a        = face_normal_a.norm_square() > 0;
        const bool           face_b        = face_normal_b.norm_square() > 0;
        const Tensor<1, dim> direction_a   = face_a ? face_normal_a : normal_a;
        const Tensor<1, dim> direction_b   = face_b ? face_normal_b : normal_b;
        const bool ends_meet = direction_a.norm_square() > 0 && direction_b.norm_square() > 0 &&
                               direction_a * direction_b > facing_limit;
        if (face_a != face_b)
          // one body's face, the other's corner (or a body without faces):
          // the face's normal, whichever body is flatter (a block's face
          // passing the rear corner of the block under it was held there
          // by that corner's leaning mass gradient)
          common = face_a ? direction_a : Tensor<1, dim>(-direction_b);
        else if (ends_meet)
          common = direction_a - direction_b;
        else if (surfaces)
          {
            // one body's surface for the pair's whole interface: with the
            // larger mass at each node, the normal jumps between the two
            // bodies' surfaces across it (and a block's corner or a disk's
            // staircase edge tilts it), which drags a sliding body and
            // damps collisions
            common = flatter(a.body, b.body) ? direction_a : Tensor<1, dim>(-direction_b);
          }
        else
          common = a.mass >= b.mass ? normal_a : Tensor<1, dim>(-normal_b);
      }
    else if (parameters.normals == ContactParameters::Normals::average)
      common = normal_a - normal_b;
    else
      common = a.mass * normal_a - b.mass * normal_b;
    const double norm = common.norm();
    return norm > 0 ? Tensor<1, dim>(common / norm) : Tensor<1, dim>();
  }

  template <int dim>
  Tensor<1, dim>
  BardenhagenContact<dim>::face_normal(const typename BodyFields<dim>::Record &r) const
  {
    // nine tenths of the mass at the node carries a normal (points near an
    // edge or a corner carry none: there a record of a block's front face
    // next to its corner took the front face's normal against a wedge's
    // face, and the block hopped)
    if (!(r.mass_surface > 0) || r.mass_surface < 0.9 * r.mass)
      return Tensor<1, dim>();
    if (on_one_face(r))
      return r.mass_surface_normal / r.mass_surface_normal.norm();
    // points of two faces: those a cell or two deep near an edge reach the
    // nodes of both faces (a wedge's points near its side tilted the
    // slope's records under a cube's side planes by a few degrees); the
    // face whose direction nine tenths of the mass projects onto (for
    // faces at right angles, the mass under it)
    if (r.body + 1 >= face_direction_start.size())
      return Tensor<1, dim>();
    double         largest = 0;
    Tensor<1, dim> direction;
    for (unsigned int k = face_direction_start[r.body]; k < face_direction_start[r.body + 1]; ++k)
      {
        const double along = r.mass_surface_normal * face_directions[k];
        if (along > largest)
          {
            largest   = along;
            direction = face_directions[k];
          }
      }
    return largest >= 0.9 * r.mass ? direction : Tensor<1, dim>();
  }

  template <int dim>
  bool
  BardenhagenContact<dim>::flatter(const unsigned int p, const unsigned int q) const
  {
    if (body_surface_radii[p] != body_surface_radii[q])
      return body_surface_radii[p] > body_surface_radii[q];
    // the volumes are sums over the points, whose round-off follows the
    // points' order and the MPI ranks: between two equal disks seeded
    // conforming the choice followed that round-off, and one and two
    // ranks took different normals (their runs took different numbers of
    // steps)
    const double volume_p = body_volumes[p], volume_q = body_volumes[q];
    if (std::abs(volume_p - volume_q) > 1e-9 * std::max(volume_p, volume_q))
      return volume_p > volume_q;
    return p < q;
  }

  template <int dim>
  bool
  BardenhagenContact<dim>::approach_only_at_edge(const Tensor<1, dim> &normal_a,
                                                 const Tensor<1, dim> &normal_b) const
  {
    // the 2001 rule holds bodies whose normal traction is compressive
    // together even while they separate; at an edge the normal is the
    // fitted plane's, and the bodies' stresses along it say little:
    // holding them together there held a block passing the front end of
    // the one under it (3x3 points per cell: -5.6%, now +0.4%;
    // doc/validation.md, "Stacked blocks")
    return parameters.normals == ContactParameters::Normals::fitted_at_edges &&
           meet_at_edge(normal_a, normal_b);
  }

  template <int dim>
  typename BardenhagenContact<dim>::SurfaceGap
  BardenhagenContact<dim>::pair_gap(const typename BodyFields<dim>::Record &a,
                                    const typename BodyFields<dim>::Record &b,
                                    const Tensor<1, dim> &                  normal,
                                    const Tensor<1, dim> &                  spacing,
                                    const double                            support,
                                    PairGeometry *                          geometry) const
  {
    if (geometry == nullptr)
      return surface_gap(a, b, normal, spacing, support);
    if (!geometry->gap_known)
      {
        geometry->gap       = surface_gap(a, b, normal, spacing, support);
        geometry->gap_known = true;
      }
    return geometry->gap;
  }

  template <int dim>
  typename BardenhagenContact<dim>::SurfaceGap
  BardenhagenContact<dim>::surface_gap(const typename BodyFields<dim>::Record &a,
                                       const typename BodyFields<dim>::Record &b,
                                       const Tensor<1, dim> &                  normal,
                                       const Tensor<1, dim> &                  spacing,
                                       const double                            support) const
  {
    // the surfaces meet within the step if the centroids' distance, less
    // what the bodies close along the normal in dt, is at most the distance
    // they have when touching (surfaces_meet())
    const Tensor<1, dim> centroid_a = a.mass_position / a.mass;
    const Tensor<1, dim> centroid_b = b.mass_position / b.mass;
    const Tensor<1, dim> between    = centroid_b - centroid_a;
    double               cell       = 0;
    for (unsigned int d = 0; d < dim; ++d)
      cell += std::pow(normal[d] * spacing[d], 2);
    // touching within a hundredth of a cell: bodies resting on each other
    // have their centroids at the touching distance, up to round-off and
    // the small strains, and a resting contact must keep its friction at
    // every node (a block held by friction creeps 7% of a cell in 0.25 s
    // without it, 1.3% with it; 0.1 cell would slow a rolling disk)
    // each body's surface lies an offset outside its centroid that
    // follows the spacing its points were seeded at (in cells along the
    // normal)
    const double size = std::sqrt(cell);
    // where a record's points lie under one flat face (boxes and meshes),
    // the face is where their vectors to it end, whatever its angle to the
    // grid and the points' registration with it: on a face inclined to
    // the grid the centroid's offset varies from node to node along the
    // staircase of points
    //
    // a round body's surface is located so only against a face: two round
    // bodies touch at a point, and the nodes beside it see their located
    // surfaces curve apart and hold nothing until the bodies overlap (the
    // A4 chain's disks flew apart); the centroids' offsets, which take
    // each node to lie on the surface, let those nodes act
    const bool faces = on_one_face(a) || on_one_face(b);
    const bool locate_round =
      parameters.round_surfaces != ContactParameters::RoundSurfaces::centroid_offset;
    const auto located = [&](const typename BodyFields<dim>::Record &r) {
      return surface_known(r) && faces && (r.mass_surface > 0 || locate_round);
    };
    double along    = between * normal;
    double touching = touching_tolerance * size;
    if (located(a))
      along += (centroid_a - a.mass_surface_point / a.mass_on_surface) * normal;
    else
      touching += surface_centroid_offset(a.mass_spacing / (a.mass * size)) * size;
    if (located(b))
      along += (b.mass_surface_point / b.mass_on_surface - centroid_b) * normal;
    else
      touching += surface_centroid_offset(b.mass_spacing / (b.mass * size)) * size;
    // apart, a sideways offset of the centroids beyond a quarter cell
    // counts too: off the line of centres of two round bodies the normal
    // tilts away from their distance, and two disks felt a force a cell
    // before touching; up to a quarter cell is what an edge or a curved
    // surface covering part of a node's support shifts a centroid sideways.
    // Overlapping, the part along the normal says how far.
    const double sideways   = (between - (between * normal) * normal).norm();
    const double beyond     = sideways - sideways_tolerance * std::sqrt(cell);
    const double separation = along > 0 && beyond > 0 ? std::hypot(along, beyond) : along;
    // the centroids' offsets assume each body fills a half-space behind its
    // surface; where one body covers most of the support and the other a
    // corner, its centroid lies far from its surface, and two disks
    // pressed together crept into each other at such nodes (a quarter
    // spacing in the settling pile): there the volumes the bodies bring
    // say whether they overlap. Not against a located face: a lattice
    // seeded under an inclined face sticks out of it in steps, and its
    // volumes would hold a disk rolling there (-11% at 25 degrees)
    if (!located(a) && !located(b) && overlapping(a, b, support))
      return {std::min(separation, touching), touching};
    return {separation, touching};
  }

  template <int dim>
  bool
  BardenhagenContact<dim>::overlapping(const typename BodyFields<dim>::Record &a,
                                       const typename BodyFields<dim>::Record &b,
                                       const double                            support) const
  {
    if (support <= 0 || body_specific_volumes.empty())
      return false;
    // bodies that do not overlap fill at most the node's support: sum_p
    // N_p V_p over a body's points is the integral of N over the body
    const double volume_a = unscaled_mass(a) * body_specific_volumes[a.body];
    const double volume_b = unscaled_mass(b) * body_specific_volumes[b.body];
    // a body with a few points in a corner of the support: the plane fitted
    // there, or its mass gradient, may tilt far from the surfaces', and a
    // pair held along a tilted normal slides into itself under load (with
    // such nodes acting, two disks in the settling pile with mu = 0.2 crept
    // half a spacing into each other)
    if (std::min(volume_a, volume_b) < overlap_least_share * support)
      return false;
    const double filled = volume_a + volume_b;
    return filled > (1 + overlap_tolerance) * support;
  }

  template <int dim>
  void
  BardenhagenContact<dim>::apply_pairwise_at_node(typename BodyFields<dim>::Record *begin,
                                                  typename BodyFields<dim>::Record *end,
                                                  const Tensor<1, dim> &            spacing,
                                                  const double                      dt,
                                                  const bool                        owned,
                                                  const bool                        record_forces,
                                                  const bool                        measure,
                                                  PairGeometry *                    geometry,
                                                  Scratch &                         scratch,
                                                  NodeSums &                        sums) const
  {
    using Record = typename BodyFields<dim>::Record;
    const unsigned int n        = end - begin;
    // the pairs' geometry from an earlier pass (Geometry::reuse): the
    // bodies' directions are then needed only where it lacks a part (or
    // for the output)
    const bool reuse = geometry != nullptr && pass_geometry == Geometry::reuse && !record_forces;
    auto &             normal   = scratch.normal;
    auto &             velocity = scratch.own;
    auto &             change   = scratch.change;
    auto &             slipping = scratch.slipping;
    auto &             pairs    = scratch.pairs;
    auto &             friction = scratch.friction;
    normal.resize(n);
    velocity.resize(n);
    change.resize(n);
    friction.assign(n, Tensor<1, dim>());
    slipping.assign(n, false);
    pairs.clear();
    double total_mass = 0;
    for (unsigned int a = 0; a < n; ++a)
      {
        if (!reuse)
          normal[a] = begin[a].outward_direction();
        velocity[a] = begin[a].new_velocity;
        total_mass += begin[a].mass;
      }
    const auto direction = [&](const unsigned int a) {
      return reuse ? begin[a].outward_direction() : normal[a];
    };

    // each pair in turn as at a two-body node, on the velocities the pairs
    // before it left: equal and opposite impulses, so momentum is kept
    PairGeometry *kept = geometry;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = a + 1; b < n; ++b)
        {
          PairGeometry *const pair_geometry = kept != nullptr ? kept++ : nullptr;
          const Record &      ra = begin[a], &rb = begin[b];
          if (ra.mass <= 0 || rb.mass <= 0)
            continue;
          const Tensor<1, dim> common =
            reuse ? pair_geometry->normal : pair_normal(ra, rb, normal[a], normal[b]);
          if (pair_geometry != nullptr)
            pair_geometry->normal = common;
          if (common.norm_square() == 0)
            continue;
          const double         pair_mass = ra.mass + rb.mass;
          const Tensor<1, dim> dv = (rb.mass / pair_mass) * (velocity[a] - velocity[b]);
          const double         dv_n = dv * common;
          bool                 acts = dv_n > 0;
          if (use_traction && !acts)
            {
              // the pair's normal traction, where it may hold the pair
              const auto compressed = [&]() {
                return !approach_only_at_edge(direction(a), direction(b)) &&
                       (common * (ra.mass_stress * common) + common * (rb.mass_stress * common)) /
                           pair_mass <
                         0;
              };
              if (pair_geometry == nullptr)
                acts = compressed();
              else
                {
                  if (!pair_geometry->compressed_known)
                    {
                      pair_geometry->compressed       = compressed();
                      pair_geometry->compressed_known = true;
                    }
                  acts = pair_geometry->compressed;
                }
            }
          if (acts && parameters.detection == ContactParameters::Detection::surface_position)
            acts = surfaces_meet(
              pair_gap(ra, rb, common, spacing, scratch.support_volume, pair_geometry),
              (velocity[a] - velocity[b]) * common,
              dt);
          if (!acts)
            {
              keep_pulling_impulse(ra.body, rb.body, measure && record_forces, owned, sums);
              continue;
            }
          const double mu = friction_between_bodies(ra.body, rb.body);
          const CoulombCorrection<dim> correction = coulomb_correction(dv, common, mu);
          Tensor<1, dim>               change_a   = correction.change;
          Tensor<1, dim>               friction_a = correction.friction;
          double                       tau        = correction.tangential_change;
          if (cap_friction && std::isfinite(mu))
            {
              const std::pair<unsigned int, unsigned int> pair(ra.body, rb.body);
              if (measure)
                sums.pair_impulses.push_back({pair, ra.mass * dv_n, ra.mass * tau, owned});
              const double *const capped = tau > 0 ? friction_scale.find(pair) : nullptr;
              if (capped != nullptr)
                {
                  const Tensor<1, dim> normal_part = -dv_n * common;
                  change_a = normal_part + *capped * (change_a - normal_part);
                  friction_a *= *capped;
                  tau *= *capped;
                }
            }
          velocity[a] += change_a;
          velocity[b] -= (ra.mass / rb.mass) * change_a;
          // static friction does no work: only a slipping pair's counts
          if (tau < correction.tangential_speed)
            {
              friction[a] += friction_a;
              friction[b] -= (ra.mass / rb.mass) * friction_a;
            }
          // the friction impulse m_a tau times the relative slip left,
          // (M / m_b)(|dv_t| - tau), per unit impulse scale
          pairs.push_back({a, b, change_a, tau, correction.tangential_speed,
                           ra.mass * pair_mass / rb.mass});
          if (tau < correction.tangential_speed)
            slipping[a] = slipping[b] = true;
        }
    // one impulse scale for the node (paper 002 section 2.2), so that
    // momentum stays kept
    double rate = 0;
    for (unsigned int a = 0; a < n; ++a)
      {
        change[a] = velocity[a] - begin[a].new_velocity;
        if (begin[a].mass <= 0)
          continue;
        const double mass_ratio =
          std::max(begin[a].mass / std::max(total_mass - begin[a].mass,
                                            std::numeric_limits<double>::min()),
                   1.);
        for (unsigned int d = 0; d < dim; ++d)
          rate = std::max(rate, mass_ratio * std::abs(change[a][d]) / spacing[d]);
      }
    double scale = 1;
    if (parameters.impulse_scaling > 0 && rate * dt > parameters.impulse_scaling)
      scale = parameters.impulse_scaling / (rate * dt);

    Tensor<1, dim> defect;
    for (unsigned int a = 0; a < n; ++a)
      {
        Record &r = begin[a];
        r.new_velocity += scale * change[a];
        if (record_forces)
          {
            r.normal        = normal[a];
            r.contact_force  = r.mass * scale * change[a] / dt;
            r.friction_force = r.mass * scale * friction[a] / dt;
            r.state          = change[a].norm() == 0 ? 0 : slipping[a] ? 2 : 1;
          }
        if (owned)
          {
            defect += r.mass * scale * change[a];
            sums.momentum_correction += r.mass * scale * change[a].norm();
          }
      }
    if (!owned)
      return;
    sums.momentum_defect += defect.norm();
    if (record_forces)
      for (const auto &pair : pairs)
        {
          const double tau = scale * pair.tau;
          if (heat_at_nodes)
            sums.frictional_heat += pair.heat_mass * tau * (pair.slip_speed - tau);
          const unsigned int index = pair_index(begin[pair.a].body, begin[pair.b].body);
          if (index != BodyFields<dim>::invalid)
            sums.pair_forces[index] += begin[pair.a].mass * scale * pair.change / dt;
        }
  }

  template class BardenhagenContact<2>;
  template class BardenhagenContact<3>;
} // namespace sable::mpm
