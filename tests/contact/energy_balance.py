#!/usr/bin/python3
"""The energy balance of statistics.csv (column energy_drift) and the heat
that friction makes, against Coulomb's work.

A 0.2 m elastic block slides down a plane under gravity tilted by 30 deg:
on a separate elastic plane body (Bardenhagen 2001 contact, 'largest mass'
normals) and on a friction wall, with mu = 0.2 and 0.4. A
rigid block's friction turns mu m g cos(theta) times the distance slid into
heat; the contact_heat / wall_heat columns (the friction impulses of each
step against the slip the bodies' points show after it, mapped back to the
grid) must match it within 2% (measured -0.4%, -0.3% on the plane body,
-0.1%, -0.4% on the wall; the block's elastic ringing and its start from a
stress-free state are within this), and the balance kinetic + strain +
gravitational energy + heat must hold within 0.5% of the energy released
on the plane body (measured 0.14%, 0.17%) and |energy_drift| within 1% on
the wall (measured 0.03% and 0.13% for mu = 0.2 and 0.4; there it is
relative to the energy released). Without the heat in the balance the
drift would be about 35% and 70%. The wall with mu = 0.4 failed both until
its remap pass stopped taking the friction a second time (the block rang:
wall_heat +10%, drift +10.7%).

The impacts' loss (column impact_loss): what the corrections of contact
and walls take from the points beyond the friction heat, counted at the
points. Two unequal elastic disks (0.2 and 0.12 m, 16 and 9.6 cells per
diameter) meet head-on at 4 m/s, frictionless and with mu = 0.3, under
USAVG (so that their flight apart keeps its energy): the normal
corrections, perfectly inelastic at each node, take a few percent of the
energy (measured 4.8% frictionless and 4.3% with mu = 0.3 at CFL 0.1; 9.8%
frictionless before the overlap test of the contact's detection acted at
nodes where one disk's centroid lay deep inside it), and with it counted the
balance holds within 1% at every row at CFL 0.1 (measured -0.86% during
the impact, +0.29% at worst after it; without it the drift would be -10%).
The step's part of what remains, the end value at CFL 0.5 less that at
CFL 0.1, is below 0.5% of the energy (measured +0.69% against +0.35%
frictionless, +0.49% against +0.29% with mu = 0.3; +1.17% against +0.36%
while USAVG's first half was counted as a step of its own). Ten times
softer (E = 1 MPa), the same disks end at CFL 0.5 within 0.5% of their
end at CFL 0.1 (measured +0.32% and +0.46%): the points at contact nodes
take USAVG's midpoint rule, the contact acting on its first half's
velocities too (+1.67% against +0.52% while they took MUSL's whole step).
On a grid half as fine their kinetic plus strain energy only falls, and
the loss counted exceeds what they lose by at most 1%, by the same at
CFL 0.5 as at CFL 0.1 within 0.5% of their energy (measured 0.85% and
0.37%; 0.47% and 0.46% while round pairs took the larger disk's mass
gradient as their normal; 1.03% at CFL 0.5 with the strain part to first
order in the step). In 3D, unequal spheres meeting slightly off-centre with mu = 0.3
(USAVG, CFL 0.5) lose 5.0% in the impact and the balance stays within
1.5% (measured -1.01% during the impact, the same at CFL 0.25; +0.31% at
worst after it).

A pile of 30 elastic disks (prm/gallery_pile.prm under pure FLIP, 0.6 s)
checks that the heat is not over-counted where the nodal velocities carry
noise: the friction heat is at most what left the bodies, and more than
half of it (measured 391 J of 547 J), so that it is not lost either.
Counted from the nodal velocities the correction leaves, the heat of the
same pile exceeded the gravitational energy released and the guard
stopped the run at 0.82 s with +67%. With the impacts' loss counted the
balance never gains more than 8% (measured +2.4% under the default
scheme, USAVG in a scene with contact between bodies; under MUSL +5.6% at
CFL 0.5, +1.6% at CFL 0.25: the gain of MUSL's step where grains touch,
which falls with the square of the step; before the loss was counted the
balance showed -26%). No point is lost, and no point of a grain comes
more than a tenth of a spacing inside the convex hull of another grain's
points (no interpenetration; measured: 0.22 spacings of clearance at the
least, 0.10 while two disks took the larger one's mass gradient as their
contact normal). With the papers' detection, contact at every node two disks
share ('Contact/Detection = shared nodes'), the same pile gains +38% by
0.6 s (MUSL: +54% at 0.31 s); with 'Output/Energy drift limit = 0.2'
the guard stops it, and the stop names the detection and 'surface
position'.

A run whose energy balance gains more than 'Output/Energy drift limit'
stops with the step, the time and the entry named. Two unequal disks
ringing as they fly apart after a collision, along the grid's x axis,
gain energy without contact under MUSL (seeded on the lattice, +36% by
0.8 s at CFL 0.5); with 'Output/Energy drift limit = 0.25' the guard
stops them, and the stop names 'Update scheme = USAVG' and 'Time/CFL
number' as the remedies; at 0.25 the same flight gains at most 15% by
0.8 s (measured +5.8%, seeded clipped). Under the default scheme, USAVG here, at CFL 0.5 the bodies'
kinetic + strain energy never exceeds the initial by more than 0.5%, and
the balance, with the collision's loss counted, never gains more than 3%
(measured +1.3%).
"""
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import check, check_relative, finish, read_csv, run  # noqa: E402
from particle_output import deepest_in_other_hull, particle_files  # noqa: E402

g = 9.81
theta = math.radians(30)
elastic = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
           "Particles per cell direction": 2}
block_mass = 0.2 * 0.2 * 1000
tilted = {"Dimension": 2, "Gravity": f"{g * math.sin(theta)}, {-g * math.cos(theta)}",
          "Time/End time": 0.5, "Output/Statistics interval": 10}


def on_plane_body(name, mu):
    entries = dict(tilted, **{
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 0.6", "Grid/Subdivisions": "80, 24",
        "Boundary conditions/Types": "2: fixed", "Contact/Model": "bardenhagen 2001",
        "Contact/Normals": "largest mass", "Contact/Friction coefficient": mu})
    return run(name, entries,
               [dict(elastic, Shape="box", **{"Lower corner": "0, 0", "Upper corner": "2, 0.2"}),
                dict(elastic, Shape="box", **{"Lower corner": "0.3, 0.2", "Upper corner": "0.5, 0.4"})])


def coulomb_heat(rows, mu, body):
    return mu * block_mass * g * math.cos(theta) * (rows[-1][f"body{body}_x"] - rows[0][f"body{body}_x"])


def balance_over_released(rows):
    """The largest change of kinetic + strain + gravitational energy + heat +
    plastic work - boundary work over the run, over the gravitational energy
    released by its end (energy_drift divides by at least the energy of all
    the mass over one cell height, here the fixed plane body's too)."""
    def total(r):
        return (r["kinetic_energy"] + r["strain_energy"] + r["gravity_energy"] + r["plastic_work"]
                + r["wall_heat"] + r["contact_heat"] - r["boundary_work"])
    released = rows[0]["gravity_energy"] - rows[-1]["gravity_energy"]
    return max(abs(total(r) - total(rows[0])) for r in rows) / released


for mu in (0.2, 0.4):
    _, _, rows = on_plane_body(f"plane_{mu}", mu)
    check_relative(f"block on a plane body, mu = {mu}: contact_heat = mu m g cos(theta) x slid",
                   rows[-1]["contact_heat"], coulomb_heat(rows, mu, 1), 0.02)
    error = balance_over_released(rows)
    check(f"block on a plane body, mu = {mu}: the balance holds within 0.5% of the energy released",
          error < 0.005, f"largest error {error:.2e} of it")

for mu in (0.2, 0.4):
    _, _, rows = run(f"wall_{mu}", dict(tilted, **{
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 0.4", "Grid/Subdivisions": "80, 16",
        "Boundary conditions/Types": "2: friction", "Boundary conditions/Friction coefficients": f"2: {mu}"}),
        [dict(elastic, Shape="box", **{"Lower corner": "0.3, 0", "Upper corner": "0.5, 0.2"})])
    check_relative(f"block on a friction wall, mu = {mu}: wall_heat = mu m g cos(theta) x slid",
                   rows[-1]["wall_heat"], coulomb_heat(rows, mu, 0), 0.02)
    drift = max(abs(r["energy_drift"]) for r in rows)
    check(f"block on a friction wall, mu = {mu}: |energy_drift| below 1% throughout", drift < 0.01,
          f"max {drift:.2e}")

# two blocks side by side on the mu = 0.4 wall, in contact with each other:
# at the nodes they share on the wall each body's record keeps the wall's
# own decision for the remap pass (measured: wall_heat +0.02%, drift +0.17%)
_, _, rows = run("wall_two_blocks", dict(tilted, **{
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 0.4", "Grid/Subdivisions": "80, 16",
    "Boundary conditions/Types": "2: friction", "Boundary conditions/Friction coefficients": "2: 0.4",
    "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3}),
    [dict(elastic, Shape="box", **{"Lower corner": "0.3, 0", "Upper corner": "0.5, 0.2"}),
     dict(elastic, Shape="box", **{"Lower corner": "0.5, 0", "Upper corner": "0.7, 0.2"})])
check_relative("two blocks in contact on a friction wall, mu = 0.4: wall_heat = Coulomb's work of both",
               rows[-1]["wall_heat"], coulomb_heat(rows, 0.4, 0) + coulomb_heat(rows, 0.4, 1), 0.02)
drift = max(abs(r["energy_drift"]) for r in rows)
check("two blocks in contact on a friction wall: |energy_drift| below 1% throughout", drift < 0.01,
      f"max {drift:.2e}")

# the pile: friction between disks (mu = 0.4) and on the floor (0.5)
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
pile_directory = os.path.join(os.environ.get("SABLE_WORK", "scene_test.work"), "pile")
shutil.rmtree(pile_directory, ignore_errors=True)
result = subprocess.run([os.environ.get("SABLE", "sable"), os.path.join(root, "prm", "gallery_pile.prm"),
                         "--set", "Solver/PIC fraction=0", "--set", "Time/End time=0.6",
                         "--set", "Output/Particle output interval=0.1", "--set", "Output/Statistics interval=50",
                         "--set", f"Output directory={pile_directory}"], capture_output=True, text=True)
check("pile of 30 disks under pure FLIP: runs to 0.6 s", result.returncode == 0,
      (result.stdout + result.stderr).strip().splitlines()[-1] if result.returncode else "")
rows = read_csv(os.path.join(pile_directory, "statistics.csv"))
if rows:
    released = rows[0]["gravity_energy"] - rows[-1]["gravity_energy"]
    left = released - rows[-1]["kinetic_energy"] - rows[-1]["strain_energy"]
    heat = rows[-1]["contact_heat"] + rows[-1]["wall_heat"]
    check("pile: the friction heat at most what left the bodies", heat <= left,
          f"heat {heat:.1f} J of {left:.1f} J that left the bodies ({released:.1f} J released)")
    check("pile: with the impacts' loss counted, energy_drift never above +8%",
          max(r["energy_drift"] for r in rows) <= 0.08,
          f"largest {max(r['energy_drift'] for r in rows):+.4f}, impact_loss {rows[-1]['impact_loss']:.1f} J")
    check("pile: the friction heat is a sizeable part of what left the bodies (more than half)",
          heat > 0.5 * left, f"{heat:.1f} J of {left:.1f} J")
    check("pile: no point lost", all(r["particles"] == rows[0]["particles"] for r in rows),
          f"{rows[0]['particles']:.0f} to {rows[-1]['particles']:.0f}")
    # no interpenetration: a grain's points fill it to within a fraction of
    # a spacing of its surface, so a point of another grain inside the
    # convex hull of its points lies inside it. Measured in these frames
    # (every 0.1 s): the least clearance 0.22 spacings (0.10 while two
    # disks took the larger one's mass gradient as their contact normal,
    # when in frames every 0.005 s one point came 0.01 spacings inside).
    # (The closest distance of two grains' points, which the check read
    # before, swings with the points' FLIP noise, relative velocities of
    # 1-2 m/s between touching points: 0.07 to 0.5 spacings from frame to
    # frame.)
    spacing = 0.01 / 2
    deepest = max(deepest_in_other_hull(fields["x"], fields["body"].ravel())
                  for _, fields in particle_files(pile_directory, names=("id", "body")))
    check("pile: no point of a grain more than a tenth of a spacing inside the hull of another's points",
          deepest <= 0.1 * spacing, f"deepest {deepest / spacing:+.2f} spacings (negative: clearance)")

# the papers' detection, contact at every node two bodies share, makes
# energy where the disks crowd: the same pile gains +38% by 0.6 s under
# USAVG (MUSL: +54% at 0.31 s, where the guard's 50% stopped it); with the
# guard at 20% the run stops, and the stop names the detection
result = subprocess.run([os.environ.get("SABLE", "sable"), os.path.join(root, "prm", "gallery_pile.prm"),
                         "--set", "Solver/PIC fraction=0", "--set", "Time/End time=0.6",
                         "--set", "Contact/Detection=shared nodes", "--set", "Output/Energy drift limit=0.2",
                         "--set", "Output/Particle output interval=10",
                         "--set", f"Output directory={pile_directory}_shared_nodes", "--overwrite"],
                        capture_output=True, text=True)
output = result.stdout + result.stderr
check("pile with 'Detection = shared nodes': the guard stops the run and names the detection and "
      "'surface position'",
      result.returncode != 0 and "Energy drift limit" in output and
      "'Contact/Detection = shared nodes'" in output and "surface position" in output,
      output.strip().splitlines()[-1][:200] if output.strip() else "")

# the impacts' loss: unequal disks head-on under USAVG
headon = {"Dimension": 2, "Time/End time": 0.3, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "3, 1",
          "Grid/Subdivisions": "120, 40", "Contact/Model": "bardenhagen 2001",
          "Solver/Update scheme": "USAVG", "Output/Statistics interval": 5}
headon_disks = [dict(elastic, Shape="disk", Center="0.6, 0.5", Radius=0.2, Velocity="2, 0"),
                dict(elastic, Shape="disk", Center="1.4, 0.5", Radius=0.12, Velocity="-2, 0")]
for mu in (0.0, 0.3):
    label = f"unequal disks head-on, mu = {mu}, USAVG"
    ends = []
    for cfl in (0.5, 0.1):
        _, _, rows = run(f"impact_mu{mu}_cfl{cfl}",
                         dict(headon, **{"Contact/Friction coefficient": mu, "Time/CFL number": cfl}),
                         headon_disks)
        ends.append(rows[-1]["energy_drift"])
    e0 = rows[0]["kinetic_energy"]
    loss = rows[-1]["impact_loss"] / e0
    check(f"{label}, CFL 0.1: the impacts take 2-20% of the energy", 0.02 <= loss <= 0.2,
          f"impact_loss {loss:.4f} of the initial kinetic energy, contact_heat "
          f"{rows[-1]['contact_heat'] / e0:.4f}")
    worst = max(abs(r["energy_drift"]) for r in rows)
    check(f"{label}, CFL 0.1: with it counted, |energy_drift| below 1% at every row", worst <= 0.01,
          f"largest {worst:.4f}; without the impacts' loss {rows[-1]['energy_drift'] - loss:+.4f} at the end")
    check(f"{label}: the balance at CFL 0.5 within 0.5% of CFL 0.1's at the end",
          abs(ends[0] - ends[1]) <= 0.005, f"{ends[0]:+.4f} at CFL 0.5, {ends[1]:+.4f} at CFL 0.1")

# the points at contact nodes take USAVG's midpoint rule too (the contact
# acts on the momenta at the start of the step): the same disks made ten
# times softer (E = 1 MPa, a longer impact, more of it ringing) keep the
# step's part of the balance, CFL 0.5's end value less CFL 0.1's, below
# 0.5% of the energy (measured +0.49% against +0.46%; +1.67% against
# +0.52% while those points took MUSL's whole step)
soft_disks = [dict(body, **{"Young's modulus": 1e6}) for body in headon_disks]
ends = []
for cfl in (0.5, 0.1):
    _, _, rows = run(f"impact_soft_cfl{cfl}",
                     dict(headon, **{"Contact/Friction coefficient": 0, "Time/CFL number": cfl}), soft_disks)
    ends.append(rows[-1]["energy_drift"])
check("unequal soft disks head-on, USAVG: the balance at CFL 0.5 within 0.5% of CFL 0.1's at the end",
      abs(ends[0] - ends[1]) <= 0.005, f"{ends[0]:+.4f} at CFL 0.5, {ends[1]:+.4f} at CFL 0.1")
# the strain part of the impacts' loss to second order in the step, USAVG's
# first half counted as the half it is: on a grid half as fine (8 and 4.8
# cells per diameter) the disks' kinetic plus strain energy only falls, and
# the loss counted exceeds what they lose by at most 1%, and by the same at
# CFL 0.5 as at 0.1 within 0.5% of their energy, the bound on the step's
# part of the balance above (measured 0.85% and 0.37%; 0.76% and 0.50%
# with 'Normals = mass weighted', 0.83% and 0.79% with 'largest mass';
# 0.47% and 0.46% while round pairs took the larger disk's mass gradient)
excess = []
for cfl in (0.5, 0.1):
    _, _, rows = run(f"impact_soft_coarse_cfl{cfl}",
                     dict(headon, **{"Contact/Friction coefficient": 0, "Grid/Subdivisions": "60, 20",
                                     "Time/CFL number": cfl}), soft_disks)
    mechanical = [r["kinetic_energy"] + r["strain_energy"] for r in rows]
    lost = mechanical[0] - mechanical[-1]
    excess.append((rows[-1]["impact_loss"] - lost) / mechanical[0])
    check(f"... 8 cells per diameter, CFL {cfl}: kinetic + strain energy never above the initial, and the "
          "impacts' loss within 1% of the energy of what the disks lose",
          max(mechanical) <= mechanical[0] * (1 + 1e-9) and abs(excess[-1]) <= 0.01,
          f"lost {lost:.2f} J of {mechanical[0]:.1f} J, impact_loss {rows[-1]['impact_loss']:.2f} J")
check("... the loss counted exceeds what they lose by the same at CFL 0.5 as at 0.1, within 0.5% of their energy",
      abs(excess[0] - excess[1]) <= 0.005, f"{100 * excess[0]:+.3f}% at CFL 0.5, {100 * excess[1]:+.3f}% at CFL 0.1")

# the same in 3D: unequal spheres (0.15 and 0.1 m, 9.6 and 6.4 cells per
# diameter) meeting slightly off-centre with mu = 0.3
spheres = [dict(elastic, Shape="sphere", Center="0.45, 0.25, 0.25", Radius=0.15, Velocity="2, 0, 0"),
           dict(elastic, Shape="sphere", Center="0.95, 0.27, 0.25", Radius=0.1, Velocity="-2, 0, 0")]
_, _, rows = run("impact_3d", {"Dimension": 3, "Time/End time": 0.2, "Grid/Lower corner": "0, 0, 0",
                               "Grid/Upper corner": "1.5, 0.5, 0.5", "Grid/Subdivisions": "48, 16, 16",
                               "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
                               "Solver/Update scheme": "USAVG", "Output/Statistics interval": 5}, spheres)
e0 = rows[0]["kinetic_energy"]
loss = rows[-1]["impact_loss"] / e0
worst = max(abs(r["energy_drift"]) for r in rows)
check("unequal spheres meeting off-centre, mu = 0.3, USAVG, CFL 0.5: the impacts take 2-20% of the energy, "
      "and with it counted |energy_drift| stays below 1.5% at every row",
      0.02 <= loss <= 0.2 and worst <= 0.015,
      f"impact_loss {loss:.4f} of the initial kinetic energy; largest |energy_drift| {worst:.4f}")

# two elastic disks meeting head-on, frictionless, with the 2000 rule at
# every shared node and mass-weighted normals, which rebounds faster than
# the impact (doc/validation.md): the balance gains about 25% of the
# initial energy
disk = dict(elastic, Shape="disk", Radius=0.2, **{"Young's modulus": 1e6})
code, output, rows = run("drift_limit", {
    "Dimension": 2, "Time/End time": 0.15, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "80, 40", "Contact/Model": "bardenhagen 2000", "Output/Energy drift limit": 0.05,
    "Contact/Detection": "shared nodes", "Contact/Normals": "mass weighted",
}, [dict(disk, Center="0.7, 0.5", Velocity="2, 0"), dict(disk, Center="1.3, 0.5", Velocity="-2, 0")],
    expect_success=False)
check("a gain beyond 'Output/Energy drift limit' stops the run naming step, time and the entry",
      code != 0 and "Energy drift limit" in output and "unstable at step" in output and ", time " in output,
      output.strip().splitlines()[-1] if output.strip() else "no output")
check("the rows written before the stop hold no NaN", all(all(v == v for v in r.values()) for r in rows))

# unequal disks (0.2 and 0.1 m) part after a head-on collision and ring as
# they fly apart, the small one at 3.5 m/s along the grid's x axis: their
# energy grows without contact (doc/validation.md, "Head-on collisions")
# (+36% by 0.8 s seeded on the lattice, +8% at CFL 0.25; +50% by 0.68 s
# with 'Normals = largest mass'; clipped, the default, they gain more
# slowly): with the guard at 25% the run stops. The stop names the time
# step as the remedy, and the remedy holds the balance
flight = {"Dimension": 2, "Time/End time": 0.8, "Grid/Lower corner": "-2, 0", "Grid/Upper corner": "6, 1",
          "Grid/Subdivisions": "320, 40", "Contact/Model": "bardenhagen 2001", "Output/Statistics interval": 10}
unequal = [dict(disk, Center="0.7, 0.5", Velocity="2, 0"),
           dict(disk, Center="1.2, 0.5", Radius=0.1, Velocity="-2, 0")]
musl = {"Solver/Update scheme": "MUSL"}
code, output, _ = run("ringing_flight", dict(flight, **musl, **{"Output/Energy drift limit": 0.25}),
                      [dict(body, Seeding="lattice") for body in unequal], expect_success=False)
check("ringing bodies in flight under MUSL: the stop names 'Update scheme = USAVG', 'Time/CFL number' and the "
      "section of doc/mpm.md",
      code != 0 and "Energy drift limit" in output and "'Time/CFL number' than 0.5" in output
      and "'Solver/Update scheme = USAVG'" in output and "Spinning bodies" in output,
      output.strip().splitlines()[-1] if output.strip() else "no output")
_, _, rows = run("ringing_flight_cfl025", dict(flight, **musl, **{"Time/CFL number": 0.25}), unequal)
# (+5.8% at 0.8 s, seeded clipped; +10.7% while round
# pairs took the larger disk's mass gradient as their normal)
check("... at CFL 0.25 the same flight runs to 0.8 s and gains at most 15%",
      rows[-1]["time"] > 0.8 - 1e-9 and max(r["energy_drift"] for r in rows) < 0.15,
      f"largest energy_drift {max(r['energy_drift'] for r in rows):+.4f}")
# with the stress updated in two halves (USAVG, the default in a scene with
# contact between bodies) the flight keeps its energy at CFL 0.5: kinetic +
# strain never above the initial by more than 0.5% (issue target for
# head-on collisions), and the balance with the collision's loss counted
# gains at most 3% (measured +1.2%)
_, _, rows = run("ringing_flight_usavg", flight, unequal)
e0 = rows[0]["kinetic_energy"] + rows[0]["strain_energy"]
peak = max(r["kinetic_energy"] + r["strain_energy"] for r in rows) / e0 - 1
check("... under the default scheme (USAVG) at CFL 0.5 it runs to 0.8 s, its kinetic + strain energy never "
      "above the initial by 0.5%",
      rows[-1]["time"] > 0.8 - 1e-9 and peak <= 0.005, f"largest gain {peak:+.4f}")
check("... and the balance, the collision's loss counted, never gains more than 3%",
      max(r["energy_drift"] for r in rows) < 0.03,
      f"largest energy_drift {max(r['energy_drift'] for r in rows):+.4f}")

# one contact pass under MUSL: the heat counted at the remapped velocities
# is over-counted (the settling pile's balance +44%), and the run says so
two_disks = [dict(disk, Center="0.7, 0.5", Velocity="2, 0"), dict(disk, Center="1.3, 0.5", Velocity="-2, 0")]
short = {"Dimension": 2, "Time/Maximum number of steps": 5, "Grid/Lower corner": "0, 0",
         "Grid/Upper corner": "2, 1", "Grid/Subdivisions": "80, 40", "Contact/Model": "bardenhagen 2001"}
_, output, _ = run("one_pass", dict(short, **{"Contact/Passes": "momentum update"}), two_disks)
_, default_output, _ = run("two_passes", short, two_disks)
check("one contact pass under MUSL: a note says the heat is over-counted",
      "note: 'Contact/Passes' leaves out the strain update" in output
      and "note: 'Contact/Passes'" not in default_output)
finish()
