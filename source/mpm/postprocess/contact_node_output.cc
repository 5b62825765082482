#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <sable/mpm/postprocess/contact_node_output.h>

#include <fstream>
#include <iomanip>

namespace sable::mpm
{
  template <int dim>
  void
  write_contact_nodes(const std::string &                           directory,
                      const unsigned int                            counter,
                      const double                                  time,
                      const Grid<dim> &                             grid,
                      const BodyFields<dim> &                       fields,
                      const unsigned int                            n_owned_nodes,
                      const MPI_Comm                                communicator,
                      std::vector<std::pair<double, std::string>> &series)
  {
    // one point per body record at each locally owned contact node, as an
    // unstructured grid of vertices (ASCII: these files are small)
    std::vector<const typename BodyFields<dim>::Record *> records;
    std::vector<unsigned int>                             nodes;
    for (const unsigned int node : fields.get_contact_nodes())
      if (node < n_owned_nodes)
        {
          const auto [begin, end] = fields.node_records(node);
          for (auto *r = begin; r != end; ++r)
            {
              records.push_back(r);
              nodes.push_back(node);
            }
        }
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const std::string  stem    = "contact_nodes_" + Utilities::int_to_string(counter, 5);
    const auto         piece   = [&](const unsigned int r) {
      return stem + "." + Utilities::int_to_string(r, 4) + ".vtu";
    };
    {
      std::ofstream out(directory + "/" + piece(rank));
      out << std::setprecision(9);
      const unsigned int n = records.size();
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
          << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
          << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const unsigned int node : nodes)
        {
          const Point<dim> &x = grid.node_positions()[node];
          out << x[0] << ' ' << x[1] << ' ' << (dim == 3 ? x[dim - 1] : 0.) << '\n';
        }
      out << "</DataArray></Points>\n<Cells>\n"
          << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << i << '\n';
      out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << i + 1 << '\n';
      out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        out << "1\n";
      out << "</DataArray>\n</Cells>\n<PointData>\n"
          << "<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
      for (const auto *r : records)
        out << r->body << '\n';
      out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"state\" format=\"ascii\">\n";
      for (const auto *r : records)
        out << r->state << '\n';
      out << "</DataArray>\n";
      for (const std::string field : {"normal", "contact_force"})
        {
          out << "<DataArray type=\"Float64\" Name=\"" << field
              << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
          for (const auto *r : records)
            {
              const Tensor<1, dim> &t = field == "normal" ? r->normal : r->contact_force;
              out << t[0] << ' ' << t[1] << ' ' << (dim == 3 ? t[dim - 1] : 0.) << '\n';
            }
          out << "</DataArray>\n";
        }
      out << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    }
    if (rank != 0)
      return;
    {
      std::ofstream out(directory + "/" + stem + ".pvtu");
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\">\n"
          << "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints><PDataArray type=\"Float64\" "
             "NumberOfComponents=\"3\"/></PPoints>\n<PPointData>\n"
          << "<PDataArray type=\"Int32\" Name=\"body\"/>\n<PDataArray type=\"Int32\" Name=\"state\"/>\n"
          << "<PDataArray type=\"Float64\" Name=\"normal\" NumberOfComponents=\"3\"/>\n"
          << "<PDataArray type=\"Float64\" Name=\"contact_force\" NumberOfComponents=\"3\"/>\n"
          << "</PPointData>\n";
      for (unsigned int r = 0; r < n_ranks; ++r)
        out << "<Piece Source=\"" << piece(r) << "\"/>\n";
      out << "</PUnstructuredGrid>\n</VTKFile>\n";
    }
    series.emplace_back(time, stem + ".pvtu");
    std::ofstream pvd(directory + "/contact_nodes.pvd");
    DataOutBase::write_pvd_record(pvd, series);
  }

#define SABLE_INSTANTIATE(dim)                                                         \
  template void write_contact_nodes<dim>(const std::string &,                          \
                                         const unsigned int,                           \
                                         const double,                                 \
                                         const Grid<dim> &,                            \
                                         const BodyFields<dim> &,                      \
                                         const unsigned int,                           \
                                         const MPI_Comm,                               \
                                         std::vector<std::pair<double, std::string>> &);
  SABLE_INSTANTIATE(2)
  SABLE_INSTANTIATE(3)
#undef SABLE_INSTANTIATE
} // namespace sable::mpm
