#!/usr/bin/python3
"""HDF5 + XDMF particle output (Output format = hdf5) on 1 and 2 ranks: an
elastic box 0.4 m x 0.3 m (density 1000, 2x2 points in each 0.05 m cell,
192 points of 0.625 kg) falling freely. Each particles_NNNNN.h5, read back
with h5py (Debian package python3-h5py), holds as many points as the
`particles` column of statistics.csv at that output step, with the ids
0..191; their masses sum to the body's 120 kg and every point's velocity is
(0, g t), t the time of that row (a stress-free body in free fall gains
exactly g dt per step at every node; test free_fall holds the centre of
mass to 1e-10). deal.II keeps output fields in single precision
(DataOutBase::Patch::data is float), so each value carries a rounding of up
to 2^-24 = 6e-8 relative: the tolerance for mass and velocity is 1.2e-7.
The point locations are written in double precision: those of 1 and 2
ranks (sorted; ids are numbered per rank) agree to 1e-13 m.
particles.xdmf has one entry per output time, in order, each referencing
its .h5 file. A small box on one of 3 ranks checks that ranks without
material points do not stall the collective write.

Grid output (Output/Grid output = true), same runs: grid.xdmf lists one
grid_NNNNN.h5 per particle file, at the same times. Each holds as many
cells as the `cells` column of statistics.csv (400) and 4 vertices per
cell (vertices are not merged, so that the cell fields stay with their
cells). Nodal mass: vertices at the same place carry the same value, and
summed once per place it is the body's 120 kg (the shape functions are a
partition of unity), to the 1.2e-7 of single precision. Nodal velocity:
momentum / mass of points that all move with (0, g t) is (0, g t) at every
node with mass, to 1.2e-7; zero where the mass is zero. Cell fields: the
material_points sum to 192, level is 0 (uniform grid), rank takes the
values 0..ranks-1. On 3 ranks the grid files hold the 400 cells too.
A disk falling on a grid refined at its surface (2 ranks) has hanging
nodes: a vertex at the midpoint of another cell's edge. Summed over the
vertices that are not hanging, the nodal mass is the points' total mass
(hanging nodes hold none; they show values interpolated from their
masters), to 1.2e-7; every node with mass, hanging ones included
(momentum and mass are interpolated, then divided), has v = (0, g t).
The VTU variant (2 ranks): grid.pvd lists grid_NNNNN.pvtu files whose
pieces exist and hold 400 cells together (read with meshio).

Run with Debian's /usr/bin/python3 (python3-h5py, python3-meshio)."""
import os
import subprocess
import xml.etree.ElementTree as ET

import h5py
import meshio

from scene_test import *


def read_dataset(h5, name):
    """The rows of the two-dimensional dataset `name` in file `h5` (points
    by components), as lists of floats."""
    with h5py.File(h5, "r") as f:
        data = f[name]
        assert data.ndim == 2, f"{name}: shape {data.shape}"
        return data[()].astype(float).tolist()


def key(point):
    return tuple(round(x, 12) for x in point)


def series(out, stem):
    """The stem_NNNNN.h5 files in `out`, and the times and .h5 files that
    stem.xdmf lists."""
    files = sorted(f for f in os.listdir(out) if f.startswith(stem + "_") and f.endswith(".h5"))
    return (files,) + xdmf_series(os.path.join(out, stem + ".xdmf"))


def xdmf_series(path):
    """The times of an XDMF time series and the .h5 file each one's
    geometry ('file.h5:/nodes') is in."""
    times, files = [], []
    for grid in ET.parse(path).getroot().iter("Grid"):
        time = grid.find("Time")
        if time is None:
            continue
        times.append(float(time.get("Value")))
        for item in grid.find("Geometry").iter("DataItem"):
            files.append(item.text.strip().split(":")[0])
    return times, files


def check_grid(what, out, rows, times, ranks, n_points, total_mass, g, adaptive=False):
    """The grid files of a run of a body falling freely from rest."""
    grid_files, grid_times, referenced = series(out, "grid")
    check(f"{what}: grid.xdmf has one entry per grid_NNNNN.h5, at the particle output times",
          referenced == grid_files and grid_times == times, f"{len(grid_files)} files, times {grid_times}")
    worst_mass = worst_v = worst_duplicate = 0.0
    for h5, t in zip(grid_files, grid_times):
        row = min(rows, key=lambda r: abs(r["time"] - t))
        path = os.path.join(out, h5)
        nodes = read_dataset(path, "nodes")
        cells = [[int(i) for i in c] for c in read_dataset(path, "cells")]
        mass = [m[0] for m in read_dataset(path, "mass")]
        velocity = read_dataset(path, "velocity")
        points = [c[0] for c in read_dataset(path, "material_points")]
        level = [c[0] for c in read_dataset(path, "level")]
        rank = [c[0] for c in read_dataset(path, "rank")]
        check(f"{what}, {h5}: {len(cells)} cells as in statistics.csv, 4 vertices each",
              len(cells) == row["cells"] and len(nodes) == len(mass) == len(velocity) == 4 * len(cells),
              f"{len(cells)} cells, {len(nodes)} vertices, {row['cells']:g} cells in statistics.csv")
        # one value per place
        at = {}
        for x, m in zip(nodes, mass):
            worst_duplicate = max(worst_duplicate, abs(at.setdefault(key(x), m) - m))
        hanging = set()
        if adaptive:
            # hanging: a vertex at the midpoint of another cell's edge
            for c in cells:
                # (a cell's vertices may differ from each other in the last bit)
                xs = sorted({round(nodes[i][0], 12) for i in c})
                ys = sorted({round(nodes[i][1], 12) for i in c})
                xm, ym = (xs[0] + xs[1]) / 2, (ys[0] + ys[1]) / 2
                for p in ((xm, ys[0]), (xm, ys[1]), (xs[0], ym), (xs[1], ym)):
                    if key(p) in at:
                        hanging.add(key(p))
            check(f"{what}, {h5}: refined (levels {min(level):g}..{max(level):g}), with hanging nodes",
                  max(level) > min(level) and len(hanging) > 0, f"{len(hanging)} hanging nodes")
        worst_mass = max(worst_mass, abs(sum(m for k, m in at.items() if k not in hanging) - total_mass) / total_mass)
        expected = g * row["time"]
        moving = [v for v, m in zip(velocity, mass) if m > 0]
        if row["time"] > 0:
            worst_v = max(worst_v, max(abs(v[1] - expected) for v in moving) / abs(expected))
        check(f"{what}, {h5}: no horizontal nodal velocity, none where the mass is zero",
              max(abs(v[0]) for v in moving) < 1e-12 and
              all(v == [0.0, 0.0, 0.0] for v, m in zip(velocity, mass) if m == 0))
        per_cell = [points[c[0]] for c in cells]
        check(f"{what}, {h5}: material_points sum to {n_points}", sum(per_cell) == n_points, f"{sum(per_cell):g}")
        check(f"{what}, {h5}: rank 0..{ranks - 1}", sorted(set(rank)) == list(range(ranks)), str(sorted(set(rank))))
        if not adaptive:
            check(f"{what}, {h5}: level 0", set(level) == {0.0}, str(sorted(set(level))))
    check(f"{what}: vertices at the same place have the same nodal mass", worst_duplicate == 0,
          f"largest difference {worst_duplicate:.2e} kg")
    check(f"{what}: nodal mass{' (not hanging)' if adaptive else ''} sums to the points' {total_mass:g} kg to 1.2e-7",
          worst_mass <= 1.2e-7, f"relative error {worst_mass:.2e}")
    check(f"{what}: nodal v_y = g t wherever there is mass, to 1.2e-7", worst_v <= 1.2e-7,
          f"largest relative error {worst_v:.2e}")


g = -9.81
entries = {
    "Dimension": 2, "Gravity": f"0, {g}", "Time/End time": 0.2,
    "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20",
    "Output/Output format": "hdf5", "Output/Particle output interval": 0.05,
    "Output/Grid output": "true",
}
body = {"Shape": "box", "Lower corner": "0.3, 0.6", "Upper corner": "0.7, 0.9",
        "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000, "Particles per cell direction": 2}

locations = {}
for ranks in (1, 2):
    name = f"hdf5_np{ranks}"
    _, output, rows = run(name, entries, [body], ranks=ranks)
    out = os.path.join(WORK, name, "output")
    check(f"{ranks} rank(s): the console names particles.xdmf", "particles.xdmf" in output)
    h5_files, times, referenced = series(out, "particles")
    check(f"{ranks} rank(s): one xdmf entry per .h5 file, each referencing it",
          len(h5_files) >= 5 and referenced == h5_files and len(times) == len(h5_files),
          f"{len(h5_files)} files, xdmf references {referenced}, {len(times)} times")
    check(f"{ranks} rank(s): xdmf times increase", times == sorted(times) and times[0] == 0, str(times))
    worst_v = worst_mass = 0.0
    for h5, t in zip(h5_files, times):
        # the statistics row of this output (statistics every step)
        row = min(rows, key=lambda r: abs(r["time"] - t))
        path = os.path.join(out, h5)
        nodes = read_dataset(path, "nodes")
        mass = [m[0] for m in read_dataset(path, "mass")]
        velocity = read_dataset(path, "velocity")
        ids = [int(i[0]) for i in read_dataset(path, "id")]
        check(f"{ranks} rank(s), {h5}: {len(nodes)} points as in statistics.csv",
              len(nodes) == row["particles"] == len(mass) == len(velocity) == 192,
              f"{len(nodes)} nodes, {len(mass)} masses, {row['particles']:g} in statistics.csv")
        check(f"{ranks} rank(s), {h5}: ids 0..191", sorted(ids) == list(range(192)))
        worst_mass = max(worst_mass, abs(sum(mass) - 120.0) / 120.0)
        expected = g * row["time"]
        if row["time"] > 0:
            worst_v = max(worst_v, max(abs(v[1] - expected) for v in velocity) / abs(expected))
        check(f"{ranks} rank(s), {h5}: no horizontal velocity", max(abs(v[0]) for v in velocity) < 1e-12)
        locations.setdefault(ranks, []).append(sorted(nodes))
    check(f"{ranks} rank(s): mass sums to 120 kg to 1.2e-7", worst_mass <= 1.2e-7, f"relative error {worst_mass:.2e}")
    check(f"{ranks} rank(s): every point's v_y = g t to 1.2e-7", worst_v <= 1.2e-7, f"largest relative error {worst_v:.2e}")

    check_grid(f"{ranks} rank(s)", out, rows, times, ranks, 192, 120.0, g)

difference = max(abs(p[d] - q[d]) for a, b in zip(locations[1], locations[2]) for p, q in zip(a, b) for d in (0, 1))
check("1 and 2 ranks: the same point locations", len(locations[1]) == len(locations[2]) and difference < 1e-13,
      f"largest difference {difference:.2e} m")
# ranks without material points: deal.II 9.4's HDF5 writer would wait for
# them in a collective write; sable lets only the ranks with points write
small = {"Shape": "box", "Lower corner": "0.05, 0.9", "Upper corner": "0.1, 0.95",
         "Young's modulus": 1e6, "Density": 1000, "Particles per cell direction": 2}
try:
    code, output, rows = run("hdf5_empty_ranks", dict(entries, **{"Time/End time": 0.02, "Gravity": "0, 0",
                                                                  "Output/Particle output interval": 0.01}),
                             [small], ranks=3, expect_success=False, timeout=120)
except subprocess.TimeoutExpired:
    code, output, rows = "timeout", "", []
out = os.path.join(WORK, "hdf5_empty_ranks", "output")
h5_files = sorted(f for f in os.listdir(out) if f.endswith(".h5")) if os.path.isdir(out) else []
check("3 ranks, points on one: finishes", code == 0, f"exit {code}")
h5_files = [f for f in h5_files if f.startswith("particles_")]
check("3 ranks, points on one: every file has the 4 points",
      len(h5_files) == 3 and all(len(read_dataset(os.path.join(out, h5), "nodes")) == 4 for h5 in h5_files),
      f"{len(h5_files)} files")
grid_files = sorted(f for f in os.listdir(out) if f.startswith("grid_")) if os.path.isdir(out) else []
check("3 ranks: every grid file has the 400 cells",
      len(grid_files) == 3 and all(len(read_dataset(os.path.join(out, h5), "cells")) == 400 for h5 in grid_files),
      f"{len(grid_files)} files")

# a grid refined at the surface of a falling disk: hanging nodes
disk = {"Shape": "disk", "Center": "0.5, 0.7", "Radius": 0.2, "Bulk modulus": 1e6, "Shear modulus": 5e5,
        "Density": 1000, "Particles per cell direction": 2}
_, output, rows = run("hdf5_grid_adaptive", dict(entries, **{
    "Time/End time": 0.1, "Grid/Subdivisions": "10, 10", "Mesh refinement/Criteria": "body surface",
    "Mesh refinement/Maximum level": 2, "Mesh refinement/Refinement interval": 5}), [disk], ranks=2)
out = os.path.join(WORK, "hdf5_grid_adaptive", "output")
particle_files = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".h5"))
disk_mass = sum(m[0] for m in read_dataset(os.path.join(out, particle_files[0]), "mass"))
times, _ = xdmf_series(os.path.join(out, "grid.xdmf"))
check_grid("adaptive, 2 ranks", out, rows, times, 2, int(rows[0]["particles"]), disk_mass, g, adaptive=True)

# VTU
_, output, rows = run("vtu_grid", dict(entries, **{"Output/Output format": "vtu", "Time/End time": 0.1}),
                      [body], ranks=2)
out = os.path.join(WORK, "vtu_grid", "output")
records = [d.get("file") for d in ET.parse(os.path.join(out, "grid.pvd")).getroot().iter("DataSet")]
cells = []
for record in records:
    pieces = [p.get("Source") for p in ET.parse(os.path.join(out, record)).getroot().iter("Piece")]
    cells.append(sum(len(block.data) for piece in pieces
                     for block in meshio.read(os.path.join(out, piece)).cells))
check("VTU, 2 ranks: grid.pvd lists 3 grid_NNNNN.pvtu (2 pieces each) with 400 cells",
      len(records) == 3 and all(r.startswith("grid_") for r in records) and cells == [400] * 3,
      f"{records}, cells {cells}")
finish()
