#include <sable/base/csv_columns.h>
#include <sable/base/input_error.h>
#include <sable/mpm/bodies/point_file.h>

namespace sable::mpm
{
  template <int dim>
  PointCloud<dim>
  read_point_file(const std::string &filename)
  {
    const std::vector<std::string> coordinates =
      dim == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
    const std::vector<std::string> velocity =
      dim == 2 ? std::vector<std::string>{"vx", "vy"} : std::vector<std::string>{"vx", "vy", "vz"};
    std::vector<std::string> allowed = coordinates, required = coordinates;
    allowed.push_back("volume");
    required.push_back("volume");
    allowed.insert(allowed.end(), velocity.begin(), velocity.end());

    const auto check_velocity_columns = [&](const std::string &                        where,
                                            const std::string &                        header,
                                            const std::map<std::string, unsigned int> &columns) {
      unsigned int n_velocity = 0;
      for (const auto &name : velocity)
        n_velocity += columns.count(name);
      check_input(n_velocity == 0 || n_velocity == dim,
                  where + " (the header)",
                  header,
                  "all velocity columns (" + velocity.front() + " ... " + velocity.back() +
                    ") or none");
    };

    PointCloud<dim> cloud;
    read_csv_columns(filename,
                     std::to_string(dim) + "D points file",
                     allowed,
                     required,
                     check_velocity_columns,
                     [&](const CsvRow &row) {
                       Point<dim> x;
                       for (unsigned int d = 0; d < dim; ++d)
                         x[d] = row.number(coordinates[d]);
                       const double volume = row.number("volume");
                       check_input(volume > 0,
                                   row.place("volume"),
                                   volume,
                                   "a number > 0 (m^" + std::to_string(dim) + ")");
                       cloud.positions.push_back(x);
                       cloud.volumes.push_back(volume);
                       if (row.has(velocity[0]))
                         {
                           Tensor<1, dim> v;
                           for (unsigned int d = 0; d < dim; ++d)
                             v[d] = row.number(velocity[d]);
                           cloud.velocities.push_back(v);
                         }
                     });
    check_input(!cloud.positions.empty(), filename, "no points", "a header line and at least one point");
    return cloud;
  }

  template PointCloud<2>
  read_point_file<2>(const std::string &);
  template PointCloud<3>
  read_point_file<3>(const std::string &);
} // namespace sable::mpm
