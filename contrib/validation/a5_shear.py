#!/usr/bin/python3
"""Scene A5 (paper 000, Figs. 5-8): what a shear run of a grain pack gives.

Usage: contrib/validation/a5_shear.py RUN_OUTPUT [--work DIR] [--width W]
           [--period P] [--wall-velocity V] [--mean-diameter D]
           [--levels 0.25 0.5 0.75] [--bins N]

RUN_OUTPUT is the output directory of a run of prm/granular_shear.prm or
prm/granular_shear_small.prm (particles.pvd and statistics.csv). Writes into
DIR (default a5_shear.work):
- profiles.csv, profiles.png: the vertical displacement of the material,
  averaged over columns of the box (bins in x, the points' current x), at
  the shear levels nearest to --levels (shear = wall travel / box width),
  as the paper's Fig. 8; displacements follow each point through the
  periodic seam (the outputs are unwrapped step by step, so the outputs
  must be less than half a period of travel apart);
- the shear band width at each level: the x-extent over which the profile,
  as a fraction of the wall's displacement, goes from 0.1 to 0.9 (where the
  shear is taken up; the rest of the pack moves with one wall or the
  other), in mean grain diameters (--mean-diameter, default the paper's
  57 um; the packs in prm/ have 55.0 um and 54.6 um) and as a fraction of
  the box width;
- stress_difference_<shear>.png: the principal stress difference
  sigma_1 - sigma_2 of every point (the force chains), at each level;
- with --compare OTHER_OUTPUT (e.g. a sticking run): side_by_side.png,
  the equivalent plastic strain of both runs' points at the last level
  (the paper's Fig. 6), each run's plastic work in its title; the printed
  numbers are RUN_OUTPUT's only (run the script on OTHER_OUTPUT for its
  band widths and energies);
- energy.png, energy.csv: plastic work and contact friction heat against
  the shear, and the moving wall's force along its motion, F = (dW/dt) / V
  from the boundary work W (the fixed wall does no work), in N per metre of
  depth.
The numbers are printed. Needs Debian's python3-matplotlib, numpy, meshio."""
import argparse
import csv
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
    sys.exit(f"a5_shear.py: {error.name} is missing; install python3-matplotlib python3-meshio "
             "and run with /usr/bin/python3")


def outputs(directory):
    """(time, fields) of every particle output, points sorted by id."""
    pvd = os.path.join(directory, "particles.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"a5_shear.py: {directory} has no particles.pvd (the run wrote no particle output)")
    for dataset in ElementTree.parse(pvd).getroot().iter("DataSet"):
        pvtu = os.path.join(directory, dataset.get("file"))
        pieces = [os.path.join(os.path.dirname(pvtu), p.get("Source"))
                  for p in ElementTree.parse(pvtu).getroot().iter("Piece")]
        meshes = [m for m in (meshio.read(p) for p in pieces) if len(m.points)]
        names = ["id", "body", "stress"] + (["equivalent_plastic_strain"]
                                            if "equivalent_plastic_strain" in meshes[0].point_data else [])
        fields = {name: np.concatenate([m.point_data[name] for m in meshes]) for name in names}
        fields["x"] = np.concatenate([m.points[:, :2] for m in meshes]).astype(float)
        order = np.argsort(fields["id"].ravel())
        yield float(dataset.get("timestep")), {k: v[order] for k, v in fields.items()}


def read_statistics(directory):
    with open(os.path.join(directory, "statistics.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def band_width(centres, profile):
    """x-extent between the first crossings of 0.1 and 0.9 (profile as a
    fraction of the wall displacement, increasing towards the moving
    wall), by linear interpolation."""
    def crossing(level):
        above = np.nonzero(profile >= level)[0]
        if len(above) == 0:
            return np.nan
        i = above[0]
        if i == 0:
            return centres[0]
        x0, x1, f0, f1 = centres[i - 1], centres[i], profile[i - 1], profile[i]
        return x0 + (level - f0) / (f1 - f0) * (x1 - x0)
    return crossing(0.9) - crossing(0.1)


def side_by_side(args):
    """The equivalent plastic strain of two runs at the last level."""
    level = args.levels[-1]
    panels = []
    for directory, label in zip((args.output, args.compare), args.labels):
        snapshots = list(outputs(directory))
        times = np.array([t for t, _ in snapshots])
        k = int(np.argmin(np.abs(args.wall_velocity * times / args.width - level)))
        fields = snapshots[k][1]
        if "equivalent_plastic_strain" not in fields:
            sys.exit(f"a5_shear.py: {directory} has no equivalent_plastic_strain (not von Mises grains)")
        stats = read_statistics(directory)
        panels.append((label, times[k], fields["x"], fields["equivalent_plastic_strain"].ravel(),
                       np.interp(times[k], stats["time"], stats["plastic_work"])))
    top = max(max(np.percentile(p[3], 99.5) for p in panels), 1e-3)
    figure, axes = plt.subplots(1, 2, figsize=(10, 4.8), sharey=True, constrained_layout=True)
    for ax, (label, t, x, strain, plastic) in zip(axes, panels):
        height = args.period if args.period > 0 else np.ptp(x[:, 1])
        size = (72 * 4.0 * np.sqrt(0.7 * args.width * height / len(x)) / args.width) ** 2
        order = np.argsort(strain)
        scatter = ax.scatter(x[order, 0] * 1e3, x[order, 1] * 1e3, c=strain[order], s=size, marker="s",
                             cmap="viridis", vmin=0, vmax=top, linewidths=0)
        ax.set_aspect("equal")
        ax.set_xlim(0, args.width * 1e3)
        if args.period > 0:
            ax.set_ylim(0, args.period * 1e3)
        ax.set_xlabel("x [mm]")
        ax.set_title(f"{label}: {args.wall_velocity * t / args.width:.0%} shear, plastic work {plastic:.3g} J/m",
                     fontsize=10)
    axes[0].set_ylabel("y [mm]")
    figure.colorbar(scatter, ax=axes, label="equivalent plastic strain", shrink=0.85)
    figure.savefig(os.path.join(args.work, "side_by_side.png"), dpi=120)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output")
    parser.add_argument("--work", default="a5_shear.work")
    parser.add_argument("--width", type=float, default=1.2e-3, help="box width (x), m")
    parser.add_argument("--period", type=float, default=1.2e-3, help="period along y, m (0: not periodic)")
    parser.add_argument("--wall-velocity", type=float, default=100.0, help="moving wall's speed, m/s")
    parser.add_argument("--mean-diameter", type=float, default=57e-6,
                        help="mean grain diameter, m (the paper's; the packs in prm/: 55.0e-6 and 54.6e-6)")
    parser.add_argument("--levels", type=float, nargs="+", default=[0.25, 0.5, 0.75])
    parser.add_argument("--bins", type=int, default=30, help="columns across the box")
    parser.add_argument("--compare", default=None, help="output directory of a second run (e.g. sticking)")
    parser.add_argument("--labels", nargs=2, default=["mu = 0.3", "sticking"], help="the two runs' names")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.compare:
        side_by_side(args)

    # displacements, unwrapped output by output
    times, displacement, snapshots = [], [], []
    previous = None
    for t, fields in outputs(args.output):
        if previous is None:
            total = np.zeros_like(fields["x"])
        else:
            if len(fields["x"]) != len(previous["x"]):
                sys.exit("a5_shear.py: the number of points changed between outputs")
            step = fields["x"] - previous["x"]
            if args.period > 0:
                step[:, 1] -= args.period * np.round(step[:, 1] / args.period)
            total = total + step
        times.append(t)
        displacement.append(total.copy())
        snapshots.append(fields)
        previous = fields
    times = np.array(times)
    shear = args.wall_velocity * times / args.width

    edges = np.linspace(0, args.width, args.bins + 1)
    centres = 0.5 * (edges[1:] + edges[:-1])
    rows = []
    figure, axes = plt.subplots(figsize=(6, 4.5))
    print(f"{'shear':>6} {'time [us]':>9} {'band [um]':>9} {'band / D':>8} {'band / W':>8}")
    for level in args.levels:
        k = int(np.argmin(np.abs(shear - level)))
        x = snapshots[k]["x"][:, 0]
        v = displacement[k][:, 1]
        wall = args.wall_velocity * times[k]
        index = np.clip(np.digitize(x, edges) - 1, 0, args.bins - 1)
        profile = np.array([v[index == i].mean() if np.any(index == i) else np.nan for i in range(args.bins)])
        width = band_width(centres, profile / wall)
        print(f"{shear[k]:6.2f} {times[k] * 1e6:9.3f} {width * 1e6:9.1f} {width / args.mean_diameter:8.2f} "
              f"{width / args.width:8.3f}")
        for c, p in zip(centres, profile):
            rows.append((shear[k], c, p, p / wall))
        axes.plot(profile / wall, centres / args.width, marker="o", ms=3,
                  label=f"{shear[k]:.0%} shear: band {width / args.mean_diameter:.1f} D")
    axes.set_xlabel("vertical displacement / wall displacement")
    axes.set_ylabel("x / box width")
    axes.set_title("column-averaged vertical displacement")
    axes.legend()
    figure.tight_layout()
    figure.savefig(os.path.join(args.work, "profiles.png"), dpi=130)
    plt.close(figure)
    with open(os.path.join(args.work, "profiles.csv"), "w") as f:
        f.write("shear,x,vertical_displacement,fraction_of_wall\n")
        for r in rows:
            f.write(",".join(f"{v:.6g}" for v in r) + "\n")

    # force chains
    for level in args.levels:
        k = int(np.argmin(np.abs(shear - level)))
        s = snapshots[k]["stress"].reshape(-1, 3, 3)
        difference = 2 * np.sqrt(0.25 * (s[:, 0, 0] - s[:, 1, 1]) ** 2 + s[:, 0, 1] ** 2)
        x = snapshots[k]["x"]
        figure, axes = plt.subplots(figsize=(6.2, 5.4))
        top = np.percentile(difference, 99)
        # markers about as wide as the point spacing (the pack fills ~70%)
        height = args.period if args.period > 0 else np.ptp(x[:, 1])
        spacing = np.sqrt(0.7 * args.width * height / len(x))
        size = (72 * 4.6 * spacing / args.width) ** 2
        order = np.argsort(difference)  # the chains drawn last, on top
        scatter = axes.scatter(x[order, 0] * 1e3, x[order, 1] * 1e3, c=difference[order] / 1e9, s=size,
                               marker="s", cmap="magma_r", vmin=0, vmax=top / 1e9, linewidths=0)
        axes.set_aspect("equal")
        axes.set_xlim(0, args.width * 1e3)
        if args.period > 0:
            axes.set_ylim(0, args.period * 1e3)
        axes.set_xlabel("x [mm]")
        axes.set_ylabel("y [mm]")
        axes.set_title(f"principal stress difference at {shear[k]:.0%} shear")
        figure.colorbar(scatter, ax=axes, label="sigma_1 - sigma_2 [GPa]")
        figure.tight_layout()
        figure.savefig(os.path.join(args.work, f"stress_difference_{round(100 * shear[k]):02d}.png"), dpi=130)
        plt.close(figure)

    # energies and the wall force
    stats = read_statistics(args.output)
    t = stats["time"]
    stat_shear = args.wall_velocity * t / args.width
    power = np.gradient(stats["boundary_work"], t) if len(t) > 2 else np.zeros_like(t)
    force = power / args.wall_velocity
    with open(os.path.join(args.work, "energy.csv"), "w") as f:
        f.write("time,shear,plastic_work,contact_heat,boundary_work,wall_force\n")
        for i in range(len(t)):
            f.write(f"{t[i]:.6g},{stat_shear[i]:.6g},{stats['plastic_work'][i]:.6g},"
                    f"{stats['contact_heat'][i]:.6g},{stats['boundary_work'][i]:.6g},{force[i]:.6g}\n")
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    top.plot(stat_shear, stats["plastic_work"], label="plastic work")
    top.plot(stat_shear, stats["contact_heat"], label="contact friction heat")
    top.plot(stat_shear, stats["boundary_work"], label="work of the walls", ls="--")
    top.set_ylabel("J per m of depth")
    top.legend()
    bottom.plot(stat_shear, force / 1e3)
    bottom.set_ylabel("moving wall's force [kN/m]")
    bottom.set_xlabel("average shear (wall travel / width)")
    figure.tight_layout()
    figure.savefig(os.path.join(args.work, "energy.png"), dpi=130)
    plt.close(figure)
    last = -1
    print(f"at {stat_shear[last]:.0%} shear: plastic work {stats['plastic_work'][last]:.4g} J/m, contact friction heat "
          f"{stats['contact_heat'][last]:.4g} J/m, work of the walls {stats['boundary_work'][last]:.4g} J/m, "
          f"mean wall force {stats['boundary_work'][last] / (args.wall_velocity * t[last]) / 1e3:.4g} kN/m")
    print(f"written to {args.work}")


if __name__ == "__main__":
    main()
