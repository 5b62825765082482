#ifndef sable_mpm_postprocess_contact_node_output_h
#define sable_mpm_postprocess_contact_node_output_h

#include <deal.II/base/mpi.h>

#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/grid.h>

#include <string>
#include <utility>
#include <vector>

namespace sable::mpm
{
  /**
   * The contact nodes of the last momentum-update pass (Output/Contact
   * node output): one point per body record at each locally owned contact
   * node, with the body, its state (0 free, 1 stick, 2 slip), its normal
   * and the contact force on it, as contact_nodes_NNNNN.pvtu with one
   * ASCII .vtu per rank (collective); the file is added to @p series and
   * contact_nodes.pvd rewritten.
   */
  template <int dim>
  void
  write_contact_nodes(const std::string &                           directory,
                      const unsigned int                            counter,
                      const double                                  time,
                      const Grid<dim> &                             grid,
                      const BodyFields<dim> &                       fields,
                      const unsigned int                            n_owned_nodes,
                      const MPI_Comm                                communicator,
                      std::vector<std::pair<double, std::string>> &series);
} // namespace sable::mpm

#endif
