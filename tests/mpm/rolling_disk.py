#!/usr/bin/python3
"""An elastic disk rolling down a friction wall (SPEC scene A1, theta = pi/6,
mu = 0.5, 8 cells per diameter, to t = 0.5 s), with
'Boundary conditions/Friction wall contact = material'.

The rigid disk rolls without slipping, x - x0 = (1/3) g t^2 sin(theta).
With 'approach' contact (a wall node acts whenever its velocity
approaches the wall) nodes a cell away from the disk's surface, whose
velocity is dominated by the stress of the surface points, carry the
disk's weight ahead of the contact point: the disk lags by 60% and climbs
0.05 m off the wall by 0.5 s. With the material check measured values are
x / x_rigid = 0.816, v / v_rigid = 0.888 and a largest rise of the centre
of 0.014 m; the bounds below leave room around them.

With 'surface position' contact (the wall acts where the body's surface,
from the node's mass centroid, reaches it) only the node at the contact
holds the disk, as the one contact point holds a rigid disk. Issue target:
rolling within 3% of the rigid travel at 16 cells per diameter, checked on
the A1 case and on a smaller, stiffer disk at another angle and friction
that the criterion was not tuned on, with the linear and with the GIMP
shape functions ('Grid/Shape functions = gimp'). Measured x / x_rigid,
seeded clipped (the default): A1 0.9970 (linear), 1.0014 (GIMP); the
stiffer disk 1.0038, 1.0016 (seeded on the lattice: 0.9792, 0.9859,
0.9803, 0.9930).

At 8 cells per diameter GIMP lags 2-3% (A1 0.9802, the stiffer disk
0.9677; on the lattice 0.9733, 0.9802): the grid does not hold the disk's
rotation. With 'Solver/Affine transfers' (GIMP and USL) both come within
2% of the rigid travel and closer than GIMP alone (measured 1.0153 and
0.9949; on the lattice 0.9913 and 1.0001).

A disk seeded on the lattice next to a friction wall gets a note at the
start of the run, one seeded conforming or clipped none. One seeded with a
single point per cell direction under gravity gets another: its spin turns
into strain (at 16 cells per diameter it rolls 30-70% behind the rigid
disk in any seeding)."""
import math
from scene_test import *

g, theta, mu, R = 9.8, math.pi / 6, 0.5, 0.5


def scene(name, contact, theta=theta, mu=mu, R=R, cells_per_diameter=8, end=0.5, G=2.5e6,
          shape_functions="linear", scheme={}):
    n = round(cells_per_diameter / (2 * R))
    return run(name, dict(scheme, **{
        "Grid/Shape functions": shape_functions,
        "Dimension": 2,
        "Gravity": f"{g * math.sin(theta)}, {-g * math.cos(theta)}",
        "Time/End time": end,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "6, 1.5",
        "Grid/Subdivisions": f"{6 * n}, {round(1.5 * n)}",
        "Boundary conditions/Types": "2: friction",
        "Boundary conditions/Friction coefficients": f"2: {mu}",
        "Boundary conditions/Friction wall contact": contact,
    }), [{"Shape": "disk", "Center": f"1, {R}", "Radius": R,
         "Bulk modulus": 4 * G, "Shear modulus": G, "Density": 3000,
         "Particles per cell direction": 3, "Lithostatic initial stress": "true"}])[2]


def measure(rows, theta=theta):
    last = rows[-1]
    t = last["time"]
    a = g * math.sin(theta) * 2 / 3
    x = (last["body0_x"] - rows[0]["body0_x"]) / (0.5 * a * t * t)
    v = last["body0_vx"] / (a * t)
    lift = max(r["body0_y"] for r in rows) - rows[0]["body0_y"]
    return x, v, lift


x, v, lift = measure(scene("rolling_material", "material"))
check("material contact: x / x_rigid in [0.75, 1.02]", 0.75 <= x <= 1.02, f"{x:.3f}")
check("material contact: v / v_rigid in [0.80, 1.05]", 0.80 <= v <= 1.05, f"{v:.3f}")
check("material contact: centre rises less than 0.02 m", lift < 0.02, f"{lift:.4f} m")

x_old, v_old, lift_old = measure(scene("rolling_approach", "approach"))
check("material contact rolls further than approach contact", x > x_old + 0.2,
      f"x / x_rigid {x:.3f} (material) vs {x_old:.3f} (approach)")

# 16 cells per diameter to t = 1 s: A1 (pi/6, 0.5; 'material' lags 9.6%),
# and R = 0.25 m, four times stiffer, pi/4, mu = 0.6 > tan(theta)/3 (rolls)
for name, kwargs in (("A1 pi/6, mu 0.5", dict()),
                     ("R 0.25, 4x stiffer, pi/4, mu 0.6",
                      dict(theta=math.pi / 4, mu=0.6, R=0.25, end=0.6, G=10e6))):
    for shape_functions in ("linear", "gimp"):
        rows = scene(f"rolling_surface_{len(name)}_{shape_functions}", "surface position",
                     cells_per_diameter=16, shape_functions=shape_functions,
                     **dict(dict(end=1.0), **kwargs))
        x, v, lift = measure(rows, kwargs.get("theta", theta))
        label = f"surface-position contact, {shape_functions} shape functions, {name}"
        check(f"{label}: x / x_rigid within 3% at 16 cells per diameter", abs(x - 1) <= 0.03,
              f"{x:.4f}")
        check(f"{label}: particles kept", rows[-1]["particles"] == rows[0]["particles"],
              f"{rows[-1]['particles']} of {rows[0]['particles']}")

# 8 cells per diameter: GIMP lags 2-3%, the affine transfers roll closer
affine = {"Solver/Update scheme": "USL", "Solver/Affine transfers": "true"}
for name, kwargs in (("A1 pi/6, mu 0.5", dict()),
                     ("R 0.25, 4x stiffer, pi/4, mu 0.6",
                      dict(theta=math.pi / 4, mu=0.6, R=0.25, end=0.6, G=10e6))):
    kwargs = dict(dict(end=1.0, cells_per_diameter=8, shape_functions="gimp"), **kwargs)
    x_gimp, _, _ = measure(scene(f"rolling_8_{len(name)}_gimp", "surface position", **kwargs),
                           kwargs.get("theta", theta))
    x_affine, _, _ = measure(scene(f"rolling_8_{len(name)}_affine", "surface position",
                                   scheme=affine, **kwargs), kwargs.get("theta", theta))
    label = f"affine transfers, 8 cells per diameter, {name}"
    check(f"{label}: x / x_rigid within 2%", abs(x_affine - 1) <= 0.02, f"{x_affine:.4f}")
    check(f"{label}: closer than GIMP without them",
          abs(x_affine - 1) < abs(x_gimp - 1), f"{x_affine - 1:+.4f} against {x_gimp - 1:+.4f}")

def start_output(name, gravity="0, 0", **disk):
    """What two steps of a disk at a friction wall print."""
    return run(name, {
        "Dimension": 2, "Time/Maximum number of steps": 2, "Gravity": gravity,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1", "Grid/Subdivisions": "16, 8",
        "Boundary conditions/Types": "2: friction",
        "Boundary conditions/Friction coefficients": "2: 0.5",
    }, [dict({"Shape": "disk", "Center": "1, 0.3", "Radius": 0.25,
              "Bulk modulus": 1e7, "Shear modulus": 2.5e6, "Density": 3000}, **disk)])[1]


# a disk seeded on the lattice that meets a friction wall gets a note at the
# start (its staircase edge rolls like a polygon); seeded conforming or
# clipped, none
for seeding in ("lattice", "conforming", "clipped"):
    output = start_output(f"seeding_note_{seeding}", Seeding=seeding)
    noted = "note: 1 disk seeded on the lattice" in output
    check(f"{seeding} seeding: the seeding note {'is' if seeding == 'lattice' else 'is not'} printed",
          noted == (seeding == "lattice"), output.splitlines()[1] if len(output.splitlines()) > 1 else output)
# one point per cell direction: a rolling disk turns its spin into strain
# (doc/mpm.md, "Spinning bodies"), and the run says so where gravity can
# make it roll; with two points, or without gravity or spin, it does not
for k, gravity in ((1, "0, -9.8"), (2, "0, -9.8"), (1, "0, 0")):
    output = start_output(f"single_point_note_{k}_{gravity[-1]}", gravity,
                          **{"Particles per cell direction": k})
    noted = "with one point per cell direction" in output
    expected = k == 1 and gravity != "0, 0"
    check(f"{k} point(s) per cell direction, gravity {gravity}: the note on one point per cell "
          f"{'is' if expected else 'is not'} printed", noted == expected)
finish()
