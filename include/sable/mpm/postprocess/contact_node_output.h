#ifndef sable_mpm_postprocess_contact_node_output_h
#define sable_mpm_postprocess_contact_node_output_h

#include <deal.II/base/data_out_base.h>

#include <sable/mpm/contact/body_fields.h>
#include <sable/mpm/grid.h>

#include <string>
#include <tuple>
#include <vector>

namespace sable::mpm
{
  /**
   * The contact nodes of the last momentum-update pass as deal.II output
   * patches (Output/Contact node output): one point per body record at
   * each locally owned contact node, with the body, its state (0 free,
   * 1 stick, 2 slip), its normal and the contact force on it. Written
   * through OutputSeries like the particles (VTU or HDF5 + XDMF; values in
   * single precision, as deal.II's patches hold them).
   */
  template <int dim>
  class ContactNodeOutput : public DataOutInterface<0, dim>
  {
  public:
    /// Patches for the records of the nodes below @p n_owned_nodes.
    void
    build_patches(const Grid<dim> &       grid,
                  const BodyFields<dim> & fields,
                  const unsigned int      n_owned_nodes);

    bool
    empty() const
    {
      return patches.empty();
    }

  private:
    const std::vector<DataOutBase::Patch<0, dim>> &
    get_patches() const override
    {
      return patches;
    }

    std::vector<std::string>
    get_dataset_names() const override;

    std::vector<
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 DataComponentInterpretation::DataComponentInterpretation>>
    get_nonscalar_data_ranges() const override;

    std::vector<DataOutBase::Patch<0, dim>> patches;
  };
} // namespace sable::mpm

#endif
