#!/usr/bin/python3
"""Photoelastic fringe pictures of the A4 scenes (paper 002, Figs. 9-11).

Reads the particle output of a run of prm/a4_collinear.prm, a4_zigzag.prm or
a4_glued.prm (with 'Output/Smoothed stress output = true', as the scenes
set it), takes at each of the paper's frame times t c_L/D the output step
closest to it, rasters the smoothed in-plane principal stress difference
sigma_1 - sigma_2 (field smoothed_stress_difference) on pixels of one cell
(the scenes have one point per cell), and renders cos((sigma_1 - sigma_2)/f)
in grey, as the paper did: dark fringes where the difference is an odd
multiple of pi f. f is fixed once, on case (a), and used for every case
(--f to change it; --calibrate prints the value the rule below gives on a
run of case (a)):
    f = P99 / (3 * 2 pi),
P99 the 99th percentile of sigma_1 - sigma_2 over the points at the middle
frame of case (a) (t c_L/D = 5.5): about three fringe orders in the most
loaded disks. The default, 14.6 MPa, is this rule on case (a) at 80 cells
per diameter, the paper's resolution (at 40 cells it gives 12.3 MPa: the
contact stresses are sharper on the finer grid). The pin and the ceiling (bodies after the disks, rigid) are
drawn in blue.

Writes one PNG per case with the three frames stacked.

Usage: contrib/validation/a4_fringes.py OUTPUT_DIR --case collinear|zigzag|glued
           [--png FILE] [--f PASCAL] [--calibrate]
Needs python3-matplotlib and python3-meshio (Debian)."""
import argparse
import math
import os
import sys
from xml.etree import ElementTree

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import meshio
    import numpy as np
except ImportError as error:
    sys.exit(f"a4_fringes.py: {error.name} is missing; install python3-matplotlib and python3-meshio "
             "(Debian packages)")

D = 0.01
C_L = math.sqrt((102e9 + 4.0 / 3.0 * 72e9) / 1900.0)
T_UNIT = D / C_L
FRAMES = {"collinear": (2.2, 5.5, 7.7), "zigzag": (3.0, 6.0, 9.0), "glued": (1.4, 3.6, 5.8)}
LABELS = {"collinear": "(a) four collinear disks", "zigzag": "(b) zig-zag disks, $\\mu$ = 0.5",
          "glued": "(c) zig-zag disks, glued"}
DEFAULT_F = 1.458e7
DISKS = {"collinear": 4, "zigzag": 5, "glued": 5}


def output_steps(directory):
    root = ElementTree.parse(os.path.join(directory, "particles.pvd")).getroot()
    return [(float(d.get("timestep")), os.path.join(directory, d.get("file"))) for d in root.iter("DataSet")]


def read_frame(path):
    """Positions, cell size, sigma_1 - sigma_2 and body of the points of one
    output step, all ranks' pieces joined."""
    pieces = [path]
    if path.endswith(".pvtu"):
        root = ElementTree.parse(path).getroot()
        pieces = [os.path.join(os.path.dirname(path), p.get("Source")) for p in root.iter("Piece")]
    positions, difference, volume, body = [], [], [], []
    for piece in pieces:
        mesh = meshio.read(piece)
        if len(mesh.points) == 0:
            continue
        if "smoothed_stress_difference" not in mesh.point_data:
            sys.exit(f"a4_fringes.py: {piece} has no smoothed_stress_difference "
                     "(run with 'Output/Smoothed stress output = true')")
        positions.append(mesh.points[:, :2])
        difference.append(mesh.point_data["smoothed_stress_difference"].ravel())
        volume.append(mesh.point_data["initial_volume"].ravel())
        body.append(mesh.point_data["body"].ravel())
    return (np.concatenate(positions), np.concatenate(difference), np.concatenate(volume),
            np.concatenate(body))


def closest_step(steps, t):
    return min(steps, key=lambda step: abs(step[0] / T_UNIT - t))


def raster(positions, values, pixel):
    """Values on a pixel raster (NaN where no point falls)."""
    lower = positions.min(axis=0)
    index = np.floor((positions - lower) / pixel + 0.5).astype(int)
    image = np.full((index[:, 1].max() + 1, index[:, 0].max() + 1), np.nan)
    image[index[:, 1], index[:, 0]] = values
    return image, lower


def render(directory, case, f, png):
    steps = output_steps(directory)
    fig, axes = plt.subplots(len(FRAMES[case]), 1, figsize=(7, 2.2 * len(FRAMES[case]) + 0.4))
    for axis, t in zip(axes, FRAMES[case]):
        time, path = closest_step(steps, t)
        positions, difference, volume, body = read_frame(path)
        pixel = math.sqrt(np.median(volume))  # one point per cell
        fringes = np.where(body < DISKS[case], np.cos(difference / f), np.nan)
        image, lower = raster(positions, fringes, pixel)
        rigid, _ = raster(positions, np.where(body < DISKS[case], np.nan, 1.0), pixel)
        extent = [lower[0] / D - 0.5 * pixel / D, lower[0] / D + (image.shape[1] - 0.5) * pixel / D,
                  lower[1] / D - 0.5 * pixel / D, lower[1] / D + (image.shape[0] - 0.5) * pixel / D]
        axis.imshow(image, origin="lower", extent=extent, cmap="gray", vmin=-1, vmax=1,
                    interpolation="nearest")
        axis.imshow(rigid, origin="lower", extent=extent, cmap="Blues", vmin=0, vmax=2,
                    interpolation="nearest")
        axis.set_title(f"t c$_L$/D = {time / T_UNIT:.2f} (paper's frame {t})", fontsize=9)
        axis.set_xlabel("x / D", fontsize=8)
        axis.set_ylabel("y / D", fontsize=8)
        axis.tick_params(labelsize=7)
    fig.suptitle(f"{LABELS[case]}: cos(($\\sigma_1-\\sigma_2$)/f), f = {f / 1e6:.3g} MPa", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def calibrate(directory):
    """f by the rule of the module doc on a run of case (a)."""
    time, path = closest_step(output_steps(directory), 5.5)
    _, difference, _, body = read_frame(path)
    return np.percentile(difference, 99) / (3 * 2 * math.pi)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory")
    parser.add_argument("--case", required=True, choices=list(FRAMES))
    parser.add_argument("--png", default=None)
    parser.add_argument("--f", type=float, default=DEFAULT_F)
    parser.add_argument("--calibrate", action="store_true")
    args = parser.parse_args()
    if not os.path.exists(os.path.join(args.directory, "particles.pvd")):
        sys.exit(f"a4_fringes.py: {args.directory} has no particles.pvd: not the output directory of "
                 "an A4 run with particle output")
    if not args.f > 0:
        sys.exit(f"a4_fringes.py: --f = {args.f}; allowed: a stress > 0 (Pa)")
    if args.calibrate:
        if args.case != "collinear":
            sys.exit("a4_fringes.py: --calibrate fixes f on case (a): use --case collinear")
        print(f"f = {calibrate(args.directory):.4g} Pa")
        return
    render(args.directory, args.case, args.f,
           args.png or os.path.join(args.directory, f"a4_{args.case}_fringes.png"))


if __name__ == "__main__":
    main()
