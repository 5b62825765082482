#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/mpm/bodies/point_file.h>

#include <fstream>
#include <cmath>
#include <map>
#include <set>

namespace sable::mpm
{
  template <int dim>
  PointCloud<dim>
  read_point_file(const std::string &filename)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("invalid input: cannot open the points file '" + filename + "'");

    const std::vector<std::string> coordinates =
      dim == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
    const std::vector<std::string> velocity =
      dim == 2 ? std::vector<std::string>{"vx", "vy"} : std::vector<std::string>{"vx", "vy", "vz"};
    std::set<std::string> names;
    std::string           known;
    for (const auto &group : {coordinates, std::vector<std::string>{"volume"}, velocity})
      for (const auto &name : group)
        {
          names.insert(name);
          known += (known.empty() ? "" : ", ") + name;
        }

    PointCloud<dim>                     cloud;
    std::map<std::string, unsigned int> column; // name -> field index
    std::string                         text;
    unsigned int                        n_fields = 0;
    for (unsigned int line = 1; std::getline(in, text); ++line)
      {
        const std::string where = filename + ", line " + std::to_string(line);
        const std::string trimmed = Utilities::trim(text);
        if (trimmed.empty() || trimmed[0] == '#')
          continue;
        std::vector<std::string> fields = Utilities::split_string_list(trimmed, ',');
        if (column.empty())
          {
            // the header
            for (unsigned int k = 0; k < fields.size(); ++k)
              {
                const std::string &name = fields[k];
                check_input(names.count(name) == 1,
                            where + ", column " + std::to_string(k + 1),
                            name,
                            "a column name of a " + std::to_string(dim) + "D points file: " + known);
                check_input(column.count(name) == 0,
                            where + ", column " + std::to_string(k + 1),
                            name,
                            "each column once");
                column[name] = k;
              }
            for (const auto &name : coordinates)
              check_input(column.count(name) == 1,
                          where + " (the header)",
                          trimmed,
                          "a column '" + name + "' (columns: " + known + ")");
            check_input(column.count("volume") == 1,
                        where + " (the header)",
                        trimmed,
                        "a column 'volume' (columns: " + known + ")");
            unsigned int n_velocity = 0;
            for (const auto &name : velocity)
              n_velocity += column.count(name);
            check_input(n_velocity == 0 || n_velocity == dim,
                        where + " (the header)",
                        trimmed,
                        "all velocity columns (" + velocity.front() + " ... " + velocity.back() +
                          ") or none");
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
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = number(coordinates[d]);
        const double volume = number("volume");
        check_input(volume > 0,
                    where + ", column " + std::to_string(column.at("volume") + 1) + " (volume)",
                    volume,
                    "a number > 0 (m^" + std::to_string(dim) + ")");
        cloud.positions.push_back(x);
        cloud.volumes.push_back(volume);
        if (column.count(velocity[0]))
          {
            Tensor<1, dim> v;
            for (unsigned int d = 0; d < dim; ++d)
              v[d] = number(velocity[d]);
            cloud.velocities.push_back(v);
          }
      }
    check_input(!cloud.positions.empty(), filename, "no points", "a header line and at least one point");
    return cloud;
  }

  template PointCloud<2>
  read_point_file<2>(const std::string &);
  template PointCloud<3>
  read_point_file<3>(const std::string &);
} // namespace sable::mpm
