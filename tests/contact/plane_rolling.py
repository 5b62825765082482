#!/usr/bin/python3
"""A disk rolling down a plane body whose face lies between grid lines.

The scene of contrib/validation/plane_rolling.py: a disk (R = 0.2 m, 16
cells per diameter, seeded clipped, the default) rolls down an elastic
plane body (a box on the fixed floor), both E = 10 MPa, nu = 0.3,
rho = 1000 kg/m^3, lithostatic initial stress, gravity tilted by theta,
Bardenhagen 2001 with friction mu, to 0.5 s. The rigid disk travels
g sin(theta) t^2 / 3. Issue target: within 3% at 16 cells per diameter
for any rolling disk on a plane body, at any registration of the face
with the grid.

Checked where the contact used to fail (doc/validation.md, "Rolling on a
plane body whose face lies between grid lines"), 30 deg, mu = 0.5:
- the face a quarter cell off a grid line, so the box's top row of points
  lies on it (their vectors to the face are zero, and they carried none:
  -5.3%; measured now -0.49%);
- half a cell off (the disk's surface from its centroid, the node taken to
  lie on it: -9.3%; now -0.56%);
- 15 deg, mu = 0.2, seven eighths of a cell off: the disk's nodes at the
  point lie above the face, where the box's records are light; MUSL's remap
  pass found the slip again but could take friction only up to mu times
  its own small normal impulse, and the disk ran ahead (+4.73%; now -0.76%
  with the step's two passes capped together);
and one case not tuned on: 50 deg, mu = 0.5, R = 0.25 m (20 cells per
diameter), 0.4 cells off (measured -0.10%). The disk's largest rise off
its start stays below a tenth of a cell (it hopped up to a quarter cell).
With 'Contact/Round body surfaces = centroid offset' half a cell off it
lags again (-9.41%).
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "mpm"))
sys.path.insert(0, os.path.join(ROOT, "contrib", "validation"))
from scene_test import check, finish, run  # noqa: E402
import plane_rolling  # noqa: E402

G = plane_rolling.G
for offset, theta, mu, radius in ((0.25, 30, 0.5, 0.2), (0.5, 30, 0.5, 0.2), (0.875, 15, 0.2, 0.2),
                                  (0.4, 50, 0.5, 0.25)):
    entries, bodies = plane_rolling.scene(offset, theta, mu, radius, "", 0.5, {})
    code, output, rows = run(f"plane_rolling_{offset}_{theta}", entries, bodies)
    what = f"{theta} deg, mu {mu}, R {radius} m, face {offset} cells off the grid line"
    check(f"{what}: the run ends", code == 0 and rows, output.strip().splitlines()[-1])
    if not rows:
        continue
    t = rows[-1]["time"]
    travel = rows[-1]["body1_x"] - rows[0]["body1_x"]
    error = travel / (G * math.sin(math.radians(theta)) / 3 * t * t) - 1
    check(f"{what}: travel within 3% of the rigid rolling disk's", abs(error) <= 0.03, f"{error:+.2%}")
    # Coulomb at every row: the friction between the bodies at most mu times
    # their pressing normal force, none while the 2001 rule's hold pulls.
    # The grid's axes are the face's up to the face's tilt under the disk
    # (measured below 1e-4 rad: a pulling force shows 1e-5 to 1e-4 of
    # itself along x, a pressing one up to 3e-4 of mu times itself): 1e-3
    # of the normal force allowed
    excess = max(abs(r["contact0_1_fx"]) - mu * max(-r["contact0_1_fy"], 0) - 1e-3 * abs(r["contact0_1_fy"])
                 for r in rows[1:])
    check(f"{what}: friction at most mu times the pressing normal force at every row",
          excess <= 1e-6 * plane_rolling.MATERIAL["Density"] * radius ** 2 * G, f"largest excess {excess:.3g} N")
    rise = max(r["body1_y"] for r in rows) - rows[0]["body1_y"]
    check(f"{what}: the disk stays on the plane (rises less than 0.1 cell)",
          rise < 0.1 * plane_rolling.H, f"{rise / plane_rolling.H:.3f} cells")

# 'Round body surfaces = centroid offset' keeps the estimate the located
# surfaces replaced (for disks resting on bodies, which it holds more
# quietly): half a cell off the grid line the disk lags again (measured
# -9.41%)
entries, bodies = plane_rolling.scene(0.5, 30, 0.5, 0.2, "", 0.5,
                                      {"Contact/Round body surfaces": "centroid offset"})
code, output, rows = run("plane_rolling_centroid_offset", entries, bodies)
if rows:
    t = rows[-1]["time"]
    error = (rows[-1]["body1_x"] - rows[0]["body1_x"]) / (G * math.sin(math.radians(30)) / 3 * t * t) - 1
    check("'centroid offset', face half a cell off: the disk's surface from its centroid, it lags "
          "(travel at least 5% short)", error <= -0.05, f"{error:+.2%}")
else:
    check("'centroid offset': the run ends", False, output.strip().splitlines()[-1])
finish()
