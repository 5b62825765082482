#!/usr/bin/python3
"""Snapshots of a 2D MPM run: the material points at chosen times, coloured
by their speed, and the energies of statistics.csv over time.

Usage: contrib/gallery/snapshots.py OUTPUT_DIR [--times 0,0.15,0.3,0.6]
           [--png FILE]
OUTPUT_DIR is a run's output directory (particles.pvd, statistics.csv); the
picture goes to FILE (default: OUTPUT_DIR/snapshots.png). For each time the
particle file written closest to it is shown. Needs Debian's python3-meshio
and python3-matplotlib."""
import argparse
import csv
import os
import sys
import xml.etree.ElementTree as ElementTree

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import meshio
    import numpy as np
except ImportError as error:
    sys.exit(f"snapshots.py: {error.name} is missing; install python3-matplotlib and python3-meshio "
             "and run with /usr/bin/python3")


def particle_files(directory):
    """(time, path) of every particle file the run listed in particles.pvd."""
    root = ElementTree.parse(os.path.join(directory, "particles.pvd")).getroot()
    return [(float(d.get("timestep")), os.path.join(directory, d.get("file"))) for d in root.iter("DataSet")]


def read_points(path):
    """Positions and speeds of the points of one output step (.pvtu or .vtu),
    joining the pieces of every rank."""
    pieces = [path]
    if path.endswith(".pvtu"):
        root = ElementTree.parse(path).getroot()
        pieces = [os.path.join(os.path.dirname(path), p.get("Source")) for p in root.iter("Piece")]
    positions, speeds = [], []
    for piece in pieces:
        mesh = meshio.read(piece)
        if len(mesh.points) == 0:
            continue
        positions.append(mesh.points[:, :2])
        speeds.append(np.linalg.norm(mesh.point_data["velocity"], axis=1))
    return np.concatenate(positions), np.concatenate(speeds)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory")
    parser.add_argument("--times", default="0,0.15,0.3,0.6")
    parser.add_argument("--png", default=None)
    args = parser.parse_args()
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
    top = max(s.max() for _, s in data)
    lower = np.min([p.min(axis=0) for p, _ in data], axis=0)
    upper = np.max([p.max(axis=0) for p, _ in data], axis=0)

    figure = plt.figure(figsize=(3.6 * len(chosen), 6.0))
    grid = figure.add_gridspec(2, len(chosen), height_ratios=[1.2, 1], hspace=0.05)
    for column, ((time, _), (positions, speeds)) in enumerate(zip(chosen, data)):
        axes = figure.add_subplot(grid[0, column])
        shown = axes.scatter(positions[:, 0], positions[:, 1], c=speeds, s=max(0.6, 2500 / len(speeds)), vmin=0, vmax=top,
                             cmap="viridis", linewidths=0)
        axes.set_xlim(lower[0] - 0.05, upper[0] + 0.05)
        axes.set_ylim(lower[1] - 0.05, upper[1] + 0.05)
        axes.set_aspect("equal")
        axes.set_title(f"t = {time:.2f} s")
        axes.set_xlabel("x [m]")
        if column == 0:
            axes.set_ylabel("y [m]")
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
    figure.savefig(png, dpi=110, bbox_inches="tight")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
