#!/usr/bin/python3
"""Validation scene A4 in small: the stress wave through disk assemblies
(paper 002, Figs. 9-11) on the coarse variants of prm/a4_collinear.prm,
a4_zigzag.prm and a4_glued.prm, 20 cells per diameter (the scenes' own 80
changed by --set "Grid/Subdivisions"), particle files only at the start
and the end. Arrival times from contrib/validation/a4_stress_waves.py (1%
of the pin's largest force; see there), in t c_L/D.

Measured on these runs (and at 40 cells, doc/validation/a4.md):
- (a) collinear: arrivals 0.02, 0.90, 1.97, 3.07 (40 cells, with the
  normals of the heavier body at each node: 0.01, 0.95, 2.01, 3.34): the
  mean transit across the three disks between the pin's contact and the
  last disk-disk contact is 1.02 D/c_L (1.11). Tolerance:
  within 15% of D/c_L (the issue's bound). A wave at the shear speed
  c_S = 0.60 c_L would take 1.66.
- glued (c) reaches the far contact 0-1 at 4.00, slipping (b) at 5.05 (40
  cells: 3.97 and 5.17). Check: (c) earlier than (b) by more than
  0.5 D/c_L, half the measured gap; the contacts before the sliding ones
  (pin, 3-4) are reached at the same time in both (1e-9), since the
  scenes differ only in disk-disk friction and no disk-disk contact acts
  before the wave arrives.
- frictionless walls take no tangential load: the ceiling (a fixed wall
  body, friction 0) carries |f_x| <= 1e-9 of its largest normal force
  (measured 5e-14: round-off), and so does the frictionless pin on the
  disk it pushes (|f_y| 6e-14 of |f_x|).
- no disk penetrates another or the ceiling: at the end, every point of a
  disk lies at least R - h/4 from the centre of every other disk (at
  t = 0 at least R: the points are seeded inside their own disk; the
  contacts' elastic compression is bounded by the pin's travel,
  v_pin t = 56 um = 0.11 h; measured 1.01 R), and no point is more than
  h/4 above the ceiling's face (measured 0.64 h below it).
- no NaN (sable stops on one with an error) and finite statistics."""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("SABLE_SOURCE", os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "mpm"))
sys.path.insert(0, os.path.join(SOURCE, "contrib", "validation"))
from scene_test import SABLE, WORK, check, finish  # noqa: E402
import a4_stress_waves as a4  # noqa: E402

CELLS = 20
h = a4.D / CELLS
R = a4.D / 2

results = {}
for case in a4.CASES:
    rows, wall, points = a4.run(SABLE, case, CELLS, WORK, particles=False)
    results[case] = (rows, a4.summary(rows, case))
    finite = all(math.isfinite(v) for r in rows for v in r.values())
    check(f"{case}: {len(rows)} rows of statistics, all finite", finite and len(rows) > 100)

# (a) transit across one disk
s = results["collinear"][1]
times = s["times"]
print("collinear arrivals", times)
mean_transit = (times[-1] - times[0]) / 3
check("(a) mean transit across a disk within 15% of D/c_L", abs(mean_transit - 1) <= 0.15,
      f"{mean_transit:.3f} D/c_L (arrivals {', '.join(f'{t:.2f}' for t in times)})")
check("(a) arrivals in order along the path", all(t1 > t0 for t0, t1 in zip(times, times[1:])))

# (c) glued faster than (b) slipping
b, c = results["zigzag"][1]["times"], results["glued"][1]["times"]
print("zigzag arrivals", b, "glued arrivals", c)
check("(c) glued reaches the far contact 0-1 before (b) slipping, by > 0.5 D/c_L",
      b[-1] is not None and c[-1] is not None and b[-1] - c[-1] > 0.5,
      f"glued {c[-1]:.2f}, slipping {b[-1]:.2f}")
check("(b) and (c) reach the pin's contact and 3-4 at the same time",
      all(abs(x - y) <= 1e-9 for x, y in zip(b[:2], c[:2])), f"{b[:2]} and {c[:2]}")

# frictionless walls and pin: no tangential load
for case in ("zigzag", "glued"):
    rows = results[case][0]
    for a in (1, 3):
        normal = max(abs(r[f"contact{a}_6_fy"]) for r in rows)
        tangential = max(abs(r[f"contact{a}_6_fx"]) for r in rows)
        check(f"{case}: ceiling on disk {a}: no tangential load", normal > 0 and tangential <= 1e-9 * normal,
              f"|f_x| {tangential:.3g}, largest |f_y| {normal:.3g} N/m")
    normal = max(abs(r["contact4_5_fx"]) for r in rows)
    tangential = max(abs(r["contact4_5_fy"]) for r in rows)
    check(f"{case}: frictionless pin: no tangential load", normal > 0 and tangential <= 1e-9 * normal,
          f"|f_y| {tangential:.3g}, largest |f_x| {normal:.3g} N/m")

# no penetration, from the last particle file
try:
    import meshio
    import numpy as np
    from xml.etree import ElementTree
except ImportError as error:
    sys.exit(f"a4_stress_waves_test.py: {error.name} is missing (python3-meshio, python3-numpy)")
for case in a4.CASES:
    n_disks = a4.CASES[case][2]
    directory = os.path.join(WORK, f"a4_{case}_n{CELLS}")
    last = list(ElementTree.parse(os.path.join(directory, "particles.pvd")).getroot().iter("DataSet"))[-1]
    pvtu = os.path.join(directory, last.get("file"))
    pieces = [os.path.join(directory, p.get("Source")) for p in ElementTree.parse(pvtu).getroot().iter("Piece")]
    meshes = [meshio.read(p) for p in pieces]
    x = np.concatenate([m.points[:, :2] for m in meshes if len(m.points)])
    body = np.concatenate([m.point_data["body"].ravel() for m in meshes if len(m.points)]).astype(int)
    row = results[case][0][-1]
    closest = math.inf
    for a in range(n_disks):
        for other in range(n_disks):
            if other == a:
                continue
            centre = np.array([row[f"body{other}_x"], row[f"body{other}_y"]])
            closest = min(closest, np.linalg.norm(x[body == a] - centre, axis=1).min())
    check(f"{case}: no disk penetrates another (points >= R - h/4 from other centres)",
          closest >= R - h / 4, f"closest {closest / R:.4f} R")
    if a4.CASES[case][7] is not None:
        ceiling = (1 + 1 / math.sqrt(2)) * a4.D
        highest = x[body < n_disks][:, 1].max()
        check(f"{case}: no disk enters the ceiling", highest <= ceiling + h / 4,
              f"highest point {(highest - ceiling) / h:.3f} h from the ceiling")
finish()
