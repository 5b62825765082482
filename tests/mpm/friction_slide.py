#!/usr/bin/python3
"""A box on a Coulomb friction wall under tilted gravity (angle theta).

tan(theta) > mu: the box slides with a = g (sin(theta) - mu cos(theta));
the acceleration fitted to v_cm(t) after the first 0.05 s must be within 2%.
tan(theta) < mu: the box sticks; its tangential drift must stay below 0.1%
of a cell. The box starts from the lithostatic stress and is stiff enough
that its own elastic shear (about rho g H^2 / G = 2.5e-5 m here) is below that bound."""
import math
from scene_test import *

g, mu, h = 9.81, 0.3, 0.1


def scene(name, theta):
    return run(name, {
        "Dimension": 2,
        "Gravity": f"{g * math.sin(theta)}, {-g * math.cos(theta)}",
        "Time/End time": 0.3,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "3, 1", "Grid/Subdivisions": f"{int(3 / h)}, {int(1 / h)}",
        "Boundary conditions/Types": "2: friction",
        "Boundary conditions/Friction coefficients": f"2: {mu}",
    }, [{"Shape": "box", "Lower corner": "0.5, 0", "Upper corner": "1.5, 0.5",
         "Bulk modulus": 2e8, "Shear modulus": 1e8, "Density": 1000,
         "Particles per cell direction": 2, "Lithostatic initial stress": "true"}])[2]


theta = math.radians(30)
rows = [r for r in scene("slide", theta) if r["time"] >= 0.05]
n = len(rows)
mean_t = sum(r["time"] for r in rows) / n
mean_v = sum(r["body0_vx"] for r in rows) / n
slope = sum((r["time"] - mean_t) * (r["body0_vx"] - mean_v) for r in rows) / sum((r["time"] - mean_t) ** 2 for r in rows)
check_relative("sliding: a = g (sin - mu cos)", slope, g * (math.sin(theta) - mu * math.cos(theta)), 0.02)

rows = scene("stick", math.radians(10))
drift = max(abs(r["body0_x"] - rows[0]["body0_x"]) for r in rows)
check("sticking: tangential drift < 0.1% of a cell", drift < 1e-3 * h, f"max drift {drift:.3e} m (bound {1e-3 * h:g} m)")
finish()
