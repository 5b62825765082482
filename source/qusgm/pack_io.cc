// Packs and run states in files (see sable/qusgm/pack_io.h).
#include <sable/base/input_error.h>
#include <sable/qusgm/pack_io.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <numeric>
#include <sstream>

namespace sable::qusgm
{
  namespace
  {
    std::string
    lower(std::string s)
    {
      for (char &c : s)
        c = std::tolower(static_cast<unsigned char>(c));
      return s;
    }

    /// Fields separated by commas, semicolons, blanks or tabs.
    std::vector<std::string>
    split_fields(const std::string &line)
    {
      std::vector<std::string> fields;
      std::string              field;
      for (const char c : line)
        if (c == ',' || c == ';' || c == ' ' || c == '\t' || c == '\r' || c == '\n')
          {
            if (!field.empty())
              fields.push_back(field);
            field.clear();
          }
        else
          field += c;
      if (!field.empty())
        fields.push_back(field);
      return fields;
    }

    bool
    parse_double(const std::string &token, double &value)
    {
      if (token.empty())
        return false;
      char *end = nullptr;
      value     = std::strtod(token.c_str(), &end);
      return end != token.c_str() && *end == '\0';
    }

    bool
    parse_id(const std::string &token, std::uint64_t &value)
    {
      if (token.empty() || !std::isdigit(static_cast<unsigned char>(token[0])))
        return false;
      char *end = nullptr;
      errno     = 0;
      value     = std::strtoull(token.c_str(), &end, 10);
      return errno == 0 && *end == '\0';
    }

    std::string
    join(const std::vector<std::string> &words, const std::string &separator = " ")
    {
      std::string text;
      for (std::size_t k = 0; k < words.size(); ++k)
        text += (k ? separator : "") + words[k];
      return text;
    }

    /**
     * A column a table may have: its names (lower case), the quantity it
     * gives (columns of one quantity exclude each other) and whether some
     * column of that quantity is required.
     */
    struct ColumnSpec
    {
      std::vector<std::string> names;
      std::string              quantity;
      bool                     required;
    };

    /// Name the columns a spec understands, for messages.
    std::string
    known_names(const std::vector<ColumnSpec> &spec)
    {
      std::vector<std::string> names;
      for (const ColumnSpec &c : spec)
        names.push_back(join(c.names, "|"));
      return join(names, ", ");
    }

    /**
     * The spec entry of each header word, refusing unknown words, a column
     * given twice, two columns for one quantity, and a missing required
     * quantity. @p where is "<file>, line <n>".
     */
    std::vector<unsigned int>
    map_header(const std::vector<std::string> &words,
               const std::vector<ColumnSpec>  &spec,
               const std::string              &where)
    {
      std::vector<unsigned int>          roles;
      std::map<std::string, unsigned int> quantity_column;
      for (unsigned int k = 0; k < words.size(); ++k)
        {
          const std::string name = lower(words[k]);
          unsigned int      role  = spec.size();
          for (unsigned int s = 0; s < spec.size() && role == spec.size(); ++s)
            if (std::find(spec[s].names.begin(), spec[s].names.end(), name) !=
                spec[s].names.end())
              role = s;
          const std::string column = where + ", column " + std::to_string(k + 1);
          check_input(role < spec.size(),
                      column,
                      words[k],
                      "a column name sable knows: " + known_names(spec) +
                        " (case-blind); say what each column holds, or remove it");
          const auto before = quantity_column.find(spec[role].quantity);
          if (before != quantity_column.end())
            check_input(false,
                        column,
                        words[k],
                        "one column per quantity: column " +
                          std::to_string(before->second + 1) + " '" +
                          words[before->second] + "' already gives the " +
                          spec[role].quantity);
          quantity_column[spec[role].quantity] = k;
          roles.push_back(role);
        }
      for (const ColumnSpec &c : spec)
        check_input(!c.required || quantity_column.count(c.quantity),
                    where + " (the header)",
                    join(words),
                    "a column for the " + c.quantity + " (" + join(c.names, " or ") + ")");
      return roles;
    }

    /// The columns of a pack file (Yade's matId only in Yade's files).
    enum PackColumn
    {
      col_x,
      col_y,
      col_z,
      col_radius,
      col_diameter,
      col_e,
      col_nu,
      col_rho,
      col_id,
      col_material_id
    };

    std::vector<ColumnSpec>
    pack_spec(const bool yade)
    {
      std::vector<ColumnSpec> spec = {{{"x"}, "x coordinate", true},
                                      {{"y"}, "y coordinate", true},
                                      {{"z"}, "z coordinate", true},
                                      {{"r", "radius"}, "grain size", true},
                                      {{"diameter"}, "grain size", true},
                                      {{"e", "youngs_modulus"}, "Young's modulus", false},
                                      {{"nu", "poisson_ratio"}, "Poisson's ratio", false},
                                      {{"rho", "density"}, "density", false},
                                      {{"id"}, "grain id", false}};
      if (yade)
        spec.push_back({{"matid"}, "Yade material id", false});
      return spec;
    }

    bool
    is_pack_column(const std::string &word)
    {
      const std::string name = lower(word);
      for (const ColumnSpec &c : pack_spec(true))
        if (std::find(c.names.begin(), c.names.end(), name) != c.names.end())
          return true;
      return false;
    }

    /// Number of a field, or an InputError naming file, line and column.
    double
    number(const std::vector<std::string> &fields,
           const unsigned int              k,
           const std::string              &where,
           const std::string              &column_name)
    {
      double value = 0;
      check_input(parse_double(fields[k], value),
                  where + ", column " + std::to_string(k + 1) + " (" + column_name + ")",
                  fields[k],
                  "a number");
      return value;
    }

    std::uint64_t
    id_number(const std::vector<std::string> &fields,
              const unsigned int              k,
              const std::string              &where,
              const std::string              &column_name)
    {
      std::uint64_t value = 0;
      check_input(parse_id(fields[k], value),
                  where + ", column " + std::to_string(k + 1) + " (" + column_name + ")",
                  fields[k],
                  "a whole number >= 0");
      return value;
    }

    /// Pack file of columns (named, Yade or four plain numbers).
    Pack
    read_columns(std::istream        &in,
                 const std::string   &source,
                 const GrainDefaults &defaults,
                 std::string         &description)
    {
      std::vector<std::string>  header, comment_header;
      std::vector<unsigned int> roles;
      unsigned int              comment_header_line = 0, header_line = 0, yade_line = 0;
      std::string               yade_format;
      bool                      header_known = false, yade = false;
      Pack                      pack;
      std::string               line;
      unsigned int              line_number = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string where = source + ", line " + std::to_string(line_number);
          const auto        first = line.find_first_not_of(" \t\r");
          if (first == std::string::npos)
            continue;
          if (line[first] == '#')
            {
              if (header_known)
                continue;
              const std::vector<std::string> words = split_fields(line.substr(first + 1));
              if (line.compare(first, 7, "#format") == 0 && words.size() >= 2)
                {
                  yade_format = words[1];
                  yade_line   = line_number;
                }
              else if (words.size() >= 4 && is_pack_column(words[0]))
                {
                  comment_header      = words;
                  comment_header_line = line_number;
                }
              continue;
            }
          const std::vector<std::string> fields = split_fields(line);
          if (!header_known)
            {
              double dummy;
              header_known = true;
              if (!parse_double(fields[0], dummy))
                {
                  header      = fields;
                  header_line = line_number;
                  roles       = map_header(header, pack_spec(false), where);
                  continue;
                }
              if (!yade_format.empty() && yade_format != "x_y_z_r_attrs")
                {
                  std::istringstream       parts(yade_format);
                  std::string              part;
                  while (std::getline(parts, part, '_'))
                    header.push_back(part);
                  header_line = yade_line;
                  yade        = true;
                }
              else if (!comment_header.empty())
                {
                  header      = comment_header;
                  header_line = comment_header_line;
                  yade        = !yade_format.empty();
                }
              else
                check_input(yade_format.empty(),
                            source,
                            "#format " + yade_format,
                            "Yade's x_y_z_r_attrs files with the comment line "
                            "'# x y z r ...' naming the columns");
              if (!header.empty())
                {
                  roles = map_header(header,
                                     pack_spec(yade),
                                     source + ", line " + std::to_string(header_line));
                }
            }
          if (header.empty())
            {
              std::vector<double> values(fields.size());
              bool                numeric = fields.size() == 4;
              for (unsigned int k = 0; k < fields.size() && numeric; ++k)
                numeric = parse_double(fields[k], values[k]);
              check_input(numeric,
                          where,
                          line,
                          "four numbers x y z r, or a header line naming the "
                          "columns (" +
                            known_names(pack_spec(false)) + ")");
              pack.add_grain(Point<3>(values[0], values[1], values[2]),
                             values[3],
                             defaults.youngs_modulus,
                             defaults.poisson_ratio,
                             defaults.density);
              continue;
            }
          check_input(fields.size() == header.size(),
                      where,
                      line,
                      std::to_string(header.size()) + " fields, as the header on line " +
                        std::to_string(header_line) + " names: " + join(header));
          std::array<double, col_material_id> value{};
          value[col_e]   = defaults.youngs_modulus;
          value[col_nu]  = defaults.poisson_ratio;
          value[col_rho] = defaults.density;
          std::uint64_t id = pack.size();
          for (unsigned int k = 0; k < fields.size(); ++k)
            if (roles[k] == col_id)
              id = id_number(fields, k, where, header[k]);
            else if (roles[k] != col_material_id)
              value[roles[k]] = number(fields, k, where, header[k]);
          const bool by_diameter =
            std::find(roles.begin(), roles.end(), col_diameter) != roles.end();
          pack.add_grain(Point<3>(value[col_x], value[col_y], value[col_z]),
                         by_diameter ? 0.5 * value[col_diameter] : value[col_radius],
                         value[col_e],
                         value[col_nu],
                         value[col_rho],
                         id);
        }
      if (header.empty())
        description = "columns x y z r (no header)";
      else
        description = (yade ? "Yade text export, columns " : "columns ") + join(header);
      return pack;
    }

    /// The last snapshot of a LAMMPS/LIGGGHTS text dump.
    Pack
    read_lammps_dump(std::istream        &in,
                     const std::string   &source,
                     const GrainDefaults &defaults,
                     std::string         &description)
    {
      struct Snapshot
      {
        std::string                           timestep;
        std::size_t                           n_atoms = 0;
        std::array<double, 6>                 box{};
        bool                                  have_box = false, triclinic = false;
        std::vector<std::string>              columns;
        unsigned int                          columns_line = 0;
        std::vector<std::pair<unsigned int, std::vector<std::string>>> rows;
      } snapshot;
      std::string  line;
      unsigned int line_number = 0;
      auto         next_line = [&](const std::string &what) {
        const bool ok = static_cast<bool>(std::getline(in, line));
        ++line_number;
        check_input(ok,
                    source + ", line " + std::to_string(line_number),
                    "(end of file)",
                    what);
        return split_fields(line);
      };
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string where = source + ", line " + std::to_string(line_number);
          if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
          check_input(line.rfind("ITEM:", 0) == 0,
                      where,
                      line,
                      "an 'ITEM:' line of a LAMMPS dump (the snapshot before it has "
                      "more atoms than its 'NUMBER OF ATOMS')");
          const std::string item = line.substr(5);
          if (item.find("TIMESTEP") != std::string::npos)
            {
              snapshot          = Snapshot(); // only the last one is kept
              const auto fields = next_line("the timestep");
              snapshot.timestep = fields.empty() ? "" : fields[0];
            }
          else if (item.find("NUMBER OF ATOMS") != std::string::npos)
            {
              const auto    fields = next_line("the number of atoms");
              std::uint64_t n      = 0;
              check_input(fields.size() == 1 && parse_id(fields[0], n),
                          source + ", line " + std::to_string(line_number),
                          line,
                          "the number of atoms");
              snapshot.n_atoms = n;
            }
          else if (item.find("BOX BOUNDS") != std::string::npos)
            {
              snapshot.triclinic = item.find("xy") != std::string::npos;
              for (unsigned int a = 0; a < 3; ++a)
                {
                  const auto fields = next_line("three lines of box bounds");
                  bool       ok     = fields.size() >= 2;
                  for (unsigned int k = 0; k < 2 && ok; ++k)
                    ok = parse_double(fields[k], snapshot.box[2 * a + k]);
                  check_input(ok,
                              source + ", line " + std::to_string(line_number),
                              line,
                              "box bounds: lo hi [tilt]");
                }
              snapshot.have_box = true;
            }
          else if (item.find("ATOMS") != std::string::npos)
            {
              snapshot.columns      = split_fields(item.substr(item.find("ATOMS") + 5));
              snapshot.columns_line = line_number;
              for (std::size_t k = 0; k < snapshot.n_atoms; ++k)
                {
                  const auto fields = next_line(std::to_string(snapshot.n_atoms) +
                                                " atom lines ('NUMBER OF ATOMS')");
                  check_input(fields.size() == snapshot.columns.size(),
                              source + ", line " + std::to_string(line_number),
                              line,
                              std::to_string(snapshot.columns.size()) +
                                " fields, as the ATOMS line " +
                                std::to_string(snapshot.columns_line) + " names");
                  snapshot.rows.emplace_back(line_number, fields);
                }
            }
          else
            next_line("the value of " + line); // UNITS, TIME: one line each
        }
      const Snapshot &last = snapshot;
      check_input(last.rows.size() == last.n_atoms && !last.columns.empty(),
                  source,
                  "timestep " + last.timestep,
                  "a last snapshot with an ATOMS section of 'NUMBER OF ATOMS' lines");

      // Which column gives what: the first of the alternatives present.
      const std::string atoms_line = source + ", line " + std::to_string(last.columns_line);
      auto              find       = [&](const std::vector<std::string> &names) {
        for (const std::string &name : names)
          {
            const auto k = std::find(last.columns.begin(), last.columns.end(), name);
            if (k != last.columns.end())
              return std::make_pair(int(k - last.columns.begin()), name);
          }
        return std::make_pair(-1, std::string());
      };
      std::array<std::pair<int, std::string>, 3> coordinate;
      for (unsigned int a = 0; a < 3; ++a)
        {
          const std::string c = std::string(1, char('x' + a));
          coordinate[a]       = find({c, c + "u", c + "s", c + "su"});
          check_input(coordinate[a].first >= 0,
                      atoms_line,
                      "ITEM: ATOMS " + join(last.columns),
                      "a column " + c + ", " + c + "u, " + c + "s or " + c + "su");
          const bool scaled = coordinate[a].second.find('s') != std::string::npos;
          check_input(!scaled || (last.have_box && !last.triclinic),
                      atoms_line,
                      coordinate[a].second,
                      "scaled coordinates only with an orthogonal BOX BOUNDS section "
                      "(dump x y z instead)");
        }
      const auto radius = find({"radius"}), diameter = find({"diameter"});
      check_input(radius.first >= 0 || diameter.first >= 0,
                  atoms_line,
                  "ITEM: ATOMS " + join(last.columns),
                  "a column radius or diameter");
      check_input(radius.first < 0 || diameter.first < 0,
                  atoms_line,
                  "ITEM: ATOMS " + join(last.columns),
                  "one of radius and diameter (both give the grain size)");
      const auto id = find({"id"}), density = find({"density"}), mass = find({"mass"});

      struct Atom
      {
        std::uint64_t id;
        Point<3>      x;
        double        r, rho;
      };
      std::vector<Atom> atoms;
      for (std::size_t k = 0; k < last.rows.size(); ++k)
        {
          const auto &[row_line, fields] = last.rows[k];
          const std::string where        = source + ", line " + std::to_string(row_line);
          Atom              atom;
          atom.id = id.first >= 0 ? id_number(fields, id.first, where, "id") : k;
          for (unsigned int a = 0; a < 3; ++a)
            {
              atom.x[a] = number(fields, coordinate[a].first, where, coordinate[a].second);
              if (coordinate[a].second.find('s') != std::string::npos)
                atom.x[a] = last.box[2 * a] + atom.x[a] * (last.box[2 * a + 1] - last.box[2 * a]);
            }
          atom.r = radius.first >= 0 ? number(fields, radius.first, where, "radius") :
                                       0.5 * number(fields, diameter.first, where, "diameter");
          atom.rho = defaults.density;
          if (density.first >= 0)
            atom.rho = number(fields, density.first, where, "density");
          else if (mass.first >= 0)
            atom.rho = number(fields, mass.first, where, "mass") /
                       (4. / 3. * M_PI * atom.r * atom.r * atom.r);
          atoms.push_back(atom);
        }
      std::stable_sort(atoms.begin(), atoms.end(), [](const Atom &a, const Atom &b) {
        return a.id < b.id;
      });
      Pack pack;
      for (const Atom &atom : atoms)
        pack.add_grain(atom.x,
                       atom.r,
                       defaults.youngs_modulus,
                       defaults.poisson_ratio,
                       atom.rho,
                       atom.id);
      description = "LAMMPS dump, timestep " + last.timestep + ", columns " +
                    coordinate[0].second + " " + coordinate[1].second + " " +
                    coordinate[2].second + " " +
                    (radius.first >= 0 ? "radius" : "diameter") +
                    (density.first >= 0 ? " density" : mass.first >= 0 ? " mass" : "") +
                    (id.first >= 0 ? " id" : "");
      return pack;
    }

    /// A CSV file with a header of names: the rows with the spec entry of
    /// each column.
    struct NamedTable
    {
      std::vector<std::string>  header;
      std::vector<unsigned int> roles;
      struct Row
      {
        std::string              where;
        std::vector<std::string> fields;
      };
      std::vector<Row> rows;

      /// Column of spec entry @p role, or -1.
      int
      column(const unsigned int role) const
      {
        const auto k = std::find(roles.begin(), roles.end(), role);
        return k == roles.end() ? -1 : int(k - roles.begin());
      }
    };

    NamedTable
    read_named_table(const std::string &filename, const std::vector<ColumnSpec> &spec)
    {
      std::ifstream in(filename);
      check_input(static_cast<bool>(in),
                  "State file",
                  filename,
                  "an existing, readable file (a state directory written by sable)");
      NamedTable   table;
      std::string  line;
      unsigned int line_number = 0, header_line = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string where = filename + ", line " + std::to_string(line_number);
          const auto        first = line.find_first_not_of(" \t\r");
          if (first == std::string::npos || line[first] == '#')
            continue;
          const auto fields = split_fields(line);
          if (table.header.empty())
            {
              table.header = fields;
              header_line  = line_number;
              table.roles  = map_header(fields, spec, where);
              continue;
            }
          check_input(fields.size() == table.header.size(),
                      where,
                      line,
                      std::to_string(table.header.size()) +
                        " fields, as the header on line " + std::to_string(header_line) +
                        " names: " + join(table.header));
          table.rows.push_back({where, fields});
        }
      check_input(!table.header.empty(), filename, "(empty)", "a header line of column names");
      return table;
    }

    void
    write_number(std::ostream &out, const double value)
    {
      out << ',' << value;
    }

    void
    check_written(std::ofstream &out, const std::string &filename)
    {
      out.close();
      if (!out)
        throw std::runtime_error("cannot write '" + filename + "'");
    }
  } // namespace


  Pack
  read_pack(const std::string   &filename,
            const GrainDefaults &defaults,
            std::string         *description)
  {
    std::ifstream in(filename);
    check_input(static_cast<bool>(in),
                "Pack file",
                filename,
                "an existing, readable file: columns by name (x y z r ...), a Yade "
                "text export or a LAMMPS dump");
    const std::string source = "Pack file " + filename;
    // A LAMMPS dump starts with an ITEM: line.
    std::string first_line;
    while (std::getline(in, first_line) &&
           first_line.find_first_not_of(" \t\r") == std::string::npos)
      ;
    in.clear();
    in.seekg(0);
    std::string what;
    Pack        pack = first_line.rfind("ITEM:", 0) == 0 ?
                         read_lammps_dump(in, source, defaults, what) :
                         read_columns(in, source, defaults, what);
    pack.check(source);
    if (description)
      *description = what;
    return pack;
  }


  void
  write_pack(const Pack &pack, const std::string &filename)
  {
    std::ofstream out(filename);
    out << "id,x,y,z,r,E,nu,rho\n" << std::setprecision(17);
    for (unsigned int i = 0; i < pack.size(); ++i)
      {
        out << pack.id[i];
        for (unsigned int a = 0; a < 3; ++a)
          write_number(out, pack.centre[i][a]);
        write_number(out, pack.radius[i]);
        write_number(out, pack.youngs_modulus[i]);
        write_number(out, pack.poisson_ratio[i]);
        write_number(out, pack.density[i]);
        out << '\n';
      }
    check_written(out, filename);
  }


  void
  write_state(const PackState &state, const std::string &directory)
  {
    namespace fs = std::filesystem;
    fs::create_directories(directory);
    const Pack &pack = state.pack;
    write_pack(pack, (fs::path(directory) / "grains.csv").string());
    {
      const std::string filename = (fs::path(directory) / "walls.csv").string();
      std::ofstream     out(filename);
      out << "wall,position,undeformed_length,normal_force\n" << std::setprecision(17);
      for (unsigned int w = 0; w < 6; ++w)
        {
          out << Walls::name(w);
          write_number(out, state.walls.position[w]);
          write_number(out, state.undeformed_lengths[Walls::axis(w)]);
          write_number(out, state.wall_force[w]);
          out << '\n';
        }
      check_written(out, filename);
    }
    const std::string load_columns =
      ",normal_force,overlap,tangential_force_x,tangential_force_y,"
      "tangential_force_z,torsional_couple\n";
    std::ofstream pairs((fs::path(directory) / "contacts.csv").string());
    std::ofstream walls((fs::path(directory) / "wall_contacts.csv").string());
    pairs << "i,j" << load_columns << std::setprecision(17);
    walls << "i,wall" << load_columns << std::setprecision(17);
    for (const ContactLoad &c : state.contacts)
      {
        std::ostream &out = c.wall ? walls : pairs;
        out << pack.id[c.i] << ',';
        if (c.wall)
          out << Walls::name(c.other);
        else
          out << pack.id[c.other];
        write_number(out, c.normal_force);
        write_number(out, c.overlap);
        for (unsigned int d = 0; d < 3; ++d)
          write_number(out, c.tangential_force[d]);
        write_number(out, c.torsional_couple);
        out << '\n';
      }
    check_written(pairs, (fs::path(directory) / "contacts.csv").string());
    check_written(walls, (fs::path(directory) / "wall_contacts.csv").string());
  }


  PackState
  read_state(const std::string &directory, const GrainDefaults &defaults)
  {
    namespace fs = std::filesystem;
    check_input(fs::is_directory(directory),
                "Pack/File (Source = state)",
                directory,
                "a state directory written by sable (e.g. output/<scene>/final_state)");
    PackState state;
    state.pack = read_pack((fs::path(directory) / "grains.csv").string(), defaults);
    const Pack &pack = state.pack;

    // Walls: each once, one undeformed length per axis.
    {
      const std::vector<ColumnSpec> spec = {{{"wall"}, "wall", true},
                                            {{"position"}, "position", true},
                                            {{"undeformed_length"}, "undeformed length", true},
                                            {{"normal_force"}, "normal force", false}};
      const NamedTable table =
        read_named_table((fs::path(directory) / "walls.csv").string(), spec);
      std::array<bool, 6> seen{};
      std::array<bool, 3> length_seen{};
      for (const auto &row : table.rows)
        {
          const int    k = table.column(0);
          unsigned int w = 6;
          for (unsigned int v = 0; v < 6; ++v)
            if (row.fields[k] == Walls::name(v))
              w = v;
          check_input(w < 6 && !seen[w],
                      row.where + ", column " + std::to_string(k + 1) + " (wall)",
                      row.fields[k],
                      "x_min, y_min, z_min, x_max, y_max or z_max, each once");
          seen[w]                 = true;
          state.walls.position[w] = number(row.fields, table.column(1), row.where, "position");
          const double length =
            number(row.fields, table.column(2), row.where, "undeformed_length");
          const unsigned int a = Walls::axis(w);
          check_input(length > 0 &&
                        (!length_seen[a] || length == state.undeformed_lengths[a]),
                      row.where + ", column " + std::to_string(table.column(2) + 1) +
                        " (undeformed_length)",
                      row.fields[table.column(2)],
                      "a length > 0, the same for both walls of an axis");
          state.undeformed_lengths[a] = length;
          length_seen[a]              = true;
          if (table.column(3) >= 0)
            state.wall_force[w] = number(row.fields, table.column(3), row.where, "normal_force");
        }
      for (unsigned int w = 0; w < 6; ++w)
        check_input(seen[w],
                    (fs::path(directory) / "walls.csv").string(),
                    std::string("no row for ") + Walls::name(w),
                    "one row per wall: x_min, y_min, z_min, x_max, y_max, z_max");
    }

    // Contacts, by grain id.
    std::map<std::uint64_t, unsigned int> index;
    for (unsigned int i = 0; i < pack.size(); ++i)
      index[pack.id[i]] = i;
    for (const bool wall : {false, true})
      {
        const std::string filename =
          (fs::path(directory) / (wall ? "wall_contacts.csv" : "contacts.csv")).string();
        const std::vector<ColumnSpec> spec = {
          {{"i"}, "first grain", true},
          {{wall ? "wall" : "j"}, wall ? "wall" : "second grain", true},
          {{"normal_force"}, "normal force", false},
          {{"overlap"}, "overlap", false},
          {{"tangential_force_x"}, "tangential force x", true},
          {{"tangential_force_y"}, "tangential force y", true},
          {{"tangential_force_z"}, "tangential force z", true},
          {{"torsional_couple"}, "torsional couple", true}};
        const NamedTable table = read_named_table(filename, spec);
        std::map<std::pair<unsigned int, unsigned int>, std::string> seen;
        for (const auto &row : table.rows)
          {
            ContactLoad c;
            c.wall          = wall;
            c.where         = row.where;
            const auto grain = [&](const unsigned int role) {
              const int         k  = table.column(role);
              const std::string name = role == 0 ? "i" : "j";
              const auto        id = id_number(row.fields, k, row.where, name);
              check_input(index.count(id),
                          row.where + ", column " + std::to_string(k + 1) + " (" + name + ")",
                          row.fields[k],
                          "the id of a grain in grains.csv");
              return index[id];
            };
            c.i = grain(0);
            if (wall)
              {
                const int k = table.column(1);
                c.other     = 6;
                for (unsigned int v = 0; v < 6; ++v)
                  if (row.fields[k] == Walls::name(v))
                    c.other = v;
                check_input(c.other < 6,
                            row.where + ", column " + std::to_string(k + 1) + " (wall)",
                            row.fields[k],
                            "x_min, y_min, z_min, x_max, y_max or z_max");
              }
            else
              {
                c.other = grain(1);
                check_input(c.other != c.i,
                            row.where + ", column " + std::to_string(table.column(1) + 1) +
                              " (j)",
                            row.fields[table.column(1)],
                            "a grain other than i");
              }
            for (unsigned int d = 0; d < 3; ++d)
              c.tangential_force[d] = number(row.fields,
                                             table.column(4 + d),
                                             row.where,
                                             spec[4 + d].names[0]);
            c.torsional_couple =
              number(row.fields, table.column(7), row.where, "torsional_couple");
            if (table.column(2) >= 0)
              c.normal_force = number(row.fields, table.column(2), row.where, "normal_force");
            if (table.column(3) >= 0)
              c.overlap = number(row.fields, table.column(3), row.where, "overlap");
            // A pair is stored from its lower index; the force on the other
            // grain is the opposite, the couple about the line from the
            // other grain is the same.
            if (!wall && c.other < c.i)
              {
                std::swap(c.i, c.other);
                c.tangential_force = -c.tangential_force;
              }
            const auto key    = std::make_pair(c.i, c.other);
            const auto before = seen.find(key);
            if (before != seen.end())
              check_input(false,
                          row.where,
                          join(row.fields, ","),
                          "each contact once (it is also on " + before->second + ")");
            seen[key] = row.where;
            state.contacts.push_back(c);
          }
      }
    return state;
  }
} // namespace sable::qusgm
