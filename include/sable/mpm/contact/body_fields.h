#ifndef sable_mpm_contact_body_fields_h
#define sable_mpm_contact_body_fields_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/numbers.h>

#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * Per-body grid fields, kept only where they differ from the single
   * total field: at contact nodes, the nodes whose support holds material
   * points of two or more bodies. A node stores one record per body present
   * there; nothing is allocated per body x node, and the table is rebuilt
   * every step in O(particles) (DESIGN.md principle 3).
   *
   * Building: clear(), then add(node, body) for every (node, body) pair a
   * cell's particles touch, then allocate(); records of a contact node are
   * contiguous and sorted by body.
   */
  template <int dim>
  class BodyFields
  {
  public:
    struct Record
    {
      unsigned int   body;
      double         mass;
      Tensor<1, dim> momentum;
      Tensor<1, dim> force;
      /// sum_p m_p grad N: its direction is the body's outward normal
      Tensor<1, dim> mass_gradient;
      /// sum_p m_p N x_p: over mass, the body's centroid near the node
      Tensor<1, dim> mass_position;
      /// sum_p m_p N s_p: over mass, the spacing the points near the node
      /// were seeded at (s_p = V_p^(1/dim) of the initial volume)
      double mass_spacing;
      /// sum_p m_p sigma_p N (in-plane part), for the traction criterion
      SymmetricTensor<2, dim> mass_stress;
      /// sum_p m_p N n_p over the points that carry the unit normal n_p of
      /// the face they lie under (box and mesh bodies; turned with the
      /// body's rotation): the body's surface normal at the node, also
      /// where the face is inclined to the grid
      Tensor<1, dim> mass_surface_normal;
      /// sum_p m_p N over the same points: at most mass; as large as the
      /// length of mass_surface_normal where they all lie under one face
      double mass_surface;
      /// sum_p m_p N (x_p + t_p) over the points that carry the vector
      /// t_p to their body's surface (ParticleLayout::to_surface_stored):
      /// over mass_on_surface, a point on the surface near the node,
      /// whatever the registration of the points with the grid
      Tensor<1, dim> mass_surface_point;
      /// sum_p m_p N over the same points
      double mass_on_surface;
      Tensor<1, dim>          old_velocity;
      Tensor<1, dim>          new_velocity;
      /// what the contact and the walls changed in new_velocity in the last
      /// pass (zero at a moving wall's node, whose work is boundary work),
      /// for the loss of the impacts (GridToParticle::measure_corrections())
      Tensor<1, dim> correction;
      /// set by the contact pass after the momentum update, for output:
      /// the body's normal, the contact force on it, and its state
      /// (0 free, 1 stick, 2 slip)
      Tensor<1, dim> normal;
      Tensor<1, dim> contact_force;
      /// the friction part of contact_force where the body slips (zero
      /// where it sticks: static friction does no work)
      Tensor<1, dim> friction_force;
      unsigned int   state;
      /// the friction walls' tangential velocity change in the momentum
      /// update, for their heat at the remapped velocities
      Tensor<1, dim> wall_change;
      /// per wall axis (the axis of the wall's normal): the tangential
      /// speed a friction wall left in the momentum update (zero where it
      /// held the record), for the remap pass; bit d of wall_acted says
      /// whether the wall on axis d acted
      Tensor<1, dim> wall_slip;
      unsigned int   wall_acted = 0;

      /// The body's unit outward direction at the node, mass_gradient
      /// normalised (zero where it vanishes).
      Tensor<1, dim>
      outward_direction() const
      {
        const double norm = mass_gradient.norm();
        return norm > 0 ? Tensor<1, dim>(mass_gradient / norm) : Tensor<1, dim>();
      }
    };

    static constexpr unsigned int invalid = numbers::invalid_unsigned_int;

    void
    clear(const unsigned int n_nodes);

    void
    add(const unsigned int node, const unsigned int body)
    {
      add(node, body, extra_bodies);
    }

    /// As add(), for threads that never add to the same node at the same
    /// time (cells of one colour): the pairs beyond a node's first body go
    /// to the caller's @p extra, handed over by add_extra_bodies(). The
    /// table does not depend on the order of the pairs (allocate() sorts).
    void
    add(const unsigned int                                   node,
        const unsigned int                                   body,
        std::vector<std::pair<unsigned int, unsigned int>> &extra)
    {
      unsigned int &first = first_body[node];
      if (first == invalid)
        first = body;
      else if (first != body)
        extra.emplace_back(node, body);
    }

    /// Not thread-safe: one thread at a time.
    void
    add_extra_bodies(const std::vector<std::pair<unsigned int, unsigned int>> &extra)
    {
      extra_bodies.insert(extra_bodies.end(), extra.begin(), extra.end());
    }

    /// Create the zeroed records of all contact nodes.
    void
    allocate();

    /// Zero mass, momentum and force of every record (keeps normals and
    /// stresses), for a second particle-to-grid pass.
    void
    zero_momenta();

    /// Zero every record but its body, for a pass that sums all of it again.
    void
    zero_records();

    bool
    is_contact_node(const unsigned int node) const
    {
      return first_record[node] != invalid;
    }

    /// The record of @p body at contact node @p node.
    Record &
    record(const unsigned int node, const unsigned int body)
    {
      Record *r = &records[first_record[node]];
      while (r->body != body)
        ++r;
      return *r;
    }

    const Record &
    record(const unsigned int node, const unsigned int body) const
    {
      const Record *r = &records[first_record[node]];
      while (r->body != body)
        ++r;
      return *r;
    }

    /// The number of records, and the place of @p r among them.
    std::size_t
    n_all_records() const
    {
      return records.size();
    }

    std::size_t
    index_of(const Record &r) const
    {
      return &r - records.data();
    }

    const std::vector<unsigned int> &
    get_contact_nodes() const
    {
      return contact_nodes;
    }

    /// Records of contact node @p node: [begin, end).
    std::pair<Record *, Record *>
    node_records(const unsigned int node)
    {
      Record *const begin = &records[first_record[node]];
      return {begin, begin + n_records[node]};
    }

    /// Records of contact node @p node: [begin, end).
    std::pair<const Record *, const Record *>
    node_records(const unsigned int node) const
    {
      const Record *const begin = &records[first_record[node]];
      return {begin, begin + n_records[node]};
    }

  private:
    std::vector<unsigned int>                            first_body;
    std::vector<std::pair<unsigned int, unsigned int>>   extra_bodies;
    /// allocate()'s scratch: the extra bodies, node after node
    std::vector<unsigned int>                            extra_by_node;
    std::vector<unsigned int>                            first_record;
    std::vector<unsigned int>                            n_records;
    std::vector<unsigned int>                            contact_nodes;
    std::vector<Record>                                  records;
  };
} // namespace sable::mpm

#endif
