// Reading a parameter file whose `include` lines name files relative to it.
#ifndef sable_base_parameter_file_h
#define sable_base_parameter_file_h

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace sable
{
  /**
   * Parse @p filename into @p prm as ParameterHandler::parse_input() does,
   * except that a line `include other.prm` names a file relative to the
   * folder of the file it stands in (deal.II reads it relative to the
   * working directory). The included files are read in place of their
   * include lines (up to 20 levels deep); then deal.II's messages count the
   * lines of that whole text. A file that cannot be read is an InputError
   * naming it and the line that includes it.
   */
  void
  parse_parameter_file(dealii::ParameterHandler &prm,
                       const std::string        &filename,
                       bool                      skip_undefined = false);

  /**
   * Every entry of @p prm with its value, as ("Subsection/.../Entry",
   * value) in the order ParameterHandler prints them; a value that is a
   * number or a list of numbers is written in the shortest form that reads
   * back to the same numbers, so that "1e9" and "1000000000" read the same
   * ("1e+09").
   */
  std::vector<std::pair<std::string, std::string>>
  parameter_entries(const dealii::ParameterHandler &prm);

  /**
   * The entries of @p saved and @p now (as parameter_entries() gives them)
   * whose values differ and that @p may_change does not accept, one line
   * each: "\n  Subsection/Entry: 'old' in the checkpoint, 'new' now"; an
   * empty string if there are none.
   */
  std::string
  entry_differences(const std::vector<std::pair<std::string, std::string>> &saved,
                    const std::vector<std::pair<std::string, std::string>> &now,
                    const std::function<bool(const std::string &)>         &may_change);
} // namespace sable

#endif
