#!/usr/bin/python3
"""A disk at rest on a plane body stays; set rolling, it rolls on; set
sliding without friction, it keeps its spin.

The scene of contrib/validation/disk_at_rest.py: a soft disk (R = 0.2 m,
12.8 cells per diameter, K = 1 MPa, G = 0.5 MPa, seeded clipped) settled on
an elastic plane body, Bardenhagen 2001, gravity 9.81 m/s^2 straight down,
then 0.5 s. A rigid disk on a plane is in neutral equilibrium: at rest it
stays, rolling at v it rolls on at v, and sliding without friction it keeps
its spin, since normal forces on a circle pass through its centre.

Checked with the default 'Contact/Round body surfaces = contact point':
- at rest, the plane's face on a grid line and half a cell off it, 0.5
  cells off the disk's centre: it moves less than 1% of a cell in 0.5 s
  (the issue's bound for a block held by friction; measured 0.46% and
  0.11%; with 'located' 9.1% and 6.9%, its weight on the node under its
  lowest point, a pivot);
- its centre over a node, started rolling at 2 mm/s (mu = 0.5): at 0.5 s
  it rolls at 0.9 to 1.1 times that (measured 0.94; 'located' 7.8, an
  inverted pendulum about the node, which the last check asks to see);
- the same start without friction: omega R at 0.5 s within 20% of the
  start (measured 0.87; 'located' 13.0, the weight's moment about the node
  it slides off; 'centroid offset' 1.30).
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "mpm"))
sys.path.insert(0, os.path.join(ROOT, "contrib", "validation"))
from scene_test import check, finish, run  # noqa: E402
import disk_at_rest  # noqa: E402

H, R, START = disk_at_rest.H, disk_at_rest.R, disk_at_rest.START_SPEED


def scene(name, offset, centre_x, mu, start, estimate="contact point"):
    entries, bodies = disk_at_rest.scene(offset, centre_x, mu, start,
                                         {"Contact/Round body surfaces": estimate})
    code, output, rows = run(name, entries, bodies)
    check(f"{name}: the run ends", code == 0 and rows, output.strip().splitlines()[-1])
    return rows


for offset in (0, 0.5):
    rows = scene(f"rest_{offset}", offset, 0.5 + 0.3 * H, 0.5, False)
    drift = max(abs(r["body1_x"] - rows[0]["body1_x"]) for r in rows) / H
    check(f"at rest, face {offset} cells off the grid line: moves less than 1% of a cell in 0.5 s",
          drift < 0.01, f"{100 * drift:.2f}% of a cell")

rows = scene("rolling_start", 0, 0.5, 0.5, True)
ratio = rows[-1]["body1_vx"] / START
check("started rolling over a node: rolls on at 0.9 to 1.1 times its start", 0.9 <= ratio <= 1.1,
      f"{ratio:.3f}")

rows = scene("frictionless_spin", 0, 0.5, 0, True)
ratio = -rows[-1]["body1_omega"] * R / START
check("started sliding without friction: keeps its spin within 20%", 0.8 <= ratio <= 1.2,
      f"omega R / start {ratio:.3f}")

rows = scene("rolling_start_located", 0, 0.5, 0.5, True, "located")
ratio = rows[-1]["body1_vx"] / START
check("with 'located' the node under the disk is a pivot: the rolling start grows at least 3-fold",
      ratio >= 3, f"{ratio:.3f}")

finish()
