#!/usr/bin/python3
"""The force network of a QuSGM pack: a segment between the centres of every
two grains in contact, its width and colour the normal force, the grains as
faint dots.

Usage: contrib/gallery/force_network.py STATE_DIR [--png FILE]
STATE_DIR is a state directory a QuSGM run writes (final_state/ or
prepared_state/: grains.csv and contacts.csv); the picture goes to FILE
(default: STATE_DIR/force_network.png). Needs Debian's python3-matplotlib."""
import argparse
import csv
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    import numpy as np
except ImportError as error:
    sys.exit(f"force_network.py: {error.name} is missing; install python3-matplotlib "
             "and run with /usr/bin/python3")


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("state")
    parser.add_argument("--png", default=None)
    args = parser.parse_args()
    for name in ("grains.csv", "contacts.csv"):
        if not os.path.exists(os.path.join(args.state, name)):
            sys.exit(f"force_network.py: {args.state} has no {name}: not a QuSGM state directory "
                     "(final_state/ or prepared_state/ of a run's output)")
    grains = {int(g["id"]): np.array([float(g[c]) for c in "xyz"]) * 1e3 for g in read(os.path.join(args.state, "grains.csv"))}
    contacts = [(int(c["i"]), int(c["j"]), float(c["normal_force"]))
                for c in read(os.path.join(args.state, "contacts.csv"))]
    if not contacts:
        sys.exit(f"force_network.py: {args.state}/contacts.csv holds no contacts")
    forces = np.array([f for _, _, f in contacts])
    segments = [(grains[i], grains[j]) for i, j, _ in contacts]
    largest = forces.max()

    figure = plt.figure(figsize=(7, 6))
    axes = figure.add_subplot(projection="3d")
    centres = np.array(list(grains.values()))
    axes.scatter(centres[:, 0], centres[:, 1], centres[:, 2], s=4, c="0.7", depthshade=False)
    colours = plt.cm.inferno_r(0.15 + 0.85 * forces / largest)
    axes.add_collection3d(Line3DCollection(segments, colors=colours, linewidths=0.3 + 3.5 * forces / largest))
    axes.set_xlabel("x [mm]")
    axes.set_ylabel("y [mm]")
    axes.set_zlabel("z [mm]")
    mappable = plt.cm.ScalarMappable(cmap="inferno_r", norm=plt.Normalize(0, largest))
    figure.colorbar(mappable, ax=axes, shrink=0.7, label="normal force [N]")
    axes.set_title(f"{len(grains)} grains, {len(contacts)} contacts")
    png = args.png or os.path.join(args.state, "force_network.png")
    figure.savefig(png, dpi=110, bbox_inches="tight")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
