#!/usr/bin/python3
"""A block on a deformable plane body under tilted gravity: Coulomb friction
between two bodies, against the rigid block, in 2D and 3D.

Block: 0.2 m square (cube in 3D), E = 10 MPa, nu = 0.3, rho = 1000 kg/m^3,
on a separate plane body of the same material (0.2 m thick in 2D, 0.1 m in
3D, fixed at its bottom), gravity 9.81 m/s^2 tilted by theta, cells of
0.025 m, 2 points per cell direction, `bardenhagen 2001`, default detection.
A rigid block slides with a = g (sin theta - mu cos theta) if tan theta > mu,
else sticks.
- Sliding cases: the acceleration fitted to x(t) over 0.05 s .. T (the block
  starts stress-free: its first bounce is left out), error against rigid.
- Sticking cases (mu >= tan theta): started settled under the tilted gravity
  ('Solver/Settling steps'), the travel over T in cells (target below 1%).
Each case runs with the normal choices given by --normals.

Usage: contrib/validation/body_friction.py [--sable build/sable]
           [--work DIR] [--dim 2|3] [--angles 20,30,40] [--frictions 0.2,0.4,0.6]
           [--normals "flatter body,largest mass"] [--end-time T]
           [--set "Section/Entry=value" ...]
Prints a markdown table (and writes it to DIR/body_friction_<dim>d.md)."""
import argparse
import math
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
G = 9.81
H = 0.025  # cell size, m
MATERIAL = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
            "Particles per cell direction": 2}


# --set: entries given to every run (e.g. "Grid/Shape functions=gimp")
EXTRA_ENTRIES = {}


def scene(dim, theta, mu, normals, end_time, settle):
    """The scene's entries and bodies."""
    t = math.radians(theta)
    gravity = [G * math.sin(t), -G * math.cos(t)] + [0] * (dim - 2)
    if dim == 2:
        size, plane_top, block = (3.0, 0.6), 0.2, ((0.3, 0.2), (0.5, 0.4))
    else:
        size, plane_top, block = (1.5, 0.4, 0.3), 0.1, ((0.2, 0.1, 0.05), (0.4, 0.3, 0.25))
    entries = {
        "Dimension": dim, "Gravity": ", ".join(map(str, gravity)), "Time/End time": end_time,
        "Grid/Lower corner": ", ".join(["0"] * dim), "Grid/Upper corner": ", ".join(map(str, size)),
        "Grid/Subdivisions": ", ".join(str(round(s / H)) for s in size),
        "Boundary conditions/Types": "2: fixed", "Contact/Model": "bardenhagen 2001",
        "Contact/Normals": normals, "Contact/Friction coefficient": mu,
        "Output/Statistics interval": 10, "Solver/Settling steps": 40000 if settle else 0,
        **EXTRA_ENTRIES,
    }
    plane_upper = (size[0], plane_top) + tuple(size[2:])
    bodies = [dict(MATERIAL, Shape="box", **{"Lower corner": ", ".join(["0"] * dim),
                                             "Upper corner": ", ".join(map(str, plane_upper))}),
              dict(MATERIAL, Shape="box", **{"Lower corner": ", ".join(map(str, block[0])),
                                             "Upper corner": ", ".join(map(str, block[1]))})]
    return entries, bodies


def measure(run, dim, theta, mu, normals, end_time):
    """(kind, value, wall time): the acceleration's relative error when the
    rigid block slides, the travel in cells when it sticks."""
    t = math.radians(theta)
    rigid = G * (math.sin(t) - mu * math.cos(t))
    sticks = rigid <= 0
    entries, bodies = scene(dim, theta, mu, normals, end_time, sticks)
    name = f"block{dim}d_{theta:g}_{mu:g}_{normals.replace(' ', '_')}"
    start = time.time()
    _, _, rows = run(name, entries, bodies)
    wall = time.time() - start
    x0 = rows[0]["body1_x"]
    if sticks:
        return "stick", (rows[-1]["body1_x"] - x0) / H, wall
    samples = [(r["time"], r["body1_x"] - x0) for r in rows if r["time"] >= 0.05]
    matrix = np.array([[1, s, s * s / 2] for s, _ in samples])
    a = np.linalg.lstsq(matrix, np.array([x for _, x in samples]), rcond=None)[0][2]
    return "slide", (a - rigid) / rigid, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "body_friction.work"))
    parser.add_argument("--dim", type=int, default=2, choices=(2, 3))
    parser.add_argument("--angles", default="20,30,40")
    parser.add_argument("--frictions", default="0.2,0.4,0.6")
    parser.add_argument("--normals", default="flatter body,largest mass")
    parser.add_argument("--end-time", type=float, default=0.5)
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                        help='an entry for every run, e.g. "Grid/Shape functions=gimp"')
    args = parser.parse_args()
    EXTRA_ENTRIES.update(entry.split("=", 1) for entry in args.set)
    os.environ["SABLE"] = os.path.abspath(args.sable)
    os.environ["SABLE_WORK"] = os.path.abspath(args.work)
    sys.path.insert(0, os.path.join(ROOT, "tests", "mpm"))
    from scene_test import run  # noqa: E402 (reads SABLE and SABLE_WORK)

    normals = args.normals.split(",")
    lines = [f"| θ, μ | rigid | " + " | ".join(normals) + " |", "|---" * (len(normals) + 2) + "|"]
    for theta in map(float, args.angles.split(",")):
        for mu in map(float, args.frictions.split(",")):
            t = math.radians(theta)
            rigid = G * (math.sin(t) - mu * math.cos(t))
            cells = [f"{theta:g}°, {mu:g}", f"a = {rigid:.3f} m/s²" if rigid > 0 else "sticks"]
            for n in normals:
                kind, value, wall = measure(run, args.dim, theta, mu, n, args.end_time)
                cells.append(f"{value:+.2%}" if kind == "slide" else f"travel {value:.1e} cells")
                print(f"{args.dim}D theta {theta:g} mu {mu:g} {n}: {cells[-1]} ({wall:.0f} s)", flush=True)
            lines.append("| " + " | ".join(cells) + " |")
    table = "\n".join(lines) + "\n"
    path = os.path.join(args.work, f"body_friction_{args.dim}d.md")
    with open(path, "w") as f:
        f.write(table)
    print(table + f"(written to {path})")


if __name__ == "__main__":
    main()
