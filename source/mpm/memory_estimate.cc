#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <sable/base/input_error.h>
#include <sable/mpm/memory_estimate.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace sable::mpm
{
  namespace
  {
    std::string
    gigabytes(const double bytes)
    {
      std::ostringstream text;
      text << std::setprecision(3) << bytes / 1e9 << " GB";
      return text.str();
    }

    /// MemAvailable of /proc/meminfo, else the free pages.
    double
    host_available_memory()
    {
      std::ifstream in("/proc/meminfo");
      std::string   name, unit;
      double        kilobytes = 0;
      while (in >> name >> kilobytes >> unit)
        if (name == "MemAvailable:")
          return kilobytes * 1024.;
      return static_cast<double>(::sysconf(_SC_AVPHYS_PAGES)) * ::sysconf(_SC_PAGESIZE);
    }
  } // namespace


  template <int dim>
  MemoryEstimate
  estimate_memory(const Scene<dim> &scene)
  {
    const GridParameters<dim> &grid = scene.grid;
    MemoryEstimate             estimate;
    estimate.cells     = 1;
    double cell_volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        estimate.cells *= grid.subdivisions[d];
        cell_volume *= (grid.upper_corner[d] - grid.lower_corner[d]) / grid.subdivisions[d];
      }
    const double grid_bytes = estimate.cells * bytes_per_cell[dim - 2];
    estimate.entry          = "Grid/Subdivisions";
    for (unsigned int d = 0; d < dim; ++d)
      estimate.value += (d ? ", " : "") + std::to_string(grid.subdivisions[d]);

    double largest = 0;
    const auto &bodies = scene.simulator.bodies;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const BodyParameters<dim> &body = bodies[b];
        double                     volume = 1;
        if (body.shape == BodyParameters<dim>::Shape::box)
          for (unsigned int d = 0; d < dim; ++d)
            volume *= body.upper_corner[d] - body.lower_corner[d];
        else if (body.shape == BodyParameters<dim>::Shape::mesh)
          volume = body.mesh.measure();
        else
          volume = (dim == 2 ? M_PI : 4. / 3. * M_PI) * std::pow(body.radius, dim);
        const double points =
          body.shape == BodyParameters<dim>::Shape::points ?
            body.cloud.positions.size() :
            volume / cell_volume * std::pow(double(body.particles_per_direction), dim);
        estimate.material_points += points;
        if (points > largest)
          {
            largest = points;
            if (points * bytes_per_material_point[dim - 2] > grid_bytes)
              {
                const bool file = body.shape == BodyParameters<dim>::Shape::points;
                estimate.entry  = "Body " + std::to_string(b) +
                                 (file ? "/Points file" : "/Particles per cell direction");
                estimate.value = file ? body.points_file : std::to_string(body.particles_per_direction);
              }
          }
      }
    estimate.bytes = grid_bytes + estimate.material_points * bytes_per_material_point[dim - 2];
    return estimate;
  }


  double
  available_memory(MPI_Comm communicator)
  {
    // one rank per host counts its host's memory
    MPI_Comm host;
    MPI_Comm_split_type(communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
    const bool first_on_host = dealii::Utilities::MPI::this_mpi_process(host) == 0;
    MPI_Comm_free(&host);
    return dealii::Utilities::MPI::sum(first_on_host ? host_available_memory() : 0., communicator);
  }


  template <int dim>
  void
  check_memory(const Scene<dim> &scene, MPI_Comm communicator)
  {
    const MemoryEstimate estimate  = estimate_memory(scene);
    const double         available = available_memory(communicator);
    if (estimate.bytes <= available)
      return;
    std::ostringstream message;
    message << std::setprecision(3) << "invalid input: '" << estimate.entry << " = "
            << estimate.value << "'; allowed: a scene that fits into memory. It needs at least "
            << gigabytes(estimate.bytes) << " (" << estimate.cells << " cells at "
            << bytes_per_cell[dim - 2] << " bytes, " << estimate.material_points
            << " material points at " << bytes_per_material_point[dim - 2]
            << " bytes), the machine has " << gigabytes(available)
            << " available (MemAvailable in /proc/meminfo, summed over the hosts of the run)";
    throw InputError(message.str());
  }

  template MemoryEstimate estimate_memory<2>(const Scene<2> &);
  template MemoryEstimate estimate_memory<3>(const Scene<3> &);
  template void check_memory<2>(const Scene<2> &, MPI_Comm);
  template void check_memory<3>(const Scene<3> &, MPI_Comm);
} // namespace sable::mpm
