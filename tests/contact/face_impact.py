#!/usr/bin/python3
"""A disk thrown head-on at a free box: contact at touch, at any
registration of the box's face with the grid.

A disk (R = 0.2 m, 16 cells per diameter, seeded clipped, the default) at
2 m/s towards a free 0.4 m square box, 5 cm from its face, both E = 10 MPa,
nu = 0.3, rho = 1000 kg/m^3, 2x2 points per cell, no gravity, Bardenhagen
2001 without friction and with mu = 0.3, to 0.25 s; the box's face on a
grid line and a quarter and half a cell off it. The surfaces touch at
t = 0.025 s. Checked, issue targets for head-on collisions:
- the first contact force comes when the surfaces touch, within the time
  the disk takes to travel a tenth of a cell (measured 0.0251 s at every
  offset; with the disk's surface from its centroids' offsets, 0.3 cell
  early a quarter cell off and 0.13 cell early half a cell off);
- the kinetic and strain energy never exceed the initial by more than
  0.5% (measured +0.00%; with the centroids' offsets +0.47% and +0.51% on
  the grid line), and the restitution is at most 1;
- the collision does not depend on the registration: the restitution at
  the three offsets within 0.02 of each other (measured 0.847-0.857; with
  the centroids' offsets 0.742-0.810).
Momentum is checked to round-off where a round body meets a face by test
a2_a3 (a sphere thrown onto a free plate) and at nodes of three or more
bodies by multi_body_nodes.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import check, finish, run  # noqa: E402

H = 0.025
SPEED = 2.0
GAP = 0.05
ELASTIC = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
           "Particles per cell direction": 2}

restitutions = {}
for mu in (0, 0.3):
    for offset in (0, 0.25, 0.5):
        face = 1.0 + offset * H
        code, output, rows = run(f"face_impact_{mu}_{offset}", {
            "Dimension": 2, "Gravity": "0, 0", "Time/End time": 0.25,
            "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1", "Grid/Subdivisions": "80, 40",
            "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": mu,
        }, [dict(ELASTIC, Shape="box", **{"Lower corner": f"{face!r}, 0.3",
                                          "Upper corner": f"{face + 0.4!r}, 0.7"}),
            dict(ELASTIC, Shape="disk", Center=f"{face - 0.2 - GAP!r}, 0.55", Radius=0.2,
                 Velocity=f"{SPEED}, 0")])
        what = f"mu = {mu}, face {offset} cells off the grid line"
        check(f"{what}: the run ends", code == 0 and rows, output.strip().splitlines()[-1])
        if not rows:
            continue
        touch = GAP / SPEED
        first = next((r["time"] for r in rows if r["contact0_1_fx"] != 0), float("inf"))
        check(f"{what}: the first contact force when the surfaces touch (within 0.1 cell of travel)",
              abs(first - touch) * SPEED <= 0.1 * H,
              f"at {first:.5f} s, touching at {touch:.5f} s")
        energy = [r["kinetic_energy"] + r["strain_energy"] for r in rows]
        check(f"{what}: the energy never above the initial by more than 0.5%",
              max(energy) <= 1.005 * energy[0], f"{max(energy) / energy[0] - 1:+.4f}")
        restitution = (rows[-1]["body0_vx"] - rows[-1]["body1_vx"]) / SPEED
        restitutions.setdefault(mu, []).append(restitution)
        check(f"{what}: restitution at most 1", restitution <= 1, f"{restitution:.4f}")
for mu, values in restitutions.items():
    check(f"mu = {mu}: the restitution the same at every offset within 0.02",
          max(values) - min(values) <= 0.02, ", ".join(f"{e:.4f}" for e in values))
finish()
