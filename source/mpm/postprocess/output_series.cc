#include <deal.II/base/utilities.h>

#include <sable/mpm/postprocess/output_series.h>

#include <fstream>

namespace sable::mpm
{
  OutputSeries::OutputSeries(const std::string &directory,
                             const std::string &name,
                             const OutputFormat format)
    : directory(directory)
    , name(name)
    , format(format)
  {}

  std::string
  OutputSeries::series_file() const
  {
    return name + (format == OutputFormat::hdf5 ? ".xdmf" : ".pvd");
  }

  template <int patch_dim, int spacedim>
  void
  OutputSeries::write(const DataOutInterface<patch_dim, spacedim> &data_out,
                      const bool                                   has_patches,
                      const unsigned int                           counter,
                      const double                                 time,
                      const MPI_Comm                               communicator)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    if (format == OutputFormat::vtu)
      {
        files.emplace_back(time,
                           data_out.write_vtu_with_pvtu_record(
                             directory + "/", name, counter, communicator, 5));
        if (rank == 0)
          {
            std::ofstream pvd(directory + "/" + name + ".pvd");
            DataOutBase::write_pvd_record(pvd, files);
          }
        return;
      }

    // one file for all ranks; no merging of vertices at the same place
    // (material points may share a location, and cell data must stay with
    // its cell)
    const std::string  file = name + "_" + Utilities::int_to_string(counter, 5) + ".h5";
    const unsigned int first_writer =
      Utilities::MPI::min(has_patches ? rank : numbers::invalid_unsigned_int, communicator);
    if (first_writer == numbers::invalid_unsigned_int)
      return;
    MPI_Comm writers;
    MPI_Comm_split(communicator, has_patches ? 0 : MPI_UNDEFINED, rank, &writers);
    XDMFEntry entry;
    if (has_patches)
      {
        DataOutBase::DataOutFilter filter(
          DataOutBase::DataOutFilterFlags(/*filter_duplicate_vertices=*/false,
                                          /*xdmf_hdf5_output=*/true));
        data_out.write_filtered_data(filter);
        data_out.write_hdf5_parallel(filter, directory + "/" + file, writers);
        entry = data_out.create_xdmf_entry(filter, file, time, writers);
        MPI_Comm_free(&writers);
      }
    xdmf_entries.push_back(Utilities::MPI::broadcast(communicator, entry, first_writer));
    if (rank == 0)
      data_out.write_xdmf_file(xdmf_entries, directory + "/" + name + ".xdmf", MPI_COMM_SELF);
  }

  template void
  OutputSeries::write(const DataOutInterface<0, 2> &, bool, unsigned int, double, MPI_Comm);
  template void
  OutputSeries::write(const DataOutInterface<0, 3> &, bool, unsigned int, double, MPI_Comm);
  template void
  OutputSeries::write(const DataOutInterface<2, 2> &, bool, unsigned int, double, MPI_Comm);
  template void
  OutputSeries::write(const DataOutInterface<3, 3> &, bool, unsigned int, double, MPI_Comm);
} // namespace sable::mpm
