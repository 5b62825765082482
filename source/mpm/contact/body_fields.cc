#include <sable/mpm/contact/body_fields.h>

#include <algorithm>

namespace sable::mpm
{
  template <int dim>
  void
  BodyFields<dim>::clear(const unsigned int n_nodes)
  {
    first_body.assign(n_nodes, invalid);
    extra_bodies.clear();
    if (first_record.size() != n_nodes)
      {
        first_record.assign(n_nodes, invalid);
        n_records.assign(n_nodes, 0);
      }
    else
      for (const unsigned int node : contact_nodes)
        {
          first_record[node] = invalid;
          n_records[node]    = 0;
        }
    contact_nodes.clear();
    records.clear();
  }

  template <int dim>
  void
  BodyFields<dim>::allocate()
  {
    // the extra pairs bucketed by node (a counting sort: sorting every pair,
    // each present once per cell around its node, cost more than the rest
    // of the search); n_records is zero at every node here
    for (const auto &[node, body] : extra_bodies)
      if (n_records[node]++ == 0)
        contact_nodes.push_back(node);
    std::sort(contact_nodes.begin(), contact_nodes.end());
    unsigned int offset = 0;
    for (const unsigned int node : contact_nodes)
      {
        first_record[node] = offset;
        offset += n_records[node];
        n_records[node] = 0;
      }
    extra_by_node.resize(extra_bodies.size());
    for (const auto &[node, body] : extra_bodies)
      extra_by_node[first_record[node] + n_records[node]++] = body;

    Record zero{};
    for (const unsigned int node : contact_nodes)
      {
        const auto begin = extra_by_node.begin() + first_record[node];
        auto       end   = begin + n_records[node];
        std::sort(begin, end);
        end                = std::unique(begin, end);
        first_record[node] = records.size();
        // the node's bodies, sorted: the first one seen (never among the
        // extra ones) merged into the extra ones
        bool first_placed = false;
        for (auto body = begin; body != end; ++body)
          {
            if (!first_placed && first_body[node] < *body)
              {
                zero.body = first_body[node];
                records.push_back(zero);
                first_placed = true;
              }
            zero.body = *body;
            records.push_back(zero);
          }
        if (!first_placed)
          {
            zero.body = first_body[node];
            records.push_back(zero);
          }
        n_records[node] = records.size() - first_record[node];
      }
  }

  template <int dim>
  void
  BodyFields<dim>::zero_momenta()
  {
    for (Record &r : records)
      {
        r.mass     = 0;
        r.momentum = 0;
        r.force    = 0;
      }
  }

  template class BodyFields<2>;
  template class BodyFields<3>;
} // namespace sable::mpm
