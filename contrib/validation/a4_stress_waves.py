#!/usr/bin/python3
"""Validation scene A4 (Bardenhagen, Brackbill, Sulsky 2001, "002",
Figs. 9-11): a stress wave through disk assemblies driven by a loading pin.

Runs prm/a4_collinear.prm (a), a4_zigzag.prm (b, mu = 0.5) and a4_glued.prm
(c, stick) at the given cells per diameter (or reads the statistics.csv of
runs made before, --read), and from the contact force of every pair along
the load path (statistics.csv, columns contact<a>_<b>_fx, _fy) gives

- the arrival time of the wave at each contact, in t c_L / D with
  c_L = sqrt((K + 4G/3)/rho) = 10208 m/s and D = 1 cm: the first time the
  pair's force exceeds a threshold, by default 1% of the largest force the
  pin exerts in the run. A fraction of one force of the run (not of each
  pair's own peak) makes the times independent of how long a run lasts and
  comparable between contacts. 1% is above the numerical precursor of an
  explicit grid scheme (information moves one cell per step, 1/CFL = 2
  times c_L here, with an amplitude that falls by orders of magnitude per
  cell ahead of the front: the forces ahead of the front are below 1e-3 of
  the pin's) and low enough that the time is that of the front, not of the
  rise behind it (the force at a contact takes about one D/c_L to rise to
  its plateau);
- the transit across each disk (difference of the arrival times at its two
  contacts) and the mean wave speed along the path from the pin's contact
  to the farthest disk-disk contact, over c_L: the path is the chain of
  chords between a disk's two contact points (D for the collinear disks;
  D/sqrt2 for a zig-zag disk whose contacts are 90 degrees apart, and
  2R sin(67.5 deg) for the last one, touched by the pin at 0 and by its
  neighbour at 135 degrees).

Writes a4_arrivals.md (the table) into --output-dir (default: the work
directory) and prints it; each run's console output (with its timings) is
in WORK/a4_<case>_n<cells>/sable.log.

Usage: contrib/validation/a4_stress_waves.py [--sable build/sable]
           [--work DIR] [--cells 20 40 80] [--cases collinear zigzag glued]
           [--threshold 0.01] [--particles] [--read] [--output-dir DIR]
Without --particles the runs write no particle files (only the timing and
statistics); --particles keeps the scenes' output every 0.1 D/c_L with the
smoothed stress, for contrib/validation/a4_fringes.py."""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
D = 0.01
C_L = math.sqrt((102e9 + 4.0 / 3.0 * 72e9) / 1900.0)
T_UNIT = D / C_L
PIN_SPEED = 5.6

# name: (label, grid size in m, disks, pin body, pairs along the load path
# from the pin (body pairs a-b), chord lengths of the disks between those
# contacts in D, the paper's frame times, the ceiling body or None)
ZIGZAG_CHORDS = [2 * 0.5 * math.sin(math.radians(67.5))] + [1 / math.sqrt(2)] * 3
CASES = {
    "collinear": ("(a) four collinear disks", (0.046, 0.01), 4, 4,
                  [(3, 4), (2, 3), (1, 2), (0, 1)], [1.0, 1.0, 1.0], (2.2, 5.5, 7.7), None),
    "zigzag": ("(b) five zig-zag disks, mu = 0.5", (0.045, 0.0195), 5, 5,
               [(4, 5), (3, 4), (2, 3), (1, 2), (0, 1)], ZIGZAG_CHORDS, (3.0, 6.0, 9.0), 6),
    "glued": ("(c) five zig-zag disks, glued", (0.045, 0.0195), 5, 5,
              [(4, 5), (3, 4), (2, 3), (1, 2), (0, 1)], ZIGZAG_CHORDS, (1.4, 3.6, 5.8), 6),
}


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def pair_force(rows, a, b):
    """|contact force| of pair a-b per row, N/m."""
    return [math.hypot(r[f"contact{a}_{b}_fx"], r[f"contact{a}_{b}_fy"]) for r in rows]


def arrivals(rows, case, threshold=0.01):
    """Arrival times (t c_L/D) at the contacts along the path of @p case,
    from the pin's contact on; None where the force never exceeds the
    threshold. Also returns the threshold force."""
    pairs = CASES[case][4]
    pin_force = max(pair_force(rows, *pairs[0]))
    level = threshold * pin_force
    times = []
    for a, b in pairs:
        force = pair_force(rows, a, b)
        first = next((i for i, f in enumerate(force) if f > level), None)
        times.append(rows[first]["time"] / T_UNIT if first is not None else None)
    return times, level


def summary(rows, case, threshold=0.01):
    """Arrival times, transits per disk, the mean speed over c_L along the
    path to the farthest contact reached."""
    times, level = arrivals(rows, case, threshold)
    chords = CASES[case][5]
    transits = [t1 - t0 if t0 is not None and t1 is not None else None
                for t0, t1 in zip(times, times[1:])]
    reached = [k for k, t in enumerate(times) if t is not None]
    last = reached[-1]
    speed = None
    if last > 0:
        speed = sum(chords[:last]) / (times[last] - times[0])
    return {"times": times, "transits": transits, "speed": speed, "level": level}


def subdivisions(case, cells_per_diameter):
    h = D / cells_per_diameter
    return tuple(round(length / h) for length in CASES[case][1])


def run(sable, case, cells, work, particles):
    """Run one case at one resolution; return (rows, wall time s, points)."""
    directory = os.path.join(work, f"a4_{case}_n{cells}")
    os.makedirs(directory, exist_ok=True)
    nx, ny = subdivisions(case, cells)
    command = [sable, os.path.join(ROOT, "prm", f"a4_{case}.prm"), "--overwrite",
               "--set", f"Grid/Subdivisions={nx}, {ny}",
               "--set", f"Output directory={os.path.abspath(directory)}"]
    if not particles:
        # particle files only at the start and the end
        command += ["--set", "Output/Particle output interval=1"]
    result = subprocess.run(command, capture_output=True, text=True)
    output = result.stdout + result.stderr
    with open(os.path.join(directory, "sable.log"), "w") as f:
        f.write(output)
    if result.returncode != 0:
        sys.exit(f"a4_stress_waves.py: sable failed on {case} at {cells} cells:\n{output}")
    wall = float(re.search(r"in ([0-9.e+-]+) s wall time", output).group(1))
    points = int(re.search(r"cells, ([0-9]+) material points", output).group(1))
    return read_csv(os.path.join(directory, "statistics.csv")), wall, points


def fmt(value, digits=2):
    return "-" if value is None else f"{value:.{digits}f}"


def table(results, threshold):
    """Markdown table of (case, cells, summary, wall, points) rows."""
    lines = [f"Arrival of the wave at each contact along the load path, t c_L/D "
             f"(first time the pair's force exceeds {100 * threshold:g}% of the pin's "
             "largest force); transit = difference across a disk; speed = path "
             "length over time from the pin's contact to the farthest contact, over c_L.",
             "",
             "| case | cells/D | points | wall time (s) | arrival at contacts, pin first | "
             "transits per disk | mean speed / c_L | paper's frames |",
             "|---|---|---|---|---|---|---|---|"]
    for case, cells, s, wall, points in results:
        label = CASES[case][0]
        pairs = CASES[case][4]
        times = ", ".join(f"{a}-{b}: {fmt(t)}" for (a, b), t in zip(pairs, s["times"]))
        transits = ", ".join(fmt(t) for t in s["transits"])
        frames = ", ".join(str(t) for t in CASES[case][6])
        lines.append(f"| {label} | {cells} | {points if points is not None else '-'} | {fmt(wall, 1)} | {times} | {transits} | "
                     f"{fmt(s['speed'])} | {frames} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default="a4.work")
    parser.add_argument("--cells", type=int, nargs="+", default=[20])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--threshold", type=float, default=0.01)
    parser.add_argument("--particles", action="store_true",
                        help="keep the scenes' particle output (for the fringes)")
    parser.add_argument("--read", action="store_true",
                        help="read WORK/a4_<case>_n<cells>/statistics.csv instead of running")
    parser.add_argument("--output-dir", default=None)
    args = parser.parse_args()
    if not 0 < args.threshold < 1:
        sys.exit(f"a4_stress_waves.py: --threshold = {args.threshold}; allowed: (0, 1)")
    os.makedirs(args.work, exist_ok=True)
    results = []
    for case in args.cases:
        for cells in args.cells:
            if args.read:
                path = os.path.join(args.work, f"a4_{case}_n{cells}", "statistics.csv")
                if not os.path.exists(path):
                    sys.exit(f"a4_stress_waves.py: {path} is missing (run without --read first)")
                rows, wall, points = read_csv(path), None, None
            else:
                rows, wall, points = run(args.sable, case, cells, args.work, args.particles)
            results.append((case, cells, summary(rows, case, args.threshold), wall, points))
    text = table(results, args.threshold)
    print(text)
    output_dir = args.output_dir or args.work
    os.makedirs(output_dir, exist_ok=True)
    with open(os.path.join(output_dir, "a4_arrivals.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
