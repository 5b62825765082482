#include <sable/mpm/postprocess/contact_node_output.h>

namespace sable::mpm
{
  template <int dim>
  void
  ContactNodeOutput<dim>::build_patches(const Grid<dim> &      grid,
                                        const BodyFields<dim> &fields,
                                        const unsigned int     n_owned_nodes)
  {
    const unsigned int n_values = 2 + 2 * dim;
    patches.clear();
    for (const unsigned int node : fields.get_contact_nodes())
      if (node < n_owned_nodes)
        {
          const auto [begin, end] = fields.node_records(node);
          for (auto *r = begin; r != end; ++r)
            {
              DataOutBase::Patch<0, dim> patch;
              patch.vertices[0] = grid.node_positions()[node];
              patch.patch_index = patches.size();
              patch.data.reinit(n_values, 1);
              patch.data(0, 0) = r->body;
              patch.data(1, 0) = r->state;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  patch.data(2 + d, 0)       = r->normal[d];
                  patch.data(2 + dim + d, 0) = r->contact_force[d];
                }
              patches.push_back(std::move(patch));
            }
        }
  }

  template <int dim>
  std::vector<std::string>
  ContactNodeOutput<dim>::get_dataset_names() const
  {
    std::vector<std::string> names = {"body", "state"};
    for (const std::string vector : {"normal", "contact_force"})
      for (unsigned int d = 0; d < dim; ++d)
        names.push_back(vector);
    return names;
  }

  template <int dim>
  std::vector<std::tuple<unsigned int,
                         unsigned int,
                         std::string,
                         DataComponentInterpretation::DataComponentInterpretation>>
  ContactNodeOutput<dim>::get_nonscalar_data_ranges() const
  {
    return {{2, 1 + dim, "normal", DataComponentInterpretation::component_is_part_of_vector},
            {2 + dim,
             1 + 2 * dim,
             "contact_force",
             DataComponentInterpretation::component_is_part_of_vector}};
  }

  template class ContactNodeOutput<2>;
  template class ContactNodeOutput<3>;
} // namespace sable::mpm
