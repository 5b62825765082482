#!/usr/bin/python3
"""Dense random pack of non-overlapping disks (--dim 2) or spheres (--dim 3)
in a box, written as CSV for 'Bodies file/File' (doc/mpm.md, "Many bodies
from a file"): a header 'x,y,radius' ('x,y,z,radius'), then one grain per
row, lengths in the units of the arguments (m for sable).

Diameters: a log-normal distribution truncated to [--min-diameter,
--max-diameter] whose log has the standard deviation --sigma and whose
(truncated, by number) mean is --mean-diameter; the log-mean is solved for.
Defaults are scene A5's (SPEC.md; paper 000): 31-250 um, mean 57 um.

Algorithm: draw diameters until the grains' area (volume) reaches
--fraction of the box; place them from large to small by random sequential
addition (--trials random positions each; a grain that finds no free spot
goes where it overlaps least); then relaxation sweeps push every
overlapping pair apart along the line of centres (each grain by its share,
smaller grains moving more) and back inside the box, until no pair is
closer than the gap. Grains still overlapping after --sweeps sweeps are
dropped (smallest first) and counted. The achieved fraction is printed and
written as a comment line.

Gap: surfaces of two grains at least --gap times the smaller radius apart
(and a grain at least --gap times its radius from a wall), so that no two
grains touch at t = 0 (--gap 0: they may).

--cross x (y, z): grains may cross the box's faces normal to these axes
(their centres stay inside): the grains a wall holds in scene A5. The area
(volume) fraction counts only the parts inside the box.
--periodic y: the pack is periodic along these axes (gaps measured across
the seam, centres wrapped into the box).

Reproducible: the same arguments and --seed give the same file.
Only numpy is needed.
"""
import argparse
import math
import sys

import numpy as np


def truncated_lognormal_mean(mu, sigma, low, high):
    """Number mean of exp(N(mu, sigma^2)) restricted to [low, high]."""
    phi = lambda z: 0.5 * (1 + math.erf(z / math.sqrt(2)))
    a = (math.log(low) - mu) / sigma
    b = (math.log(high) - mu) / sigma
    mass = phi(b) - phi(a)
    return math.exp(mu + sigma**2 / 2) * (phi(b - sigma) - phi(a - sigma)) / mass


def log_mean_for(mean, sigma, low, high):
    """mu with truncated_lognormal_mean(mu) = mean (increasing in mu)."""
    lo, hi = math.log(low) - 10 * sigma, math.log(high) + 10 * sigma
    if not low < mean < high:
        raise SystemExit(f"--mean-diameter {mean} must lie in ({low}, {high})")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if truncated_lognormal_mean(mid, sigma, low, high) < mean:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def ball_measure(radius, dim):
    return math.pi * radius**2 if dim == 2 else 4 / 3 * math.pi * radius**3


def cap_measure(radius, depth, dim):
    """Area (volume) of the part of a disk (ball) beyond a plane at distance
    radius - depth from its centre, 0 <= depth <= 2 radius."""
    if depth <= 0:
        return 0.0
    depth = min(depth, 2 * radius)
    if dim == 2:
        d = radius - depth
        return radius**2 * math.acos(d / radius) - d * math.sqrt(max(radius**2 - d * d, 0.0))
    return math.pi * depth**2 * (3 * radius - depth) / 3


def draw_diameters(rng, args, box_measure, dim):
    mu = log_mean_for(args.mean_diameter, args.sigma, args.min_diameter, args.max_diameter)
    diameters, total = [], 0.0
    while total < args.fraction * box_measure:
        d = math.exp(rng.normal(mu, args.sigma))
        if args.min_diameter <= d <= args.max_diameter:
            diameters.append(d)
            total += ball_measure(d / 2, dim)
    return mu, np.sort(np.array(diameters))[::-1]


class Pack:
    def __init__(self, args, dim):
        self.dim = dim
        self.lower = np.array(args.lower if args.lower else [0.0] * dim, dtype=float)
        self.size = np.array(args.box, dtype=float)
        self.gap = args.gap
        axes = "xyz"
        self.periodic = np.array([axes[d] in args.periodic for d in range(dim)])
        self.cross = np.array([axes[d] in args.cross for d in range(dim)])

    def separation(self, x, centres):
        """Vectors from centres to x, shortest across periodic axes."""
        delta = x - centres
        for d in range(self.dim):
            if self.periodic[d]:
                delta[:, d] -= self.size[d] * np.round(delta[:, d] / self.size[d])
        return delta

    def required(self, r, radii):
        """Smallest allowed centre distance of a grain of radius r to others."""
        return r + radii + self.gap * np.minimum(r, radii)

    def confine(self, x, r):
        """x moved inside the box (walls keep a gap; crossing axes only
        keep the centre inside; periodic axes wrap)."""
        for d in range(self.dim):
            low, high = self.lower[d], self.lower[d] + self.size[d]
            if self.periodic[d]:
                x[d] = low + (x[d] - low) % self.size[d]
            elif self.cross[d]:
                x[d] = min(max(x[d], low), high)
            else:
                margin = r * (1 + self.gap)
                x[d] = min(max(x[d], low + margin), high - margin)
        return x

    def random_position(self, rng, r):
        x = self.lower + rng.random(self.dim) * self.size
        return self.confine(x, r)


def place(pack, rng, radii, trials):
    dim = pack.dim
    centres = np.zeros((len(radii), dim))
    for i, r in enumerate(radii):
        best, best_overlap = None, math.inf
        for _ in range(trials):
            x = pack.random_position(rng, r)
            if i == 0:
                best, best_overlap = x, 0.0
                break
            distance = np.linalg.norm(pack.separation(x, centres[:i]), axis=1)
            overlap = np.max(pack.required(r, radii[:i]) - distance)
            if overlap < best_overlap:
                best, best_overlap = x, overlap
            if overlap <= 0:
                break
        centres[i] = best
    return centres


def overlapping_pairs(pack, centres, radii):
    """(i, j, separation vector from j to i, distance, required) of the
    pairs closer than allowed."""
    pairs = []
    for i in range(len(radii)):
        delta = pack.separation(centres[i], centres[i + 1:])
        distance = np.linalg.norm(delta, axis=1)
        need = pack.required(radii[i], radii[i + 1:])
        for k in np.nonzero(distance < need * (1 - 1e-12))[0]:
            pairs.append((i, i + 1 + k, delta[k], distance[k], need[k]))
    return pairs


def relax(pack, rng, centres, radii, sweeps):
    for sweep in range(sweeps):
        pairs = overlapping_pairs(pack, centres, radii)
        if not pairs:
            return sweep
        for i, j, delta, distance, need in pairs:
            if distance < 1e-14 * need:
                delta = rng.normal(size=pack.dim)
                distance = np.linalg.norm(delta)
            push = (need - distance) * 1.01 * delta / distance
            # the smaller grain moves more (shares by the other's measure)
            wi = radii[j] ** pack.dim / (radii[i] ** pack.dim + radii[j] ** pack.dim)
            centres[i] = pack.confine(centres[i] + wi * push, radii[i])
            centres[j] = pack.confine(centres[j] - (1 - wi) * push, radii[j])
    return sweeps


def measure_inside(pack, centres, radii):
    """Area (volume) of the grains inside the box: all of it except the
    caps beyond the faces of crossing axes."""
    total = 0.0
    for x, r in zip(centres, radii):
        inside = ball_measure(r, pack.dim)
        for d in range(pack.dim):
            if pack.cross[d]:
                low, high = pack.lower[d], pack.lower[d] + pack.size[d]
                inside -= cap_measure(r, low - (x[d] - r), pack.dim)
                inside -= cap_measure(r, (x[d] + r) - high, pack.dim)
        total += inside
    return total


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="CSV file to write")
    parser.add_argument("--dim", type=int, choices=(2, 3), default=2)
    parser.add_argument("--box", type=float, nargs="+", required=True,
                        help="box edge lengths (dim numbers)")
    parser.add_argument("--lower", type=float, nargs="+", help="box lower corner (default 0)")
    parser.add_argument("--fraction", type=float, default=0.7,
                        help="target area (volume) fraction, in (0, 0.9)")
    parser.add_argument("--min-diameter", type=float, default=31e-6)
    parser.add_argument("--max-diameter", type=float, default=250e-6)
    parser.add_argument("--mean-diameter", type=float, default=57e-6)
    parser.add_argument("--sigma", type=float, default=0.5,
                        help="standard deviation of the log of the diameter (> 0)")
    parser.add_argument("--gap", type=float, default=0.01,
                        help="least surface gap over the smaller radius, >= 0")
    parser.add_argument("--cross", default="", help="axes whose faces grains may cross, e.g. x")
    parser.add_argument("--periodic", default="", help="periodic axes, e.g. y")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--trials", type=int, default=2000,
                        help="random positions tried per grain")
    parser.add_argument("--sweeps", type=int, default=200, help="relaxation sweeps at most")
    args = parser.parse_args(argv)

    dim = args.dim
    if len(args.box) != dim or min(args.box) <= 0:
        parser.error(f"--box needs {dim} positive lengths, got {args.box}")
    if args.lower is not None and len(args.lower) != dim:
        parser.error(f"--lower needs {dim} numbers, got {args.lower}")
    if not 0 < args.fraction < 0.9:
        parser.error(f"--fraction {args.fraction} must lie in (0, 0.9)")
    if not 0 < args.min_diameter < args.max_diameter:
        parser.error("need 0 < --min-diameter < --max-diameter")
    if args.sigma <= 0 or args.gap < 0:
        parser.error("need --sigma > 0 and --gap >= 0")
    for name, axes in (("--cross", args.cross), ("--periodic", args.periodic)):
        if any(a not in "xyz"[:dim] for a in axes):
            parser.error(f"{name} {axes}: axes among {'xyz'[:dim]}")
    if set(args.cross) & set(args.periodic):
        parser.error("an axis cannot be both --cross and --periodic")
    if max(args.box) < args.min_diameter:
        parser.error("the box is smaller than the smallest grain")

    rng = np.random.default_rng(args.seed)
    pack = Pack(args, dim)
    box_measure = float(np.prod(pack.size))
    mu, diameters = draw_diameters(rng, args, box_measure, dim)
    too_large = diameters > (1 - 1e-9) * np.min(pack.size)
    if np.any(too_large):
        diameters = diameters[~too_large]
        print(f"dropped {np.count_nonzero(too_large)} grains larger than the box", file=sys.stderr)
    radii = diameters / 2
    centres = place(pack, rng, radii, args.trials)
    sweeps = relax(pack, rng, centres, radii, args.sweeps)

    # grains still too close: drop the smaller of each pair until none is
    dropped = 0
    while True:
        pairs = overlapping_pairs(pack, centres, radii)
        if not pairs:
            break
        i, j = pairs[0][0], pairs[0][1]
        k = i if radii[i] < radii[j] else j
        centres = np.delete(centres, k, axis=0)
        radii = np.delete(radii, k)
        dropped += 1

    fraction = measure_inside(pack, centres, radii) / box_measure
    mean = float(np.mean(2 * radii))
    summary = (f"{len(radii)} grains, area fraction {fraction:.4f} (target {args.fraction}), "
               f"mean diameter {mean:.6g} (distribution {args.mean_diameter:.6g}), "
               f"diameters {2 * radii.min():.6g}-{2 * radii.max():.6g}, "
               f"{sweeps} relaxation sweeps, {dropped} dropped")
    if dim == 3:
        summary = summary.replace("area fraction", "volume fraction")
    axes = "xyz"[:dim]
    with open(args.output, "w") as f:
        f.write(f"# disk_pack.py --dim {dim} --box {' '.join(map(repr, args.box))}"
                f" --fraction {args.fraction} --seed {args.seed}\n")
        f.write(f"# diameters: log-normal, sigma {args.sigma}, log-mean {mu:.6g},"
                f" truncated to [{args.min_diameter:.6g}, {args.max_diameter:.6g}], mean"
                f" {args.mean_diameter:.6g}; gap {args.gap}; cross '{args.cross}';"
                f" periodic '{args.periodic}'\n")
        f.write(f"# {summary}\n")
        f.write(",".join(axes) + ",radius\n")
        for x, r in zip(centres, radii):
            f.write(",".join(f"{v:.10g}" for v in x) + f",{r:.10g}\n")
    print(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
