// The tables the contact pass is built on, against plain std:: containers:
// - PairTable (the friction cap's per-pair sums and scales): random pairs of
//   bodies, many repeated, summed in the table and in a std::map; every sum
//   must be bitwise equal (the same additions in the same order), unknown
//   pairs absent, the visiting order the order of first insertion, and a
//   cleared table reused must hold only the new pairs;
// - BodyFields (the records of the contact nodes): (node, body) pairs added
//   in a random order with duplicates, from one list and from per-thread
//   lists; the contact nodes must be exactly the nodes with two or more
//   bodies, ascending, each with its bodies sorted and unique.
#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/contact/pair_table.h>

#include <test_support.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace sable::mpm;
using sable_tests::check;

namespace
{
  void
  pair_table()
  {
    std::mt19937                                 random(7);
    PairTable<std::pair<double, double>>         table;
    std::uniform_real_distribution<>             value(-1., 1.);
    for (const unsigned int n_bodies : {3u, 300u, 20000u})
      {
        table.clear();
        std::map<std::pair<unsigned int, unsigned int>, std::pair<double, double>> expected;
        std::vector<std::pair<unsigned int, unsigned int>>                         first_seen;
        std::uniform_int_distribution<unsigned int> body(0, n_bodies - 1);
        for (unsigned int i = 0; i < 100000; ++i)
          {
            // bodies near the top of the 32-bit range test the key packing
            const unsigned int a = body(random), b = body(random) + (i % 7 == 0 ? 4000000000u : 0u);
            const std::pair<unsigned int, unsigned int> pair(std::min(a, b), std::max(a, b));
            const double x = value(random), y = value(random);
            if (expected.count(pair) == 0)
              first_seen.push_back(pair);
            expected[pair].first += x;
            expected[pair].second += y;
            table[pair].first += x;
            table[pair].second += y;
          }
        const std::string name = "PairTable, " + std::to_string(n_bodies) + " bodies: ";
        check(name + "holds " + std::to_string(table.size()) + " pairs, as many as std::map (" +
                std::to_string(expected.size()) + ")",
              table.size() == expected.size());
        bool equal = true;
        for (const auto &[pair, sums] : expected)
          {
            const auto *found = table.find(pair);
            equal = equal && found != nullptr && found->first == sums.first &&
                    found->second == sums.second;
          }
        check(name + "every pair's sums bitwise equal to std::map's", equal);
        std::vector<std::pair<unsigned int, unsigned int>> visited;
        table.for_each([&](const auto &pair, const auto &) { visited.push_back(pair); });
        check(name + "visits the pairs in the order of first insertion", visited == first_seen);
        check(name + "an absent pair is not found",
              table.find({n_bodies + 5, n_bodies + 6}) == nullptr);
      }
    table.clear();
    check("PairTable cleared: empty, nothing found",
          table.empty() && table.find({1, 2}) == nullptr);
    table[{1, 2}].first = 3.;
    check("PairTable reused after clear: one pair, its new value",
          table.size() == 1 && table.find({1, 2})->first == 3. && table.find({1, 2})->second == 0.);
  }

  void
  body_fields()
  {
    constexpr unsigned int n_nodes = 5000, n_bodies = 40;
    std::mt19937           random(11);
    std::uniform_int_distribution<unsigned int> node(0, n_nodes - 1), body(0, n_bodies - 1);
    BodyFields<2>                               fields;
    // two steps on the same table: the second must not see the first's nodes
    for (const unsigned int n_pairs : {20000u, 3000u})
      {
        fields.clear(n_nodes);
        std::vector<std::set<unsigned int>> expected(n_nodes);
        // half through add(), half through per-thread lists handed over
        std::vector<std::pair<unsigned int, unsigned int>> extra_a, extra_b;
        for (unsigned int i = 0; i < n_pairs; ++i)
          {
            const unsigned int n = node(random), b = body(random);
            expected[n].insert(b);
            if (i % 3 == 0)
              fields.add(n, b);
            else
              fields.add(n, b, i % 3 == 1 ? extra_a : extra_b);
          }
        fields.add_extra_bodies(extra_b);
        fields.add_extra_bodies(extra_a);
        fields.allocate();

        std::vector<unsigned int> expected_nodes;
        for (unsigned int n = 0; n < n_nodes; ++n)
          if (expected[n].size() >= 2)
            expected_nodes.push_back(n);
        const std::string name = "BodyFields, " + std::to_string(n_pairs) + " pairs: ";
        check(name + std::to_string(fields.get_contact_nodes().size()) +
                " contact nodes, ascending, exactly those with two or more bodies (" +
                std::to_string(expected_nodes.size()) + ")",
              fields.get_contact_nodes() == expected_nodes);
        bool bodies_right = true, flags_right = true;
        for (unsigned int n = 0; n < n_nodes; ++n)
          {
            flags_right = flags_right && fields.is_contact_node(n) == (expected[n].size() >= 2);
            if (!fields.is_contact_node(n))
              continue;
            const auto [begin, end] = fields.node_records(n);
            std::vector<unsigned int> bodies;
            for (auto r = begin; r != end; ++r)
              bodies.push_back(r->body);
            bodies_right = bodies_right &&
                           bodies == std::vector<unsigned int>(expected[n].begin(), expected[n].end());
            for (const unsigned int b : expected[n])
              bodies_right = bodies_right && fields.record(n, b).body == b &&
                             fields.record(n, b).mass == 0.;
          }
        check(name + "is_contact_node() true exactly at the contact nodes", flags_right);
        check(name + "each contact node holds its bodies sorted and once, zeroed", bodies_right);
      }
  }
} // namespace

int
main()
{
  pair_table();
  body_fields();
  return sable_tests::n_failures() == 0 ? 0 : 1;
}
