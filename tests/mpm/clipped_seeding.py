#!/usr/bin/python3
"""Disks and spheres seeded clipped ('Seeding = clipped'): the lattice's
points, each sub-cell the surface cuts carrying the part of the body inside
it at that part's centroid (a part under a tenth of its sub-cell joins the
largest part of its cell; a cell holding only such a part seeds nothing).

1. Mass and centre of mass (momentum at 1 m/s, no gravity) of a disk at 16
   cells per diameter and of a sphere at 8, centred off the grid lines and
   off the points' lattice: those of the body less the cells left out,
   which the test finds apart by sampling each sub-cell of the cells the
   surface cuts at 96^2 (24^3) points (the disk loses 5.3e-5 of its mass and its
   centre of mass moves 3e-4 cells; the sphere 6.3e-4 and 3.8e-4 cells).
   Within 2e-5 of the mass and 2e-5 cells: the sampling's error and that
   of the program's quadrature (sub-boxes of 2^-8 of a sub-cell in 2D,
   2^-5 in 3D, counted by their centres) are near 1e-6. The lattice's
   errors are printed beside (its edge is a staircase: 3e-3 and 6e-3 of
   the mass, 3e-2 and 6e-3 cells).
   The same on two MPI ranks (each sub-cell seeded once) to 1e-12, and for
   a disk crossing a periodic face (its image seeded with the same parts).
2. No seeding note (the lattice's staircase note) for a clipped disk at a
   friction wall."""
import itertools
import math

import numpy as np

from scene_test import *

rho = 1000
material = {"Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": rho, "Velocity": "1, 0"}


def measure(name, dim, seeding, centre, radius, cells, ranks=0, periodic=False):
    upper = ", ".join(["1"] * dim)
    entries = {"Dimension": dim, "Gravity": ", ".join(["0"] * dim), "Time/Maximum number of steps": 1,
               "Grid/Lower corner": ", ".join(["0"] * dim), "Grid/Upper corner": upper,
               "Grid/Subdivisions": ", ".join([str(cells)] * dim)}
    if periodic:
        entries["Grid/Periodic axes"] = "x"
    body = dict(material, Shape="disk" if dim == 2 else "sphere", Radius=radius, Seeding=seeding,
                Center=", ".join(map(repr, centre)), Velocity=", ".join(["1"] + ["0"] * (dim - 1)),
                **{"Particles per cell direction": 2})
    _, _, rows = run(name, entries, [body], ranks=ranks)
    first = rows[0]
    mass = first["momentum_x"]
    com = [first[f"body0_{c}"] for c in "xyz"[:dim]]
    return mass, com, first["particles"]


def left_out(dim, centre, radius, h):
    """Volume and first moment of the cells (2 points per direction) whose
    part inside the ball is under a tenth of a sub-cell, by sampling."""
    n = 96 if dim == 2 else 24
    s = h / 2
    grid = np.meshgrid(*[(np.arange(n) + 0.5) / n * s] * dim, indexing="ij")
    c = np.array(centre)
    volume, moment = 0.0, np.zeros(dim)
    ranges = [range(int((c[d] - radius) / h) - 1, int((c[d] + radius) / h) + 2) for d in range(dim)]
    for index in itertools.product(*ranges):
        lower = np.array(index) * h
        near = np.sum(np.maximum(0, np.maximum(lower - c, c - lower - h)) ** 2)
        far = np.sum(np.maximum(abs(c - lower), abs(lower + h - c)) ** 2)
        if near >= radius ** 2 or far <= radius ** 2:
            continue
        cell_volume, cell_moment = 0.0, np.zeros(dim)
        for sub in itertools.product((0, 1), repeat=dim):
            x = [lower[d] + sub[d] * s + grid[d] for d in range(dim)]
            inside = sum((x[d] - c[d]) ** 2 for d in range(dim)) < radius ** 2
            cell_volume += inside.sum() * (s / n) ** dim
            cell_moment += np.array([x[d][inside].sum() for d in range(dim)]) * (s / n) ** dim
        if 0 < cell_volume < 0.1 * s ** dim:
            volume += cell_volume
            moment += cell_moment
    return volume, moment


for dim, cells, radius, centre in [(2, 40, 0.2, (0.5123, 0.4571)), (3, 20, 0.2, (0.5123, 0.4571, 0.4839))]:
    exact = rho * (math.pi * radius ** 2 if dim == 2 else 4 / 3 * math.pi * radius ** 3)
    h = 1.0 / cells
    results = {}
    for seeding in ("lattice", "clipped"):
        mass, com, points = measure(f"mass_{dim}d_{seeding}", dim, seeding, centre, radius, cells)
        shift = max(abs(c - x) for c, x in zip(com, centre)) / h
        results[seeding] = (mass, com, points)
        print(f"  {dim}D {seeding}: {points:.0f} points, mass {mass / exact - 1:+.2e} relative, "
              f"centre of mass {shift:.2e} cells off")
    mass, com, points = results["clipped"]
    body = "disk" if dim == 2 else "sphere"
    lost_volume, lost_moment = left_out(dim, centre, radius, h)
    expected_mass = exact - rho * lost_volume
    expected_com = (exact * np.array(centre) - rho * lost_moment) / expected_mass
    check(f"{dim}D clipped {body}: mass that of the {body} less the cells left out, within 2e-5",
          abs(mass - expected_mass) <= 2e-5 * exact,
          f"{mass / exact - 1:+.3e} of rho times its {'area' if dim == 2 else 'volume'}, expected "
          f"{expected_mass / exact - 1:+.3e} (lattice {results['lattice'][0] / exact - 1:+.2e})")
    error = max(abs(a - b) for a, b in zip(com, expected_com)) / h
    check(f"{dim}D clipped {body}: centre of mass that of the {body} less the cells left out, within 2e-5 cells",
          error <= 2e-5, f"{error:.1e} cells off the expected, which is "
          f"{max(abs(a - b) for a, b in zip(expected_com, centre)) / h:.1e} cells off the centre")
    mass2, com2, points2 = measure(f"mass_{dim}d_clipped_mpi2", dim, "clipped", centre, radius, cells, ranks=2)
    check(f"{dim}D clipped {body} on two ranks: the same points, mass and centre of mass to 1e-12",
          points2 == points and abs(mass2 / mass - 1) <= 1e-12
          and max(abs(a - b) for a, b in zip(com, com2)) <= 1e-12,
          f"{points2:.0f} points, mass {mass2 / mass - 1:+.1e}")

# a disk across the periodic face x = 0 (its centre at x = 0.0623): the
# parts seeded on both sides are those of the disk moved into the grid
mass, com, points = measure("periodic_inside", 2, "clipped", (0.5623, 0.4571), 0.2, 40)
mass_p, com_p, points_p = measure("periodic_across", 2, "clipped", (0.0623, 0.4571), 0.2, 40, periodic=True)
check("clipped disk across a periodic face: the points and mass of the same disk inside the grid",
      points_p == points and abs(mass_p / mass - 1) <= 1e-12, f"{points_p:.0f} against {points:.0f} points, "
      f"mass {mass_p / mass - 1:+.1e}")

# no staircase note for a clipped disk
_, output, _ = run("seeding_note", {
    "Dimension": 2, "Time/Maximum number of steps": 2,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1", "Grid/Subdivisions": "16, 8",
    "Boundary conditions/Types": "2: friction", "Boundary conditions/Friction coefficients": "2: 0.5",
}, [{"Shape": "disk", "Center": "1, 0.3", "Radius": 0.25, "Seeding": "clipped",
     "Bulk modulus": 1e7, "Shear modulus": 2.5e6, "Density": 3000}])
check("a clipped disk at a friction wall gets no seeding note", "seeded on the lattice" not in output)
finish()
