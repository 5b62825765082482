// Macroscopic strain, stress and moduli of the pack, the increments.csv
// table, and VTU files of the grains.
#ifndef sable_qusgm_macroscopic_h
#define sable_qusgm_macroscopic_h

#include <sable/qusgm/contact_network.h>
#include <sable/qusgm/minimizer.h>
#include <sable/qusgm/pack.h>
#include <sable/qusgm/work_functional.h>

#include <boost/serialization/version.hpp>

#include <array>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace sable::qusgm
{
  /**
   * The pack's state as increments.csv reports it. A quantity that is not
   * defined (the sliding ratio without contacts) is NaN here and an empty
   * field in the table.
   */
  struct MacroscopicState
  {
    std::array<double, 3> strain{}; ///< (L0 - L)/L0, compression positive
    /// mean normal force on the two walls of an axis / their current area
    std::array<double, 3> stress{};
    /// the same force / the area of the box at zero strain (L0)
    std::array<double, 3> nominal_stress{};
    double confining_stress  = 0;   ///< tr(sigma)/3
    double deviatoric_stress = 0;   ///< axial minus mean lateral
    double sliding_ratio     = 0;   ///< sliding / closed contacts (NaN: none)
    double coordination      = 0;   ///< mean contacts per grain
    double solid_fraction    = 0;   ///< grain volume / box volume
    unsigned int n_contacts  = 0;

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int version)
    {
      for (unsigned int a = 0; a < 3; ++a)
        ar &strain[a] &stress[a];
      ar &confining_stress &deviatoric_stress &sliding_ratio &coordination &solid_fraction
        &n_contacts;
      if (version >= 1)
        for (unsigned int a = 0; a < 3; ++a)
          ar &nominal_stress[a];
    }
  };

  MacroscopicState
  measure(const Walls        &walls,
          const std::array<double, 3> &undeformed_lengths,
          const ContactState &state,
          const Pack         &pack,
          unsigned int        axis);

  /**
   * Fit isotropic Hooke's law d_sigma_l = K tr(d_eps) + 2 G dev(d_eps)_l to
   * one stress-strain interval (least squares; the two columns are
   * orthogonal). Returns NaN for a modulus the interval does not determine
   * (G under isotropic strain, both without strain); increments.csv writes
   * it as an empty field.
   */
  std::pair<double, double>
  fit_moduli(const std::array<double, 3> &d_stress,
             const std::array<double, 3> &d_strain);

  /**
   * The increments.csv table: every number with 17 significant digits, an
   * undefined value (NaN) as an empty field.
   */
  class IncrementTable
  {
  public:
    /// With @p append, continue an existing table (no header).
    explicit IncrementTable(const std::string &filename, bool append = false);

    void
    write(unsigned int             increment,
          const std::string       &stage,
          const MacroscopicState  &m,
          double                   bulk_modulus,
          double                   shear_modulus,
          const IncrementResult   &result,
          double                   wall_time);

    /// Why the rows so far could not all be written (a full disk), naming
    /// the file; empty if they were.
    const std::string &
    problem() const
    {
      return failure;
    }

  private:
    std::string   filename;
    std::ofstream out;
    std::string   failure;
  };

  /// Grains as points with radius, coordination and residual (VTU).
  void
  write_grains_vtu(const std::string   &filename,
                   const Pack          &pack,
                   const ContactState  &state);
  /**
   * The force network of the committed configuration as line segments
   * (VTU): grain centre to grain centre, or to the wall contact point, with
   * the normal force P, the tangential force |Q| and its mobilisation
   * |Q| / (mu P) (1: sliding).
   *
   * Collective over the network's ranks: @p stem.vtu on one rank; with
   * more, every rank writes the contacts it owns to @p stem.RRRR.vtu and
   * the first the record @p stem.pvtu. Returns the name to list in a .pvd
   * record (relative to @p directory).
   */
  std::string
  write_contacts_vtu(const std::string    &directory,
                     const std::string    &stem,
                     const Pack           &pack,
                     const Walls          &walls,
                     const ContactNetwork &network,
                     const ContactModel   &model);
} // namespace sable::qusgm

// Version 1 added the nominal stress.
BOOST_CLASS_VERSION(sable::qusgm::MacroscopicState, 1)

#endif
