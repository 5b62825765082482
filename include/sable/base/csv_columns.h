#ifndef sable_base_csv_columns_h
#define sable_base_csv_columns_h

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sable
{
  /// One data line of a file read by read_csv_columns().
  class CsvRow
  {
  public:
    /// "file, line N", for messages.
    const std::string &
    where() const
    {
      return location;
    }

    /// The file line.
    unsigned int
    line() const
    {
      return line_number;
    }

    bool
    has(const std::string &name) const
    {
      return columns.count(name) == 1;
    }

    /// "file, line N, column K (name)", for messages about a value.
    std::string
    place(const std::string &name) const;

    /// The named field as a finite number; otherwise an InputError naming
    /// the place and the field.
    double
    number(const std::string &name) const;

  private:
    friend void
    read_csv_columns(const std::string &,
                     const std::string &,
                     const std::vector<std::string> &,
                     const std::vector<std::string> &,
                     const std::function<void(const std::string &, const std::string &,
                                              const std::map<std::string, unsigned int> &)> &,
                     const std::function<void(const CsvRow &)> &);

    std::string                                location;
    unsigned int                               line_number = 0;
    std::map<std::string, unsigned int>        columns;
    std::vector<std::string>                   fields;
  };

  /**
   * Read a CSV file whose first line that is not blank or a '#' comment
   * names its columns in any order, each of @p allowed at most once and
   * every one of @p required; then call @p row for each data line (blank
   * and '#' lines skipped). @p what names the file in messages ("2D points
   * file"). An unopenable file, an unknown, repeated or missing column
   * and a line with another number of fields than the header are an
   * InputError naming the file and line; @p check_header (where, header
   * line, column indices) may refuse more.
   */
  void
  read_csv_columns(const std::string &                                             filename,
                   const std::string &                                             what,
                   const std::vector<std::string> &                                allowed,
                   const std::vector<std::string> &                                required,
                   const std::function<void(const std::string &, const std::string &,
                                            const std::map<std::string, unsigned int> &)> &check_header,
                   const std::function<void(const CsvRow &)> &                     row);
} // namespace sable

#endif
