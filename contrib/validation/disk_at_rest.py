#!/usr/bin/python3
"""A disk at rest on a deformable plane body: how far it creeps, and why.

Disk: R = 0.2 m, K = 1 MPa, G = 0.5 MPa, rho = 1000 kg/m^3, 2x2 points per
cell, 32 cells per metre (12.8 cells per diameter), seeded as the program's
default. Plane: a box of the same material, 0.125 m thick plus the offset
of its face from the grid line, on the grid's fixed floor. Gravity
9.81 m/s^2 straight down, `bardenhagen 2001`, friction mu between the bodies,
settled with `Solver/Settling steps` to 1e-6, then run 0.5 s.

Three experiments, each with the three `Contact/Round body surfaces`
estimates (`contact point`, the default; `located`; `centroid offset`):
  rest   the disk's centre 0.3 cells off a grid line, the face 0, 0.3 and
         0.5 cells off one: the largest |dx| of the disk's centre of mass
         after settling (a disk at rest should stay);
  roll   the centre over a node, then a rolling start of 2 mm/s
         (omega = -v/R): a rigid disk on a plane rolls on at 2 mm/s; the
         table gives v at the end and the growth rate of v while it grows
         (a disk pivoting about a fixed point under its centre, an
         inverted pendulum, diverges at sqrt(2 g / (3 R)));
  spin   the same start, frictionless: the disk should slide at 2 mm/s
         and keep its spin, since normal forces on a circle pass through
         its centre; the table gives omega R at the end.

Usage: contrib/validation/disk_at_rest.py [--sable build/sable] [--work DIR]
           [--set "Section/Entry=value" ...]
Prints a markdown table (and writes it to DIR/disk_at_rest.md)."""
import argparse
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests", "mpm"))
G = 9.81
H = 1 / 32  # cell size, m
R = 0.2
K, SHEAR = 1e6, 0.5e6
MATERIAL = {"Young's modulus": 9 * K * SHEAR / (3 * K + SHEAR),
            "Poisson's ratio": (3 * K - 2 * SHEAR) / (2 * (3 * K + SHEAR)),
            "Density": 1000, "Particles per cell direction": 2}
START_SPEED = 0.002
ESTIMATES = ("contact point", "located", "centroid offset")


def scene(face_offset, centre_x, mu, start, extra):
    top = 0.125 + face_offset * H
    entries = {
        "Dimension": 2, "Gravity": f"0, {-G}", "Time/End time": 0.5,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1.5, 1.25",
        "Grid/Subdivisions": f"{round(1.5 / H)}, {round(1.25 / H)}",
        "Boundary conditions/Types": "2: fixed", "Contact/Model": "bardenhagen 2001",
        "Contact/Friction coefficient": mu, "Solver/Settling steps": 20000,
        "Solver/Settling tolerance": 1e-6, "Output/Statistics interval": 1, **extra,
    }
    disk = dict(MATERIAL, Shape="disk", Center=f"{centre_x}, {top + R}", Radius=R)
    if start:
        disk["Velocity"] = f"{START_SPEED}, 0"
        disk["Angular velocity"] = -START_SPEED / R
    plane = dict(MATERIAL, Shape="box",
                 **{"Lower corner": "0, 0", "Upper corner": f"1.5, {top}"})
    return entries, [plane, disk]


def growth_rate(rows):
    """The least-squares rate of ln |v| over the rows where |v| lies between
    twice and 25 times the start (None if it never doubles)."""
    points = [(r["time"], math.log(abs(r["body1_vx"]))) for r in rows
              if 2 * START_SPEED < abs(r["body1_vx"]) < 25 * START_SPEED]
    if len(points) < 10:
        return None
    n = len(points)
    mean_t = sum(p[0] for p in points) / n
    mean_l = sum(p[1] for p in points) / n
    return (sum((t - mean_t) * (l - mean_l) for t, l in points)
            / sum((t - mean_t) ** 2 for t, _ in points))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "disk_at_rest.work"))
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE")
    args = parser.parse_args()
    os.environ["SABLE"] = os.path.abspath(args.sable)
    os.environ["SABLE_WORK"] = os.path.abspath(args.work)
    import scene_test  # reads SABLE and SABLE_WORK
    extra = dict(entry.split("=", 1) for entry in args.set)
    pendulum = math.sqrt(2 * G / (3 * R))
    lines = [f"R = {R} m, {2 * R / H:.1f} cells per diameter, K = 1 MPa, G = 0.5 MPa"
             + (f", {'; '.join(args.set)}" if args.set else ""), "",
             "| experiment | " + " | ".join(f"`{e}`" for e in ESTIMATES) + " |",
             "|---|" + "---|" * len(ESTIMATES)]
    experiments = [(f"rest, face {offset:g} cells off: largest \\|dx\\| / cell",
                    (offset, 0.5 + 0.3 * H, 0.5, False)) for offset in (0, 0.3, 0.5)]
    experiments += [("roll, centre over a node: v at 0.5 s / start; growth rate, 1/s "
                     f"(inverted pendulum {pendulum:.2f})", (0, 0.5, 0.5, True)),
                    ("spin, frictionless: omega R at 0.5 s / start", (0, 0.5, 0, True))]
    for name, (offset, centre_x, mu, start) in experiments:
        cells = []
        for estimate in ESTIMATES:
            entries, bodies = scene(offset, centre_x, mu, start,
                                    dict({"Contact/Round body surfaces": estimate}, **extra))
            tag = name.split(",")[0] + f"_{offset:g}_" + estimate.split()[0]
            code, output, rows = scene_test.run(tag, entries, bodies, expect_success=False)
            if code != 0 or not rows:
                cells.append("run failed")
                continue
            if not start:
                x0 = rows[0]["body1_x"]
                cells.append(f"{100 * max(abs(r['body1_x'] - x0) for r in rows) / H:.2f}%")
            elif mu > 0:
                rate = growth_rate(rows)
                cells.append(f"{rows[-1]['body1_vx'] / START_SPEED:.2f}"
                             + (f"; {rate:.2f}" if rate is not None else "; does not double"))
            else:
                cells.append(f"{-rows[-1]['body1_omega'] * R / START_SPEED:.2f}")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
        print(lines[-1], flush=True)
    os.makedirs(args.work, exist_ok=True)
    with open(os.path.join(args.work, "disk_at_rest.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
