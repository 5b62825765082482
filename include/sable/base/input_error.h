#ifndef sable_base_input_error_h
#define sable_base_input_error_h

#include <sstream>
#include <stdexcept>
#include <string>

namespace sable
{
  /**
   * A problem with the user's input (parameter file, pack file, API call).
   * The message names the entry, the value given and what is allowed; the
   * program prints it and exits before any work or output.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Throw an InputError "<entry> = <value>: <allowed>" unless @p condition.
  template <typename ValueType>
  inline void
  check_input(const bool         condition,
              const std::string &entry,
              const ValueType &  value,
              const std::string &allowed)
  {
    if (!condition)
      {
        std::ostringstream message;
        message << "invalid input: '" << entry << " = " << value
                << "'; allowed: " << allowed;
        throw InputError(message.str());
      }
  }
} // namespace sable

#endif
