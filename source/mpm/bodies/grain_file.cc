#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/mpm/bodies/grain_file.h>

#include <cmath>
#include <fstream>
#include <map>

namespace sable::mpm
{
  template <int dim>
  std::vector<Grain<dim>>
  read_grain_file(const std::string &filename)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("invalid input: cannot open the grain file '" + filename + "'");

    const std::vector<std::string> names =
      dim == 2 ? std::vector<std::string>{"x", "y", "radius"} :
                 std::vector<std::string>{"x", "y", "z", "radius"};
    std::string known;
    for (const auto &name : names)
      known += (known.empty() ? "" : ", ") + name;

    std::vector<Grain<dim>>             grains;
    std::map<std::string, unsigned int> column; // name -> field index
    std::string                         text;
    unsigned int                        n_fields = 0;
    for (unsigned int line = 1; std::getline(in, text); ++line)
      {
        const std::string where   = filename + ", line " + std::to_string(line);
        const std::string trimmed = Utilities::trim(text);
        if (trimmed.empty() || trimmed[0] == '#')
          continue;
        const std::vector<std::string> fields = Utilities::split_string_list(trimmed, ',');
        if (column.empty())
          {
            // the header
            for (unsigned int k = 0; k < fields.size(); ++k)
              {
                const std::string where_column = where + ", column " + std::to_string(k + 1);
                check_input(std::find(names.begin(), names.end(), fields[k]) != names.end(),
                            where_column,
                            fields[k],
                            "a column name of a " + std::to_string(dim) + "D grain file: " + known);
                check_input(column.count(fields[k]) == 0, where_column, fields[k], "each column once");
                column[fields[k]] = k;
              }
            for (const auto &name : names)
              check_input(column.count(name) == 1,
                          where + " (the header)",
                          trimmed,
                          "a column '" + name + "' (columns: " + known + ")");
            n_fields = fields.size();
            continue;
          }
        check_input(fields.size() == n_fields,
                    where,
                    trimmed,
                    std::to_string(n_fields) + " fields, as the header names");
        const auto number = [&](const std::string &name) {
          const std::string &field = fields[column.at(name)];
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
          check_input(used > 0 && used == field.size() && std::isfinite(value),
                      where + ", column " + std::to_string(column.at(name) + 1) + " (" + name + ")",
                      field,
                      "a number");
          return value;
        };
        Grain<dim> grain;
        for (unsigned int d = 0; d < dim; ++d)
          grain.centre[d] = number(names[d]);
        grain.radius = number("radius");
        grain.line   = line;
        check_input(grain.radius > 0,
                    where + ", column " + std::to_string(column.at("radius") + 1) + " (radius)",
                    grain.radius,
                    "a number > 0 (m)");
        grains.push_back(grain);
      }
    check_input(!grains.empty(), filename, "no grains", "a header line and at least one grain");
    return grains;
  }

  template std::vector<Grain<2>>
  read_grain_file<2>(const std::string &);
  template std::vector<Grain<3>>
  read_grain_file<3>(const std::string &);
} // namespace sable::mpm
