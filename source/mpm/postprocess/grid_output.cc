#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <sable/mpm/particle_layout.h>
#include <sable/mpm/postprocess/grid_output.h>

namespace sable::mpm
{
  template <int dim>
  GridOutput<dim>::GridOutput(const std::string &directory, const OutputFormat format)
    : series(directory, "grid", format)
  {}

  template <int dim>
  void
  GridOutput<dim>::write(const Grid<dim> &                      grid,
                         const Particles::ParticleHandler<dim> &particles,
                         const unsigned int                     counter,
                         const double                           time,
                         const unsigned int                     base_level)
  {
    using Layout                        = ParticleLayout<dim>;
    constexpr unsigned int n_components = 1 + dim;
    const auto &           triangulation = grid.triangulation;
    const MPI_Comm         communicator  = triangulation.get_communicator();

    // mass and momentum of the material points on the grid's nodes, node
    // by node as in the simulator's transfers
    LinearAlgebra::distributed::Vector<double> nodal(grid.make_partitioner(n_components));
    double *const             values = nodal.get_values();
    typename Grid<dim>::Shape shape;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const typename Grid<dim>::CellData &data = grid.cell_data(cell);
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const auto props = particle.get_properties();
              grid.evaluate(data,
                            particle.get_reference_location(),
                            props[Layout::initial_volume],
                            shape);
              for (unsigned int k = 0; k < shape.n_nodes; ++k)
                {
                  double *const node   = values + shape.nodes[k] * n_components;
                  const double  weight = props[Layout::mass] * shape.values[k];
                  node[0] += weight;
                  for (unsigned int d = 0; d < dim; ++d)
                    node[1 + d] += weight * props[Layout::velocity + d];
                }
            }
        }
    nodal.compress(VectorOperation::add);
    nodal.update_ghost_values();

    // the same on an FESystem of Q1 elements, which DataOut can show as a
    // scalar and a vector field. Hanging nodes hold no data: they get the
    // values of their constraints, for mass and momentum, so that a hanging
    // node's velocity is a mass-weighted mean of its masters' velocities
    const FESystem<dim> fe(FE_Q<dim>(1), 1 + dim);
    DoFHandler<dim>     dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    AffineConstraints<double> constraints;
    constraints.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    constraints.close();

    LinearAlgebra::distributed::Vector<double> mass_momentum(dof_handler.locally_owned_dofs(),
                                                             communicator);
    std::vector<types::global_dof_index>       dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const typename Grid<dim>::CellData &data = grid.cell_data(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (mass_momentum.in_local_range(dofs[i]) && !constraints.is_constrained(dofs[i]))
              {
                const auto [component, vertex] = fe.system_to_component_index(i);
                mass_momentum(dofs[i]) =
                  nodal.local_element(data.nodes[vertex] * n_components + component);
              }
        }
    constraints.distribute(mass_momentum);

    // (mass, velocity) and the cell fields
    LinearAlgebra::distributed::Vector<double> fields(dof_handler.locally_owned_dofs(),
                                                      communicator);
    Vector<float> n_points(triangulation.n_active_cells());
    Vector<float> level(triangulation.n_active_cells());
    Vector<float> rank(triangulation.n_active_cells());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int index = cell->active_cell_index();
          n_points[index]          = particles.n_particles_in_cell(cell);
          level[index]             = cell->level() - static_cast<int>(base_level);
          rank[index]              = cell->subdomain_id();
          cell->get_dof_indices(dofs);
          for (unsigned int v = 0; v < Grid<dim>::nodes_per_cell; ++v)
            {
              const auto mass_dof = dofs[fe.component_to_system_index(0, v)];
              if (!fields.in_local_range(mass_dof))
                continue; // a vertex's dofs all have one owner
              const double mass = mass_momentum(mass_dof);
              fields(mass_dof)  = mass;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const auto dof = dofs[fe.component_to_system_index(1 + d, v)];
                  fields(dof)    = mass > 0. ? mass_momentum(dof) / mass : 0.;
                }
            }
        }

    DataOut<dim>             data_out;
    std::vector<std::string> names(1, "mass");
    names.resize(1 + dim, "velocity");
    std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
      1 + dim, DataComponentInterpretation::component_is_part_of_vector);
    interpretation[0] = DataComponentInterpretation::component_is_scalar;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(fields, names, DataOut<dim>::type_dof_data, interpretation);
    data_out.add_data_vector(n_points, "material_points", DataOut<dim>::type_cell_data);
    data_out.add_data_vector(level, "level", DataOut<dim>::type_cell_data);
    data_out.add_data_vector(rank, "rank", DataOut<dim>::type_cell_data);
    data_out.build_patches(grid.get_mapping());
    series.write(data_out,
                 triangulation.n_locally_owned_active_cells() > 0,
                 counter,
                 time,
                 communicator);
  }

  template class GridOutput<2>;
  template class GridOutput<3>;
} // namespace sable::mpm
