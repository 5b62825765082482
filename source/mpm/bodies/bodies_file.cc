#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/mpm/bodies/bodies_file.h>
#include <sable/mpm/bodies/grain_file.h>
#include <sable/mpm/parameter_tools.h>

#include <filesystem>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    /// "Lower x wall velocity", ... for face 2 d + side
    std::string
    wall_entry(const unsigned int face)
    {
      return std::string(face % 2 == 0 ? "Lower " : "Upper ") + "xyz"[face / 2] + " wall velocity";
    }
  } // namespace

  template <int dim>
  void
  BodiesFile<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("File",
                      "",
                      Patterns::Anything(),
                      "Empty (no bodies from a file), or a CSV file of "
                      "grains, one disk (2D) or sphere (3D) body per row: a "
                      "header naming the columns x, y (, z), radius (m), "
                      "then one row per grain; lines starting with '#' are "
                      "skipped (contrib/packs/disk_pack.py writes such "
                      "files). The bodies come after those of the 'Body k' "
                      "subsections (Number of bodies counts only these), "
                      "all with the entries of this subsection, and have no "
                      "columns of their own in statistics.csv. A relative "
                      "path is read from the parameter file's folder.");
    for (unsigned int face = 0; face < 2 * dim; ++face)
      prm.declare_entry(wall_entry(face),
                        "",
                        Patterns::Anything(),
                        "Empty: no grain of the file may reach beyond this "
                        "face of the grid. Else m/s (" + std::to_string(dim) +
                          " numbers): the grains that do (their centres "
                          "inside the grid) are held by the face: bodies "
                          "of prescribed velocity (see 'Body k/Prescribed "
                          "velocity') moving with this velocity, seeded "
                          "only inside the grid.");
    prm.declare_entry("Wall velocity start time",
                      "0",
                      Patterns::Double(),
                      "s, >= 0: when the grains held by the faces start to "
                      "move with their wall velocity (at rest before).");
    BodyParameters<dim>::declare_template_parameters(prm);
  }

  template <int dim>
  void
  BodiesFile<dim>::parse_parameters(ParameterHandler &prm)
  {
    const std::string path = "Bodies file/";
    file                   = Utilities::trim(prm.get("File"));
    holds.assign(2 * dim, false);
    wall_velocities.assign(2 * dim, Tensor<1, dim>());
    for (unsigned int face = 0; face < 2 * dim; ++face)
      if (!Utilities::trim(prm.get(wall_entry(face))).empty())
        {
          holds[face]           = true;
          wall_velocities[face] = read_vector<dim>(prm, wall_entry(face), path);
        }
    wall_start_time = prm.get_double("Wall velocity start time");
    check_input(wall_start_time >= 0, path + "Wall velocity start time", wall_start_time, "a number >= 0 (s)");
    // the template's entries matter (and are checked) only with a file
    if (!file.empty())
      {
        body_template.parse_template_parameters(prm, path);
        body_template.radius = 1; // each grain's is checked as it is read
        body_template.check(path);
      }
  }

  template <int dim>
  std::vector<BodyParameters<dim>>
  BodiesFile<dim>::create_bodies(const std::string &          folder,
                                 const Point<dim> &           lower,
                                 const Point<dim> &           upper,
                                 const std::array<bool, dim> &periodic) const
  {
    std::vector<BodyParameters<dim>> bodies;
    if (file.empty())
      return bodies;
    for (unsigned int face = 0; face < 2 * dim; ++face)
      if (holds[face] && periodic[face / 2])
        check_input(false,
                    "Bodies file/" + wall_entry(face),
                    "given",
                    "empty: the faces of a periodic axis (Grid/Periodic axes) hold no "
                    "grains");
    const std::filesystem::path path(file);
    const std::string           found =
      path.is_absolute() || folder.empty() ? file : (std::filesystem::path(folder) / path).string();
    std::vector<Grain<dim>> grains;
    try
      {
        grains = read_grain_file<dim>(found);
      }
    catch (const InputError &error)
      {
        check_input(false, "Bodies file/File", file, error.what());
      }

    std::ostringstream grid_box;
    grid_box << "[" << lower << "] - [" << upper << "]";
    bodies.reserve(grains.size());
    for (const Grain<dim> &grain : grains)
      {
        const std::string where = found + ", line " + std::to_string(grain.line);
        std::ostringstream centre;
        centre << grain.centre;
        for (unsigned int d = 0; d < dim; ++d)
          check_input(grain.centre[d] >= lower[d] && grain.centre[d] <= upper[d],
                      where + " (x, y" + (dim == 3 ? ", z" : "") + ")",
                      centre.str(),
                      "a grain centre inside the grid " + grid_box.str());
        BodyParameters<dim> body = body_template;
        body.shape               = BodyParameters<dim>::Shape::disk;
        body.center              = grain.centre;
        body.radius              = grain.radius;
        body.statistics_columns  = false;
        body.origin              = where + ": ";
        unsigned int held_by     = numbers::invalid_unsigned_int;
        for (unsigned int face = 0; face < 2 * dim; ++face)
          {
            const unsigned int d = face / 2;
            // a grain crossing a periodic face is seeded wrapped
            if (periodic[d])
              continue;
            const bool beyond    = face % 2 == 0 ? grain.centre[d] - grain.radius < lower[d] :
                                                   grain.centre[d] + grain.radius > upper[d];
            if (!beyond)
              continue;
            check_input(holds[face],
                        where + " (radius)",
                        grain.radius,
                        "a grain inside the grid " + grid_box.str() +
                          ", or one reaching beyond a face that holds grains "
                          "(Bodies file/" + wall_entry(face) + " is empty)");
            if (held_by != numbers::invalid_unsigned_int)
              check_input(false,
                          where + " (radius)",
                          grain.radius,
                          "a grain reaching beyond one face of the grid (it "
                          "crosses those of Bodies file/" + wall_entry(held_by) + " and " +
                            wall_entry(face) + ")");
            held_by = face;
          }
        if (held_by != numbers::invalid_unsigned_int)
          {
            body.clipped_by_grid       = true;
            body.prescribed            = true;
            body.prescribed_velocity   = wall_velocities[held_by];
            body.prescribed_start_time = wall_start_time;
            body.velocity              = Tensor<1, dim>();
            body.angular_velocity      = Tensor<1, 3>();
          }
        bodies.push_back(body);
      }
    return bodies;
  }

  template struct BodiesFile<2>;
  template struct BodiesFile<3>;
} // namespace sable::mpm
