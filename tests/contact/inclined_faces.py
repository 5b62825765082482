#!/usr/bin/python3
"""Friction between faces inclined to the grid: a block on a wedge.

A 0.2 m square block (a mesh body, one quadrilateral) rests on the sloping
face of an elastic wedge (a mesh body fixed at its base by the grid's
floor, its high end against the slip wall on the left), both E = 10 MPa, nu = 0.3, rho = 1000 kg/m^3, cells of 0.025 m,
2x2 points per cell, gravity vertical, Bardenhagen 2001 contact with the
default normals ('flatter body'). Both faces are staircases of points; the
rigid block slides down the slope with a = g (sin theta - mu cos theta).
The acceleration along the slope is fitted to the travel over 0.05..0.5 s:
within 2% of the rigid value at theta = 30 deg with mu = 0 and 0.2, at
20 deg with mu = 0.2 and at 45 deg with mu = 0.6 (measured -0.01%, +0.38%,
+0.56%, -0.14%). The block stays on
the slope: its centre moves less than a quarter cell across it. With
mu = 0.7 at 30 deg, started settled ('Solver/Settling steps'), it sticks:
it moves less than 1% of a cell in 0.5 s (measured 2.4e-4 cells; 2e-6 with
the centroids' estimate of the surfaces).

In 3D a cube of 0.2 x 0.2 x 0.15 m (a hexahedron) slides on a wedge of
hexahedra 0.6 m long, 0.25 m wide between slip walls, to 0.3 s; at 30 deg
with mu = 0.2 it is within 2% of the rigid value too (measured +0.17%).
There the wedge's records under the cube's sides hold points of its slope
and a few of its side faces (those a cell or two deep near the edge); they
take the slope's direction, on which nine tenths of their mass projects.
Taking the mass gradient there instead, the cube slid 4.3% slow.

Taken from the mass gradients of the staircase points, the normal tilts
from node to node: the same block then stuck at mu = 0.2 (a = -0.16 m/s^2
at 30 deg) and slid at 0.47 of the rigid value without friction.
At 45 deg with mu = 0.6 the 2001 rule pulled the block back in a fifth of
its steps (the staircases' steps separating while compressed); with the
friction capped per step only, by mu times that step's net normal
impulse, the pulling steps had none and the others mu times theirs: 4%
more than mu m g cos theta, and the block slid 8.8% slow. The pull is now
carried to the next steps' cap (doc/mpm.md, "Contact between bodies").

Started as seeded, the wedge rings under the sudden gravity (its surface
moves at up to 0.1 m/s) and throws the block: with mu = 0.4 at 30 deg and
0.5 at 40 deg the block then slides 20% fast (no contact force in 13% of
the rows), where the centroids' estimate of the surfaces, which found
contact a little early, held it within 0.8%. Settled with contacts
sticking ('Solver/Settling friction = stick': under the scene's gravity,
held where it was set down, the wedge settled with it), it slides from
that equilibrium within 1% of the rigid block (measured +0.10% and
-0.04%; with the centroids' estimate -0.07% and -0.30%).

A disk (R = 0.2 m, 16 cells per diameter, seeded conforming), the disk
and the wedge started with lithostatic stress (near their equilibrium
under gravity, as the plane body of test plane_rolling), rolls on the 2D
wedge at 25, 35, 40 and 45 deg within 3% of the rigid rolling disk
(measured +0.72%, -1.53%, -1.08%, -1.74%). Both surfaces are located
where the points' vectors to them end (doc/mpm.md, "Detection"). Started
stress-free, the wedge rings under the sudden gravity and throws the disk:
-3.05%, -3.39%, -1.07%, -2.54% (with the disk's surface from its
centroids' offsets +2.02%, +0.08%, +1.93%, +0.86%; with the wedge's
surface from its centroids' too, -3.9%, -5.7%, -7.1% and -5.0%). Started
near equilibrium, the clipped disk at 16 angle-friction pairs from 20 to
45 deg is within 1.4% on average, 14 of them within 3% (doc/validation.md,
"Faces inclined to the grid"; the worst -3.45% at 20 deg with mu = 0.4).

A rigid wedge, a body of prescribed velocity zero, holds a block as the
elastic one does: at 30 deg without friction, 20 deg with mu = 0.2, 40
deg with 0.5, 45 deg with 0.6 the block slides within 1% of the rigid
value (measured -0.00%, +0.00%, -0.08%, -0.04%), and in 3D at 30 deg with
mu = 0.2; settled with mu = 0.7 at 30 deg it stays (2e-5 cells). The
contact weighs such a body's records a billion times heavier; before the
sums of its face normals were weighed with them, its records took no face
normal, and the block stuck (-98% to -110% of the rigid acceleration).

Points within two cells of a face carry its normal (none within a cell
of another face); their records take it where nine tenths of their mass
carries one normal (or projects onto one of the body's face directions,
where two faces' points meet). The normals
turn with their body's rotation (doc/mpm.md, "Contact between bodies").
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import WORK, check, finish, run  # noqa: E402

g = 9.81
h = 0.025
length = 2.0      # the wedge's base
base = 0.1        # its height at the low end
side = 0.2        # the block
start = 0.3       # where the block's lower corner sits along the slope
length_3d = 0.6   # in 3D: the wedge's base,
start_3d = 0.1    # the block's start along the slope,
width_3d = 0.25   # its width (and the grid's),
depth_3d = 0.15   # the cube's extent across the slope,
end_3d = 0.3      # and the time slid

meshes = os.path.abspath(os.path.join(WORK, "inclined_faces_meshes"))
os.makedirs(meshes, exist_ok=True)


def write_quad(path, corners):
    """A UCD file of one quadrilateral with the corners counter-clockwise."""
    with open(path, "w") as f:
        f.write("4 1 0 0 0\n")
        for i, (x, y) in enumerate(corners):
            f.write(f"{i + 1} {x!r} {y!r} 0\n")
        f.write("1 0 quad 1 2 3 4\n")


def write_hexahedron(path, corners, z0, z1):
    """A UCD file of one hexahedron: the quadrilateral `corners` extruded
    from z0 to z1."""
    with open(path, "w") as f:
        f.write("8 1 0 0 0\n")
        for k, z in enumerate((z0, z1)):
            for i, (x, y) in enumerate(corners):
                f.write(f"{4 * k + i + 1} {x!r} {y!r} {z!r}\n")
        f.write("1 0 hex 1 2 3 4 5 6 7 8\n")


def slide(theta_degrees, mu, settling_steps=0, dim=2, settling_friction="scene", driven=False):
    """Return the fitted and rigid accelerations along the slope, the
    largest move across it and the largest travel along it. With `driven`
    the wedge is a body of prescribed velocity zero: rigid and fixed."""
    theta = math.radians(theta_degrees)
    wedge_length = length if dim == 2 else length_3d
    top = base + wedge_length * math.tan(theta)
    down = np.array([math.cos(theta), -math.sin(theta)])   # along the slope
    out = np.array([math.sin(theta), math.cos(theta)])     # the wedge's normal
    corner = np.array([0, top]) + (start if dim == 2 else start_3d) * down
    name = f"inclined_faces_{dim}d_{theta_degrees}_{mu}{'_driven' if driven else ''}"
    wedge = os.path.join(meshes, f"wedge_{dim}d_{theta_degrees}.inp")
    block = os.path.join(meshes, f"block_{dim}d_{theta_degrees}.inp")
    wedge_corners = [(0, 0), (wedge_length, 0), (wedge_length, base), (0, top)]
    block_corners = [tuple(corner), tuple(corner + side * down),
                     tuple(corner + side * (down + out)), tuple(corner + side * out)]
    rows_y = math.ceil((top + 0.45) / h)
    if dim == 2:
        write_quad(wedge, wedge_corners)
        write_quad(block, block_corners)
        grid = {"Grid/Lower corner": "0, 0", "Grid/Upper corner": f"{length}, {rows_y * h!r}",
                "Grid/Subdivisions": f"{round(length / h)}, {rows_y}", "Gravity": f"0, {-g}",
                "Time/End time": 0.5, "Boundary conditions/Types": "0: slip, 2: fixed"}
    else:
        # the wedge as wide as the grid between slip walls, the cube's
        # sides a cell and a half inside it
        write_hexahedron(wedge, wedge_corners, 0, width_3d)
        write_hexahedron(block, block_corners, (width_3d - depth_3d) / 2, (width_3d + depth_3d) / 2)
        grid = {"Grid/Lower corner": "0, 0, 0",
                "Grid/Upper corner": f"{length_3d}, {rows_y * h!r}, {width_3d}",
                "Grid/Subdivisions": f"{round(length_3d / h)}, {rows_y}, {round(width_3d / h)}",
                "Gravity": f"0, {-g}, 0", "Time/End time": end_3d,
                "Boundary conditions/Types": "0: slip, 2: fixed, 4: slip, 5: slip"}
    elastic = {"Shape": "mesh", "Young's modulus": 1e7, "Poisson's ratio": 0.3,
               "Density": 1000, "Particles per cell direction": 2}
    wedge_body = dict(elastic, **{"Mesh file": wedge})
    if driven:
        wedge_body["Prescribed velocity"] = "0, 0" if dim == 2 else "0, 0, 0"
    _, _, rows = run(name, dict(grid, **{
        "Dimension": dim, "Contact/Model": "bardenhagen 2001",
        "Contact/Friction coefficient": mu, "Output/Statistics interval": 10,
        "Solver/Settling steps": settling_steps, "Solver/Settling friction": settling_friction,
    }), [wedge_body, dict(elastic, **{"Mesh file": block})])
    t = np.array([r["time"] for r in rows])
    moved = np.array([[r["body1_x"] - rows[0]["body1_x"], r["body1_y"] - rows[0]["body1_y"]]
                      for r in rows])
    along, across = moved @ down, moved @ out
    late = t >= 0.05
    matrix = np.vstack([np.ones(late.sum()), t[late], t[late] ** 2 / 2]).T
    fitted = np.linalg.lstsq(matrix, along[late], rcond=None)[0][2]
    return (fitted, g * (math.sin(theta) - mu * math.cos(theta)), np.abs(across).max(),
            np.abs(along).max())


def check_slide(what, fitted, rigid, across, tolerance, across_cells):
    """The block's acceleration within `tolerance` of the rigid one, and
    its largest move across the slope below `across_cells` cells."""
    check(f"{what}: the acceleration along the slope within {tolerance:.0%} of the rigid one",
          abs(fitted - rigid) <= tolerance * rigid,
          f"a = {fitted:.4f}, rigid {rigid:.4f} m/s^2 ({(fitted - rigid) / rigid:+.2%})")
    check(f"{what}: it stays on the slope (moves less than {across_cells} h across it)",
          across < across_cells * h, f"{across * 1000:.3f} mm")


for dim, theta, mu in ((2, 30, 0.0), (2, 30, 0.2), (2, 20, 0.2), (2, 45, 0.6), (3, 30, 0.2)):
    fitted, rigid, across, _ = slide(theta, mu, dim=dim)
    check_slide(f"{dim}D block on a {theta} deg wedge, mu = {mu}", fitted, rigid, across, 0.02, 0.25)


def roll(theta_degrees, mu):
    """A disk (R = 0.2 m, 16 cells per diameter, seeded conforming) set
    down touching the 2D wedge's slope, both with lithostatic initial
    stress; return its fitted and the rigid
    rolling disk's acceleration along the slope (2/3 g sin theta)."""
    theta = math.radians(theta_degrees)
    top = base + length * math.tan(theta)
    down = np.array([math.cos(theta), -math.sin(theta)])
    out = np.array([math.sin(theta), math.cos(theta)])
    centre = np.array([0, top]) + start * down + radius * out
    wedge = os.path.join(meshes, f"wedge_2d_{theta_degrees}.inp")
    write_quad(wedge, [(0, 0), (length, 0), (length, base), (0, top)])
    rows_y = math.ceil((top + 0.5) / h)
    elastic = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
               "Particles per cell direction": 2, "Lithostatic initial stress": "true"}
    _, _, rows = run(f"inclined_faces_disk_{theta_degrees}_{mu}", {
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": f"{length}, {rows_y * h!r}",
        "Grid/Subdivisions": f"{round(length / h)}, {rows_y}", "Gravity": f"0, {-g}",
        "Time/End time": 0.5, "Boundary conditions/Types": "0: slip, 2: fixed",
        "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": mu,
        "Output/Statistics interval": 10,
    }, [dict(elastic, **{"Shape": "mesh", "Mesh file": wedge}),
        dict(elastic, **{"Shape": "disk", "Radius": radius, "Seeding": "conforming",
                         "Center": f"{centre[0]!r}, {centre[1]!r}"})])
    t = np.array([r["time"] for r in rows])
    along = np.array([[r["body1_x"] - rows[0]["body1_x"], r["body1_y"] - rows[0]["body1_y"]]
                      for r in rows]) @ down
    late = t >= 0.05
    matrix = np.vstack([np.ones(late.sum()), t[late], t[late] ** 2 / 2]).T
    return np.linalg.lstsq(matrix, along[late], rcond=None)[0][2], 2 / 3 * g * math.sin(theta)


radius = 0.2
for theta, mu in ((25, 0.5), (35, 0.5), (40, 0.5), (45, 0.6)):
    fitted, rigid = roll(theta, mu)
    check(f"disk rolling on a {theta} deg wedge, mu = {mu}: the acceleration within 3% of the rigid "
          "rolling disk's", abs(fitted - rigid) <= 0.03 * rigid,
          f"a = {fitted:.4f}, rigid {rigid:.4f} m/s^2 ({(fitted - rigid) / rigid:+.2%})")

# settled held by friction, the wedge with it, then sliding from that
# equilibrium: the rigid wedge's problem
for theta, mu in ((30, 0.4), (40, 0.5)):
    fitted, rigid, _, _ = slide(theta, mu, settling_steps=20000, settling_friction="stick")
    check(f"2D block on a {theta} deg wedge, mu = {mu}, settled sticking: the acceleration along "
          "the slope within 1% of the rigid one", abs(fitted - rigid) <= 0.01 * rigid,
          f"a = {fitted:.4f}, rigid {rigid:.4f} m/s^2 ({(fitted - rigid) / rigid:+.2%})")

# mu above tan theta: started settled, the block stays where it is
_, _, _, travel = slide(30, 0.7, settling_steps=20000)
check("block on a 30 deg wedge, mu = 0.7 (sticks): it moves less than 1% of a cell in 0.5 s",
      travel < 0.01 * h, f"{travel / h:.2e} cells")

# a rigid wedge: a body of prescribed velocity, whose records the contact
# weighs a billion times heavier; its face normals' sums must be weighed
# with its mass (they were not, its records lost their face, and the block
# stuck)
for dim, theta, mu in ((2, 30, 0.0), (2, 20, 0.2), (2, 40, 0.5), (2, 45, 0.6), (3, 30, 0.2)):
    fitted, rigid, across, _ = slide(theta, mu, dim=dim, driven=True)
    check_slide(f"{dim}D block on a fixed (prescribed) {theta} deg wedge, mu = {mu}", fitted, rigid, across,
                0.01, 0.05)
_, _, _, travel = slide(30, 0.7, settling_steps=20000, driven=True)
check("block on a fixed (prescribed) 30 deg wedge, mu = 0.7 (sticks): it moves less than 1% of a cell "
      "in 0.5 s", travel < 0.01 * h, f"{travel / h:.2e} cells")
finish()
