#ifndef sable_mpm_contact_pair_table_h
#define sable_mpm_contact_pair_table_h

#include <cstdint>
#include <utility>
#include <vector>

namespace sable::mpm
{
  /**
   * A value per pair of bodies, in one flat table with open addressing.
   *
   * The friction cap looks pairs up at every contact node and sums tens of
   * thousands of pairs per step in a dense pack; a node-based hash map
   * allocated one block per pair and freed them all every pass. Here
   * clear() keeps the storage, and the pairs are visited in the order they
   * were first inserted, so that what is built from them does not depend on
   * the table's size.
   */
  template <typename Value>
  class PairTable
  {
  public:
    using Pair = std::pair<unsigned int, unsigned int>;

    /// Remove every pair; the storage stays for the next use.
    void
    clear()
    {
      for (const unsigned int slot : used)
        keys[slot] = empty_key;
      used.clear();
    }

    bool
    empty() const
    {
      return used.empty();
    }

    std::size_t
    size() const
    {
      return used.size();
    }

    /// The value of @p pair, value-initialised when it is new.
    Value &
    operator[](const Pair &pair)
    {
      // at most half full, so that probe sequences stay short
      if (2 * (used.size() + 1) > keys.size())
        grow();
      const std::uint64_t key  = as_key(pair);
      unsigned int        slot = first_slot(key);
      while (keys[slot] != key)
        {
          if (keys[slot] == empty_key)
            {
              keys[slot]   = key;
              values[slot] = Value();
              used.push_back(slot);
              break;
            }
          slot = (slot + 1) & mask();
        }
      return values[slot];
    }

    /// The value of @p pair, or nullptr if the table does not hold it.
    const Value *
    find(const Pair &pair) const
    {
      if (used.empty())
        return nullptr;
      const std::uint64_t key = as_key(pair);
      for (unsigned int slot = first_slot(key);; slot = (slot + 1) & mask())
        {
          if (keys[slot] == key)
            return &values[slot];
          if (keys[slot] == empty_key)
            return nullptr;
        }
    }

    /// Call @p visit(pair, value) for every pair, in the order of insertion.
    template <typename Visitor>
    void
    for_each(const Visitor &visit) const
    {
      for (const unsigned int slot : used)
        visit(Pair(keys[slot] >> 32, keys[slot] & 0xffffffffu), values[slot]);
    }

  private:
    /// no pair of bodies has two invalid numbers
    static constexpr std::uint64_t empty_key = ~std::uint64_t(0);

    static std::uint64_t
    as_key(const Pair &pair)
    {
      return (std::uint64_t(pair.first) << 32) | pair.second;
    }

    unsigned int
    mask() const
    {
      return keys.size() - 1;
    }

    /// Fibonacci hashing: the top bits of the key times 2^64 / phi.
    unsigned int
    first_slot(const std::uint64_t key) const
    {
      return (key * 0x9e3779b97f4a7c15ull) >> (64 - bits);
    }

    /// Double the slots (at least 64) and insert the pairs again, keeping
    /// their order.
    void
    grow()
    {
      std::vector<std::uint64_t> old_keys;
      std::vector<Value>         old_values;
      std::vector<unsigned int>  old_used;
      old_keys.swap(keys);
      old_values.swap(values);
      old_used.swap(used);
      bits = old_keys.empty() ? 6 : bits + 1;
      keys.assign(std::size_t(1) << bits, empty_key);
      values.resize(keys.size());
      for (const unsigned int slot : old_used)
        {
          const std::uint64_t key = old_keys[slot];
          unsigned int        s   = first_slot(key);
          while (keys[s] != empty_key)
            s = (s + 1) & mask();
          keys[s]   = key;
          values[s] = old_values[slot];
          used.push_back(s);
        }
    }

    unsigned int               bits = 0;
    std::vector<std::uint64_t> keys;
    std::vector<Value>         values;
    /// the occupied slots, in the order of insertion
    std::vector<unsigned int>  used;
  };
} // namespace sable::mpm

#endif
