#!/usr/bin/python3
"""Validation scene A1 (Bardenhagen, Brackbill, Sulsky 2000, Figs. 2-4): an
elastic disk on an incline, 2D.

Runs the four cases of prm/a1_*.prm (theta, mu) = (pi/3, 0.3), (pi/3, 0.9),
(pi/3, 0.5), (pi/6, 0.5) at 4, 8 and 16 cells per disk diameter (cells 0.5 R,
0.25 R, 0.125 R), compares the disk's centre of mass with the rigid-disk
solution from rest,
    x(t) - x0 = 1/2 a t^2,  v(t) = a t,
    a = |g| (sin(theta) - mu cos(theta))   if tan(theta) > 3 mu  (slips),
    a = 2/3 |g| sin(theta)                 otherwise             (rolls),
and writes a1_table.md and a1_incline.png into --output-dir (default: the
work directory; doc/validation for the report).

Usage: contrib/validation/a1_incline.py [--sable build/sable]
           [--work DIR] [--end-time T] [--output-dir DIR]
           [--set "Section/Entry=value" ...]
The scene files are the middle-resolution ones in prm/; the other
resolutions change only `Grid/Subdivisions` (and the output directory)."""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
G = 9.8
RADIUS = 0.5
GRID = (6.0, 1.5)  # grid size, m (prm/a1_*.prm)
CELLS_PER_DIAMETER = (4, 8, 16)
# name, theta, mu, label
CASES = [
    ("a1_mu03_theta60", math.pi / 3, 0.3, r"$\theta=\pi/3$, $\mu=0.3$"),
    ("a1_mu09_theta60", math.pi / 3, 0.9, r"$\theta=\pi/3$, $\mu=0.9$"),
    ("a1_mu05_theta60", math.pi / 3, 0.5, r"$\theta=\pi/3$, $\mu=0.5$"),
    ("a1_mu05_theta30", math.pi / 6, 0.5, r"$\theta=\pi/6$, $\mu=0.5$"),
]


def rigid_acceleration(theta, mu):
    """Centre acceleration of a rigid disk from rest, and whether it slips."""
    if math.tan(theta) > 3 * mu:
        return G * (math.sin(theta) - mu * math.cos(theta)), True
    return 2.0 / 3.0 * G * math.sin(theta), False


def variant(text, cells_per_diameter, output_directory, end_time):
    """The scene text at another resolution (and end time)."""
    h = 2 * RADIUS / cells_per_diameter
    nx, ny = (round(length / h) for length in GRID)
    text, n = re.subn(r"(?m)^(\s*set Subdivisions\s*=).*$", rf"\g<1> {nx}, {ny}", text)
    assert n == 1, "Subdivisions not found"
    text, n = re.subn(r"(?m)^(\s*set Output directory\s*=).*$", rf"\g<1> {output_directory}", text)
    assert n == 1, "Output directory not found"
    if end_time is not None:
        text, n = re.subn(r"(?m)^(\s*set End time\s*=).*$", rf"\g<1> {end_time}", text)
        assert n == 1, "End time not found"
    return text


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


# --set: entries given to every run (e.g. "Grid/Shape functions=gimp")
EXTRA_SETTINGS = []


def run(sable, prm_path, directory, cells, end_time=None):
    """Run one case at one resolution; return (rows, wall time, points)."""
    name = os.path.splitext(os.path.basename(prm_path))[0]
    os.makedirs(directory, exist_ok=True)
    scene = os.path.join(directory, f"{name}_n{cells}.prm")
    with open(prm_path) as f:
        text = variant(f.read(), cells, f"{name}_n{cells}", end_time)
    with open(scene, "w") as f:
        f.write(text)
    # every step's row: the analysis samples the trajectory
    result = subprocess.run([sable, os.path.basename(scene), "--overwrite",
                             "--set", "Output/Statistics interval=1"] +
                            [a for entry in EXTRA_SETTINGS for a in ("--set", entry)], cwd=directory,
                            capture_output=True, text=True)
    output = result.stdout + result.stderr
    if result.returncode != 0:
        sys.stderr.write(output)
        raise SystemExit(f"{scene}: sable exited with {result.returncode}")
    wall = float(re.search(r"Finished \d+ steps to t = \S+ in (\S+) s wall time", output).group(1))
    rows = read_csv(os.path.join(directory, f"{name}_n{cells}", "statistics.csv"))
    return rows, wall


def errors(rows, a):
    """Errors of x_cm - x0 and v_cm against the rigid solution: signed error
    at the end, largest absolute error over time, and the rigid values at the
    end (for relative errors)."""
    x0 = rows[0]["body0_x"]
    ex = [r["body0_x"] - x0 - 0.5 * a * r["time"] ** 2 for r in rows]
    ev = [r["body0_vx"] - a * r["time"] for r in rows]
    T = rows[-1]["time"]
    return dict(T=T, ex_end=ex[-1], ex_max=max(map(abs, ex)), x_rigid=0.5 * a * T * T,
                ev_end=ev[-1], ev_max=max(map(abs, ev)), v_rigid=a * T,
                steps=int(rows[-1]["step"]), points=int(rows[0]["particles"]),
                lift=max(r["body0_y"] for r in rows) - rows[0]["body0_y"])


def order(hs, es):
    """Least-squares slope of log(error) against log(h)."""
    if any(e <= 0 for e in es) or len(set(hs)) < 2:
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
    global CELLS_PER_DIAMETER
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "a1_incline.work"))
    parser.add_argument("--end-time", type=float, default=None,
                        help="override the scenes' end time (1 s)")
    parser.add_argument("--output-dir", default=None,
                        help="where the table and figure go (default: the work "
                             "directory; doc/validation updates the report)")
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                        help='an entry for every run, e.g. "Grid/Shape functions=gimp"')
    parser.add_argument("--cells", default=",".join(map(str, CELLS_PER_DIAMETER)),
                        help="cells per diameter (default 4,8,16)")
    args = parser.parse_args()
    args.output_dir = args.output_dir or args.work
    EXTRA_SETTINGS.extend(args.set)
    CELLS_PER_DIAMETER = tuple(int(n) for n in args.cells.split(","))
    require_matplotlib()
    sable = os.path.abspath(args.sable)
    work = os.path.abspath(args.work)

    results = {}
    for name, theta, mu, _ in CASES:
        a, slips = rigid_acceleration(theta, mu)
        for n in CELLS_PER_DIAMETER:
            rows, wall = run(sable, os.path.join(ROOT, "prm", name + ".prm"), work, n, args.end_time)
            e = errors(rows, a)
            e.update(wall=wall, rows=rows)
            results[name, n] = e
            print(f"{name} {n:2d} cells/D: {e['steps']} steps, {wall:.2f} s; x error at T "
                  f"{e['ex_end']:+.4f} m ({e['ex_end'] / e['x_rigid']:+.2%}), v error at T "
                  f"{e['ev_end']:+.4f} m/s ({e['ev_end'] / e['v_rigid']:+.2%}), lift {e['lift']:.4f} m",
                  flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    write_table(results, os.path.join(args.output_dir, "a1_table.md"))
    plot(results, os.path.join(args.output_dir, "a1_incline.png"))


def write_table(results, path):
    hs = [2 * RADIUS / n for n in CELLS_PER_DIAMETER]
    lines = [
        "| case | rigid motion | cells / D | points | steps | wall s | x err at T, m | rel. | "
        "max \\|x err\\|, m | rel. | v err at T, m/s | rel. | max \\|v err\\|, m/s | rel. | lift, m |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    orders = []
    for name, theta, mu, _ in CASES:
        a, slips = rigid_acceleration(theta, mu)
        for n in CELLS_PER_DIAMETER:
            e = results[name, n]
            lines.append(
                f"| θ = {theta_text(theta)}, μ = {mu} | {'slips' if slips else 'rolls'} | {n} | "
                f"{e['points']} | {e['steps']} | {e['wall']:.2f} | "
                f"{e['ex_end']:+.4f} | {e['ex_end'] / e['x_rigid']:+.2%} | "
                f"{e['ex_max']:.4f} | {e['ex_max'] / e['x_rigid']:.2%} | "
                f"{e['ev_end']:+.4f} | {e['ev_end'] / e['v_rigid']:+.2%} | "
                f"{e['ev_max']:.4f} | {e['ev_max'] / e['v_rigid']:.2%} | {e['lift']:.4f} |")
        per = [results[name, n] for n in CELLS_PER_DIAMETER]
        orders.append((name, theta, mu,
                       order(hs, [abs(e["ex_end"]) for e in per]), order(hs, [e["ex_max"] for e in per]),
                       order(hs, [abs(e["ev_end"]) for e in per]), order(hs, [e["ev_max"] for e in per])))
    T = results[CASES[0][0], CELLS_PER_DIAMETER[0]]["T"]
    lines += [
        "",
        f"T = {T:g} s. Errors are computed minus rigid (negative: behind the rigid disk); "
        "relative errors are divided by the rigid displacement x_rigid(T) - x0 or velocity "
        "v_rigid(T); max is over all steps. Lift: the largest rise of the centre of mass "
        "above its initial height. Wall time from the program's final line (one MPI rank).",
        "",
        "Observed convergence order (least-squares slope of log error against log h over "
        "the three resolutions; n/a if an error is zero):",
        "",
        "| case | x err at T | max x err | v err at T | max v err |",
        "|---|---|---|---|---|"]
    for name, theta, mu, o1, o2, o3, o4 in orders:
        lines.append(f"| θ = {theta_text(theta)}, μ = {mu} | " +
                     " | ".join("n/a" if math.isnan(o) else f"{o:.2f}" for o in (o1, o2, o3, o4)) + " |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


def theta_text(theta):
    return "π/3" if abs(theta - math.pi / 3) < 1e-12 else "π/6"


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5), sharex=True)
    styles = {4: ":", 8: "--", 16: "-."}
    for col, (name, theta, mu, label) in enumerate(CASES):
        a, slips = rigid_acceleration(theta, mu)
        T = results[name, CELLS_PER_DIAMETER[0]]["T"]
        ts = [T * i / 200 for i in range(201)]
        ax_x, ax_v = axes[0][col], axes[1][col]
        ax_x.plot(ts, [0.5 * a * t * t for t in ts], "k-", lw=2, label="rigid disk")
        ax_v.plot(ts, [a * t for t in ts], "k-", lw=2, label="rigid disk")
        for n in CELLS_PER_DIAMETER:
            rows = results[name, n]["rows"]
            x0 = rows[0]["body0_x"]
            t = [r["time"] for r in rows]
            ax_x.plot(t, [r["body0_x"] - x0 for r in rows], styles[n], label=f"{n} cells / D")
            ax_v.plot(t, [r["body0_vx"] for r in rows], styles[n], label=f"{n} cells / D")
        ax_x.set_title(f"{label} ({'slips' if slips else 'rolls'})")
        ax_x.set_ylabel(r"$x_{cm} - x_0$ (m)")
        ax_v.set_ylabel(r"$v_{cm}$ (m/s)")
        ax_v.set_xlabel("t (s)")
        for ax in (ax_x, ax_v):
            ax.grid(True, lw=0.3)
        ax_x.legend(fontsize=8)
    fig.suptitle("A1: elastic disk on an incline (MPM, MUSL, CFL 0.5) against the rigid-disk solution")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("wrote", path)


if __name__ == "__main__":
    main()
