#!/usr/bin/python3
"""A disk rolling down a deformable plane body whose face lies a fraction of a
cell off the grid lines: contact between bodies at every registration.

Disk: R = 0.2 m, E = 10 MPa, nu = 0.3, rho = 1000 kg/m^3, 16 cells per
diameter (cells of 0.025 m), 2 points per cell direction, seeded as
--seeding says (default: the program's default). Plane: a box of the same
material, 0.1 m thick plus the offset, on the grid's fixed floor; both with
lithostatic initial stress. Gravity 9.81 m/s^2 tilted by theta, friction mu
between the bodies, `bardenhagen 2001`, the disk set down touching the plane.
The rigid disk rolls without slipping (mu >= tan(theta) / 3) and travels
x = g sin(theta) t^2 / 3; the table gives the travel at the end against it
and the largest rise of the centre off its start.

Usage: contrib/validation/plane_rolling.py [--sable build/sable]
           [--work DIR] [--offsets 0,0.25,0.33,0.5,0.67] [--angle 30]
           [--friction 0.5] [--radius 0.2] [--seeding clipped]
           [--end-time 0.5] [--set "Section/Entry=value" ...]
Prints a markdown table (and writes it to DIR/plane_rolling.md)."""
import argparse
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests", "mpm"))
G = 9.81
H = 0.025  # cell size, m
MATERIAL = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
            "Particles per cell direction": 2, "Lithostatic initial stress": "true"}


def scene(offset, theta, mu, radius, seeding, end_time, extra):
    t = math.radians(theta)
    top = 0.1 + offset * H
    entries = {
        "Dimension": 2, "Gravity": f"{G * math.sin(t)}, {-G * math.cos(t)}",
        "Time/End time": end_time,
        "Grid/Lower corner": "0, 0", "Grid/Upper corner": "3, 0.8",
        "Grid/Subdivisions": f"{round(3 / H)}, {round(0.8 / H)}",
        "Boundary conditions/Types": "2: fixed", "Contact/Model": "bardenhagen 2001",
        "Contact/Friction coefficient": mu, "Output/Statistics interval": 10, **extra,
    }
    disk = dict(MATERIAL, Shape="disk", Center=f"0.3, {top + radius}", Radius=radius)
    if seeding:
        disk["Seeding"] = seeding
    plane = dict(MATERIAL, Shape="box", **{"Lower corner": "0, 0", "Upper corner": f"3, {top}"})
    return entries, [plane, disk]


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "plane_rolling.work"))
    parser.add_argument("--offsets", default="0,0.25,0.33,0.5,0.67")
    parser.add_argument("--angle", type=float, default=30)
    parser.add_argument("--friction", type=float, default=0.5)
    parser.add_argument("--radius", type=float, default=0.2)
    parser.add_argument("--seeding", default="")
    parser.add_argument("--end-time", type=float, default=0.5)
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE")
    args = parser.parse_args()
    if math.tan(math.radians(args.angle)) / 3 > args.friction:
        sys.exit(f"plane_rolling.py: mu = {args.friction} < tan(theta)/3: the rigid disk slips")
    os.environ["SABLE"] = os.path.abspath(args.sable)
    os.environ["SABLE_WORK"] = os.path.abspath(args.work)
    import scene_test  # reads SABLE and SABLE_WORK
    extra = dict(entry.split("=", 1) for entry in args.set)
    lines = [f"theta = {args.angle} deg, mu = {args.friction}, R = {args.radius} m, "
             f"{2 * args.radius / H:.0f} cells per diameter, seeding "
             f"{args.seeding or 'default'}, {args.end_time} s"
             + (f", {'; '.join(args.set)}" if args.set else ""), "",
             "| face off the grid line, cells | travel / rigid − 1 | largest rise, mm |",
             "|---|---|---|"]
    rigid = G * math.sin(math.radians(args.angle)) / 3
    for offset in (float(o) for o in args.offsets.split(",")):
        entries, bodies = scene(offset, args.angle, args.friction, args.radius, args.seeding,
                                args.end_time, extra)
        code, output, rows = scene_test.run(f"offset_{offset:g}", entries, bodies)
        if code != 0 or not rows:
            lines.append(f"| {offset:g} | run failed | |")
            continue
        t = rows[-1]["time"]
        travel = rows[-1]["body1_x"] - rows[0]["body1_x"]
        # the rise across the slope, in the tilted frame's normal direction
        rise = max(r["body1_y"] for r in rows) - rows[0]["body1_y"]
        lines.append(f"| {offset:g} | {100 * (travel / (rigid * t * t) - 1):+.2f}% | "
                     f"{1000 * rise:.1f} |")
        print(lines[-1], flush=True)
    os.makedirs(args.work, exist_ok=True)
    with open(os.path.join(args.work, "plane_rolling.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
