#!/usr/bin/python3
"""Friction against a driven body: bodies set down at rest on a conveyor.

A belt (a box of prescribed velocity V = 1 m/s) carries, under gravity and
with Coulomb friction mu between them (Bardenhagen 2001 contact):
1. A block (2D: 0.2 m square, mu = 0.3; 3D: 0.2 m cube, mu = 0.6), set
   down at rest. The rigid block slides with a = mu g until it moves with
   the belt at t* = V / (mu g), then rides along: x(t) = mu g t^2 / 2 up to
   t*, then x(t*) + V (t - t*). Checked: x(t) within 1% of the rigid
   block's travel at every row (measured 0.02% in 2D, 0.3% in 3D; the
   elastic block starts stress-free and settles into its elastic
   equilibrium as it starts to slide), and at the end it moves with the
   belt, |v - V| below 1% of V (measured 0.0000 V and 0.005 V).
2. A disk (R = 0.2 m, 16 cells per diameter, seeded conforming, mu = 0.3),
   set down at rest: friction drives it forward (a = mu g) and spins it up
   (alpha = 2 mu g / R) until its bottom moves with the belt at
   t* = V / (3 mu g), when the disk's centre moves at V / 3. Checked: its
   bottom reaches the belt's speed (within 1% of V) at a time within 5% of
   t* (measured -2.9%), its centre's speed then within 0.03 V of V / 3
   (measured +0.002 V; rows every 5 steps, and the disk bounces as it
   settles into its elastic equilibrium).
   After t* the rigid disk rolls on at V / 3. Checked: its centre at 0.5 s
   within 0.03 V of V / 3 (measured +0.009 V). The disk meets the driven
   belt at a point (doc/mpm.md, "Contact at a point"); before it did, the
   point's test of the belt's surface took the belt's scaled masses for
   its own, the disk rested on the node nearest its lowest point, was
   dragged along, and reached 0.445 V.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import check, finish, run  # noqa: E402

g = 9.81
V = 1.0
elastic = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
           "Particles per cell direction": 2}


def conveyor(dim, mu, end_time, cell, body):
    size = (3.0, 0.8) if dim == 2 else (1.3, 0.4, 0.3)
    down = f"0, {-g}" + (", 0" if dim == 3 else "")
    belt_upper = "2.4, 0.2" if dim == 2 else "1.0, 0.1, 0.3"
    entries = {"Dimension": dim, "Gravity": down, "Time/End time": end_time,
               "Grid/Lower corner": ", ".join(["0"] * dim), "Grid/Upper corner": ", ".join(map(str, size)),
               "Grid/Subdivisions": ", ".join(str(round(s / cell)) for s in size),
               "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": mu,
               "Output/Statistics interval": 5}
    belt = dict(elastic, Shape="box", **{"Lower corner": ", ".join(["0"] * dim), "Upper corner": belt_upper,
                                         "Prescribed velocity": f"{V}, 0" + (", 0" if dim == 3 else "")})
    return run(f"conveyor_{dim}d_{body['Shape']}", entries, [belt, body])[2]


for dim, mu, end_time, cell, block in [
        (2, 0.3, 0.5, 0.025, {"Lower corner": "0.7, 0.2", "Upper corner": "0.9, 0.4"}),
        (3, 0.6, 0.3, 0.05, {"Lower corner": "0.2, 0.1, 0.05", "Upper corner": "0.4, 0.3, 0.25"})]:
    rows = conveyor(dim, mu, end_time, cell, dict(elastic, Shape="box", **block))
    t_star = V / (mu * g)

    def rigid(t):
        return 0.5 * mu * g * min(t, t_star) ** 2 + V * max(t - t_star, 0)

    what = f"block on a conveyor, {dim}D, mu = {mu}"
    travel = [(r["time"], r["body1_x"] - rows[0]["body1_x"]) for r in rows]
    worst = max(abs(x - rigid(t)) for t, x in travel) / rigid(travel[-1][0])
    check(f"{what}: x(t) within 1% of the rigid block's travel (slides at mu g, then rides along)",
          worst <= 0.01, f"largest error {worst:.2%} of the travel")
    check(f"{what}: moves with the belt at the end (|v - V| below 1% of V)",
          abs(rows[-1]["body1_vx"] - V) <= 0.01 * V, f"v = {rows[-1]['body1_vx']:.4f} m/s")

R = 0.2
mu = 0.3
rows = conveyor(2, mu, 0.5, 0.025, dict(elastic, Shape="disk", Center=f"0.8, {0.2 + R}", Radius=R,
                                        Seeding="conforming"))
t_star = V / (3 * mu * g)
# the first row at which its bottom has caught up with the belt (within 1%)
rolling = next((r for r in rows if r["time"] > 0.01 and r["body1_vx"] + r["body1_omega"] * R >= 0.99 * V), None)
check("disk on a conveyor: its bottom reaches the belt's speed within 5% of t* = V / (3 mu g)",
      rolling is not None and abs(rolling["time"] - t_star) <= 0.05 * t_star,
      f"at {rolling['time']:.4f} s, t* = {t_star:.4f} s" if rolling else "never")
check("disk on a conveyor: its centre then moves at V / 3 (within 0.03 V)",
      rolling is not None and abs(rolling["body1_vx"] - V / 3) <= 0.03 * V,
      f"v = {rolling['body1_vx']:.4f} m/s" if rolling else "")
check("disk on a conveyor: it rolls on at V / 3 (its centre at 0.5 s within 0.03 V)",
      abs(rows[-1]["body1_vx"] - V / 3) <= 0.03 * V, f"v = {rows[-1]['body1_vx']:.4f} m/s")
finish()
