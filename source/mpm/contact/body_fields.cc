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
    // in node order: where contact nodes are many (a dense pack of small
    // grains) a pass over all nodes costs less than sorting them
    if (contact_nodes.size() * 16 > n_records.size())
      {
        contact_nodes.clear();
        for (unsigned int node = 0; node < n_records.size(); ++node)
          if (n_records[node] > 0)
            contact_nodes.push_back(node);
      }
    else
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
        // the node's extra bodies sorted and without repeats, in place
        // (a handful, one per cell around the node: an insertion sort)
        unsigned int *const begin    = extra_by_node.data() + first_record[node];
        unsigned int        n_unique = 0;
        for (unsigned int i = 0; i < n_records[node]; ++i)
          {
            const unsigned int body = begin[i];
            unsigned int       j    = n_unique;
            while (j > 0 && begin[j - 1] > body)
              --j;
            if (j > 0 && begin[j - 1] == body)
              continue;
            for (unsigned int k = n_unique; k > j; --k)
              begin[k] = begin[k - 1];
            begin[j] = body;
            ++n_unique;
          }
        unsigned int *const end = begin + n_unique;
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

  template <int dim>
  void
  BodyFields<dim>::zero_records()
  {
    for (Record &r : records)
      {
        const unsigned int body = r.body;
        r                       = Record{};
        r.body                  = body;
      }
  }

  template class BodyFields<2>;
  template class BodyFields<3>;
} // namespace sable::mpm
