#!/usr/bin/python3
"""Free fall of an elastic box (USL and MUSL, FLIP and a PIC blend): the
centre-of-mass velocity is g t to 1e-10 relative, the position follows the
discrete symplectic-Euler update y_{n+1} = y_n + dt_{n+1} v_{n+1} to round-off,
and 1/2 g t^2 to within the O(dt) term 1/2 g t dt_max of that update."""
from scene_test import *

g = -9.81
for scheme in ("USL", "MUSL"):
    for pic in (0, 0.3):
        _, _, rows = run(f"free_fall_{scheme}_{pic}", {
            "Dimension": 2, "Gravity": f"0, {g}",
            "Time/End time": 0.25, "Time/CFL number": 0.5,
            "Solver/Update scheme": scheme, "Solver/PIC fraction": pic,
            "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20",
        }, [{"Shape": "box", "Lower corner": "0.3, 0.6", "Upper corner": "0.7, 0.9",
             "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000,
             "Particles per cell direction": 2}])
        y0 = rows[0]["body0_y"]
        worst_v = worst_step = worst_half = 0.0
        dt_max = max(r["dt"] for r in rows)
        for previous, row in zip(rows, rows[1:]):
            t = row["time"]
            worst_v = max(worst_v, abs(row["body0_vy"] - g * t) / abs(g * t))
            expected = previous["body0_y"] + row["dt"] * row["body0_vy"]
            worst_step = max(worst_step, abs(row["body0_y"] - expected))
            # |y - y0 - g t^2/2| against the bound g t dt_max / 2
            worst_half = max(worst_half, abs(row["body0_y"] - y0 - 0.5 * g * t * t) / (0.5 * abs(g) * t * dt_max))
        name = f"{scheme}, PIC {pic}"
        check(f"{name}: v_cm = g t to 1e-10 relative", worst_v < 1e-10, f"max relative error {worst_v:.2e}")
        check(f"{name}: y_cm follows symplectic Euler to round-off", worst_step < 1e-13, f"max deviation {worst_step:.2e} m")
        check(f"{name}: |y - y0 - g t^2/2| <= g t dt_max / 2", worst_half <= 1.0 + 1e-9, f"max ratio {worst_half:.4f}")
        check(f"{name}: horizontal velocity stays zero", max(abs(r["body0_vx"]) for r in rows) < 1e-12)
finish()
