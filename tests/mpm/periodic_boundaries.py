#!/usr/bin/python3
"""Periodic grids ('Grid/Periodic axes').

A periodic grid has no preferred place: a scene moved by whole cells along
its periodic axes is the same scene. Two elastic disks collide off-centre
with Coulomb friction (mu = 0.3, Bardenhagen 2001 contact, spin), once in
the middle of a grid periodic in x and y, and once moved by (20, 10) cells
so that both disks straddle the y seam at the start and they meet on the x
seam (near the corner where all four images meet). The second run must give
the first one's statistics: energies, contact heat, momentum and the
bodies' velocities, spins and positions (less the shift, wrapped). The
tolerance is 1e-9 of each column's largest magnitude: the two runs add the
same numbers in another order and at positions differing by the shift, so
they agree to round-off (about 1e-15) as long as no contact decision sits at
a round-off tie; a node folded across the seam with the wrong weight, a
point's mass moment taken at the wrong image (the contact detection reads
it) or a point lost at the seam changes them by 1e-3 or more within a few
steps. Points are counted at every step (none lost at the seams). The
disks are seeded on the lattice, whose points lie at the same places
relative to their cells in both runs; clipped (the default) places the
points of the surface at centroids computed from the centre, which differ
by round-off between the runs, and over the collision the columns then
agree to 1.5e-9.

Two threads give the one-thread statistics of the seam run to 1e-9 (the
cells at the upper faces share nodes with those at the lower faces: the
thread colouring must see it).

On two ranks (the partition cuts the seams, the nodes there are summed
across ranks) the seam run without contact (one velocity field: the disks
merge) gives the one-rank statistics to 1e-9. With contact two ranks are
refused: contact reads the other rank's points near it as ghost particles,
which deal.II 9.4 does not send across periodic faces.

With GIMP shape functions ('Grid/Shape functions = gimp') a point next to
a seam reaches the nodes beyond it directly, at their image shift: the
seam run again gives the middle run's statistics to 1e-9 (and differs
from the linear run), also on two threads. GIMP on two ranks is refused.

A disk crossing the x seam at constant velocity, no contact, comes back to
its start after one period: every point within 1e-6 of its initial
position (the VTU output's single precision), none lost.

Bad input: a boundary condition on a periodic face, fewer than 3 cells
along a periodic axis, gravity along a periodic axis and a body longer than
the period are refused before any work, naming the entry."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_test import WORK, check, finish, run  # noqa: E402

try:
    import meshio
    import numpy as np
except ImportError as error:
    sys.exit(f"periodic_boundaries.py: {error.name} is missing (python3-numpy, python3-meshio)")

L = (2.0, 1.0)
H = 0.05


def collision(shift):
    def wrap(x, d):
        return x % L[d]

    entries = {
        "Time/End time": 1,
        "Time/Maximum number of steps": 150,
        "Grid/Lower corner": "0, 0",
        "Grid/Upper corner": f"{L[0]}, {L[1]}",
        "Grid/Subdivisions": "40, 20",
        "Grid/Periodic axes": "x, y",
        "Contact/Model": "bardenhagen 2001",
        "Contact/Friction coefficient": 0.3,
    }
    common = {"Shape": "disk", "Radius": 0.2, "Material": "linear elastic", "Density": 1000,
              "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Seeding": "lattice"}
    centres = [(0.745, 0.45), (1.255, 0.58)]
    bodies = []
    for (x, y), v, w in zip(centres, (5, -5), (2, 0)):
        bodies.append(dict(common, **{"Center": f"{wrap(x + shift[0], 0)}, {wrap(y + shift[1], 1)}",
                                      "Velocity": f"{v}, 0", "Angular velocity": w}))
    return entries, bodies


def columns_agree(name, reference, rows, shift):
    check(f"{name}: as many rows", len(rows) == len(reference), f"{len(rows)} vs {len(reference)}")
    worst, where = 0.0, ""
    for key in reference[0]:
        a = np.array([r[key] for r in reference])
        b = np.array([r[key] for r in rows[:len(reference)]])
        if key.startswith("body") and key[-2:] in ("_x", "_y"):
            d = "xy".index(key[-1])
            # the position less the shift, to the nearest image
            b = b - shift[d]
            b = b - L[d] * np.round((b - a) / L[d])
        scale = max(np.abs(a).max(), 1e-300)
        error = np.abs(a - b).max() / scale
        if error > worst:
            worst, where = error, key
    check(f"{name}: every statistics column as the reference's to 1e-9 of its largest magnitude",
          worst <= 1e-9, f"largest difference {worst:.3g} ({where})")
    n = [r["particles"] for r in rows]
    check(f"{name}: no point lost", min(n) == max(n) == reference[0]["particles"], f"{min(n):.0f}-{max(n):.0f}")


shift = (20 * H, 10 * H)
entries, bodies = collision((0, 0))
_, _, middle = run("middle", entries, bodies)
entries, bodies = collision(shift)
_, output, seam = run("seam", entries, bodies)
contact = max(r["contact_heat"] for r in middle)
check("the disks meet and slip (contact heat > 0)", contact > 0, f"{contact:.4g} J")
columns_agree("moved onto the seams", middle, seam, shift)
_, _, threads = run("seam_2_threads", entries, bodies, args=("--threads", "2"))
columns_agree("on the seams, two threads", seam, threads, (0, 0))
single = dict(entries, **{"Contact/Model": "none"})
_, _, one_rank = run("seam_single_field", single, bodies)
_, _, ranks = run("seam_single_field_2_ranks", single, bodies, ranks=2)
columns_agree("on the seams without contact, two ranks", one_rank, ranks, (0, 0))
code, output, _ = run("seam_2_ranks", entries, bodies, ranks=2, expect_success=False)
check("refused: contact on a periodic grid on two ranks (names Grid/Periodic axes)",
      code != 0 and "Grid/Periodic axes" in output, output.strip().splitlines()[-1] if output.strip() else "")

# the same with GIMP shape functions, whose points reach nodes across the
# seam directly (not only through the folded upper-face nodes)
gimp_runs = []
for tag, offset in (("middle", (0, 0)), ("seam", shift)):
    entries, bodies = collision(offset)
    entries["Grid/Shape functions"] = "gimp"
    gimp_runs.append(run(f"gimp_{tag}", entries, bodies)[2])
columns_agree("GIMP, moved onto the seams", gimp_runs[0], gimp_runs[1], shift)
# a cell's points reach the nodes of its neighbours: the thread colouring
# must keep the blocks of one colour that far apart
columns_agree("GIMP on the seams, two threads", gimp_runs[1],
              run("gimp_seam_2_threads", entries, bodies, args=("--threads", "2"))[2], (0, 0))
change = max(abs(a["kinetic_energy"] - b["kinetic_energy"]) for a, b in zip(middle, gimp_runs[0]))
check("GIMP changes the run (kinetic energy differs from the linear run's)",
      change > 1e-6 * max(r["kinetic_energy"] for r in middle), f"{change:.3g} J")
code, output, _ = run("gimp_2_ranks", dict(entries, **{"Contact/Model": "none"}), bodies, ranks=2,
                      expect_success=False)
check("refused: GIMP on two ranks (names Grid/Shape functions)",
      code != 0 and "Grid/Shape functions" in output, output.strip().splitlines()[-1] if output.strip() else "")

# --- one period at constant velocity ----------------------------------------
period_entries = {
    "Time/End time": 0.4,           # 2 m at 5 m/s
    "Time/CFL number": 0.4,
    "Grid/Lower corner": "0, 0",
    "Grid/Upper corner": f"{L[0]}, {L[1]}",
    "Grid/Subdivisions": "40, 20",
    "Grid/Periodic axes": "x",
    "Output/Particle output interval": 0.4,
}
disk = {"Shape": "disk", "Center": "1.9, 0.5", "Radius": 0.2, "Velocity": "5, 0",
        "Material": "linear elastic", "Density": 1000, "Young's modulus": 1e6, "Poisson's ratio": 0.3}
_, output, rows = run("one_period", period_entries, [disk])
directory = os.path.join(WORK, "one_period", "output")
files = sorted(f for f in os.listdir(directory) if f.startswith("particles_") and f.endswith(".vtu"))
first, last = (meshio.read(os.path.join(directory, f)) for f in (files[0], files[-1]))
order0, order1 = (np.argsort(m.point_data["id"].ravel()) for m in (first, last))
p0, p1 = first.points[order0, :2], last.points[order1, :2]
t_end = rows[-1]["time"]
check("one period: ends at 0.4 s", abs(t_end - 0.4) < 1e-9, f"{t_end}")
check("one period: every point kept", len(p0) == len(p1) and rows[-1]["particles"] == rows[0]["particles"],
      f"{len(p0)} and {len(p1)}")
if len(p0) == len(p1):
    error = np.abs(p1 - p0).max()
    check("one period: every point back at its start to 1e-6 m", error <= 1e-6, f"{error:.3g} m")

# --- bad input ---------------------------------------------------------------
bad = [
    ("condition on a periodic face", {"Boundary conditions/Types": "2: slip"}, "Boundary conditions/Types"),
    ("too few cells", {"Grid/Subdivisions": "40, 2"}, "Grid/Subdivisions"),
    ("gravity along the axis", {"Gravity": "0, -9.81"}, "Gravity"),
]
for what, change, entry in bad:
    e = dict(period_entries, **{"Grid/Periodic axes": "y"}, **change)
    code, output, _ = run("bad", e, [disk], expect_success=False)
    check(f"refused: {what} (names {entry})", code != 0 and entry in output and "periodic" in output,
          output.strip().splitlines()[-1] if output.strip() else "no output")
long_body = {
    "Shape": "box", "Lower corner": "0.1, -0.6", "Upper corner": "0.5, 0.6",
    "Material": "linear elastic", "Density": 1000, "Young's modulus": 1e6, "Poisson's ratio": 0.3}
code, output, _ = run("bad", dict(period_entries, **{"Grid/Periodic axes": "y"}), [long_body],
                      expect_success=False)
check("refused: a body longer than the period", code != 0 and "period" in output,
      output.strip().splitlines()[-1] if output.strip() else "no output")
finish()
