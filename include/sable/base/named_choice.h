#ifndef sable_base_named_choice_h
#define sable_base_named_choice_h

#include <deal.II/base/patterns.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sable
{
  /**
   * The names of an enumeration's values in a parameter file, written once:
   * the Selection pattern of the entry and the parsing both come from the
   * same list, so a choice is never spelled twice.
   *
   *   static const NamedChoice<Shape> shapes{{"disk", Shape::disk}, {"box", Shape::box}};
   *   prm.declare_entry("Shape", "disk", shapes.pattern(), "...");
   *   shape = shapes.value(prm.get("Shape"));
   */
  template <typename Enum>
  class NamedChoice
  {
  public:
    NamedChoice(std::initializer_list<std::pair<const char *, Enum>> choices)
      : choices(choices.begin(), choices.end())
    {}

    /// "a|b|c", for Patterns::Selection and Patterns::MultipleSelection.
    std::string
    names() const
    {
      std::string result;
      for (const auto &[name, value] : choices)
        result += (result.empty() ? "" : "|") + std::string(name);
      return result;
    }

    dealii::Patterns::Selection
    pattern() const
    {
      return dealii::Patterns::Selection(names());
    }

    /// The value named @p name (which the entry's pattern has checked).
    Enum
    value(const std::string &name) const
    {
      for (const auto &[n, v] : choices)
        if (name == n)
          return v;
      throw std::invalid_argument("'" + name + "' is not one of " + names());
    }

    std::string
    name(const Enum value) const
    {
      for (const auto &[n, v] : choices)
        if (v == value)
          return n;
      throw std::invalid_argument("unnamed choice");
    }

  private:
    std::vector<std::pair<const char *, Enum>> choices;
  };
} // namespace sable

#endif
