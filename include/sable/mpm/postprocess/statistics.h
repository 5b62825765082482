#ifndef sable_mpm_postprocess_statistics_h
#define sable_mpm_postprocess_statistics_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/particles/particle_handler.h>

#include <sable/mpm/contact/bardenhagen_contact.h>
#include <sable/mpm/materials/material.h>
#include <sable/mpm/particle_layout.h>
#include <sable/mpm/periodicity.h>

#include <array>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace sable::mpm
{
  using namespace dealii;

  /// Global sums over all particles at one instant.
  template <int dim>
  struct Statistics
  {
    double                      kinetic_energy = 0;
    double                      strain_energy  = 0;
    /// -sum_p m_p g . x_p
    double                      gravity_energy = 0;
    /// work dissipated by plastic flow so far
    double                      plastic_work = 0;
    /// friction heat of the walls so far (BoundaryConditions::frictional_heat)
    double                      wall_heat = 0;
    /// kinetic and strain energy the corrections of contact and walls
    /// took from the points so far beyond the contact and wall heat
    /// (GridToParticle::measure_corrections(), less both heats): the normal impacts,
    /// perfectly inelastic at each node, and sticking
    double                      impact_loss = 0;
    /// impulse the bodies of prescribed velocity gave the others so far
    /// (RunState::driver_impulse)
    Tensor<1, dim>              driver_impulse;
    /**
     * The energy balance: kinetic + strain + gravitational energy + plastic
     * work + wall and contact heat + impact loss - boundary work, less its
     * value at the start, over the energy the scene can hold
     * (RunState::energy_scale(), at least the energy of all the mass over
     * one cell height). What remains is the discretisation's own gain or
     * loss: the time integration's, the transfers' (e.g. PIC's damping),
     * and the impacts at moving walls and prescribed bodies; NaN if not
     * computed.
     */
    double                      energy_drift = std::numeric_limits<double>::quiet_NaN();
    Tensor<1, dim>              momentum;
    std::vector<double>         body_mass;
    std::vector<Point<dim>>     body_position;
    std::vector<Tensor<1, dim>> body_velocity;
    /// I^-1 L about the centre of mass (2D: the z component only)
    std::vector<Tensor<1, 3>> body_angular_velocity;
    unsigned long long          n_particles = 0;
    /// active cells of the background grid (changes with adaptive meshes)
    unsigned long long          n_cells = 0;
    /// frictional work of contact so far
    /// (BardenhagenContact::frictional_heat), and the last contact force
    /// per reported pair (empty without contact)
    double                      contact_heat = 0;
    std::vector<Tensor<1, dim>> pair_forces;
    /// per reported pair, the moment of that contact force on its first
    /// body about the body's centre of mass, and of the opposite force on
    /// the second body about its centre of mass (3 components; 2D: z
    /// only); empty on a periodic grid
    std::vector<std::array<Tensor<1, 3>, 2>> pair_moments;
  };

  /**
   * statistics.csv: one row per recorded step (DESIGN.md, output
   * conventions). Only rank 0 writes; every value with 17 significant
   * digits so runs can be compared to round-off. With @p append (a resumed
   * run) the rows go after those already in the file, without a header.
   * write_row() is collective over @p communicator: a row that cannot be
   * written (a full disk) is a std::runtime_error naming the file on every
   * rank. Per-body columns for the @p bodies listed.
   */
  template <int dim>
  class StatisticsFile
  {
  public:
    StatisticsFile(const std::string &filename,
                   const std::vector<unsigned int> &bodies,
                   const bool         with_contact,
                   const bool         with_drivers,
                   const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
                   const bool         with_pair_moments,
                   const bool         write,
                   const bool         append       = false,
                   MPI_Comm           communicator = MPI_COMM_SELF);

    void
    write_row(const unsigned int       step,
              const double             time,
              const double             dt,
              const double             boundary_work,
              const Statistics<dim> &  statistics);

    /// The name of the first column whose value in this row is not a finite
    /// number, or "" if all are (a body without points, e.g. one that left
    /// the grid, has no position or velocity: its columns are not checked).
    std::string
    first_not_finite(const unsigned int     step,
                     const double           time,
                     const double           dt,
                     const double           boundary_work,
                     const Statistics<dim> &statistics) const;

  private:
    /// what one row is made of
    struct Row
    {
      double                 step;
      double                 time;
      double                 dt;
      double                 boundary_work;
      const Statistics<dim> &statistics;
    };
    struct Column
    {
      std::string                        name;
      std::function<double(const Row &)> value;
      /// the body a per-body column describes
      unsigned int body = numbers::invalid_unsigned_int;
    };
    /// the file's columns, in order: the header and every row come from it
    std::vector<Column>            columns;
    std::unique_ptr<std::ofstream> file;
    std::string                    filename;
    MPI_Comm                       communicator;
    std::string                    failure; ///< the file could not be opened
  };
  /**
   * Energies, momentum and per-body centre of mass, velocity and angular
   * velocity of the material points over all ranks (collective), and, with
   * @p contact, its frictional heat and reported pair forces, with their
   * moments about the bodies' centres of mass unless the grid is periodic
   * (the forces of the last step, @p time_step long: about the centres
   * where they were at its start).
   *
   * On a periodic grid a body's points count at their images nearest to
   * the body's circular mean position along each periodic axis, so that the
   * centre of mass and angular velocity of a body crossing the seam are
   * those of the whole body (its centre is given wrapped into the grid).
   */
  template <int dim>
  Statistics<dim>
  compute_statistics(const Triangulation<dim> &                    triangulation,
                     const Particles::ParticleHandler<dim> &       particle_handler,
                     const ParticleLayout<dim> &                   layout,
                     const std::vector<std::unique_ptr<Material>> &materials,
                     const Tensor<1, dim> &                        gravity,
                     const BardenhagenContact<dim> *               contact,
                     const Periodicity<dim> &                      periodicity,
                     const double                                  time_step = 0);
} // namespace sable::mpm

#endif
