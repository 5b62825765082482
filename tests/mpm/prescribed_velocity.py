#!/usr/bin/python3
"""A body of prescribed velocity (a loading pin, 'Body 1/Prescribed
velocity') pushes a free elastic disk (frictionless contact, no gravity, no
walls).

- the pin is at rest until its start time, then moves with exactly the
  prescribed velocity: its mean velocity and its travel to round-off;
- momentum: the pin's stays fixed, so the disk's momentum is the impulse
  the pin delivered, sum of contact force x dt over the steps (pair 0-1 of
  statistics.csv), to round-off;
- the disk leaves the pin faster than it (else it would not separate) and
  at most at twice its speed (an elastic body hit by a rigid wall: the
  rigid-disk value 2V is the bound, with energy only lost in the contact);
- energy: the pin's work (and its own kinetic energy when it starts)
  enters the balance as boundary work, so the balance gains nothing
  (without it the disk's kinetic energy would be a gain of the whole
  supplied energy);
- two MPI ranks give the same disk velocity, pin travel, work and
  momentum (1e-9 relative: summation order only);
- a prescribed body without a contact model is refused, naming the entry;
- a driver holds still while the other bodies settle ('Solver/Settling
  steps'): a piston beside a block resting on a plane body (mu = 0.3,
  gravity) starts at 0.01 s of the run. The bodies settle, the piston is
  where it was seeded when the run starts, at rest until 0.05 s and then
  at exactly its velocity, and pushing the block at constant speed it
  needs mu m g within 5% (measured +0.7%). Before, the piston started
  when the settling's own clock passed its start time and pushed the
  block along while the bodies settled, off the grid after 2.6 s of
  damped motion."""
import math
from scene_test import *

V, start = 5.6, 2e-7
material = {"Material": "linear elastic", "Density": 1900, "Bulk modulus": 102e9, "Shear modulus": 72e9,
            "Particles per cell direction": 1}
entries = {
    "Dimension": 2,
    "Time/End time": 4e-6, "Time/CFL number": 0.5,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "0.02, 0.012", "Grid/Subdivisions": "40, 24",
    "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0,
}
disk = dict(material, **{"Shape": "disk", "Center": "0.008, 0.006", "Radius": 0.005})
pin = dict(material, **{"Group": 1, "Shape": "box", "Lower corner": "0.013, 0.005", "Upper corner": "0.015, 0.007",
                        "Prescribed velocity": f"{-V}, 0", "Prescribed velocity start time": start})
rows = run("push", entries, [disk, pin])[2]

# the pin: at rest before its start time, then exactly -V
before = [r for r in rows if r["time"] - r["dt"] < start and r["step"] > 0]
after = [r for r in rows if r["time"] - r["dt"] >= start]
check("pin at rest before its start time", all(r["body1_vx"] == 0 and r["body1_vy"] == 0 for r in before),
      f"{len(before)} steps")
worst = max(abs(r["body1_vx"] + V) + abs(r["body1_vy"]) for r in after)
check("pin velocity exactly the prescribed one after it", worst <= 1e-14 * V, f"largest deviation {worst:.3g} m/s")
travel = rows[-1]["body1_x"] - rows[0]["body1_x"]
expected = -V * sum(r["dt"] for r in after)
# each step adds v dt to positions of about 0.014 m, rounding each by about
# 1e-18 m: over the run's few hundred steps some 1e-16 m, 1e-11 of the
# 2e-5 m travel
check_relative("pin travel = V x (time since the start)", travel, expected, 1e-10)

# momentum: the disk's equals the impulse the pin gave it
pin_mass = 1900 * 0.002 * 0.002  # the box fills whole cells: its points' mass exactly
impulse = 0.
worst = 0.
for r in rows[1:]:
    impulse += r["contact0_1_fx"] * r["dt"]
    disk_momentum = r["momentum_x"] - pin_mass * r["body1_vx"]
    worst = max(worst, abs(disk_momentum - impulse))
disk_momentum = rows[-1]["momentum_x"] - pin_mass * rows[-1]["body1_vx"]
check("disk momentum = impulse from the pin at every step (round-off)", worst <= 1e-12 * abs(disk_momentum),
      f"largest difference {worst:.3g} of {abs(disk_momentum):.4g} kg m/s")
check("the disk moved away from the pin: its momentum points along -x", disk_momentum < 0)

# the disk leaves faster than the pin and at most at 2V
speed = -rows[-1]["body0_vx"]
check("disk separates: V < v <= 2V", V < speed <= 2 * V * (1 + 1e-3), f"v = {speed:.4g} m/s = {speed / V:.4g} V")

# energy: the pin's work is boundary work
work = rows[-1]["boundary_work"]
kinetic_disk = 0.5 * disk_momentum ** 2 / (1900 * math.pi * 0.005 ** 2)
check("pin work counted: boundary work >= the disk's kinetic energy", work > 0.9 * kinetic_disk,
      f"work {work:.4g} J, disk kinetic energy about {kinetic_disk:.4g} J")
drift = max(r["energy_drift"] for r in rows)
check("energy balance: no gain beyond 0.1%", drift <= 1e-3, f"largest drift {drift:.3g}")

# the same on two MPI ranks (the drivers' records on ghost nodes, the work
# summed over owned nodes only): equal to round-off
rows2 = run("push_mpi2", entries, [disk, pin], ranks=2)[2]
for column in ("body0_vx", "body1_x", "boundary_work", "momentum_x"):
    a, b = rows[-1][column], rows2[-1][column]
    check(f"2 ranks: final {column} as on 1 rank", abs(a - b) <= 1e-9 * max(abs(a), 1e-300),
          f"{a:.15g} and {b:.15g}")

# a driver holds still while the other bodies settle
g, mu, push_speed, push_start = 9.81, 0.3, 0.5, 0.01
elastic = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000, "Particles per cell direction": 2}
code, output, rows = run("settled_push", {
    "Dimension": 2, "Gravity": f"0, {-g}", "Time/End time": 0.5, "Grid/Lower corner": "0, 0",
    "Grid/Upper corner": "2, 0.6", "Grid/Subdivisions": "80, 24", "Boundary conditions/Types": "2: fixed",
    "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": mu, "Solver/Settling steps": 40000,
    "Output/Statistics interval": 5,
}, [dict(elastic, Shape="box", **{"Lower corner": "0, 0", "Upper corner": "2, 0.2"}),
    dict(elastic, Shape="box", **{"Lower corner": "0.5, 0.2", "Upper corner": "0.7, 0.4"}),
    dict(elastic, Shape="box", **{"Lower corner": "0.3, 0.21", "Upper corner": "0.5, 0.35",
                                  "Prescribed velocity": f"{push_speed}, 0",
                                  "Prescribed velocity start time": push_start})], expect_success=False)
check("a piston beside a resting block: the bodies settle", code == 0 and "Settled under gravity" in output,
      output.strip().splitlines()[-1] if output.strip() else "")
if code == 0:
    check("... the piston is where it was seeded when the run starts", abs(rows[0]["body2_x"] - 0.4) <= 1e-12,
          f"x = {rows[0]['body2_x']:.15g}")
    # (a step takes the velocity of the time it starts at)
    moved = max(abs(r["body2_x"] - 0.4) for r in rows if r["time"] - r["dt"] < push_start)
    speeds = [r["body2_vx"] for r in rows if r["time"] - r["dt"] >= push_start]
    check("... at rest until its start time, then at exactly its velocity",
          moved <= 1e-12 and max(abs(v - push_speed) for v in speeds) <= 1e-12,
          f"moved {moved:.2e} m before, speeds {min(speeds)} to {max(speeds)} m/s after")
    # the impulse's rate fitted from 0.2 s on (the block, hit at 0.01 s,
    # rings and hops at first)
    pushing = [(r["time"], r["driver_impulse_x"]) for r in rows if r["time"] >= 0.2]
    mean_t = sum(t for t, _ in pushing) / len(pushing)
    mean_j = sum(j for _, j in pushing) / len(pushing)
    force = sum((t - mean_t) * (j - mean_j) for t, j in pushing) / sum((t - mean_t) ** 2 for t, _ in pushing)
    weight = 0.2 * 0.2 * 1000 * g
    check("... pushing the block at constant speed takes mu m g (within 5%)",
          abs(force / (mu * weight) - 1) <= 0.05, f"{force:.2f} N against {mu * weight:.2f} N")

# a driver needs contact to act on other bodies
code, output, _ = run("no_contact", dict(entries, **{"Contact/Model": "none"}), [disk, pin], expect_success=False)
check("prescribed body without contact refused, naming Contact/Model",
      code != 0 and "Contact/Model" in output and "prescribed" in output, output.strip()[-200:])
code, output, _ = run("bad_vector", entries, [disk, dict(pin, **{"Prescribed velocity": "1"})], expect_success=False)
check("a prescribed velocity of one number refused, naming it",
      code != 0 and "Body 1/Prescribed velocity" in output, output.strip()[-200:])
finish()
