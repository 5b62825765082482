#ifndef sable_mpm_postprocess_output_series_h
#define sable_mpm_postprocess_output_series_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <sable/mpm/parameters.h>

#include <string>
#include <utility>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /**
   * One kind of output (material points, grid) over a run: writes the
   * files of one output time and keeps the series file up to date.
   *
   * - vtu: <name>_NNNNN.pvtu with one .vtu per rank, and <name>.pvd;
   * - hdf5: <name>_NNNNN.h5, written by all ranks together (MPI-IO,
   *   DataOutInterface::write_hdf5_parallel), and <name>.xdmf.
   *
   * The series (files and XDMF entries) is kept in checkpoints, so that a
   * resumed run continues it.
   */
  class OutputSeries
  {
  public:
    OutputSeries(const std::string &directory,
                 const std::string &name,
                 const OutputFormat format);

    /**
     * Write the patches of @p data_out (built on every rank; collective)
     * as output number @p counter at @p time. @p has_patches: whether this
     * rank built any patches. deal.II 9.4's parallel HDF5 writer hangs if a
     * rank has none (it skips collective dataset writes), so only ranks
     * with patches write, and the first of them hands the XDMF entry on.
     */
    template <int patch_dim, int spacedim>
    void
    write(const DataOutInterface<patch_dim, spacedim> &data_out,
          const bool                                   has_patches,
          const unsigned int                           counter,
          const double                                 time,
          const MPI_Comm                               communicator);

    /// The series file: <name>.pvd or <name>.xdmf.
    std::string
    series_file() const;

    /// vtu: (time, .pvtu file) per output, for the .pvd
    std::vector<std::pair<double, std::string>> files;
    /// hdf5: one entry per output, for the .xdmf
    std::vector<XDMFEntry> xdmf_entries;

  private:
    std::string  directory;
    std::string  name;
    OutputFormat format;
  };
} // namespace sable::mpm

#endif
