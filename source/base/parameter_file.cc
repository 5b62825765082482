#include <sable/base/input_error.h>
#include <sable/base/parameter_file.h>

#include <filesystem>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace sable
{
  namespace
  {
    namespace fs = std::filesystem;

    /// The file an include line names ("" if @p line is none).
    std::string
    included_file(const std::string &line)
    {
      std::string text = line.substr(0, line.find('#'));
      const auto  first = text.find_first_not_of(" \t");
      if (first == std::string::npos || text.compare(first, 7, "include") != 0)
        return "";
      text           = text.substr(first + 7);
      const auto begin = text.find_first_not_of(" \t");
      const auto end   = text.find_last_not_of(" \t\r");
      if (begin == std::string::npos || (begin == 0 && !text.empty()))
        return ""; // "include" alone, or a longer word
      return text.substr(begin, end - begin + 1);
    }

    std::string
    trim(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\r");
      if (begin == std::string::npos)
        return "";
      return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
    }

    /// @p value with numbers in a canonical form.
    std::string
    canonical(const std::string &value)
    {
      std::string        result;
      std::istringstream items(value);
      std::string        item;
      bool               first = true;
      while (std::getline(items, item, ','))
        {
          item = trim(item);
          char        *end    = nullptr;
          const double number = std::strtod(item.c_str(), &end);
          if (!item.empty() && *end == '\0')
            {
              // the shortest text that reads back to the same number
              char       text[64];
              const auto written = std::to_chars(text, text + sizeof(text), number);
              item.assign(text, written.ptr);
            }
          result += (first ? "" : ", ") + item;
          first = false;
        }
      return result;
    }

    /// The text of @p filename with its include lines replaced by the files.
    void
    expand(const fs::path &filename, std::ostream &out, const unsigned int depth, bool &any)
    {
      std::ifstream in(filename);
      if (!in)
        throw InputError("cannot read the parameter file '" + filename.string() +
                         "': it does not exist or is not readable");
      std::string  line;
      unsigned int line_number = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string name = included_file(line);
          if (name.empty())
            {
              out << line << '\n';
              continue;
            }
          any                 = true;
          const fs::path path = fs::path(name).is_absolute() ? fs::path(name) :
                                                               filename.parent_path() / name;
          const std::string where =
            "line " + std::to_string(line_number) + " of '" + filename.string() + "'";
          if (!std::ifstream(path))
            throw InputError("cannot read the file '" + path.string() + "' included at " + where +
                             " ('include " + name +
                             "'): it does not exist or is not readable (an include names a file "
                             "relative to the folder of the file it stands in)");
          if (depth >= 20)
            throw InputError("the include at " + where +
                             " is 20 levels deep: do the files include each other?");
          expand(path, out, depth + 1, any);
        }
    }
  } // namespace


  void
  parse_parameter_file(dealii::ParameterHandler &prm,
                       const std::string        &filename,
                       const bool                skip_undefined)
  {
    std::ostringstream text;
    bool               any = false;
    expand(fs::path(filename), text, 0, any);
    if (!any)
      {
        // deal.II's messages then count the lines of the file itself
        prm.parse_input(filename, "", skip_undefined);
        return;
      }
    std::istringstream in(text.str());
    prm.parse_input(in, filename + " (with its includes)", "", skip_undefined);
  }


  std::vector<std::pair<std::string, std::string>>
  parameter_entries(const dealii::ParameterHandler &prm)
  {
    std::ostringstream printed;
    prm.print_parameters(printed, dealii::ParameterHandler::ShortPRM);
    std::vector<std::pair<std::string, std::string>> entries;
    std::vector<std::string>                         path;
    std::istringstream                               in(printed.str());
    std::string                                      line;
    while (std::getline(in, line))
      {
        line = trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
          {
            std::string name;
            for (const std::string &section : path)
              name += section + "/";
            const auto equals = line.find('=');
            entries.emplace_back(name + trim(line.substr(4, equals - 4)),
                                 canonical(line.substr(equals + 1)));
          }
      }
    return entries;
  }
} // namespace sable


namespace sable
{
  std::string
  entry_differences(const std::vector<std::pair<std::string, std::string>> &saved,
                    const std::vector<std::pair<std::string, std::string>> &now,
                    const std::function<bool(const std::string &)>         &may_change)
  {
    const std::map<std::string, std::string> before(saved.begin(), saved.end());
    const std::map<std::string, std::string> after(now.begin(), now.end());
    std::set<std::string>                    names;
    for (const auto &[name, value] : before)
      names.insert(name);
    for (const auto &[name, value] : after)
      names.insert(name);
    std::string text;
    for (const std::string &name : names)
      {
        const auto        old_value = before.find(name);
        const auto        new_value = after.find(name);
        const std::string a =
          old_value == before.end() ? "(not in that scene)" : "'" + old_value->second + "'";
        const std::string b =
          new_value == after.end() ? "(not in this scene)" : "'" + new_value->second + "'";
        if (a != b && !may_change(name))
          text += "\n  " + name + ": " + a + " in the checkpoint, " + b + " now";
      }
    return text;
  }
} // namespace sable
