#!/usr/bin/python3
"""Snapshots of a 2D MPM run: the material points at chosen times, coloured
by their speed (or by body), and the energies of statistics.csv over time.

Usage: contrib/gallery/snapshots.py OUTPUT_DIR [--times 0,0.15,0.3,0.6]
           [--png FILE] [--dpi 110] [--color speed|body] [--grid]
           [--mesh FILE [--mesh-scale S] [--mesh-translation X,Y]]
OUTPUT_DIR is a run's output directory (particles.pvd, statistics.csv); the
picture goes to FILE (default: OUTPUT_DIR/snapshots.png). For each time the
particle file written closest to it is shown. --grid draws the background
grid's cells as refined at that time (the run's grid.pvd, written with
'Output/Grid output = true'); --mesh adds a first panel with the cells of
a body's mesh file (Shape = mesh; give the body's 'Mesh scale' and 'Mesh
translation') over the points of the first snapshot. Needs Debian's python3-meshio and python3-matplotlib."""
import argparse
import csv
import os
import sys
import xml.etree.ElementTree as ElementTree

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    import meshio
    import numpy as np
except ImportError as error:
    sys.exit(f"snapshots.py: {error.name} is missing; install python3-matplotlib and python3-meshio "
             "and run with /usr/bin/python3")


def particle_files(directory, collection="particles.pvd"):
    """(time, path) of every file the run listed in particles.pvd (or in
    another collection: grid.pvd)."""
    root = ElementTree.parse(os.path.join(directory, collection)).getroot()
    return [(float(d.get("timestep")), os.path.join(directory, d.get("file"))) for d in root.iter("DataSet")]


def pieces_of(path):
    """The .vtu files of one output step: the pieces of every rank of a .pvtu."""
    if not path.endswith(".pvtu"):
        return [path]
    root = ElementTree.parse(path).getroot()
    return [os.path.join(os.path.dirname(path), p.get("Source")) for p in root.iter("Piece")]


def read_points(path):
    """Positions, speeds and bodies of the points of one output step (.pvtu
    or .vtu), joining the pieces of every rank."""
    positions, speeds, bodies = [], [], []
    for piece in pieces_of(path):
        mesh = meshio.read(piece)
        if len(mesh.points) == 0:
            continue
        positions.append(mesh.points[:, :2])
        speeds.append(np.linalg.norm(mesh.point_data["velocity"], axis=1))
        bodies.append(np.ravel(mesh.point_data["body"]))
    return np.concatenate(positions), np.concatenate(speeds), np.concatenate(bodies)


def cell_polygons(path, scale=1.0, translation=(0.0, 0.0)):
    """The 2D cells (triangles, quadrilaterals) of a mesh file or of one grid
    output step as polygons, mapped by x -> scale x + translation."""
    polygons = []
    for piece in pieces_of(path):
        mesh = meshio.read(piece)
        points = scale * mesh.points[:, :2] + np.asarray(translation)
        for block in mesh.cells:
            if block.type in ("triangle", "quad"):
                polygons += [points[c] for c in block.data]
    return polygons


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory")
    parser.add_argument("--times", default="0,0.15,0.3,0.6")
    parser.add_argument("--png", default=None)
    parser.add_argument("--dpi", type=float, default=110)
    parser.add_argument("--color", choices=("speed", "body"), default="speed")
    parser.add_argument("--grid", action="store_true")
    parser.add_argument("--mesh", default=None)
    parser.add_argument("--mesh-scale", type=float, default=1.0)
    parser.add_argument("--mesh-translation", default="0,0")
    args = parser.parse_args()
    if args.grid and not os.path.exists(os.path.join(args.directory, "grid.pvd")):
        sys.exit(f"snapshots.py: {args.directory} has no grid.pvd: run the scene with 'Output/Grid output = true'")
    if args.mesh and not os.path.exists(args.mesh):
        sys.exit(f"snapshots.py: no mesh file {args.mesh}")
    for name in ("particles.pvd", "statistics.csv"):
        if not os.path.exists(os.path.join(args.directory, name)):
            sys.exit(f"snapshots.py: {args.directory} has no {name}: not the output directory of an MPM run "
                     "with particle output ('Output/Particle output interval')")
    files = particle_files(args.directory)
    if not files:
        sys.exit(f"snapshots.py: {args.directory}/particles.pvd lists no particle files")
    times = [float(t) for t in args.times.split(",")]
    chosen = [min(files, key=lambda f: abs(f[0] - t)) for t in times]
    data = [read_points(path) for _, path in chosen]
    top = max(s.max() for _, s, _ in data)
    lower = np.min([p.min(axis=0) for p, _, _ in data], axis=0)
    upper = np.max([p.max(axis=0) for p, _, _ in data], axis=0)
    grids = []
    if args.grid:
        # the grid files are numbered and timed as the particle files
        grid_files = particle_files(args.directory, "grid.pvd")
        grids = [cell_polygons(min(grid_files, key=lambda f: abs(f[0] - time))[1]) for time, _ in chosen]
        lower = np.minimum(lower, np.min([np.min(np.concatenate(g), axis=0) for g in grids], axis=0) + 0.05)
        upper = np.maximum(upper, np.max([np.max(np.concatenate(g), axis=0) for g in grids], axis=0) - 0.05)
    body_mesh = []
    if args.mesh:
        translation = [float(t) for t in args.mesh_translation.split(",")]
        body_mesh = cell_polygons(args.mesh, args.mesh_scale, translation)

    first = 1 if body_mesh else 0  # a first panel for the mesh file
    figure = plt.figure(figsize=(3.6 * (len(chosen) + first), 6.0))
    grid = figure.add_gridspec(2, len(chosen) + first, height_ratios=[1.2, 1], hspace=0.3)
    if body_mesh:
        # the mesh's cells over the points seeded in them (the first
        # snapshot), the upper right quarter of its bounding box, where
        # cells and points can be told apart
        axes = figure.add_subplot(grid[0, 0])
        axes.add_collection(PolyCollection(body_mesh, facecolors="none", edgecolors="crimson", linewidths=0.6))
        positions = data[0][0]
        axes.scatter(positions[:, 0], positions[:, 1], c="k", s=2, linewidths=0)
        corners = np.concatenate(body_mesh)
        low, high = corners.min(axis=0), corners.max(axis=0)
        middle = (low + high) / 2
        axes.set_xlim(middle[0], high[0] + 0.02 * (high[0] - low[0]))
        axes.set_ylim(middle[1], high[1] + 0.02 * (high[1] - low[1]))
        axes.set_aspect("equal")
        axes.set_title(f"{os.path.basename(args.mesh)} and the points")
        axes.set_xlabel("x [m]")
        axes.set_ylabel("y [m]")
    for column, ((time, _), (positions, speeds, bodies)) in enumerate(zip(chosen, data)):
        axes = figure.add_subplot(grid[0, column + first])
        if grids:
            axes.add_collection(PolyCollection(grids[column], facecolors="none", edgecolors="0.6",
                                               linewidths=0.4))
        size = max(0.6, 2500 / len(speeds))
        if args.color == "speed":
            shown = axes.scatter(positions[:, 0], positions[:, 1], c=speeds, s=size, vmin=0, vmax=top,
                                 cmap="viridis", linewidths=0)
        else:
            axes.scatter(positions[:, 0], positions[:, 1], c=bodies % 20, s=size, vmin=0, vmax=19,
                         cmap="tab20", linewidths=0)
        axes.set_xlim(lower[0] - 0.05, upper[0] + 0.05)
        axes.set_ylim(lower[1] - 0.05, upper[1] + 0.05)
        axes.set_aspect("equal")
        axes.set_title(f"t = {time:.2f} s")
        axes.set_xlabel("x [m]")
        if column + first == 0:
            axes.set_ylabel("y [m]")
    if args.color == "speed":
        figure.colorbar(shown, ax=figure.axes, label="speed [m/s]", shrink=0.8)

    with open(os.path.join(args.directory, "statistics.csv")) as f:
        rows = [{k: float(v) for k, v in r.items() if v != ""} for r in csv.DictReader(f)]
    axes = figure.add_subplot(grid[1, :])
    t = [r["time"] for r in rows]
    for column, label in [("kinetic_energy", "kinetic"), ("strain_energy", "strain"),
                          ("contact_heat", "contact friction heat"), ("wall_heat", "floor friction heat")]:
        if column in rows[0]:
            axes.plot(t, [r[column] for r in rows], label=label)
    axes.set_xlabel("t [s]")
    axes.set_ylabel("energy [J]")
    axes.legend(loc="upper right")
    png = args.png or os.path.join(args.directory, "snapshots.png")
    figure.savefig(png, dpi=args.dpi, bbox_inches="tight", pil_kwargs={"optimize": True})
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
