#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>

#include <sable/mpm/boundaries/boundary_conditions.h>
#include <sable/mpm/surface_offset.h>
#include <sable/mpm/contact/coulomb.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace sable::mpm
{
  template <int dim>
  BoundaryConditions<dim>::BoundaryConditions(
    const std::map<types::boundary_id, BoundaryParameters<dim>> &parameters)
    : parameters(parameters)
  {}

  template <int dim>
  void
  BoundaryConditions<dim>::setup(const Grid<dim> &grid)
  {
    constraints.clear();
    std::vector<types::global_dof_index> face_dofs(
      GeometryInfo<dim>::vertices_per_face);
    for (const auto &cell : grid.get_dof_handler().active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : GeometryInfo<dim>::face_indices())
          if (cell->at_boundary(f))
            {
              const auto it = parameters.find(cell->face(f)->boundary_id());
              if (it == parameters.end() ||
                  it->second.type == BoundaryType::free)
                continue;
              cell->face(f)->get_dof_indices(face_dofs);
              for (const auto dof : face_dofs)
                constraints.push_back({grid.local_index(dof),
                                       f / 2,
                                       f % 2 == 1 ? 1. : -1.,
                                       it->first,
                                       cell->face(f)->center()[f / 2],
                                       cell->extent_in_direction(f / 2)});
            }
    // each (node, wall) once, in the order of boundary ids so that corner
    // nodes see their walls in a fixed order on every rank
    const auto key = [](const NodeConstraint &c) {
      return std::make_tuple(c.id, c.node, c.direction, c.sign);
    };
    std::sort(constraints.begin(),
              constraints.end(),
              [&](const auto &a, const auto &b) { return key(a) < key(b); });
    // a node between wall cells of two sizes (adaptive grids) takes the
    // larger: its shape function reaches that far into the material, and
    // the larger offset lets the wall act early rather than late
    for (unsigned int i = constraints.size(); i-- > 1;)
      if (key(constraints[i - 1]) == key(constraints[i]))
        constraints[i - 1].cell_size =
          std::max(constraints[i - 1].cell_size, constraints[i].cell_size);
    constraints.erase(std::unique(constraints.begin(),
                                  constraints.end(),
                                  [&](const auto &a, const auto &b) {
                                    return key(a) == key(b);
                                  }),
                      constraints.end());
    constrained.assign(grid.n_relevant_nodes(), 0);
    friction_constrained.assign(grid.n_relevant_nodes(), false);
    moving_constrained.assign(grid.n_relevant_nodes(), false);
    constrained_list.clear();
    for (const NodeConstraint &c : constraints)
      {
        constrained[c.node] = 1;
        constrained_list.push_back(c.node);
        const BoundaryType type = parameters.find(c.id)->second.type;
        if (type == BoundaryType::friction)
          friction_constrained[c.node] = true;
        if (type == BoundaryType::moving)
          moving_constrained[c.node] = true;
      }
    std::sort(constrained_list.begin(), constrained_list.end());
    constrained_list.erase(std::unique(constrained_list.begin(), constrained_list.end()),
                           constrained_list.end());
  }

  template <int dim>
  void
  BoundaryConditions<dim>::apply_to_initial(std::vector<double> &      velocity,
                                            const std::vector<double> &mass) const
  {
    for (const NodeConstraint &c : constraints)
      if (mass[c.node] > 0. && parameters.find(c.id)->second.type != BoundaryType::friction)
        apply_one(c, &velocity[c.node * dim]);
  }

  template <int dim>
  void
  BoundaryConditions<dim>::apply_to_initial_bodies(BodyFields<dim> &fields) const
  {
    for (const NodeConstraint &c : constraints)
      if (fields.is_contact_node(c.node) &&
          parameters.find(c.id)->second.type != BoundaryType::friction)
        {
          const auto [begin, end] = fields.node_records(c.node);
          for (auto *r = begin; r != end; ++r)
            if (r->mass > 0.)
              apply_one(c, &r->new_velocity[0]);
        }
  }

  template <int dim>
  double
  BoundaryConditions<dim>::tangential_speed(const NodeConstraint &c, const double *v)
  {
    double square = 0;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != c.direction)
        square += v[d] * v[d];
    return std::sqrt(square);
  }

  template <int dim>
  void
  BoundaryConditions<dim>::apply_one_remapped(const NodeConstraint &c,
                                              double *              v,
                                              const double          slip) const
  {
    if (parameters.find(c.id)->second.type != BoundaryType::friction)
      {
        apply_one(c, v);
        return;
      }
    if (slip < 0.)
      return;
    // The node's points already carry the friction of the momentum update:
    // taking the same fraction of the remapped tangential velocity again
    // would move them slower than their velocities (a sliding block then
    // rang and gained energy), and re-deciding contact here pumped energy
    // into a block at rest. So the wall keeps what it decided: no normal
    // velocity, and no more slip than it left (none where it held).
    v[c.direction]     = 0.;
    const double speed = tangential_speed(c, v);
    if (speed > slip)
      for (unsigned int d = 0; d < dim; ++d)
        if (d != c.direction)
          v[d] *= slip / speed;
  }

  template <int dim>
  double
  BoundaryConditions<dim>::apply_one(const NodeConstraint &c, double *v) const
  {
    const BoundaryParameters<dim> &wall = parameters.find(c.id)->second;
    switch (wall.type)
      {
        case BoundaryType::fixed:
          for (unsigned int d = 0; d < dim; ++d)
            v[d] = 0.;
          return -1.;
        case BoundaryType::slip:
          v[c.direction] = 0.;
          return -1.;
        case BoundaryType::moving:
          {
            const Tensor<1, dim> wall_velocity = velocity_of(wall);
            for (unsigned int d = 0; d < dim; ++d)
              v[d] = wall_velocity[d];
            return -1.;
          }
        case BoundaryType::friction:
          {
            // SPEC step 6 with the wall (at rest) as the other body: act
            // only while the node approaches the wall
            Tensor<1, dim> velocity, normal;
            for (unsigned int d = 0; d < dim; ++d)
              velocity[d] = v[d];
            normal[c.direction] = c.sign;
            if (velocity * normal <= 0.)
              return -1.;
            const CoulombCorrection<dim> correction =
              coulomb_correction(velocity,
                                 normal,
                                 sticking ? std::numeric_limits<double>::infinity() :
                                            wall.friction);
            for (unsigned int d = 0; d < dim; ++d)
              v[d] += correction.change[d];
            return correction.tangential_fraction();
          }
        case BoundaryType::free:
          return -1.;
      }
    return -1.;
  }

  template <int dim>
  double
  BoundaryConditions<dim>::apply_one_counting(const NodeConstraint &c,
                                              double *              v,
                                              const double          mass,
                                              double &              heat) const
  {
    const BoundaryParameters<dim> &wall = parameters.find(c.id)->second;
    Tensor<1, dim>                 before, wall_velocity;
    for (unsigned int d = 0; d < dim; ++d)
      before[d] = v[d];
    if (wall.type == BoundaryType::moving)
      wall_velocity = velocity_of(wall);
    const double result = apply_one(c, v);
    Tensor<1, dim> change;
    for (unsigned int d = 0; d < dim; ++d)
      change[d] = v[d] - before[d];
    // the work of the wall's force m dv/dt against the node's velocity
    // relative to the wall after the step, as friction heat is counted
    // (Nairn, Bardenhagen & Smith 2018): zero where the wall holds the node,
    // the friction force times the slip left on a sliding node
    Tensor<1, dim> after;
    for (unsigned int d = 0; d < dim; ++d)
      after[d] = v[d];
    heat = -mass * (change * (after - wall_velocity));
    return result;
  }

  template <int dim>
  double
  BoundaryConditions<dim>::apply(std::vector<double> &      velocity,
                                 const std::vector<double> &mass,
                                 const unsigned int         n_owned_nodes)
  {
    double work = 0;
    slip_left.assign(constraints.size(), -1.);
    out_of_reach.assign(constraints.size(), false);
    last_heat.assign(constraints.size(), 0.);
    if (heat_at_remap)
      tangential_change.assign(constraints.size() * dim, 0.);
    for (unsigned int i = 0; i < constraints.size(); ++i)
      {
        const NodeConstraint &c = constraints[i];
        if (mass[c.node] <= 0.)
          continue;
        double *const                  v    = &velocity[c.node * dim];
        const BoundaryParameters<dim> &wall = parameters.find(c.id)->second;
        if (wall.type == BoundaryType::moving && c.node < n_owned_nodes)
          {
            const Tensor<1, dim> wall_velocity = velocity_of(wall);
            for (unsigned int d = 0; d < dim; ++d)
              work += mass[c.node] * (wall_velocity[d] - v[d]) * wall_velocity[d];
          }
        if (wall.type == BoundaryType::friction && out_of_reach_of(c, v, mass[c.node]))
          {
            out_of_reach[i] = true;
            continue;
          }
        Tensor<1, dim> before;
        if (heat_at_remap)
          for (unsigned int d = 0; d < dim; ++d)
            before[d] = v[d];
        const double held = apply_one_counting(c, v, mass[c.node], last_heat[i]);
        if (held >= 0.)
          slip_left[i] = tangential_speed(c, v);
        if (heat_at_remap)
          {
            last_heat[i]                 = 0;
            const Tensor<1, dim> change = friction_change(c, before, v, held);
            for (unsigned int d = 0; d < dim; ++d)
              tangential_change[i * dim + d] = change[d];
          }
        if (c.node < n_owned_nodes)
          frictional_heat += last_heat[i];
      }
    return work;
  }

  template <int dim>
  bool
  BoundaryConditions<dim>::out_of_reach_of(const NodeConstraint &c,
                                           const double *        v,
                                           const double          mass) const
  {
    const BoundaryParameters<dim> &wall = parameters.find(c.id)->second;
    // how far the node moves toward the wall in this step
    const double approach = extent_time_step * c.sign * v[c.direction];
    switch (wall.wall_contact)
      {
        case WallContact::approach:
          return false;
        case WallContact::material:
          {
            Assert(material_extent != nullptr, ExcInternalError());
            // distance from the wall to the nearest material around the node
            const double *extent = material_extent + c.node * 2 * dim + 2 * c.direction;
            const double  gap = c.sign < 0. ? extent[0] - c.position : c.position + extent[1];
            return gap - approach > 0.;
          }
        case WallContact::surface_position:
          {
            Assert(mass_moment != nullptr, ExcInternalError());
            // the body's surface lies surface_centroid_offset cells outside
            // the node's mass centroid: on a flat surface at the wall
            // exactly; on a round body rolling on the wall only at the node
            // nearest its contact (a node a cell ahead sees the surface
            // about a fifteenth of a cell up at eight cells per radius)
            const double *moment   = mass_moment + c.node * (dim + 1);
            const double  centroid = moment[c.direction] / mass;
            const double  offset =
              surface_centroid_offset(moment[dim] / (mass * c.cell_size));
            const double gap = c.sign * (c.position - centroid) -
                               (offset + touching_tolerance) * c.cell_size;
            return gap - approach > 0.;
          }
      }
    return false;
  }

  template <int dim>
  Tensor<1, dim>
  BoundaryConditions<dim>::friction_change(const NodeConstraint &c,
                                           const Tensor<1, dim> &before,
                                           const double *        after,
                                           const double          held) const
  {
    // static friction does no work: only a node that slips (the wall
    // removed less than all of its tangential velocity) counts
    Tensor<1, dim> change;
    if (parameters.find(c.id)->second.type != BoundaryType::friction || held < 0. || held >= 1.)
      return change;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != c.direction)
        change[d] = after[d] - before[d];
    return change;
  }

  template <int dim>
  void
  BoundaryConditions<dim>::count_heat_on_remapped(const std::vector<double> &velocity,
                                                  const std::vector<double> &mass,
                                                  const unsigned int         n_owned_nodes)
  {
    if (!heat_at_remap || tangential_change.size() != constraints.size() * dim)
      return;
    for (unsigned int i = 0; i < constraints.size(); ++i)
      {
        const unsigned int node = constraints[i].node;
        if (node >= n_owned_nodes)
          continue;
        // no positive work on the slip (MultiBodyContact does the same)
        double heat = 0;
        for (unsigned int d = 0; d < dim; ++d)
          heat -= mass[node] * tangential_change[i * dim + d] * velocity[node * dim + d];
        frictional_heat += std::max(heat, 0.);
      }
  }

  template <int dim>
  bool
  BoundaryConditions<dim>::needs_material_extent() const
  {
    for (const auto &[id, wall] : parameters)
      if (wall.type == BoundaryType::friction && wall.wall_contact == WallContact::material)
        return true;
    return false;
  }

  template <int dim>
  bool
  BoundaryConditions<dim>::needs_mass_moment() const
  {
    for (const auto &[id, wall] : parameters)
      if (wall.type == BoundaryType::friction &&
          wall.wall_contact == WallContact::surface_position)
        return true;
    return false;
  }

  template <int dim>
  void
  BoundaryConditions<dim>::set_mass_moment(const double *moment, const double time_step)
  {
    mass_moment      = moment;
    extent_time_step = time_step;
  }

  template <int dim>
  void
  BoundaryConditions<dim>::set_material_extent(const double *extent,
                                               const double  time_step)
  {
    material_extent  = extent;
    extent_time_step = time_step;
  }

  template <int dim>
  void
  BoundaryConditions<dim>::apply_to_remapped(std::vector<double> &      velocity,
                                             const std::vector<double> &mass) const
  {
    for (unsigned int i = 0; i < constraints.size(); ++i)
      if (mass[constraints[i].node] > 0.)
        apply_one_remapped(constraints[i], &velocity[constraints[i].node * dim], slip_left[i]);
  }

  template <int dim>
  void
  BoundaryConditions<dim>::apply_to_bodies(BodyFields<dim> &  fields,
                                           const bool         remapped,
                                           const unsigned int n_owned_nodes)
  {
    for (unsigned int i = 0; i < constraints.size(); ++i)
      if (fields.is_contact_node(constraints[i].node) &&
          !(i < out_of_reach.size() && out_of_reach[i]))
        {
          const bool counted = !remapped && constraints[i].node < n_owned_nodes;
          if (counted)
            frictional_heat -= last_heat[i];
          // the records count the heat at contact nodes
          if (!remapped && heat_at_remap)
            for (unsigned int d = 0; d < dim; ++d)
              tangential_change[i * dim + d] = 0;
          const auto [begin, end] = fields.node_records(constraints[i].node);
          for (auto *r = begin; r != end; ++r)
            if (r->mass > 0.)
              {
                double *const v = &r->new_velocity[0];
                if (remapped)
                  {
                    const unsigned int axis = constraints[i].direction;
                    apply_one_remapped(constraints[i],
                                       v,
                                       (r->wall_acted >> axis) & 1u ? r->wall_slip[axis] : -1.);
                    continue;
                  }
                double held;
                if (!counted)
                  held = apply_one(constraints[i], v);
                else if (heat_at_remap)
                  {
                    const Tensor<1, dim> before = r->new_velocity;
                    double               heat   = 0;
                    held = apply_one_counting(constraints[i], v, r->mass, heat);
                    r->wall_change += friction_change(constraints[i], before, v, held);
                  }
                else
                  {
                    double heat = 0;
                    held = apply_one_counting(constraints[i], v, r->mass, heat);
                    frictional_heat += heat;
                  }
                // the record's own decision, as a node's
                if (held >= 0.)
                  {
                    const unsigned int axis = constraints[i].direction;
                    r->wall_slip[axis]      = tangential_speed(constraints[i], v);
                    r->wall_acted |= 1u << axis;
                  }
              }
        }
  }

  template class BoundaryConditions<2>;
  template class BoundaryConditions<3>;
} // namespace sable::mpm
