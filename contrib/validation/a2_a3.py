#!/usr/bin/python3
"""Validation scenes A2 and A3 (Bardenhagen, Guilkey, Roessig, Brackbill,
Witzel, Foster 2001, Figs. 3-8): an elastic sphere on an elastic plane, 3D,
with Bardenhagen-2001 frictional contact between the two bodies.

Cases (scene files in prm/, written at cell R/4):
- a2_noslip: sphere R = 1.6 m on an incline, theta = pi/4, mu = 0.495;
  rigid sphere rolls without slipping, x - x0 = (25 sqrt(2)/14) t^2.
- a2_slip: theta = pi/3, mu = 0.286; rigid sphere rolls and slips,
  x - x0 = (5/2)(sqrt(3) - 2/7) t^2.
- a3_backspin: R = 1 m on a flat plane, mu = 0.5, spin 5 rad/s, at rest:
  x - x0 = (5/2) t^2 for t <= 2/7 s, then (5/2)(2/7)^2 + (10/7)(t - 2/7).
A2 runs at cells R/2, R/4, R/8, A3 at R/4 and R/8 (`--resolutions` limits
the set). Each run compares the sphere's centre of mass (body0_x, body0_vx
of statistics.csv, every step) with the rigid solution and writes the final
particle state once, from which the sphere's spin omega R / v_cm is taken,
and prints the contact moment on the sphere over the friction's moment
(columns contact0_1_ma_z, contact0_1_fx: 1 where the normal forces act
through the centre; where they resist the turning, below 1 while friction
drives the spin, A2, and above 1 while it slows the spin, A3).
Output: a2_a3_table.md and a2_a3.png in --output-dir (default: the work
directory; doc/validation for the report).

Usage: contrib/validation/a2_a3.py [--sable build/sable] [--work DIR]
           [--end-time T] [--resolutions 2,4,8] [--cases a2_noslip,...]
           [--output-dir DIR] [--set "Section/Entry=value" ...]
The scene files run as they are, with `--set` for `Grid/Subdivisions`, the
output directory, the end time and (for the spin) the particle output
interval. Particle files are read with meshio (Debian's /usr/bin/python3
with python3-meshio, and python3-matplotlib for the plot)."""
import argparse
import csv
import glob
import math
import os
import re
import subprocess
import sys

import meshio
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
G = 10.0


def a2_noslip(t):
    a = 25 * math.sqrt(2) / 7
    return 0.5 * a * t * t, a * t


def a2_slip(t):
    a = 5 * (math.sqrt(3) - 2.0 / 7.0)
    return 0.5 * a * t * t, a * t


def a3_backspin(t):
    t1 = 2.0 / 7.0
    if t <= t1:
        return 2.5 * t * t, 5 * t
    return 2.5 * t1 * t1 + 10.0 / 7.0 * (t - t1), 10.0 / 7.0


# name, radius, grid size (m), cells per radius, rigid solution, label, rigid omega R / v
CASES = [
    ("a2_noslip", 1.6, (20.0, 4.8, 4.8), (2, 4, 8), a2_noslip,
     r"A2 no-slip: $\theta=\pi/4$, $\mu=0.495$", lambda t: 1.0),
    ("a2_slip", 1.6, (20.0, 4.8, 4.8), (2, 4, 8), a2_slip,
     r"A2 slip: $\theta=\pi/3$, $\mu=0.286$",
     lambda t: 2.5 * 0.286 * 0.5 / (math.sqrt(3) / 2 - 0.286 * 0.5)),
    ("a3_backspin", 1.0, (5.0, 3.0, 3.0), (4, 8), a3_backspin,
     r"A3 backspin: $\mu=0.5$, $\omega_0=5$ rad/s",
     lambda t: (5 - 12.5 * t) / (5 * t) if t < 2.0 / 7.0 else 1.0),
]


# --set: entries given to every run (e.g. "Grid/Shape functions=gimp")
EXTRA_SETTINGS = []


def settings(cells, output_directory, end_time, output_interval):
    """The --set options for another resolution, output directory, end
    time and particle output interval of a scene file."""
    values = {"Grid/Subdivisions": ", ".join(str(c) for c in cells),
              "Output directory": output_directory,
              "Output/Particle output interval": output_interval,
              # every step's row: the analysis samples the trajectory
              "Output/Statistics interval": 1}
    if end_time is not None:
        values["Time/End time"] = end_time
    arguments = []
    for entry, value in values.items():
        arguments += ["--set", f"{entry}={value}"]
    for entry in EXTRA_SETTINGS:
        arguments += ["--set", entry]
    return arguments


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def sphere_state(directory):
    """From the last particle file: the sphere's (body 0) spin about z,
    omega_z = L_z / I_z about its centre of mass, its centre velocity, the
    lowest sphere point and the highest plane (body 1) point."""
    last = sorted(glob.glob(os.path.join(directory, "particles_*.pvtu")))[-1]
    # the pieces of the last .pvtu, one .vtu per rank
    pieces = [meshio.read(path) for path in sorted(glob.glob(last[:-len(".pvtu")] + ".*.vtu"))]
    points = np.concatenate([piece.points for piece in pieces]).astype(float)
    velocity, mass, body = (np.concatenate([piece.point_data[name] for piece in pieces]).astype(float)
                            for name in ("velocity", "mass", "body"))
    sphere, plane = body == 0, body == 1
    m, p, u = mass[sphere], points[sphere], velocity[sphere]
    c = m @ p / m.sum()
    v = m @ u / m.sum()
    L = np.sum(m * ((p[:, 0] - c[0]) * (u[:, 1] - v[1]) - (p[:, 1] - c[1]) * (u[:, 0] - v[0])))
    inertia = np.sum(m * ((p[:, 0] - c[0]) ** 2 + (p[:, 1] - c[1]) ** 2))
    return dict(omega=float(L / inertia), vx=float(v[0]), sphere_min_y=float(p[:, 1].min()),
                plane_max_y=float(points[plane, 1].max()))


def run(sable, name, radius, size, per_radius, work, end_time):
    """Run one case at cell R / per_radius; return (rows, wall time, spin)."""
    h = radius / per_radius
    cells = [round(length / h) for length in size]
    tag = f"{name}_r{per_radius}"
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(ROOT, "prm", name + ".prm")
    with open(scene) as f:
        text = f.read()
    T = end_time if end_time is not None else float(re.search(r"(?m)^\s*set End time\s*=\s*([^#\s]+)", text).group(1))
    result = subprocess.run([sable, scene, "--overwrite"] + settings(cells, tag, end_time, T), cwd=work,
                            capture_output=True, text=True)
    output = result.stdout + result.stderr
    if result.returncode != 0:
        sys.stderr.write(output)
        raise SystemExit(f"{scene}: sable exited with {result.returncode}")
    wall = float(re.search(r"Finished \d+ steps to t = \S+ in (\S+) s wall time", output).group(1))
    rows = read_csv(os.path.join(work, tag, "statistics.csv"))
    return rows, wall, sphere_state(os.path.join(work, tag))


def errors(rows, rigid):
    """x_cm - x0 and v_cm minus the rigid solution: at the end and the
    largest absolute value over all steps; rigid values at the end."""
    x0, y0 = rows[0]["body0_x"], rows[0]["body0_y"]
    ex, ev = [], []
    for r in rows:
        x, v = rigid(r["time"])
        ex.append(r["body0_x"] - x0 - x)
        ev.append(r["body0_vx"] - v)
    T = rows[-1]["time"]
    x_rigid, v_rigid = rigid(T)
    return dict(T=T, ex_end=ex[-1], ex_max=max(map(abs, ex)), x_rigid=x_rigid,
                ev_end=ev[-1], ev_max=max(map(abs, ev)), v_rigid=v_rigid,
                steps=int(rows[-1]["step"]), points=int(rows[0]["particles"]),
                lift=max(r["body0_y"] for r in rows) - y0,
                drop=min(r["body0_y"] for r in rows) - y0)


def moment_ratio(rows, radius):
    """The contact moment on the sphere about its centre of mass
    (contact0_1_ma_z), integrated over the run, over the friction force's
    moment with the arm from the centre to the plane's surface (the
    sphere starts on it: its centre R above), both at the centre's place
    when the step's forces acted (the row's less dt times its velocity).
    1: the normal forces act through the centre; where they resist the
    turning (a rolling resistance) the ratio is below 1 while friction
    drives the spin (A2) and above 1 while it slows it (A3). NaN without
    the column."""
    if "contact0_1_ma_z" not in rows[0]:
        return float("nan")
    surface = rows[0]["body0_y"] - radius
    moment = friction = 0.
    for before, r in zip(rows, rows[1:]):
        dt = r["time"] - before["time"]
        moment += r["contact0_1_ma_z"] * dt
        friction += (r["body0_y"] - dt * r["body0_vy"] - surface) * r["contact0_1_fx"] * dt
    return moment / friction if friction != 0 else float("nan")


def order(hs, es):
    """Least-squares slope of log(error) against log(h)."""
    if len(hs) < 2 or any(e <= 0 for e in es):
        return float("nan")
    lx = [math.log(h) for h in hs]
    ly = [math.log(e) for e in es]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)


def require_matplotlib():
    """Stop before any simulation if this Python cannot draw the figure."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise SystemExit(f"{sys.argv[0]}: the figure needs matplotlib, which {sys.executable} "
                         "does not have (Debian: apt-get install python3-matplotlib, then run "
                         "the script as it is, with /usr/bin/python3)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "a2_a3.work"))
    parser.add_argument("--end-time", type=float, default=None,
                        help="override the scenes' end time (1 s)")
    parser.add_argument("--resolutions", default="2,4,8",
                        help="cells per radius to run, among 2 (A2 only), 4, 8")
    parser.add_argument("--cases", default=",".join(c[0] for c in CASES))
    parser.add_argument("--output-dir", default=None,
                        help="where the table and figure go (default: the work "
                             "directory; doc/validation updates the report)")
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                        help='an entry for every run, e.g. "Grid/Shape functions=gimp"')
    args = parser.parse_args()
    args.output_dir = args.output_dir or args.work
    EXTRA_SETTINGS.extend(args.set)
    require_matplotlib()
    sable = os.path.abspath(args.sable)
    work = os.path.abspath(args.work)
    wanted = {int(n) for n in args.resolutions.split(",")}
    cases = [c for c in CASES if c[0] in args.cases.split(",")]

    results = {}
    for name, radius, size, resolutions, rigid, _, spin in cases:
        for n in resolutions:
            if n not in wanted:
                continue
            rows, wall, state = run(sable, name, radius, size, n, work, args.end_time)
            e = errors(rows, rigid)
            e.update(wall=wall, rows=rows, spin=-state["omega"] * radius / state["vx"],
                     spin_rigid=spin(e["T"]), gap=state["sphere_min_y"] - state["plane_max_y"],
                     moment=moment_ratio(rows, radius))
            results[name, n] = e
            print(f"{name} R/{n}: {e['points']} points, {e['steps']} steps, {wall:.1f} s; x error at T "
                  f"{e['ex_end']:+.4f} m ({e['ex_end'] / e['x_rigid']:+.2%}), max {e['ex_max']:.4f} m; "
                  f"v error at T {e['ev_end']:+.4f} m/s ({e['ev_end'] / e['v_rigid']:+.2%}), max "
                  f"{e['ev_max']:.4f} m/s; lift {e['lift']:.4f} m; omega R / v {e['spin']:.3f} "
                  f"(rigid {e['spin_rigid']:.3f}); contact moment / (friction x arm) "
                  f"{e['moment']:.3f}", flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    write_table(cases, results, os.path.join(args.output_dir, "a2_a3_table.md"))
    plot(cases, results, os.path.join(args.output_dir, "a2_a3.png"))


def write_table(cases, results, path):
    lines = [
        "| case | cell | points | steps | wall s | x err at T, m | rel. | max \\|x err\\|, m | rel. | "
        "v err at T, m/s | rel. | max \\|v err\\|, m/s | rel. | lift, m | ωR/v at T (rigid) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    orders = []
    for name, radius, size, resolutions, rigid, label, _ in cases:
        done = [n for n in resolutions if (name, n) in results]
        for n in done:
            e = results[name, n]
            lines.append(
                f"| {name} | R/{n} | {e['points']} | {e['steps']} | {e['wall']:.1f} | "
                f"{e['ex_end']:+.4f} | {e['ex_end'] / e['x_rigid']:+.1%} | "
                f"{e['ex_max']:.4f} | {e['ex_max'] / e['x_rigid']:.1%} | "
                f"{e['ev_end']:+.4f} | {e['ev_end'] / e['v_rigid']:+.1%} | "
                f"{e['ev_max']:.4f} | {e['ev_max'] / e['v_rigid']:.1%} | {e['lift']:.4f} | "
                f"{e['spin']:.2f} ({e['spin_rigid']:.2f}) |")
        for subset in ([n for n in done if n >= 4], done):
            if len(subset) >= 2 and (len(orders) == 0 or orders[-1][:2] != (name, tuple(subset))):
                per = [results[name, n] for n in subset]
                hs = [radius / n for n in subset]
                orders.append((name, tuple(subset),
                               order(hs, [abs(e["ex_end"]) for e in per]), order(hs, [e["ex_max"] for e in per]),
                               order(hs, [abs(e["ev_end"]) for e in per]), order(hs, [e["ev_max"] for e in per])))
    T = next(iter(results.values()))["T"]
    lines += [
        "",
        f"T = {T:g} s. Errors are computed minus rigid (negative: behind the rigid sphere); "
        "relative errors are divided by the rigid displacement x_rigid(T) - x0 or velocity "
        "v_rigid(T); max is over all steps. Lift: the largest rise of the sphere's centre of "
        "mass along the plane normal above its initial height. ωR/v: the sphere's spin about "
        "its centre of mass (from the particles) times R over v_cm at T (1 = rolling without "
        "slip). Wall time from the program's final line (one MPI rank, on a shared machine).",
        "",
        "Observed convergence order (least-squares slope of log error against log h over the "
        "listed resolutions; n/a if an error is zero):",
        "",
        "| case | cells | x err at T | max x err | v err at T | max v err |",
        "|---|---|---|---|---|---|"]
    for name, subset, o1, o2, o3, o4 in orders:
        lines.append(f"| {name} | " + ", ".join(f"R/{n}" for n in subset) + " | " +
                     " | ".join("n/a" if math.isnan(o) else f"{o:.2f}" for o in (o1, o2, o3, o4)) + " |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


def plot(cases, results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(cases), figsize=(5.5 * len(cases), 7.5), sharex=True, squeeze=False)
    styles = {2: ":", 4: "--", 8: "-."}
    for col, (name, radius, size, resolutions, rigid, label, _) in enumerate(cases):
        done = [n for n in resolutions if (name, n) in results]
        if not done:
            continue
        T = results[name, done[0]]["T"]
        ts = [T * i / 400 for i in range(401)]
        ax_x, ax_v = axes[0][col], axes[1][col]
        ax_x.plot(ts, [rigid(t)[0] for t in ts], "k-", lw=2, label="rigid sphere")
        ax_v.plot(ts, [rigid(t)[1] for t in ts], "k-", lw=2, label="rigid sphere")
        for n in done:
            rows = results[name, n]["rows"]
            x0 = rows[0]["body0_x"]
            t = [r["time"] for r in rows]
            ax_x.plot(t, [r["body0_x"] - x0 for r in rows], styles[n], label=f"cell R/{n}")
            ax_v.plot(t, [r["body0_vx"] for r in rows], styles[n], label=f"cell R/{n}")
        ax_x.set_title(label)
        ax_x.set_ylabel(r"$x_{cm} - x_0$ (m)")
        ax_v.set_ylabel(r"$v_{cm,x}$ (m/s)")
        ax_v.set_xlabel("t (s)")
        for ax in (ax_x, ax_v):
            ax.grid(True, lw=0.3)
        ax_x.legend(fontsize=8)
    fig.suptitle("A2/A3: elastic sphere on an elastic plane (MPM, Bardenhagen 2001 contact, MUSL, CFL 0.5) "
                 "against the rigid-sphere solution")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("wrote", path)


if __name__ == "__main__":
    main()
