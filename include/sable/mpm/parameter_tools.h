#ifndef sable_mpm_parameter_tools_h
#define sable_mpm_parameter_tools_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// "0, 0" (dim zeros), the default of vector entries.
  std::string
  zero_vector(const unsigned int n);

  /// The dim numbers of vector entry @p entry; @p path prefixes the entry
  /// in messages.
  template <int dim>
  Tensor<1, dim>
  read_vector(const ParameterHandler &prm, const std::string &entry, const std::string &path);

  /// "1: a, 2: b" -> {{"1", "a"}, {"2", "b"}}
  std::vector<std::pair<std::string, std::string>>
  split_map(const std::string &text);

  /// The number in @p text, or NaN if it is not one.
  double
  to_double(const std::string &text);

  /// A friction coefficient: a number >= 0, or 'stick' (infinity).
  double
  parse_friction(const std::string &text, const std::string &entry);
} // namespace sable::mpm

#endif
