#!/usr/bin/python3
"""What adaptive grids buy: scenes A1 (theta = pi/6, mu = 0.5, a rolling
disk) and A3 (backspin sphere) on a uniform coarse grid, a uniform fine grid
(one level finer), and the coarse grid refined to the fine size (a) around the
grains' surfaces and where they touch (Mesh refinement criteria 'body
surface, contact'; A3's plane keeps its surface coarse, 'Refine surface =
false') and (b) only where they touch (criterion 'contact': A1's disk at the
friction wall, A3's sphere and plane where they meet). Errors against the rigid-body
solutions of contrib/validation/a1_incline.py and a2_a3.py, wall times of
one run each on one MPI rank, all in one invocation so the times compare.

Writes adaptivity_table.md into --output-dir (default: the work directory;
doc/validation for the report).

Usage: contrib/validation/adaptivity.py [--sable build/sable] [--work DIR]
           [--output-dir DIR] [--interval N]"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from a1_incline import rigid_acceleration  # noqa: E402
from a2_a3 import a3_backspin as a3_rigid  # noqa: E402


def a1_rigid(t):
    """Rolling disk from rest (theta = pi/6, mu = 0.5): x - x0 and v."""
    a, _ = rigid_acceleration(math.pi / 6, 0.5)
    return 0.5 * a * t * t, a * t


# name, scene, coarse subdivisions, rigid solution, cell label (coarse,
# fine), refinement interval: the steps in which the centre moves about half
# a fine cell at its largest speed (A1: 3.3 m/s, dt 0.45 ms, cell 6.25 cm;
# A3: 1.43 m/s, dt 0.6 ms, cell 12.5 cm). The automatic interval would follow
# the fastest point, the spinning rim, and adapt several times as often.
CASES = [
    ("A1, theta = pi/6, mu = 0.5", "a1_mu05_theta30", (48, 12), a1_rigid, ("R/4", "R/8"), 20),
    ("A3, backspin", "a3_backspin", (20, 12, 12), a3_rigid, ("R/4", "R/8"), 70),
]


def scene_text(text, subdivisions, directory, criteria, interval):
    text, n = re.subn(r"(?m)^(\s*set Subdivisions\s*=).*$",
                      r"\g<1> " + ", ".join(map(str, subdivisions)), text)
    assert n == 1
    text, n = re.subn(r"(?m)^(\s*set Output directory\s*=).*$", rf"\g<1> {directory}", text)
    assert n == 1
    text = re.sub(r"(?m)^(\s*set Particle output interval\s*=).*$", r"\g<1> 0", text)
    if criteria:
        text += (f"\nsubsection Mesh refinement\n  set Criteria = {criteria}\n"
                 f"  set Maximum level = 1\n  set Refinement interval = {interval}\nend\n")
        # a plane under a grain: refined only where the grain touches it
        text = re.sub(r"(?ms)^(subsection Body 1\n)", r"\g<1>  set Refine surface = false\n", text)
    return text


def run(sable, work, scene, label, subdivisions, criteria, interval):
    os.makedirs(work, exist_ok=True)
    name = f"{scene}_{label}"
    with open(os.path.join(ROOT, "prm", scene + ".prm")) as f:
        text = scene_text(f.read(), subdivisions, name, criteria, interval)
    with open(os.path.join(work, name + ".prm"), "w") as f:
        f.write(text)
    # every step's row, as the analysis expects
    result = subprocess.run([sable, name + ".prm", "--overwrite", "--set", "Output/Statistics interval=1"],
                            cwd=work, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write(result.stdout + result.stderr)
        raise SystemExit(f"{name}: sable exited with {result.returncode}")
    wall = float(re.search(r"in (\S+) s wall time", result.stdout).group(1))
    with open(os.path.join(work, name, "statistics.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return rows, wall


def errors(rows, rigid):
    x0 = rows[0]["body0_x"]
    T = rows[-1]["time"]
    x_rigid, v_rigid = rigid(T)
    ex = rows[-1]["body0_x"] - x0 - x_rigid
    ex_max = max(abs(r["body0_x"] - x0 - rigid(r["time"])[0]) for r in rows)
    ev = rows[-1]["body0_vx"] - v_rigid
    return dict(ex=ex, ex_rel=ex / x_rigid, ex_max=ex_max / x_rigid, ev_rel=ev / v_rigid,
                points=int(rows[0]["particles"]), cells_start=int(rows[0]["cells"]),
                cells_max=int(max(r["cells"] for r in rows)), steps=int(rows[-1]["step"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "validation_adaptivity"))
    parser.add_argument("--output-dir", default=None,
                        help="where the table goes (default: the work directory; "
                             "doc/validation updates the report)")
    parser.add_argument("--interval", type=int, default=None,
                        help="refinement interval for every case (0: automatic)")
    args = parser.parse_args()
    args.output_dir = args.output_dir or args.work
    lines = ["| case | grid | cells (start-max) | points | steps | wall s | x err at T | max \\|x err\\| "
             "| v err at T | error / fine | time / fine |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for title, scene, coarse, rigid, (h_coarse, h_fine), interval in CASES:
        interval = args.interval if args.interval is not None else interval
        fine = tuple(2 * n for n in coarse)
        results = {}
        for label, subdivisions, criteria in (("coarse", coarse, ""), ("fine", fine, ""),
                                              ("surface", coarse, "body surface, contact"),
                                              ("contact", coarse, "contact")):
            rows, wall = run(args.sable, args.work, scene, label, subdivisions, criteria, interval)
            results[label] = (errors(rows, rigid), wall)
            print(f"{title}, {label}: x err {results[label][0]['ex_rel']:+.2%}, {wall:.1f} s", flush=True)
        e_fine, t_fine = results["fine"]
        for label, grid in (("coarse", f"uniform {h_coarse}"), ("fine", f"uniform {h_fine}"),
                            ("surface", f"{h_coarse}, {h_fine} at surfaces and contacts"),
                            ("contact", f"{h_coarse}, {h_fine} at contacts")):
            e, wall = results[label]
            lines.append(f"| {title} | {grid} | {e['cells_start']}-{e['cells_max']} | {e['points']} | "
                         f"{e['steps']} | {wall:.1f} | {e['ex_rel']:+.1%} | {e['ex_max']:.1%} | "
                         f"{e['ev_rel']:+.1%} | {abs(e['ex']) / abs(e_fine['ex']):.2f} | "
                         f"{wall / t_fine:.2f} |")
    lines.append("")
    lines.append("Errors relative to the rigid solution's displacement x_rigid(T) and velocity v_rigid(T), "
                 "T = 1 s; 'error / fine' is |x err at T| over the fine grid's, 'time / fine' the wall-time "
                 "ratio. Refinement interval: " + ("automatic" if args.interval == 0 else
                 f"{args.interval} steps" if args.interval else
                 ", ".join(f"{c[0].split(',')[0]} {c[5]} steps" for c in CASES)) + ".")
    os.makedirs(args.output_dir, exist_ok=True)
    path = os.path.join(args.output_dir, "adaptivity_table.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
