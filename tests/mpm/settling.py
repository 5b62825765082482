#!/usr/bin/python3
"""Bodies that start settled under gravity ('Solver/Settling steps').

A 0.4 m elastic disk (E = 1 MPa, 16 cells per diameter) stands on a
friction floor under gravity, touching it, at rest. Seeded stress-free it
drops into its elastic equilibrium and bounces: the centre moves 2.1 mm
(0.1 cell) and reaches 0.11 m/s within 0.2 s. Settled first (kinetic
damping until a peak of the kinetic energy is below 'Solver/Settling
tolerance' = 1e-8 of the strain energy), it must stay put, for the
neo-Hookean material (whose stress follows from F, so no initial stress
field can be prescribed) and the linear elastic one. The energy left rings
on with speeds and displacements about sqrt(1e-8) = 1e-4 of those of the
unsettled drop, which turns about the strain energy into motion: the test
allows ten times that, a speed below 1e-3 of the unsettled one (measured
7e-5) and the centre within 1e-4 cell of where the run starts (measured
7.6e-6; the earlier criterion, 1e-6 of m g h, left 6e-3 and 5e-4).

After settling, the run starts at t = 0 with the seeded velocity and spin
(first row: exactly the seeded values), and too few settling steps stop
the run with a message naming the entry. A run shorter than the settling
settles all the same.
"""
from scene_test import check, finish, run

R = 0.2
h = 1.6 / 64


def disk_on_floor(name, material, settling_steps, velocity="0, 0", spin=0, expect_success=True, end_time=0.2):
    return run(name, {"Dimension": 2, "Gravity": "0, -9.81", "Time/End time": end_time,
                      "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1.6, 0.8", "Grid/Subdivisions": "64, 32",
                      "Boundary conditions/Types": "2: friction", "Boundary conditions/Friction coefficients": "2: 0.5",
                      "Solver/Settling steps": settling_steps},
               [{"Shape": "disk", "Radius": R, "Center": f"0.5, {R}", "Material": material,
                 "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000,
                 "Particles per cell direction": 2, "Velocity": velocity, "Angular velocity": spin}],
               expect_success=expect_success)


for material in ("neo-Hookean", "linear elastic"):
    _, _, dropped = disk_on_floor("drop_" + material[:3], material, 0)
    _, _, settled = disk_on_floor("settled_" + material[:3], material, 2000)
    drop_speed = max(abs(r["body0_vy"]) for r in dropped)
    speed = max(abs(r["body0_vy"]) for r in settled)
    check(f"{material}: unsettled, the disk drops (it must, for the test to mean anything)",
          drop_speed > 0.05, f"max |v_y| {drop_speed:.3g} m/s")
    check(f"{material}: settled, max |v_y| below 1e-3 of the unsettled one", speed < 1e-3 * drop_speed,
          f"{speed:.3g} m/s against {drop_speed:.3g}")
    moved = max(abs(r["body0_y"] - settled[0]["body0_y"]) for r in settled)
    check(f"{material}: settled, the centre stays within 1e-4 of a cell", moved < 1e-4 * h,
          f"{moved / h:.2e} cells")

_, output, rows = disk_on_floor("spin", "neo-Hookean", 2000, velocity=f"{5 * R}, 0", spin=-5)
check("settled then set rolling: the first row is at t = 0 with the seeded velocity and spin",
      rows[0]["time"] == 0 and abs(rows[0]["body0_vx"] - 5 * R) < 1e-12 and abs(rows[0]["body0_vy"]) < 1e-12
      and abs(rows[0]["body0_omega"] + 5) < 1e-10 and "Settled under gravity" in output,
      f"t {rows[0]['time']}, v ({rows[0]['body0_vx']}, {rows[0]['body0_vy']}), omega {rows[0]['body0_omega']}")

# settling takes 0.08 s of damped motion; its steps are not cut at a
# shorter end time (they were, to zero length, and it never settled)
code, output, rows = disk_on_floor("short_run", "neo-Hookean", 2000, end_time=0.01, expect_success=False)
check("settles when the run is shorter than the settling", code == 0 and "Settled under gravity" in output
      and bool(rows) and abs(rows[-1]["time"] - 0.01) < 1e-12,
      output.strip().splitlines()[-1] if output.strip() else "no output")

code, output, _ = disk_on_floor("too_few", "neo-Hookean", 5, expect_success=False)
check("too few settling steps: stops naming the entry", code != 0 and "Solver/Settling steps" in output,
      output.strip().splitlines()[-1] if output.strip() else "no output")
finish()
