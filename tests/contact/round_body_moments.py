#!/usr/bin/python3
"""'Contact/Round body moments = kept': a round body receives the moment that
the contact's corrections exert at the nodes, not only what the transfer to
its points delivers.

Oblique impacts without gravity, `bardenhagen 2001`, the round body (E = 1
MPa) thrown at 1 m/s into a plane body (E = 10 MPa, fixed at its bottom)
with a sideways speed large enough that it slides through the whole
impact. A rigid body then takes a tangential impulse mu times the normal
one, m |dv_t| = mu m dv_n, and its spin follows from that impulse at the
radius: omega R = mu dv_n m R^2 / I, 2 mu dv_n for a disk, 5/2 mu dv_n for a
sphere. Measured (16 cells per diameter unless said, clipped seeding):

| case | transferred (default) | kept |
|---|---|---|
| disk, mu = 0.2, 2 m/s sideways: omega R / (2 mu dv_n) | 0.965 | 1.003 |
| disk, 8 cells per diameter, mu = 0.4, 3 m/s sideways | 0.807 | 0.875 |
| sphere, 8 cells per diameter, mu = 0.2, 2 m/s sideways | 0.880 | 0.948 |

The tangential impulse is mu times the normal one within 0.3% in every run,
so what differs is the moment: with the default a correction at a node
reaches the points about their centroid there, a fraction of a cell inside
the body. What is left with `kept` at 8 cells per diameter is the moment
the nodal forces exert (their normal parts act off the contact point).
Bounds: the disk's spin within 3% at 16 cells per diameter and 15% at 8,
the sphere's within 10% at 8 (the issue's target for a slipping sphere);
the default misses each. The rotation adds no momentum: two disks meeting
obliquely away from any wall keep their total momentum to round-off, and
no run's energy balance drifts by more than 0.5% (measured at most
0.38%, either way). On a periodic grid the option is off (a body's centre may lie
across the seam): the run is the default's, byte for byte. Two MPI ranks
spin the disk as one does, to round-off.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import WORK, check, finish, run  # noqa: E402

radius = 0.2
elastic = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
           "Particles per cell direction": 2}
round_body = dict(elastic, **{"Young's modulus": 1e6})


def oblique_impact(name, dim, cells_per_diameter, mu, sideways, moments, ranks=0):
    """A disk (sphere) thrown at (sideways, -1) m/s onto a plane body from
    two cells above it; returns the statistics rows."""
    h = 2 * radius / cells_per_diameter
    size = (2.0, 0.8) if dim == 2 else (1.6, 0.8, 0.6)
    centre = [0.4, 0.2 + radius + 2 * h] + ([0.3] if dim == 3 else [])
    _, _, rows = run(name, {
        "Dimension": dim, "Time/End time": 0.3, "Grid/Lower corner": ", ".join(["0"] * dim),
        "Grid/Upper corner": ", ".join(map(str, size)),
        "Grid/Subdivisions": ", ".join(str(round(s / h)) for s in size),
        "Boundary conditions/Types": "2: fixed", "Contact/Model": "bardenhagen 2001",
        "Contact/Friction coefficient": mu, "Contact/Round body moments": moments,
        "Output/Statistics interval": 5,
    }, [dict(elastic, Shape="box", **{"Lower corner": ", ".join(["0"] * dim),
                                      "Upper corner": ", ".join(map(str, (size[0], 0.2) + size[2:]))}),
        dict(round_body, Shape="disk" if dim == 2 else "sphere", Radius=radius,
             Center=", ".join(map(str, centre)),
             Velocity=", ".join(map(str, [sideways, -1] + [0] * (dim - 2))))], ranks=ranks)
    return rows


def spin_ratio(rows, dim, mu):
    """omega R against the rigid body's for the measured normal impulse,
    and the tangential impulse against mu times the normal one."""
    first, last = rows[0], rows[-1]
    dv_n = last["body1_vy"] - first["body1_vy"]
    dv_t = last["body1_vx"] - first["body1_vx"]
    omega = last["body1_omega"] if dim == 2 else last["body1_omega_z"]
    factor = 2 if dim == 2 else 2.5
    return -omega * radius / (factor * mu * dv_n), -dv_t / (mu * dv_n)


for dim, cells, mu, sideways, bound in [(2, 16, 0.2, 2, 0.03), (2, 8, 0.4, 3, 0.15),
                                        (3, 8, 0.2, 2, 0.10)]:
    what = f"{'disk' if dim == 2 else 'sphere'} sliding through an oblique impact, {cells} cells per " \
           f"diameter, mu = {mu}"
    ratios = {}
    for moments in ["transferred", "kept"]:
        rows = oblique_impact(f"oblique_{dim}d_{cells}_{mu}_{moments}", dim, cells, mu, sideways, moments)
        ratios[moments], coulomb = spin_ratio(rows, dim, mu)
        check(f"{what}, {moments}: tangential impulse mu times the normal one within 1%",
              abs(coulomb - 1) <= 0.01, f"{coulomb:.4f}")
        drift = max(abs(r["energy_drift"]) for r in rows)
        check(f"{what}, {moments}: energy balance within 0.5%", drift <= 0.005, f"largest {drift:+.4f}")
    check(f"{what}: with 'kept' the spin within {bound:.0%} of the rigid body's",
          abs(ratios["kept"] - 1) <= bound,
          f"omega R / rigid {ratios['kept']:.3f} (transferred {ratios['transferred']:.3f})")

# the moments are summed rank by rank: two MPI ranks differ from one only
# by round-off (measured 7e-15 of the spin)
spins = [oblique_impact(f"ranks_{ranks}", 2, 8, 0.4, 3, "kept", ranks)[-1]["body1_omega"]
         for ranks in (1, 2)]
check("disk sliding through an oblique impact, 'kept': two MPI ranks spin it as one does",
      abs(spins[1] - spins[0]) <= 1e-10 * abs(spins[0]), f"omega {spins[0]:.15g}, {spins[1]:.15g}")

# two equal disks meeting obliquely, no walls: the rotations add no momentum
rows = run("two_disks_kept", {
    "Dimension": 2, "Time/End time": 0.15, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "80, 40", "Contact/Model": "bardenhagen 2001",
    "Contact/Friction coefficient": 0.3, "Contact/Round body moments": "kept",
    "Output/Statistics interval": 1,
}, [dict(round_body, Shape="disk", Radius=0.2, Center="0.7, 0.45", Velocity="2, 0.8"),
    dict(round_body, Shape="disk", Radius=0.15, Center="1.25, 0.55", Velocity="-2, -0.8")])[2]
scale = 2 * rows[0]["kinetic_energy"] / 2.15  # sum of m |v|, |v| about 2.15 m/s
defect = max(abs(r[f"momentum_{c}"] - rows[0][f"momentum_{c}"]) for r in rows for c in "xy")
check("two disks meeting obliquely with 'kept': momentum kept to round-off", defect < 1e-12 * scale,
      f"max |p - p0| {defect:.2e} of {scale:.3g}")
spun = min(abs(rows[-1]["body0_omega"]), abs(rows[-1]["body1_omega"]))
check("two disks meeting obliquely with 'kept': both spin after the impact", spun > 0.1,
      f"|omega| {abs(rows[-1]['body0_omega']):.3f}, {abs(rows[-1]['body1_omega']):.3f} rad/s")
energy = [r["kinetic_energy"] + r["strain_energy"] for r in rows]
check("two disks meeting obliquely with 'kept': energy never above the initial",
      max(energy) <= energy[0] * (1 + 1e-9), f"max {max(energy) / energy[0] - 1:+.2e}")

# on a periodic grid the option is off: the same run as the default's
texts = []
for moments in ["transferred", "kept"]:
    run(f"periodic_{moments}", {
        "Dimension": 2, "Time/End time": 0.05, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 0.6",
        "Grid/Subdivisions": "40, 24", "Grid/Periodic axes": "x", "Boundary conditions/Types": "2: fixed",
        "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
        "Contact/Round body moments": moments, "Output/Statistics interval": 5,
    }, [dict(elastic, Shape="box", **{"Lower corner": "0, 0", "Upper corner": "1, 0.2"}),
        dict(round_body, Shape="disk", Radius=0.1, Center="0.95, 0.35", Velocity="2, -1")])
    with open(os.path.join(WORK, f"periodic_{moments}", "output", "statistics.csv")) as f:
        texts.append(f.read())
check("periodic grid: 'kept' is off, statistics.csv byte for byte the default's", texts[0] == texts[1])

finish()
