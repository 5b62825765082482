// Packs and run states in files: pack files by column name, Yade's text
// export, LAMMPS/LIGGGHTS dumps, and the state directory sable writes
// (grains, walls, contacts with their tangential history) and reads back
// to the same digits.
#ifndef sable_qusgm_pack_io_h
#define sable_qusgm_pack_io_h

#include <sable/qusgm/pack.h>

#include <array>
#include <string>
#include <vector>

namespace sable::qusgm
{
  /// Material values for grains whose file does not give them.
  struct GrainDefaults
  {
    double youngs_modulus = 70e9;
    double poisson_ratio  = 0.2;
    double density        = 2420;
  };

  /**
   * Read a pack, recognising the file by its content (doc/qusgm.md, "Pack
   * files"):
   *
   * - **columns by name** (CSV, or blank separated): a header line names
   *   the columns, in any order: `x`, `y`, `z`, the size as `r` (or
   *   `radius`) or `diameter`, and optionally `E`, `nu`, `rho` (or
   *   `density`) and `id` (names are case-blind). An unknown name, a name
   *   given twice, a size given twice (`r` and `diameter`) or a missing
   *   coordinate or size is refused, naming the file, line and column. A
   *   file without a header must have exactly four numbers per line:
   *   x y z r. The header may be a comment line (`#x y z r`).
   * - **Yade's text export** (`yade.export.text`, `export.textExt`): a first
   *   line `#format x_y_z_r` (also `x_y_z_r_matId`, `id_x_y_z_r_matId`; with
   *   `x_y_z_r_attrs` the comment line `# x y z r ...` names the columns);
   *   `matId` is read and not used.
   * - **LAMMPS/LIGGGHTS dump** (`dump custom`, text): `ITEM:` sections; the
   *   last snapshot in the file is read. Columns `id`, `x y z` (or `xu`,
   *   `xs`, `xsu`: unwrapped or scaled by the box bounds), `radius` or
   *   `diameter`, and `density` or `mass` (density = mass / volume) are
   *   used, every other LAMMPS column is skipped; the grains are sorted by
   *   id.
   *
   * Material values a file does not give come from @p defaults. Values are
   * SI. @p description, if given, receives one line saying what was read.
   * Every problem is an InputError naming the file and line.
   */
  Pack
  read_pack(const std::string   &filename,
            const GrainDefaults &defaults,
            std::string         *description = nullptr);

  /// Write `id,x,y,z,r,E,nu,rho` with 17 significant digits (read_pack
  /// reads it back to the same doubles).
  void
  write_pack(const Pack &pack, const std::string &filename);

  /**
   * One contact's reference loads, as a state file holds them. Grain-grain:
   * the force on grain `i` (grain `other` takes the opposite) and the
   * torsional couple on `i` about the line from `other` to `i`; grain-wall
   * (`wall`): force and couple (about the wall's inward normal) on `i`.
   * Indices are positions in the pack.
   */
  struct ContactLoad
  {
    unsigned int i = 0, other = 0;
    bool         wall = false;
    Tensor<1, 3> tangential_force;
    double       torsional_couple = 0;
    double       normal_force     = 0; ///< written for information only
    double       overlap          = 0; ///< written for information only
    std::string  where;                ///< file and line it was read from
  };

  /**
   * What a run continues from: the grains, the walls, the box of zero
   * strain, and every closed contact with its reference loads.
   */
  struct PackState
  {
    Pack                     pack;
    Walls                    walls;
    std::array<double, 3>    undeformed_lengths{};
    std::array<double, 6>    wall_force{}; ///< written for information only
    std::vector<ContactLoad> contacts;
  };

  /**
   * Write @p state as the directory @p directory (made if absent):
   * `grains.csv` (as write_pack), `walls.csv`, `contacts.csv` and
   * `wall_contacts.csv`, every number with 17 significant digits; contacts
   * name their grains by id. doc/qusgm.md describes the columns.
   */
  void
  write_state(const PackState &state, const std::string &directory);

  /**
   * Read a directory written by write_state() (or by hand in its format)
   * back to the same doubles. Every problem is an InputError naming the
   * file, line and column.
   */
  PackState
  read_state(const std::string &directory, const GrainDefaults &defaults);
} // namespace sable::qusgm

#endif
