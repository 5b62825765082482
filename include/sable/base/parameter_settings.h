#ifndef sable_base_parameter_settings_h
#define sable_base_parameter_settings_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sable
{
  /**
   * One entry of a parameter file given a new value on the command line,
   * `--set "Subsection/.../Entry=value"` (`Entry=value` at the top level).
   * It is applied after the file is read, as if the file had said
   * `set Entry = value` in that subsection, and checked the same way.
   */
  struct ParameterSetting
  {
    /// The subsections from the top level down, e.g. {"Body 0"}.
    std::vector<std::string> subsections;
    std::string              entry;
    std::string              value;

    /// "Subsection/.../Entry", as in the program's error messages.
    std::string
    name() const;
  };

  /**
   * Split "Subsection/.../Entry=value" (the first '=' ends the name;
   * blanks around the names and the value are dropped). Throws an
   * InputError if there is no '=' or a name is empty.
   */
  ParameterSetting
  parse_parameter_setting(const std::string &argument);

  /**
   * Give the entries of @p settings their values in @p prm, after the
   * parameter file has been parsed into it, in the order given (a later
   * setting of the same entry wins). A value that does not match the entry's
   * pattern, or a subsection or entry that @p prm does not declare, is an
   * InputError naming the setting. With @p skip_undeclared the settings of
   * undeclared entries are passed over instead: for the first passes that
   * read only some entries of a file (Model and Dimension, the number of
   * bodies) before everything is declared.
   */
  void
  apply_parameter_settings(dealii::ParameterHandler &           prm,
                           const std::vector<ParameterSetting> &settings,
                           const bool skip_undeclared = false);
} // namespace sable

#endif
