#!/usr/bin/python3
"""Elastic wave in a column between slip walls (uniaxial strain).

A column of length L moving down at v0 lands at t = 0 on a slip floor (the
normal velocity is held at zero); slip side walls keep the strain uniaxial.
The floor's force is constant while the compression front runs up and the
release front runs back, so the centre-of-mass velocity falls linearly
from -v0 and first crosses zero at t = L/c, next at 3L/c, with
c = sqrt((K + 4G/3)/rho). The measured speed 2L/(t3 - t1) must be within 2%."""
import math
from scene_test import *

K, G, rho, L, v0 = 2e6, 1e6, 1000.0, 1.0, 0.05
c = math.sqrt((K + 4 * G / 3) / rho)
for scheme in ("USL", "MUSL"):
    _, _, rows = run(f"elastic_wave_{scheme}", {
        "Dimension": 2,
        "Time/End time": 4.2 * L / c, "Time/CFL number": 0.5 if scheme == "MUSL" else 0.2,
        "Solver/Update scheme": scheme,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": f"0.2, {1.25 * L}", "Grid/Subdivisions": "4, 50",
        "Boundary conditions/Types": "0: slip, 1: slip, 2: slip",
    }, [{"Shape": "box", "Lower corner": "0, 0", "Upper corner": f"0.2, {L}",
         "Bulk modulus": K, "Shear modulus": G, "Density": rho,
         "Particles per cell direction": 2, "Velocity": f"0, {-v0}"}])
    crossings = []
    for a, b in zip(rows, rows[1:]):
        if (a["body0_vy"] < 0) != (b["body0_vy"] < 0):
            # linear interpolation of the zero crossing
            crossings.append(a["time"] + (b["time"] - a["time"]) * a["body0_vy"] / (a["body0_vy"] - b["body0_vy"]))
    check(f"{scheme}: two zero crossings of v_cm", len(crossings) >= 2, f"{crossings}")
    if len(crossings) >= 2:
        check_relative(f"{scheme}: wave speed 2L/(t3 - t1)", 2 * L / (crossings[1] - crossings[0]), c, 0.02)
        check_relative(f"{scheme}: first crossing L/c", crossings[0], L / c, 0.03)
finish()
