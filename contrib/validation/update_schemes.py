#!/usr/bin/python3
"""MUSL against USAVG: the energy of bodies that ring while they move.

Two scenes without gravity, each run under MUSL at CFL 0.5 (the defaults),
MUSL at CFL 0.25 and USAVG at CFL 0.5 (doc/mpm.md, "Stability"):
- ringing disk: a disk of R = 0.1 m (E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3,
  8 cells per diameter, on the lattice) moving at 3.46 m/s along the grid's
  x axis and spinning at 10 rad/s, 1 s (test spinning_disk);
- flight: two elastic disks (R = 0.2 and 0.1 m, same material) meeting
  head-on at 2 m/s each, Bardenhagen 2001 contact, then flying apart
  ringing, 0.8 s (test energy_balance).
Kinetic + strain energy against the initial (energy_drift for the flight,
which counts the contact's heat) is written to update_schemes.md and drawn
in update_schemes.png in --output-dir (default: the work directory;
doc/validation for the report).

Usage: contrib/validation/update_schemes.py [--sable build/sable]
           [--work DIR] [--output-dir DIR]"""
import argparse
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MATERIAL = """  set Young's modulus = 1e6
  set Poisson's ratio = 0.3
  set Density = 1000
"""


def scene(end_time, lower, upper, subdivisions, disks, contact=""):
    """A scene without gravity: the grid, the contact section and one
    elastic disk per (centre, radius, velocity, spin) of `disks`."""
    text = (f"set Dimension = 2\nset Number of bodies = {len(disks)}\nset Gravity = 0, 0\n"
            f"subsection Time\n  set End time = {end_time}\nend\n"
            f"subsection Grid\n  set Lower corner = {lower}\n  set Upper corner = {upper}\n"
            f"  set Subdivisions = {subdivisions}\nend\n")
    if contact:
        text += f"subsection Contact\n  set Model = {contact}\nend\n"
    for i, (centre, radius, velocity, spin) in enumerate(disks):
        text += (f"subsection Body {i}\n  set Shape = disk\n  set Center = {centre}\n"
                 f"  set Radius = {radius}\n  set Velocity = {velocity}\n"
                 f"  set Angular velocity = {spin}\n" + MATERIAL + "end\n")
    return text


SCENES = {
    "ringing disk": scene(1, "0, 0", "8, 1", "320, 40", [("0.5, 0.5", 0.1, "3.46, 0", 10)]),
    "flight": scene(0.8, "-2, 0", "6, 1", "320, 40",
                    [("0.7, 0.5", 0.2, "2, 0", 0), ("1.2, 0.5", 0.1, "-2, 0", 0)],
                    contact="bardenhagen 2001"),
}
# label, update scheme, CFL number
VARIANTS = [("MUSL, CFL 0.5 (defaults)", "MUSL", 0.5),
            ("MUSL, CFL 0.25", "MUSL", 0.25),
            ("USAVG, CFL 0.5", "USAVG", 0.5)]


def run(sable, work, scene, scheme, cfl):
    """Run one variant; return (rows of statistics.csv, steps, wall time)."""
    name = f"{scene.replace(' ', '_')}_{scheme}_{cfl}"
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, name + ".prm"), "w") as f:
        f.write(SCENES[scene] + f"set Output directory = {name}\n")
    # a generous drift limit: MUSL's gain is what the table shows
    result = subprocess.run([sable, name + ".prm", "--overwrite",
                             "--set", f"Solver/Update scheme={scheme}",
                             "--set", f"Time/CFL number={cfl}",
                             "--set", "Output/Statistics interval=10",
                             "--set", "Output/Energy drift limit=10"],
                            cwd=work, capture_output=True, text=True)
    output = result.stdout + result.stderr
    if result.returncode != 0:
        sys.stderr.write(output)
        raise SystemExit(f"{name}: sable exited with {result.returncode}")
    finished = re.search(r"Finished (\d+) steps to t = \S+ in (\S+) s wall time", output)
    with open(os.path.join(work, name, "statistics.csv")) as f:
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    return rows, int(finished.group(1)), float(finished.group(2))


def energy_change(scene, rows):
    """Per row: the energy against the start, as a fraction."""
    if scene == "flight":
        return [r["energy_drift"] for r in rows]
    start = rows[0]["kinetic_energy"] + rows[0]["strain_energy"]
    return [(r["kinetic_energy"] + r["strain_energy"]) / start - 1 for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "update_schemes.work"))
    parser.add_argument("--output-dir", default=None,
                        help="where the table and figure go (default: the work directory)")
    args = parser.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise SystemExit(f"{sys.argv[0]}: the figure needs matplotlib, which {sys.executable} "
                         "does not have (Debian: apt-get install python3-matplotlib, then run "
                         "the script as it is, with /usr/bin/python3)")
    sable, work = os.path.abspath(args.sable), os.path.abspath(args.work)
    output_dir = args.output_dir or work

    lines = ["| scene | run | steps | wall s | energy at the end | largest |",
             "|---|---|---|---|---|---|"]
    figure, axes = plt.subplots(1, len(SCENES), figsize=(11, 4))
    for axis, scene in zip(axes, SCENES):
        for label, scheme, cfl in VARIANTS:
            rows, steps, wall = run(sable, work, scene, scheme, cfl)
            change = energy_change(scene, rows)
            lines.append(f"| {scene} | {label} | {steps} | {wall:.2f} | "
                         f"{change[-1]:+.2%} | {max(change):+.2%} |")
            print(lines[-1], flush=True)
            axis.plot([r["time"] for r in rows], [100 * c for c in change], label=label)
        axis.set_title(scene)
        axis.set_xlabel("t, s")
        axis.axhline(0, color="grey", linewidth=0.5)
        axis.grid(alpha=0.3)
    axes[0].set_ylabel("kinetic + strain energy against the start, %")
    axes[1].set_ylabel("energy_drift (heat counted), %")
    axes[0].legend()
    figure.tight_layout()
    os.makedirs(output_dir, exist_ok=True)
    with open(os.path.join(output_dir, "update_schemes.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    figure.savefig(os.path.join(output_dir, "update_schemes.png"), dpi=110)
    print(f"wrote {output_dir}/update_schemes.md and update_schemes.png")


if __name__ == "__main__":
    main()
