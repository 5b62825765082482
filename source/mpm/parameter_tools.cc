#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/mpm/parameter_tools.h>

#include <limits>

namespace sable::mpm
{
  std::string
  zero_vector(const unsigned int n)
  {
    std::string s = "0";
    for (unsigned int i = 1; i < n; ++i)
      s += ", 0";
    return s;
  }

  template <int dim>
  Tensor<1, dim>
  read_vector(const ParameterHandler &prm,
              const std::string &     entry,
              const std::string &     path)
  {
    const std::vector<double> values =
      Utilities::string_to_double(Utilities::split_string_list(prm.get(entry)));
    check_input(values.size() == dim,
                path + entry,
                prm.get(entry),
                std::to_string(dim) + " comma-separated numbers");
    Tensor<1, dim> result;
    for (unsigned int d = 0; d < dim; ++d)
      result[d] = values[d];
    return result;
  }

  /// "1: a, 2: b" -> {{"1", "a"}, {"2", "b"}}
  std::vector<std::pair<std::string, std::string>>
  split_map(const std::string &text)
  {
    std::vector<std::pair<std::string, std::string>> result;
    for (const std::string &item : Utilities::split_string_list(text, ','))
      {
        const auto pair = Utilities::split_string_list(item, ':');
        if (pair.size() == 2)
          result.emplace_back(pair[0], pair[1]);
      }
    return result;
  }

  /// The number in @p text, or NaN if it is not one.
  double
  to_double(const std::string &text)
  {
    try
      {
        std::size_t end   = 0;
        const double value = std::stod(text, &end);
        if (end == text.size())
          return value;
      }
    catch (...)
      {}
    return std::numeric_limits<double>::quiet_NaN();
  }

  /// A friction coefficient: a number >= 0, or 'stick' (infinity).
  double
  parse_friction(const std::string &text, const std::string &entry)
  {
    if (text == "stick" || text == "inf")
      return std::numeric_limits<double>::infinity();
    const double value = to_double(text);
    check_input(value >= 0, entry, text, "a coefficient >= 0 or 'stick'");
    return value;
  }

  template Tensor<1, 2>
  read_vector<2>(const ParameterHandler &, const std::string &, const std::string &);
  template Tensor<1, 3>
  read_vector<3>(const ParameterHandler &, const std::string &, const std::string &);
} // namespace sable::mpm
