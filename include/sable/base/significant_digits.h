#ifndef sable_base_significant_digits_h
#define sable_base_significant_digits_h

#include <iomanip>
#include <sstream>
#include <string>

namespace sable
{
  /// @p value with @p digits significant digits, for messages: unlike
  /// std::to_string (six decimals), an energy of 1e-8 J or a gap of
  /// -2e-9 m does not read as zero.
  inline std::string
  significant_digits(const double value, const int digits = 3)
  {
    std::ostringstream text;
    text << std::setprecision(digits) << value;
    return text.str();
  }
} // namespace sable

#endif
