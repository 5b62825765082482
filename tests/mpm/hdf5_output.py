#!/usr/bin/env python3
"""HDF5 + XDMF particle output (Output format = hdf5) on 1 and 2 ranks: an
elastic box 0.4 m x 0.3 m (density 1000, 2x2 points in each 0.05 m cell,
192 points of 0.625 kg) falling freely. Each particles_NNNNN.h5, read back
with h5dump (Debian package hdf5-tools), holds as many points as the
`particles` column of statistics.csv at that output step, with the ids
0..191; their masses sum to the body's 120 kg and every point's velocity is
(0, g t), t the time of that row (a stress-free body in free fall gains
exactly g dt per step at every node; test free_fall holds the centre of
mass to 1e-10). deal.II keeps output fields in single precision
(DataOutBase::Patch::data is float), so each value carries a rounding of up
to 2^-24 = 6e-8 relative: the tolerance for mass and velocity is 1.2e-7.
The point locations are written in double precision: those of 1 and 2
ranks (sorted; ids are numbered per rank) agree to 1e-13 m.
particles.xdmf has one entry per output time, in order, each referencing
its .h5 file. A small box on one of 3 ranks checks that ranks without
material points do not stall the collective write."""
import os
import re
import shutil
import subprocess
from scene_test import *

if not shutil.which("h5dump"):
    raise SystemExit("[FAIL] h5dump not found: install the Debian package hdf5-tools (contrib/setup.sh does)")


def read_dataset(h5, name):
    """The rows of dataset `name` in file `h5`, all digits, through h5dump."""
    text_file = h5 + "." + name + ".txt"
    subprocess.run(["h5dump", "-d", "/" + name, "-m", "%.17g", "-y", "-w", "0", "-o", text_file, h5],
                   check=True, capture_output=True)
    with open(text_file) as f:
        values = [float(v) for v in re.split(r"[,\s]+", f.read()) if v]
    with subprocess.Popen(["h5dump", "-H", "-d", "/" + name, h5], stdout=subprocess.PIPE, text=True) as p:
        shape = re.search(r"SIMPLE \{ \( (\d+), (\d+) \)", p.stdout.read())
    n, columns = int(shape.group(1)), int(shape.group(2))
    assert len(values) == n * columns, f"{name}: {len(values)} values for {n} x {columns}"
    return [values[i * columns:(i + 1) * columns] for i in range(n)]


g = -9.81
entries = {
    "Dimension": 2, "Gravity": f"0, {g}", "Time/End time": 0.2,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20",
    "Output/Output format": "hdf5", "Output/Particle output interval": 0.05,
}
body = {"Shape": "box", "Lower corner": "0.3, 0.6", "Upper corner": "0.7, 0.9",
        "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000, "Particles per cell direction": 2}

locations = {}
for ranks in (1, 2):
    name = f"hdf5_np{ranks}"
    _, output, rows = run(name, entries, [body], ranks=ranks)
    out = os.path.join(WORK, name, "output")
    check(f"{ranks} rank(s): the console names particles.xdmf", "particles.xdmf" in output)
    h5_files = sorted(f for f in os.listdir(out) if f.endswith(".h5"))
    with open(os.path.join(out, "particles.xdmf")) as f:
        xdmf = f.read()
    times = [float(t) for t in re.findall(r'<Time Value="([^"]+)"', xdmf)]
    referenced = re.findall(r'([\w.-]+\.h5):/nodes', xdmf)
    check(f"{ranks} rank(s): one xdmf entry per .h5 file, each referencing it",
          len(h5_files) >= 5 and referenced == h5_files and len(times) == len(h5_files),
          f"{len(h5_files)} files, xdmf references {referenced}, {len(times)} times")
    check(f"{ranks} rank(s): xdmf times increase", times == sorted(times) and times[0] == 0, str(times))
    worst_v = worst_mass = 0.0
    for h5, t in zip(h5_files, times):
        # the statistics row of this output (statistics every step)
        row = min(rows, key=lambda r: abs(r["time"] - t))
        path = os.path.join(out, h5)
        nodes = read_dataset(path, "nodes")
        mass = [m[0] for m in read_dataset(path, "mass")]
        velocity = read_dataset(path, "velocity")
        ids = [int(i[0]) for i in read_dataset(path, "id")]
        check(f"{ranks} rank(s), {h5}: {len(nodes)} points as in statistics.csv",
              len(nodes) == row["particles"] == len(mass) == len(velocity) == 192,
              f"{len(nodes)} nodes, {len(mass)} masses, {row['particles']:g} in statistics.csv")
        check(f"{ranks} rank(s), {h5}: ids 0..191", sorted(ids) == list(range(192)))
        worst_mass = max(worst_mass, abs(sum(mass) - 120.0) / 120.0)
        expected = g * row["time"]
        if row["time"] > 0:
            worst_v = max(worst_v, max(abs(v[1] - expected) for v in velocity) / abs(expected))
        check(f"{ranks} rank(s), {h5}: no horizontal velocity", max(abs(v[0]) for v in velocity) < 1e-12)
        locations.setdefault(ranks, []).append(sorted(nodes))
    check(f"{ranks} rank(s): mass sums to 120 kg to 1.2e-7", worst_mass <= 1.2e-7, f"relative error {worst_mass:.2e}")
    check(f"{ranks} rank(s): every point's v_y = g t to 1.2e-7", worst_v <= 1.2e-7, f"largest relative error {worst_v:.2e}")

difference = max(abs(p[d] - q[d]) for a, b in zip(locations[1], locations[2]) for p, q in zip(a, b) for d in (0, 1))
check("1 and 2 ranks: the same point locations", len(locations[1]) == len(locations[2]) and difference < 1e-13,
      f"largest difference {difference:.2e} m")
# ranks without material points: deal.II 9.4's HDF5 writer would wait for
# them in a collective write; sable lets only the ranks with points write
small = {"Shape": "box", "Lower corner": "0.05, 0.9", "Upper corner": "0.1, 0.95",
         "Young's modulus": 1e6, "Density": 1000, "Particles per cell direction": 2}
try:
    code, output, rows = run("hdf5_empty_ranks", dict(entries, **{"Time/End time": 0.02, "Gravity": "0, 0",
                                                                  "Output/Particle output interval": 0.01}),
                             [small], ranks=3, expect_success=False, timeout=120)
except subprocess.TimeoutExpired:
    code, output, rows = "timeout", "", []
out = os.path.join(WORK, "hdf5_empty_ranks", "output")
h5_files = sorted(f for f in os.listdir(out) if f.endswith(".h5")) if os.path.isdir(out) else []
check("3 ranks, points on one: finishes", code == 0, f"exit {code}")
check("3 ranks, points on one: every file has the 4 points",
      len(h5_files) == 3 and all(len(read_dataset(os.path.join(out, h5), "nodes")) == 4 for h5 in h5_files),
      f"{len(h5_files)} files")
finish()
