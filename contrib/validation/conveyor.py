#!/usr/bin/python3
"""Bodies set down on a conveyor: friction against a driven body, and rolling
on a body whose material moves across the grid.

A belt (a 2.4 x 0.2 m box of prescribed velocity V = 1 m/s) carries, under
gravity g = 9.81 m/s^2 and with Coulomb friction mu between them, either
- a block (0.2 m square, E = 10 MPa, nu = 0.3, rho = 1000 kg/m^3), set down
  at rest: it slides with a = mu g until it moves with the belt at
  t* = V / (mu g), then rides along; or
- a disk (R = 0.2 m, same material), set down at rest: friction drives it
  forward (a = mu g) and spins it up (alpha = 2 mu g / R) until its bottom
  moves with the belt at t* = V / (3 mu g); from then on it rolls at V / 3
  without any force (in the belt's frame it rolls backwards at 2V/3 on a
  plane at rest).
Cells of 0.025 m (16 per disk diameter) unless --cells-per-metre says
otherwise, 2 points per cell direction, `bardenhagen 2001` unless --set
changes it.

For the disk the same collision is also run in the belt's frame ("disk at
rest"): the belt at rest, the disk thrown backwards at -V. The rigid disk
ends the same in both frames, rolling at V/3 relative to the belt; the
difference between the two rows is what the motion of the material across
the grid costs. Two more cases take the disk already rolling, settled
first ('Solver/Settling steps'), on an elastic belt (the same box, 100
times as dense, on a slip floor) so that nothing bounces: "spinning disk",
the belt moving at V under a disk that spins in place at omega = V / R
(its centre at rest on the grid), and "rolling disk", the same in the
belt's frame (the belt at rest, the disk rolling at -V). The rigid disk
keeps rolling at -V relative to the belt in both.

Usage: contrib/validation/conveyor.py [--sable build/sable] [--work DIR]
           [--friction 0.3] [--cases block,disk,disk at rest,spinning disk,rolling disk]
           [--dim 2|3]
           [--seeding conforming] [--cells-per-metre 40] [--end-time 0.5]
           [--set "Section/Entry=value" ...]
Prints a markdown table (and writes it to DIR/conveyor.md). Its last
columns, from 0.05 s after t* (the same time for the settled cases):
the friction force on the body over the normal force, and the moment of
the normal forces about the disk's centre (the contact's moment less the
friction's) over N R, positive where it opposes the disk's rolling
relative to the belt: a rolling resistance of that arm."""
import argparse
import os
import sys
import time

G = 9.81
BELT_SPEED = 1.0
RADIUS = 0.2
MATERIAL = {"Young's modulus": 1e7, "Poisson's ratio": 0.3, "Density": 1000,
            "Particles per cell direction": 2}
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def scene(case, mu, seeding, cells_per_metre, end_time, extra, dim=2):
    """The entries and bodies of one case (in 3D a cube or a sphere on a
    belt 0.6 m wide, the same in every other respect)."""
    at_rest = case.endswith("at rest") or case == "rolling disk"
    settled = case in ("spinning disk", "rolling disk")
    z = lambda value: f", {value}" if dim == 3 else ""  # noqa: E731 (the third coordinate)
    size = (3, 0.8) + ((0.6,) if dim == 3 else ())
    entries = {"Dimension": dim, "Gravity": f"0, {-G}" + z(0), "Time/End time": end_time,
               "Grid/Lower corner": "0, 0" + z(0), "Grid/Upper corner": ", ".join(map(str, size)),
               "Grid/Subdivisions": ", ".join(str(round(s * cells_per_metre)) for s in size),
               "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": mu,
               "Output/Statistics interval": 5, **extra}
    belt = dict(MATERIAL, Shape="box", **{"Lower corner": "0, 0" + z(0), "Upper corner": "2.4, 0.2" + z(0.6),
                                          "Prescribed velocity": f"{0 if at_rest else BELT_SPEED}, 0" + z(0)})
    if dim == 3:
        if case == "block":
            body = dict(MATERIAL, Shape="box", **{"Lower corner": "0.7, 0.2, 0.2", "Upper corner": "0.9, 0.4, 0.4"})
        else:
            body = dict(MATERIAL, Shape="sphere", Center=f"{2.0 if at_rest else 0.8}, {0.2 + RADIUS}, 0.3",
                        Radius=RADIUS, Seeding=seeding, Velocity=f"{-BELT_SPEED if at_rest else 0}, 0, 0")
        return entries, [belt, body]
    if settled:
        entries.update({"Boundary conditions/Types": "2: slip", "Solver/Settling steps": 20000})
        belt = dict(MATERIAL, Shape="box", Density=100 * MATERIAL["Density"], Velocity=belt.pop("Prescribed velocity"),
                    **{"Lower corner": "0.2, 0", "Upper corner": "2.2, 0.2"})
    if case == "block":
        body = dict(MATERIAL, Shape="box", **{"Lower corner": "0.7, 0.2", "Upper corner": "0.9, 0.4"})
    elif settled:
        body = dict(MATERIAL, Shape="disk", Center=f"1.2, {0.2 + RADIUS}", Radius=RADIUS, Seeding=seeding,
                    Velocity=f"{-BELT_SPEED if at_rest else 0}, 0",
                    **{"Angular velocity": BELT_SPEED / RADIUS})
    else:
        body = dict(MATERIAL, Shape="disk", Center=f"{2.0 if at_rest else 0.8}, {0.2 + RADIUS}",
                    Radius=RADIUS, Seeding=seeding, Velocity=f"{-BELT_SPEED if at_rest else 0}, 0")
    return entries, [belt, body]


def rolling_speed(dim):
    """The rolling disk's (sphere's) speed relative to the belt once its
    bottom moves with it, over the belt's speed: its speed v and spin
    omega R = (m R^2 / I) v add up to V, v = V / 3 (2V / 7 for a sphere)."""
    return -(1 - (1. / 3 if dim == 2 else 2. / 7))


def rigid_speed(case, mu, t, dim=2):
    """The rigid body's speed relative to the belt over the belt's speed
    (-1 at the start, 0 for the block riding along, -2/3 for the rolling
    disk, -5/7 for the rolling sphere)."""
    if case == "block":
        return min(-1 + mu * G * t / BELT_SPEED, 0.)
    if case in ("spinning disk", "rolling disk"):
        return -1.
    return min(-1 + mu * G * t / BELT_SPEED, rolling_speed(dim))


def measure(run, case, mu, seeding, cells_per_metre, end_time, extra, dim=2):
    entries, bodies = scene(case, mu, seeding, cells_per_metre, end_time, extra, dim)
    name = f"{case.replace(' ', '_')}_{mu:g}_{seeding}_{cells_per_metre:g}_{dim}d"
    spin = "body1_omega" + ("_z" if dim == 3 else "")
    moment_b = "contact0_1_mb" + ("_z" if dim == 3 else "")
    start = time.time()
    _, _, rows = run(name, entries, bodies)
    wall = time.time() - start
    # the body's speed and, for the disk, its bottom's, relative to the belt
    speed = [(r["time"], (r["body1_vx"] - r["body0_vx"]) / BELT_SPEED,
              (r["body1_vx"] + r[spin] * RADIUS - r["body0_vx"]) / BELT_SPEED) for r in rows]
    stick_time = V_stick = None
    for t, v, bottom in speed if case not in ("spinning disk", "rolling disk") else []:
        # the first row at which it has caught up with the belt (within 1%)
        if t > 0.01 and (bottom if case != "block" else v) >= -0.01:
            stick_time, V_stick = t, v
            break
    t_star = BELT_SPEED / (mu * G) * (1 if case == "block" else 1 + rolling_speed(dim))
    end = speed[-1]
    # the contact's moment on the disk about its centre, less the
    # friction's (arm R): the normal forces' moment, over N R (positive
    # against a spin that rolls the disk forwards relative to the belt)
    late = [r for r in rows if r["time"] >= max(t_star, 0) + 0.05]
    normal = sum(-r["contact0_1_fy"] for r in late)
    friction = sum(-r["contact0_1_fx"] for r in late)
    moment = sum(r[moment_b] - RADIUS * -r["contact0_1_fx"] for r in late)
    arm = -moment / (normal * RADIUS) if case != "block" and normal else float("nan")
    return {"case": case, "t*": t_star, "stick time": stick_time, "speed at stick": V_stick,
            "end speed": end[1], "rigid end speed": rigid_speed(case, mu, end[0], dim),
            "end slip": end[2] if case != "block" else end[1], "friction": friction / normal if normal else 0.,
            "arm": arm, "wall": wall}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "conveyor.work"))
    parser.add_argument("--friction", type=float, default=0.3)
    parser.add_argument("--cases", default="block,disk,disk at rest,spinning disk,rolling disk")
    parser.add_argument("--seeding", default="conforming")
    parser.add_argument("--cells-per-metre", type=float, default=40)
    parser.add_argument("--end-time", type=float, default=0.5)
    parser.add_argument("--dim", type=int, default=2, choices=(2, 3),
                        help="3: a cube and a sphere (cases block, disk, disk at rest only)")
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                        help='an entry for every run, e.g. "Grid/Shape functions=gimp"')
    args = parser.parse_args()
    extra = dict(entry.split("=", 1) for entry in args.set)
    os.environ["SABLE"] = os.path.abspath(args.sable)
    os.environ["SABLE_WORK"] = os.path.abspath(args.work)
    sys.path.insert(0, os.path.join(ROOT, "tests", "mpm"))
    from scene_test import run  # noqa: E402 (reads SABLE and SABLE_WORK)

    lines = ["| case | rigid: sticks / rolls at t* | sticks / rolls at | speed relative to the belt then "
             "(rigid) | at the end (rigid) | error at the end | bottom's slip at the end | friction / N | "
             "moment of N / (N R) | wall time |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for case in args.cases.split(","):
        if args.dim == 3 and case in ("spinning disk", "rolling disk"):
            sys.exit(f"--dim 3: case '{case}' is not built in 3D (cases: block, disk, disk at rest)")
        m = measure(run, case, args.friction, args.seeding, args.cells_per_metre, args.end_time, extra,
                    args.dim)
        rigid_at_stick = rolling_speed(args.dim) if case != "block" else 0.
        stuck = (f"{m['stick time']:.3f} s", f"{m['speed at stick']:+.3f} ({rigid_at_stick:+.3f})") \
            if m["stick time"] is not None else ("rolling from the start" if "g disk" in case else "never", "")
        t_star = "—" if "g disk" in case else f"{m['t*']:.3f} s"
        lines.append(f"| {case} | {t_star} | {stuck[0]} | {stuck[1]} | "
                     f"{m['end speed']:+.3f} ({m['rigid end speed']:+.3f}) | "
                     f"{(m['end speed'] - m['rigid end speed']):+.3f} V | {m['end slip']:+.4f} V | "
                     f"{m['friction']:+.4f} | {m['arm']:+.4f} | {m['wall']:.0f} s |")
        print(lines[-1], flush=True)
    table = "\n".join(lines) + "\n"
    path = os.path.join(args.work, "conveyor.md")
    with open(path, "w") as f:
        f.write(table)
    print(table + f"(written to {path}; speeds in units of the belt's V = {BELT_SPEED} m/s)")


if __name__ == "__main__":
    main()
