#include <deal.II/base/data_out_base.h>
#include <deal.II/grid/reference_cell.h>

#include <sable/qusgm/macroscopic.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>

namespace sable::qusgm
{
  MacroscopicState
  measure(const Walls                 &walls,
          const std::array<double, 3> &undeformed_lengths,
          const ContactState          &state,
          const Pack                  &pack,
          const unsigned int           axis)
  {
    const unsigned int n_grains = pack.size();
    double             volume   = 0;
    for (const double r : pack.radius)
      volume += 4. / 3. * M_PI * r * r * r;
    MacroscopicState m;
    for (unsigned int a = 0; a < 3; ++a)
      {
        m.strain[a] =
          (undeformed_lengths[a] - walls.length(a)) / undeformed_lengths[a];
        const double force = 0.5 * (state.wall_force[a] + state.wall_force[a + 3]);
        m.stress[a]         = force / walls.area(a);
        m.nominal_stress[a] = force / (undeformed_lengths[(a + 1) % 3] *
                                       undeformed_lengths[(a + 2) % 3]);
      }
    m.confining_stress = (m.stress[0] + m.stress[1] + m.stress[2]) / 3.;
    m.deviatoric_stress =
      m.stress[axis] -
      0.5 * (m.stress[(axis + 1) % 3] + m.stress[(axis + 2) % 3]);
    m.n_contacts = state.n_contacts;
    m.sliding_ratio = state.n_contacts > 0 ? double(state.n_sliding) / state.n_contacts :
                                             std::numeric_limits<double>::quiet_NaN();
    double total = 0;
    for (const unsigned int c : state.coordination)
      total += c;
    m.coordination   = n_grains > 0 ? total / n_grains : 0.;
    m.solid_fraction = volume / walls.volume();
    return m;
  }

  std::pair<double, double>
  fit_moduli(const std::array<double, 3> &d_stress,
             const std::array<double, 3> &d_strain)
  {
    const double nan   = std::numeric_limits<double>::quiet_NaN();
    const double trace = d_strain[0] + d_strain[1] + d_strain[2];
    double       dev2 = 0, dev_stress = 0, sum_stress = 0;
    for (unsigned int a = 0; a < 3; ++a)
      {
        const double dev = d_strain[a] - trace / 3.;
        dev2 += dev * dev;
        dev_stress += 2. * dev * d_stress[a];
        sum_stress += d_stress[a];
      }
    const double scale = std::abs(d_strain[0]) + std::abs(d_strain[1]) +
                         std::abs(d_strain[2]);
    const double k =
      std::abs(trace) > 1e-9 * scale ? sum_stress / (3. * trace) : nan;
    const double g = dev2 > 1e-18 * scale * scale ? dev_stress / (4. * dev2) : nan;
    return {k, g};
  }

  IncrementTable::IncrementTable(const std::string &filename, const bool append)
    : filename(filename)
    , out(filename, append ? std::ios::app : std::ios::out)
  {
    if (!out)
      failure = "cannot write '" + filename + "': " + std::strerror(errno);
    if (!append)
      out << "increment,stage,strain_x,strain_y,strain_z,stress_x,stress_y,"
             "stress_z,nominal_stress_x,nominal_stress_y,nominal_stress_z,"
             "confining_stress,deviatoric_stress,bulk_modulus,"
             "shear_modulus,sliding_ratio,coordination_number,solid_fraction,contacts,"
             "iterations,evaluations,residual,relative_residual,wall_time,stopped_by\n";
    out << std::setprecision(17);
  }

  void
  IncrementTable::write(const unsigned int      increment,
                        const std::string      &stage,
                        const MacroscopicState &m,
                        const double            bulk_modulus,
                        const double            shear_modulus,
                        const IncrementResult  &result,
                        const double            wall_time)
  {
    // an undefined value is an empty field
    const auto field = [this](const double value) {
      out << ',';
      if (std::isfinite(value))
        out << value;
    };
    out << increment << ',' << stage;
    for (const double e : m.strain)
      field(e);
    for (const double s : m.stress)
      field(s);
    for (const double s : m.nominal_stress)
      field(s);
    field(m.confining_stress);
    field(m.deviatoric_stress);
    field(bulk_modulus);
    field(shear_modulus);
    field(m.sliding_ratio);
    field(m.coordination);
    field(m.solid_fraction);
    out << ',' << m.n_contacts << ',' << result.iterations << ',' << result.evaluations;
    field(result.residual);
    field(result.max_contact_force > 0 ? result.residual / result.max_contact_force :
                                         std::numeric_limits<double>::quiet_NaN());
    field(wall_time);
    out << ',' << result.stopped_by << '\n';
    out.flush();
    if (!out && failure.empty())
      failure = "cannot write '" + filename + "' (increment " + std::to_string(increment) +
                "): " + std::strerror(errno);
  }

  void
  write_grains_vtu(const std::string  &filename,
                   const Pack         &pack,
                   const ContactState &state)
  {
    std::vector<dealii::DataOutBase::Patch<0, 3>> patches(pack.size());
    for (unsigned int i = 0; i < pack.size(); ++i)
      {
        patches[i].vertices[0] = pack.centre[i];
        patches[i].patch_index = i;
        patches[i].data.reinit(3, 1);
        patches[i].data(0, 0) = pack.radius[i];
        patches[i].data(1, 0) =
          i < state.coordination.size() ? state.coordination[i] : 0;
        patches[i].data(2, 0) = pack.youngs_modulus[i];
      }
    std::ofstream out(filename);
    dealii::DataOutBase::write_vtu(patches,
                                   {"radius", "coordination", "youngs_modulus"},
                                   {},
                                   dealii::DataOutBase::VtkFlags(),
                                   out);
  }

  std::string
  write_contacts_vtu(const std::string    &directory,
                     const std::string    &stem,
                     const Pack           &pack,
                     const Walls          &walls,
                     const ContactNetwork &network,
                     const ContactModel   &model)
  {
    std::vector<dealii::DataOutBase::Patch<1, 3>> patches;
    auto add = [&](const Contact &c, const Point<3> &a, const Point<3> &b,
                   const double mu) {
      if (c.p0 <= 0 || !network.owns(c))
        return;
      dealii::DataOutBase::Patch<1, 3> patch;
      patch.vertices[0]    = a;
      patch.vertices[1]    = b;
      patch.n_subdivisions = 1;
      patch.reference_cell = dealii::ReferenceCells::get_hypercube<1>();
      patch.patch_index    = patches.size();
      patch.data.reinit(3, 2);
      const double q = c.q0.norm();
      for (unsigned int v = 0; v < 2; ++v)
        {
          patch.data(0, v) = c.p0;
          patch.data(1, v) = q;
          patch.data(2, v) = mu > 0 ? q / (mu * c.p0) : 0.;
        }
      patches.push_back(patch);
    };
    for (const Contact &c : network.pairs)
      add(c, pack.centre[c.i], pack.centre[c.other], model.friction);
    for (const Contact &c : network.wall_contacts)
      {
        Point<3> contact_point = pack.centre[c.i];
        contact_point[Walls::axis(c.other)] = walls.position[c.other];
        add(c, pack.centre[c.i], contact_point, model.wall_friction);
      }
    const std::vector<std::string> names = {"normal_force",
                                            "tangential_force",
                                            "friction_mobilisation"};
    const GrainPartition &partition = network.get_partition();
    const MPI_Comm        communicator = partition.get_communicator();
    if (partition.n_ranks() == 1)
      {
        std::ofstream out(directory + "/" + stem + ".vtu");
        dealii::DataOutBase::write_vtu(patches, names, {}, dealii::DataOutBase::VtkFlags(), out);
        return stem + ".vtu";
      }
    const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(communicator);
    const auto         piece = [&](const unsigned int r) {
      return stem + "." + dealii::Utilities::int_to_string(r, 4) + ".vtu";
    };
    {
      std::ofstream out(directory + "/" + piece(rank));
      dealii::DataOutBase::write_vtu(patches, names, {}, dealii::DataOutBase::VtkFlags(), out);
    }
    if (rank == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < partition.n_ranks(); ++r)
          pieces.push_back(piece(r));
        std::ofstream record(directory + "/" + stem + ".pvtu");
        dealii::DataOutBase::write_pvtu_record(record, pieces, names, {}, dealii::DataOutBase::VtkFlags());
      }
    return stem + ".pvtu";
  }
} // namespace sable::qusgm
