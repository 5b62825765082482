#!/usr/bin/python3
"""Where the energy of a run went, from its statistics.csv (doc/mpm.md,
"Energy balance"): the gravitational energy released and the boundary work
against what stays kinetic and elastic, the friction heat of contacts and
walls, the plastic work, the loss of the normal impacts, and what no
column counts (energy_drift), at a few instants and at the end.

    energy_balance.py output/settling_pile/statistics.csv [more.csv ...] [--rows 5]
                      [--plot energy_balance.png]

With --plot, a figure of the first file: where the energy released went
over time, stacked (kinetic, strain, plastic work, contact and wall heat,
the impacts' loss), against the energy released, and energy_drift below.
"""
import argparse
import csv


def terms(first, r):
    """Released energy and where it went at row r, in J."""
    released = first["gravity_energy"] - r["gravity_energy"] + r["boundary_work"]
    return released, {
        "kinetic": r["kinetic_energy"] - first["kinetic_energy"],
        "strain": r["strain_energy"] - first["strain_energy"],
        "plastic work": r["plastic_work"],
        "contact heat": r.get("contact_heat", 0.),
        "wall heat": r["wall_heat"],
        "impacts' loss": max(r.get("impact_loss", 0.), 0.),
    }


def plot(path, rows, output):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    first = rows[0]
    time = [r["time"] for r in rows]
    parts = [terms(first, r) for r in rows]
    names = list(parts[0][1])
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                         gridspec_kw={"height_ratios": [3, 1]})
    top.stackplot(time, *[[p[1][n] for p in parts] for n in names], labels=names)
    top.plot(time, [p[0] for p in parts], "k-", linewidth=1.5, label="released (gravity + boundary work)")
    top.set_ylabel("energy (J)")
    top.legend(loc="upper left", fontsize=8)
    top.set_title(path, fontsize=9)
    bottom.plot(time, [100 * r["energy_drift"] for r in rows], "k-")
    bottom.axhline(0, color="0.6", linewidth=0.8)
    bottom.set_ylabel("energy_drift (%)")
    bottom.set_xlabel("time (s)")
    figure.tight_layout()
    figure.savefig(output, dpi=120)
    print(f"wrote {output}")


def read(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="statistics.csv files")
    parser.add_argument("--rows", type=int, default=5, help="instants shown per file (the last included)")
    parser.add_argument("--plot", help="write a figure of the first file's balance to this file")
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
            released, parts = terms(first, r)
            uncounted = released - sum(parts.values())
            values = (r["time"], released, parts["kinetic"], parts["strain"], parts["contact heat"],
                      parts["wall heat"], parts["plastic work"], r.get("impact_loss", 0.), uncounted,
                      r["energy_drift"])
            print(" ".join(f"{v:13.5g}" for v in values))
        drift = [r["energy_drift"] for r in rows]
        print(f"energy_drift: smallest {min(drift):+.4f}, largest {max(drift):+.4f}, last {drift[-1]:+.4f}\n")
    if arguments.plot:
        plot(arguments.files[0], read(arguments.files[0]), arguments.plot)


if __name__ == "__main__":
    main()
