#!/usr/bin/python3
"""Where the energy of a run went, from its statistics.csv (doc/mpm.md,
"Energy balance"): the gravitational energy released and the boundary work
against what stays kinetic and elastic, the friction heat of contacts and
walls, the plastic work, the loss of the normal impacts, and what no
column counts (energy_drift), at a few instants and at the end.

    energy_balance.py output/settling_pile/statistics.csv [more.csv ...] [--rows 5]
"""
import argparse
import csv


def read(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="statistics.csv files")
    parser.add_argument("--rows", type=int, default=5, help="instants shown per file (the last included)")
    arguments = parser.parse_args()
    columns = ("time", "released", "kinetic", "strain", "contact_heat", "wall_heat", "plastic", "impact_loss",
               "uncounted", "energy_drift")
    for path in arguments.files:
        rows = read(path)
        if not rows:
            raise SystemExit(f"{path}: no rows")
        print(f"{path} (time in s, energies in J, energy_drift a fraction; 'released': the gravitational "
              "energy released plus the boundary work; 'uncounted': released less the changes of kinetic and "
              "strain energy, the heats, the plastic work and the impacts' loss where it is a loss)")
        print(" ".join(f"{c:>13s}" for c in columns))
        step = max(1, (len(rows) - 1) // max(1, arguments.rows - 1))
        shown = rows[::step] if rows[::step][-1] is rows[-1] else rows[::step] + [rows[-1]]
        first = rows[0]
        for r in shown:
            released = first["gravity_energy"] - r["gravity_energy"] + r["boundary_work"]
            kinetic = r["kinetic_energy"] - first["kinetic_energy"]
            strain = r["strain_energy"] - first["strain_energy"]
            heat = r.get("contact_heat", 0.)
            impacts = r.get("impact_loss", 0.)
            uncounted = (released - kinetic - strain - heat - r["wall_heat"] - r["plastic_work"] -
                         max(impacts, 0.))
            values = (r["time"], released, kinetic, strain, heat, r["wall_heat"], r["plastic_work"], impacts,
                      uncounted, r["energy_drift"])
            print(" ".join(f"{v:13.5g}" for v in values))
        drift = [r["energy_drift"] for r in rows]
        print(f"energy_drift: smallest {min(drift):+.4f}, largest {max(drift):+.4f}, last {drift[-1]:+.4f}\n")


if __name__ == "__main__":
    main()
