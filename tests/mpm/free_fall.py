#!/usr/bin/python3
"""Free fall of an elastic box (USL and MUSL, FLIP and a PIC blend): the
centre-of-mass velocity is g t to 1e-10 relative, the position follows the
discrete symplectic-Euler update y_{n+1} = y_n + dt_{n+1} v_{n+1} to round-off,
and 1/2 g t^2 to within the O(dt) term 1/2 g t dt_max of that update.
Statistics only when asked: with the default 'Statistics interval = 0' the
rows are those of the steps with particle output or a progress line, the
first and the last step, each identical to the row of the same step of the
every-step run."""
import re

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

# the default statistics schedule, against the every-step run (USL, FLIP)
scene = {
    "Dimension": 2, "Gravity": f"0, {g}", "Time/End time": 0.25, "Time/CFL number": 0.5,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20",
    "Output/Particle output interval": 0.02, "Output/Progress interval": 7,
}
box = [{"Shape": "box", "Lower corner": "0.3, 0.6", "Upper corner": "0.7, 0.9",
        "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000,
        "Particles per cell direction": 2}]
_, _, all_rows = run("free_fall_every_step", scene, box)
_, _, rows = run("free_fall_default_statistics", dict(scene, **{"Output/Statistics interval": 0}), box)
with open(os.path.join(WORK, "free_fall_default_statistics", "output", "particles.pvd")) as f:
    n_outputs = len(re.findall(r'timestep="', f.read()))
# the particle output steps: the first step at or past the next output time
output_steps, next_output = [], 0.02
for r in all_rows[1:]:
    if r["time"] >= next_output * (1 - 1e-12):
        output_steps.append(int(r["step"]))
        next_output = r["time"] + 0.02
last = int(all_rows[-1]["step"])
expected = [int(r["step"]) for r in all_rows
            if int(r["step"]) % 7 == 0 or int(r["step"]) == last or int(r["step"]) in output_steps]
steps = [int(r["step"]) for r in rows]
check("default statistics: the particle output steps as the program wrote them",
      n_outputs == 1 + len(output_steps) + (last not in output_steps), f"{n_outputs} particle files")
check("default statistics: rows at output, progress, first and last steps only", steps == expected,
      f"{len(steps)} rows of {len(all_rows)} steps")
by_step = {int(r["step"]): r for r in all_rows}
check("default statistics: each row identical to the every-step run's",
      all(r == by_step[int(r["step"])] for r in rows))
finish()
