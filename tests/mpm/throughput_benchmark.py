#!/usr/bin/python3
"""Smoke run of contrib/benchmarks/throughput/run.py (issue 13's floor
problem and the box) on tiny scenes: the scenes it builds are the ones it
claims (point and cell counts from the body's and the grid's cells, the
100k case equal to the committed floor_100k.prm), the numbers it prints
add up (phases inside the loop's wall time, ns per particle-step from the
loop time), and 1 and 2 threads give the same statistics.csv. No time is
checked: only that each is parsed and positive."""
import importlib.util
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_test import SABLE, WORK, check, finish  # noqa: E402

SOURCE = os.environ.get("SABLE_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(SOURCE, "contrib", "benchmarks", "throughput", "run.py")
BUILD = os.path.dirname(os.path.abspath(SABLE))
os.makedirs(WORK, exist_ok=True)

spec = importlib.util.spec_from_file_location("throughput_run", SCRIPT)
bench = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bench)

# the 100k case is floor_100k.prm itself: 158^2 cells of 2x2 points in a
# 316^2 grid, every entry as committed (but output directory and steps)
sets, n = bench.scene("floor", 2, 100000, "out", 1000)
check("100k: 158 body cells per direction", n == 158, f"got {n}")
args = bench.write_scene(sets, os.path.join(WORK, "floor_100k_rewritten.prm"))
committed = [l.split("#")[0].split() for l in open(bench.FLOOR_PRM)]
rewritten = [l.split("#")[0].split() for l in open(args[0])]
differing = [(a, b) for a, b in zip(committed, rewritten) if a != b]
check("100k: the rewritten floor_100k.prm differs only in output directory and progress",
      len(committed) == len(rewritten) and all(a[1] in ("Output", "Progress") for a, _ in differing),
      f"{differing}")


def run(*options):
    out = os.path.join(WORK, "runs.json")
    if os.path.exists(out):
        os.remove(out)
    p = subprocess.run([SCRIPT, "--build", BUILD, "--work", os.path.join(WORK, "runs"),
                        "--json", out] + list(options), capture_output=True, text=True)
    print(p.stdout[-4000:], p.stderr[-2000:])
    if p.returncode != 0:
        check(f"run.py {' '.join(options)} succeeds", False, f"exit {p.returncode}")
        finish()
    return json.load(open(out)), p.stdout


steps = 20
floor, text = run("--sizes", "1k", "3d-1k", "--threads", "1", "2", "--steps", str(steps))
box, _ = run("--problem", "box", "--sizes", "1k", "--threads", "1", "--steps", str(steps))

# points: n^dim body cells of 2^dim points, n the whole number closest to
# (points / 2^dim)^(1/dim): 2D 1k -> n = 16, 3D 1k -> n = 5; the floor's
# grid has 2n cells per direction, the box's n
expected = {("floor", 2): (1024, 1024), ("floor", 3): (1000, 1000), ("box", 2): (1024, 256)}
for problem, runs in (("floor", floor), ("box", box)):
    for r in runs:
        points, cells = expected[(problem, r["dim"])]
        check(f"{problem} {r['case']} {r['threads']} thread(s): {points} points, {cells} cells",
              (r["points"], r["cells"]) == (points, cells), f"got {r['points']}, {r['cells']}")
        check(f"{problem} {r['case']}: {steps} steps", r["steps"] == steps, f"got {r['steps']}")
        loop = r["loop_seconds"]
        phases = r["phases_seconds"]
        # TimerOutput prints 3 significant digits: the top-level sections of
        # the step add up to at most the loop (they are timed inside it)
        # plus their rounding (0.5% each)
        inside = sum(s for p, s in phases.items() if p != "other")
        check(f"{problem} {r['case']}: phases within the loop time",
              0 < inside <= 1.03 * loop, f"sum {inside} s, loop {loop} s")
        check(f"{problem} {r['case']}: the transfers and the stress update were parsed",
              all(phases[p] > 0 for p in ("particles to grid", "grid to particles",
                                          "stress update")), f"{phases}")
        check(f"{problem} {r['case']}: ns per particle-step from the loop time",
              abs(r["ns_per_particle_step"] - 1e9 * loop / (points * steps))
              <= 1e-9 * r["ns_per_particle_step"], f"{r['ns_per_particle_step']}")
        # sable with deal.II, MPI and TBB loaded is above 10 MiB, a 1k scene
        # below 2 GiB: a KiB count in that range was parsed as such
        check(f"{problem} {r['case']}: peak RSS parsed",
              10 * 1024 < r["peak_rss_kib"] < 2 * 1024 ** 2, f"{r['peak_rss_kib']} KiB")

for case in ("2D 1k", "3D 1k"):
    runs = [r for r in floor if r["case"] == case]
    check(f"{case}: 1 and 2 threads ran", sorted(r["threads"] for r in runs) == [1, 2])
    check(f"{case}: statistics.csv identical for 1 and 2 threads",
          runs[0]["statistics"] == runs[1]["statistics"])
    check(f"{case}: reported identical", f"{case}: statistics.csv identical" in text)

# a size that is no point count is refused before any run, naming it
p = subprocess.run([SCRIPT, "--build", BUILD, "--sizes", "10q"], capture_output=True, text=True)
check("a bad size is refused, naming it", p.returncode != 0 and "'10q'" in p.stderr, p.stderr)

finish()
