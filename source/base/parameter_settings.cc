#include <deal.II/base/exceptions.h>

#include <sable/base/input_error.h>
#include <sable/base/parameter_settings.h>

#include <sstream>

namespace sable
{
  namespace
  {
    std::string
    trim(const std::string &text)
    {
      const auto first = text.find_first_not_of(" \t");
      if (first == std::string::npos)
        return "";
      const auto last = text.find_last_not_of(" \t");
      return text.substr(first, last - first + 1);
    }

    std::string
    join(const std::vector<std::string> &subsections)
    {
      std::string joined;
      for (const std::string &subsection : subsections)
        joined += (joined.empty() ? "" : "/") + subsection;
      return joined;
    }

    /// "invalid input: 'Name = value' (--set); <what>", the form of
    /// check_input()'s messages
    InputError
    setting_error(const ParameterSetting &setting, const std::string &what)
    {
      return InputError("invalid input: '" + setting.name() + " = " +
                        setting.value + "' (--set); " + what);
    }
  } // namespace

  std::string
  ParameterSetting::name() const
  {
    std::string name;
    for (const std::string &subsection : subsections)
      name += subsection + "/";
    return name + entry;
  }

  ParameterSetting
  parse_parameter_setting(const std::string &argument)
  {
    const std::string allowed =
      "\"Subsection/.../Entry=value\" (\"Entry=value\" at the top level), "
      "with the names of 'sable --print-parameters'";
    const auto equal = argument.find('=');
    check_input(equal != std::string::npos, "--set", argument, allowed);

    ParameterSetting  setting;
    const std::string name = argument.substr(0, equal);
    setting.value          = trim(argument.substr(equal + 1));
    std::size_t begin      = 0;
    while (true)
      {
        const auto        slash = name.find('/', begin);
        const std::string part =
          trim(name.substr(begin, slash == std::string::npos ? std::string::npos : slash - begin));
        check_input(!part.empty(), "--set", argument, allowed);
        if (slash == std::string::npos)
          {
            setting.entry = part;
            break;
          }
        setting.subsections.push_back(part);
        begin = slash + 1;
      }
    return setting;
  }

  void
  apply_parameter_settings(dealii::ParameterHandler &           prm,
                           const std::vector<ParameterSetting> &settings,
                           const bool                           skip_undeclared)
  {
    for (const ParameterSetting &setting : settings)
      {
        // the path down to the first subsection that does not exist, if any
        std::vector<std::string> path;
        for (const std::string &subsection : setting.subsections)
          {
            path.push_back(subsection);
            if (!prm.subsection_path_exists(path))
              break;
          }
        if (!prm.subsection_path_exists(path))
          {
            if (skip_undeclared)
              continue;
            throw setting_error(setting,
                                "the scene has no subsection '" +
                                  join(path) +
                                  "' ('sable --print-parameters' lists every entry)");
          }

        for (const std::string &subsection : setting.subsections)
          prm.enter_subsection(subsection);
        std::string problem;
        bool        undeclared = false;
        try
          {
            prm.set(setting.entry, setting.value);
          }
        catch (const dealii::ParameterHandler::ExcEntryUndeclared &)
          {
            undeclared = true;
          }
        catch (const dealii::ParameterHandler::ExcValueDoesNotMatchPattern &error)
          {
            // deal.II's text: "The string <value> does not match the given
            // pattern <pattern>."; keep the pattern
            std::ostringstream info;
            error.print_info(info);
            problem             = info.str();
            const std::string key = "pattern <";
            const auto        begin = problem.find(key);
            const auto        end   = problem.rfind('>');
            if (begin != std::string::npos && end != std::string::npos && end > begin)
              problem = "allowed: " + problem.substr(begin + key.size(), end - begin - key.size());
            else if (problem.empty())
              problem = "the value does not match the entry's pattern";
          }
        for (std::size_t i = 0; i < setting.subsections.size(); ++i)
          prm.leave_subsection();

        if (undeclared && !skip_undeclared)
          throw setting_error(
            setting,
            "the scene has no entry '" + setting.entry + "'" +
              (setting.subsections.empty() ?
                 std::string(" at the top level") :
                 " in subsection '" + join(setting.subsections) + "'") +
              " ('sable --print-parameters' lists every entry)");
        if (!problem.empty())
          throw setting_error(setting, problem);
      }
  }
} // namespace sable
