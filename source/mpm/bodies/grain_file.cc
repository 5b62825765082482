#include <sable/base/csv_columns.h>
#include <sable/base/input_error.h>
#include <sable/mpm/bodies/grain_file.h>

namespace sable::mpm
{
  template <int dim>
  std::vector<Grain<dim>>
  read_grain_file(const std::string &filename)
  {
    const std::vector<std::string> names =
      dim == 2 ? std::vector<std::string>{"x", "y", "radius"} :
                 std::vector<std::string>{"x", "y", "z", "radius"};
    std::vector<Grain<dim>> grains;
    read_csv_columns(filename,
                     std::to_string(dim) + "D grain file",
                     names,
                     names,
                     nullptr,
                     [&](const CsvRow &row) {
                       Grain<dim> grain;
                       for (unsigned int d = 0; d < dim; ++d)
                         grain.centre[d] = row.number(names[d]);
                       grain.radius = row.number("radius");
                       grain.line   = row.line();
                       check_input(grain.radius > 0,
                                   row.place("radius"),
                                   grain.radius,
                                   "a number > 0 (m)");
                       grains.push_back(grain);
                     });
    check_input(!grains.empty(), filename, "no grains", "a header line and at least one grain");
    return grains;
  }

  template std::vector<Grain<2>>
  read_grain_file<2>(const std::string &);
  template std::vector<Grain<3>>
  read_grain_file<3>(const std::string &);
} // namespace sable::mpm
