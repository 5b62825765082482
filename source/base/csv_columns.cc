#include <deal.II/base/utilities.h>

#include <sable/base/csv_columns.h>
#include <sable/base/input_error.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace sable
{
  std::string
  CsvRow::place(const std::string &name) const
  {
    return location + ", column " + std::to_string(columns.at(name) + 1) + " (" + name + ")";
  }

  double
  CsvRow::number(const std::string &name) const
  {
    const std::string &field = fields[columns.at(name)];
    std::size_t        used  = 0;
    double             value = 0;
    try
      {
        value = std::stod(field, &used);
      }
    catch (const std::exception &)
      {
        used = 0;
      }
    check_input(used > 0 && used == field.size() && std::isfinite(value), place(name), field, "a number");
    return value;
  }

  void
  read_csv_columns(const std::string &                                             filename,
                   const std::string &                                             what,
                   const std::vector<std::string> &                                allowed,
                   const std::vector<std::string> &                                required,
                   const std::function<void(const std::string &, const std::string &,
                                            const std::map<std::string, unsigned int> &)> &check_header,
                   const std::function<void(const CsvRow &)> &                     row)
  {
    // "points file" of "2D points file"
    const std::string kind = what.substr(what.find(' ') + 1);
    std::ifstream     in(filename);
    if (!in)
      throw InputError("invalid input: cannot open the " + kind + " '" + filename + "'");
    std::string known;
    for (const auto &name : allowed)
      known += (known.empty() ? "" : ", ") + name;

    CsvRow       current;
    std::string  text;
    unsigned int n_fields = 0;
    for (unsigned int line = 1; std::getline(in, text); ++line)
      {
        const std::string where   = filename + ", line " + std::to_string(line);
        const std::string trimmed = dealii::Utilities::trim(text);
        if (trimmed.empty() || trimmed[0] == '#')
          continue;
        std::vector<std::string> fields = dealii::Utilities::split_string_list(trimmed, ',');
        if (current.columns.empty())
          {
            // the header
            for (unsigned int k = 0; k < fields.size(); ++k)
              {
                const std::string &name = fields[k];
                check_input(std::find(allowed.begin(), allowed.end(), name) != allowed.end(),
                            where + ", column " + std::to_string(k + 1),
                            name,
                            "a column name of a " + what + ": " + known);
                check_input(current.columns.count(name) == 0,
                            where + ", column " + std::to_string(k + 1),
                            name,
                            "each column once");
                current.columns[name] = k;
              }
            for (const auto &name : required)
              check_input(current.columns.count(name) == 1,
                          where + " (the header)",
                          trimmed,
                          "a column '" + name + "' (columns: " + known + ")");
            if (check_header)
              check_header(where, trimmed, current.columns);
            n_fields = fields.size();
            continue;
          }
        check_input(fields.size() == n_fields,
                    where,
                    trimmed,
                    std::to_string(n_fields) + " fields, as the header names");
        current.location    = where;
        current.line_number = line;
        current.fields      = std::move(fields);
        row(current);
      }
  }
} // namespace sable
