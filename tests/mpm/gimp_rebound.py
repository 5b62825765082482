#!/usr/bin/python3
"""Two elastic disks of unequal size meet head-on and rebound (Bardenhagen
2001 contact), with GIMP shape functions ('Grid/Shape functions = gimp').

Disks of radius 0.2 m and 0.12 m (16 and 9.6 cells per diameter, 2 x 2
points per cell, E = 1e7 Pa, pure FLIP) close at 4 m/s; the small one
leaves at about 3.4 m/s, ringing, and crosses about 30 cells before 0.3 s.
Frictionless and with mu = 0.3, seeded as by default (clipped), under
MUSL at CFL 0.5 (the default) and 0.25. Checked, to 0.3 s:
 - through the impact (until 5 ms after the last contact force, about
   0.14 s), the energy kinetic + strain never exceeds the initial kinetic
   energy by more than 0.5% (the issue's bound for Bardenhagen 2001
   contact; measured: never above it), and the energy balance
   (energy_drift, the impacts' loss counted) gains at most 5% (measured
   +1.1% and +1.7% at CFL 0.5, frictionless and with friction);
 - the kinetic energy at the end is at most the initial one
   (restitution <= 1);
 - in flight after the impact the ringing disks gain energy as their points
   cross cells (+2.9% and +2.3% of the initial energy by 0.3 s at CFL
   0.5): a time-discretisation error of MUSL's step, not the contact's.
   It must converge: at CFL 0.25 at most 0.6 of the gain at 0.5 (first
   order in the step gives 0.5; measured 0.43 and 0.53), and the balance
   over the whole run at CFL 0.25 gains at most 5% (measured +1.7%);
 - the momentum along the line of impact is kept to 1e-10 of the initial
   sum m |v| (round-off; contact corrections are equal and opposite, GIMP
   keeps the partition of unity);
 - no point is lost, and every statistics column is finite.
A 3D cube on a plane body (tilted gravity, mu = 0.6, 0.02 s) checks the
same finiteness: a body's weight at a node may be tiny (1e-20) with GIMP,
and the reported pair forces once divided 0 by 0 there.
With the linear functions the same run (printed for comparison, not
checked) gains energy faster after the rebound, as the ringing small disk
crosses cells (doc/validation.md, "Clipped as the default").
Seeded on the lattice the impact takes about 5% of the energy (clipped
0.2%), which hides the flight's gain in the 0.5% bound."""
import math

from scene_test import *  # noqa: F401,F403

entries = {
    "Dimension": 2,
    "Time/End time": 0.3,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "3, 1", "Grid/Subdivisions": "120, 40",
    "Grid/Shape functions": "gimp",
    "Contact/Model": "bardenhagen 2001",
    "Output/Statistics interval": 5,
    "Contact/Reported pairs": "0-1",
    # the flight's gain is MUSL's (USAVG, the default with contact between
    # bodies, has none to converge: -0.0001 to +0.0001 at both CFL numbers)
    "Solver/Update scheme": "MUSL",
}
material = {"Shape": "disk", "Particles per cell direction": 2, "Material": "linear elastic",
            "Density": 1000, "Young's modulus": 1e7, "Poisson's ratio": 0.3}
bodies = [dict(material, Center="0.6, 0.5", Radius=0.2, Velocity="2, 0"),
          dict(material, Center="1.4, 0.5", Radius=0.12, Velocity="-2, 0")]
mass_speed = 1000 * math.pi * (0.2 ** 2 + 0.12 ** 2) * 2  # sum m |v| at the start



def energy(row):
    return row["kinetic_energy"] + row["strain_energy"]


for mu in (0.0, 0.3):
    label = f"unequal disks, mu = {mu}, GIMP"
    flight_gain = {}
    for cfl in (0.5, 0.25):
        what = f"{label}, CFL {cfl}"
        _, _, rows = run(f"gimp_mu{mu}_cfl{cfl}", dict(entries, **{
            "Contact/Friction coefficient": mu, "Time/CFL number": cfl}), bodies)
        e0 = rows[0]["kinetic_energy"]
        parted = max(r["time"] for r in rows if r["contact0_1_fx"] != 0 or r["contact0_1_fy"] != 0) + 0.005
        impact = [r for r in rows if r["time"] <= parted]
        flight = [r for r in rows if r["time"] >= parted]
        flight_gain[cfl] = (energy(flight[-1]) - energy(flight[0])) / e0
        print(f"[info] {what}: parted at {parted - 0.005:.4f} s; gain in flight to 0.3 s "
              f"{flight_gain[cfl]:+.4f} of the initial energy")
        momentum_change = max(abs(r["momentum_x"] - rows[0]["momentum_x"]) for r in rows)
        check(f"{what}: momentum along the impact kept to 1e-10 of sum m|v|",
              momentum_change <= 1e-10 * mass_speed, f"{momentum_change:.2e} kg m/s")
        check(f"{what}: no point lost", rows[-1]["particles"] == rows[0]["particles"])
        check(f"{what}: every statistics value finite", all(math.isfinite(v) for r in rows for v in r.values()))
        drift = max(r["energy_drift"] for r in (impact if cfl == 0.5 else rows))
        check(f"{what}: energy_drift never above +5% " + ("through the impact" if cfl == 0.5 else "to 0.3 s"),
              drift <= 0.05, f"largest {drift:+.2e}")
        if cfl != 0.5:
            continue
        peak = max(energy(r) for r in impact) / e0 - 1
        check(f"{what}: kinetic + strain energy never above the initial by 0.5% through the impact",
              peak <= 0.005, f"largest gain {peak:+.2e}")
        check(f"{what}: restitution <= 1 (final kinetic energy <= initial)",
              rows[-1]["kinetic_energy"] <= e0, f"{rows[-1]['kinetic_energy'] / e0:.4f} of the initial")
        bounce = rows[-1]["body1_vx"]
        check(f"{what}: the small disk rebounds (v_x > 2 m/s)", bounce > 2, f"{bounce:.3f} m/s")
    check(f"{label}: the gain in flight converges with the step (CFL 0.25 at most 0.6 of CFL 0.5's)",
          flight_gain[0.25] <= 0.6 * flight_gain[0.5],
          f"{flight_gain[0.25]:+.4f} against {flight_gain[0.5]:+.4f}")

    code, output, linear = run(f"linear_mu{mu}", dict(entries, **{
        "Contact/Friction coefficient": mu, "Grid/Shape functions": "linear"}), bodies,
        expect_success=False)
    gain = max(r["energy_drift"] for r in linear)
    print(f"[info] the same with linear shape functions: energy_drift up to {gain:+.3f} by "
          f"t = {linear[-1]['time']:.3f} s (exit code {code})")
cube = {"Shape": "box", "Particles per cell direction": 2, "Material": "linear elastic",
        "Density": 1000, "Young's modulus": 1e7, "Poisson's ratio": 0.3}
_, _, rows = run("gimp_cube_3d", {
    "Dimension": 3, "Gravity": "4.905, -8.496, 0", "Time/End time": 0.02,
    "Grid/Lower corner": "0, 0, 0", "Grid/Upper corner": "1.5, 0.4, 0.3", "Grid/Subdivisions": "60, 16, 12",
    "Grid/Shape functions": "gimp", "Boundary conditions/Types": "2: fixed",
    "Contact/Model": "bardenhagen 2001", "Contact/Normals": "largest mass",
    "Contact/Friction coefficient": 0.6, "Output/Statistics interval": 5},
    [dict(cube, **{"Lower corner": "0, 0, 0", "Upper corner": "1.5, 0.1, 0.3"}),
     dict(cube, **{"Lower corner": "0.2, 0.1, 0.05", "Upper corner": "0.4, 0.3, 0.25"})])
check("3D cube on a plane body, GIMP: every statistics value finite (pair forces included)",
      all(math.isfinite(v) for r in rows for v in r.values()) and "contact0_1_fx" in rows[-1])
finish()
