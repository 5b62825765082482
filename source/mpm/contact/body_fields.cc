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
    std::sort(extra_bodies.begin(), extra_bodies.end());
    extra_bodies.erase(std::unique(extra_bodies.begin(), extra_bodies.end()),
                       extra_bodies.end());
    Record zero{};
    for (auto it = extra_bodies.begin(); it != extra_bodies.end();)
      {
        const unsigned int node = it->first;
        contact_nodes.push_back(node);
        first_record[node] = records.size();
        // the node's bodies, sorted: the first one seen, merged into the
        // (sorted) extra ones
        bool first_placed = false;
        for (; it != extra_bodies.end() && it->first == node; ++it)
          {
            if (!first_placed && first_body[node] < it->second)
              {
                zero.body = first_body[node];
                records.push_back(zero);
                first_placed = true;
              }
            zero.body = it->second;
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
