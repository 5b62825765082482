#!/usr/bin/python3
"""Throughput of the single-field MPM step, one MPI rank, 1 and 2 threads.

Problems (2x2 or 2x2x2 points per cell, linear elastic, MUSL, output off):
  floor  (default) issue 13's problem, floor_100k.prm beside this script: a
         1 m square (cube) dropped on a fixed floor under gravity in a 2 m
         grid, three quarters (seven eighths in 3D) of it empty, 1,000 steps;
  box    a box filling a 1 m grid, slip walls, moving at (0.1, 0.05) m/s
         (the earlier throughput entries of doc/benchmarks.md, 200 steps).
A size is a point count, '10k', '400k', '3d-260k', '2d-1.5M': the body gets
the whole number of cells per direction whose points come closest to it.

Per run it prints the time loop's wall time ('Finished ... s wall time',
setup excluded, the statistics of the first and last step included), ns
per particle-step, the split per phase (the program's TimerOutput
sections; 'other' is the rest of the loop: the time step, the checks
between steps, the progress line), the
peak resident set size of the sable process (getrusage's ru_maxrss of the
child, what `/usr/bin/time -v` prints as 'Maximum resident set size') and
that per point, and the load average and idle CPU (over one second)
before the run: the machine may be shared. At the end: a Markdown table of all runs, the speed-up of each
phase from 1 to 2 threads, and whether statistics.csv is identical for
every thread count (it must be; the times compare the same results).

Usage: contrib/benchmarks/throughput/run.py [--sizes 10k 100k 400k 3d-260k]
       [--threads 1 2] [--steps 1000] [--repetitions 1] [--problem floor]
       [--build build] [--work DIR] [--json FILE] [--quiet-wait SECONDS]
       [--set 'Sec/Entry=value' ...]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
FLOOR_PRM = os.path.join(HERE, "floor_100k.prm")
DEFAULT_STEPS = {"floor": 1000, "box": 200}

# top-level TimerOutput sections of the step, in the order of the step;
# sections named '... (in ...)' are parts of another and not summed; a
# section absent from a log (an older sable) counts 0 s
PHASES = ["list cells with points", "particles to grid", "grid update and boundaries",
           "grid to particles", "stress update", "sort particles", "statistics"]
SHORT = {"list cells with points": "cells", "particles to grid": "P2G", "grid update and boundaries": "grid",
         "grid to particles": "G2P", "stress update": "stress", "sort particles": "sort",
         "statistics": "stats", "other": "other"}


def parse_size(text):
    """'100k' -> (2, 100000), '3d-260k' -> (3, 260000)."""
    m = re.fullmatch(r"(?:([23])[dD]-)?([0-9]*\.?[0-9]+)([kKM]?)", text)
    if not m:
        raise argparse.ArgumentTypeError(
            f"size '{text}': expected a point count such as 10k, 400k, 3d-260k or 2d-1.5M")
    dim = int(m.group(1) or 2)
    points = float(m.group(2)) * {"": 1, "k": 1e3, "K": 1e3, "M": 1e6}[m.group(3)]
    if not 1 <= points <= 1e9:
        raise argparse.ArgumentTypeError(f"size '{text}': {points:g} points is not in [1, 1e9]")
    return dim, int(points), text


def positive(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value} is not a whole number >= 1")
    return value


def scene(problem, dim, points, out, steps):
    """The entries of one case that differ from floor_100k.prm, and the body's cells
    per direction: the whole number n whose n^dim cells of 2^dim points
    come closest to `points`."""
    n = max(1, round((points / 2 ** dim) ** (1 / dim)))
    vec = lambda *v: ", ".join(str(x) for x in v[:dim])
    if problem == "floor":
        # a 2 m grid of 2n cells per direction; the body's n cells start
        # on a grid line near the middle, on the floor (y = 0)
        h = 1 / n
        x0 = (n // 2) * h
        sets = {"Dimension": dim,
                "Gravity": vec(0, -9.81, 0),
                "Grid/Lower corner": vec(0, 0, 0),
                "Grid/Upper corner": vec(2, 2, 2),
                "Grid/Subdivisions": vec(2 * n, 2 * n, 2 * n),
                "Body 0/Lower corner": vec(x0, 0, x0),
                "Body 0/Upper corner": vec(x0 + 1, 1, x0 + 1)}
    else:
        walls = ", ".join(f"{b}: slip" for b in range(2 * dim))
        sets = {"Dimension": dim,
                "Gravity": vec(0, 0, 0),
                "Grid/Lower corner": vec(0, 0, 0),
                "Grid/Upper corner": vec(1, 1, 1),
                "Grid/Subdivisions": vec(n, n, n),
                "Boundary conditions/Types": walls,
                "Body 0/Lower corner": vec(0, 0, 0),
                "Body 0/Upper corner": vec(1, 1, 1),
                "Body 0/Velocity": vec(0.1, 0.05, 0)}
    sets.update({"Output directory": out, "Time/Maximum number of steps": steps,
                 "Output/Progress interval": steps})
    return sets, n


def write_scene(sets, path):
    """floor_100k.prm with the entries of @p sets it holds replaced (the
    file is read in the scene's dimension: a 2D vector would not parse in
    3D, so --set after it is not enough); the rest of @p sets as --set."""
    left = dict(sets)
    lines, section = [], []
    for line in open(FLOOR_PRM):
        words = line.split()
        if words[:1] == ["subsection"]:
            section.append(line.split(None, 1)[1].strip())
        elif words[:1] == ["end"]:
            section.pop()
        elif words[:1] == ["set"]:
            entry = line.split(None, 1)[1].split("=", 1)[0].strip()
            key = "/".join(section + [entry])
            if key in left:
                line = f"{'  ' * len(section)}set {entry} = {left.pop(key)}\n"
        lines.append(line)
    with open(path, "w") as f:
        f.writelines(lines)
    args = [path]
    for key, value in left.items():
        args += ["--set", f"{key}={value}"]
    return args


def parse_log(text):
    """Points, cells, sorts, the loop's wall time and the TimerOutput
    sections (wall seconds) of a sable log."""
    head = re.search(r"(\d+) cells, (\d+) material points", text)
    done = re.search(r"Finished (\d+) steps .* in ([0-9.e+-]+) s wall time", text)
    sorts = re.search(r"Particle sort in (\d+) of (\d+) steps", text)
    if not (head and done and sorts):
        raise RuntimeError("the sable log lacks the header, the timing summary or the "
                           "'Finished' line:\n" + text[-2000:])
    sections = {}
    for m in re.finditer(r"^\| (.+?)\s+\|\s+(\d+) \|\s+([0-9.e+-]+)(m?)s \|", text, re.M):
        sections[m.group(1)] = float(m.group(3)) * (1e-3 if m.group(4) else 1)
    return {"cells": int(head.group(1)), "points": int(head.group(2)),
            "steps": int(done.group(1)), "loop_seconds": float(done.group(2)),
            "sorts": int(sorts.group(1)), "sections": sections}


def points_label(label):
    return label.split("-")[-1]


def idle_percent():
    """Idle CPU time of all cores over the next second, in per cent."""
    def sample():
        with open("/proc/stat") as f:
            ticks = [int(x) for x in f.readline().split()[1:9]]
        return ticks[3], sum(ticks)
    idle0, total0 = sample()
    time.sleep(1)
    idle1, total1 = sample()
    return 100 * (idle1 - idle0) / max(total1 - total0, 1)


def wait_quiet(seconds):
    """On a shared machine: wait up to @p seconds for a second with at
    least 90% idle CPU; the idle percentage last seen."""
    start = time.time()
    idle = idle_percent()
    while idle < 90 and time.time() - start < seconds:
        time.sleep(4)
        idle = idle_percent()
    return idle


def run_case(args, case, threads, repetition, work):
    dim, target, label = case
    name = f"{args.problem}-{dim}d-{points_label(label)}-t{threads}-r{repetition}"
    out = os.path.join(work, name)
    # the box is the floor's scene with other grid, walls and body entries
    sets, n = scene(args.problem, dim, target, out, args.steps)
    command = [args.sable, "--overwrite", "--threads", str(threads)] + \
        write_scene(sets, os.path.join(work, name + ".prm"))
    for s in args.set:
        command += ["--set", s]
    idle = wait_quiet(args.quiet_wait)
    load = open("/proc/loadavg").read().split()[0]
    log_path = os.path.join(work, name + ".log")
    with open(log_path, "w") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        # this child's own rusage: its peak resident set size in KiB
        _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    text = open(log_path).read()
    if process.returncode != 0:
        sys.exit(f"sable failed ({process.returncode}): {' '.join(command)}\n{text[-3000:]}")
    r = parse_log(text)
    loop = r["loop_seconds"]
    phases = {p: r["sections"].get(p, 0.0) for p in PHASES}
    phases["other"] = loop - sum(phases.values())
    particle_steps = r["points"] * r["steps"]
    result = {"case": f"{dim}D {points_label(label)}", "dim": dim, "cells_per_direction": n,
              "points": r["points"], "cells": r["cells"], "threads": threads,
              "repetition": repetition, "steps": r["steps"], "sorts": r["sorts"],
              "loop_seconds": loop, "ns_per_particle_step": 1e9 * loop / particle_steps,
              "phases_seconds": phases,
              "initialize_seconds": r["sections"].get("initialize", 0.0),
              "peak_rss_kib": usage.ru_maxrss,
              "kib_per_point": usage.ru_maxrss / r["points"],
              "load_before": float(load), "idle_before": idle,
              "statistics": open(os.path.join(out, "statistics.csv")).read()}
    return result


def print_run(r):
    phases = ", ".join(f"{p} {s:.3g} s ({100 * s / r['loop_seconds']:.0f}%)"
                       for p, s in r["phases_seconds"].items())
    print(f"{r['case']}: {r['points']:,} points, {r['cells']:,} cells, {r['threads']} thread(s), "
          f"run {r['repetition']}, load {r['load_before']:.2f} and {r['idle_before']:.0f}% idle before: {r['steps']} steps "
          f"(sort in {r['sorts']}) in {r['loop_seconds']:.3g} s, "
          f"{r['ns_per_particle_step']:.0f} ns per particle-step, peak RSS "
          f"{r['peak_rss_kib'] / 1024:.0f} MiB = {r['kib_per_point']:.2f} KiB per point\n"
          f"  {phases}", flush=True)


def print_tables(results):
    names = list(results[0]["phases_seconds"])
    print("\n| case | points | threads | run | load, idle | sorts/steps | loop s | ns/particle-step | "
          + " | ".join(f"{SHORT[p]} ns" for p in names) + " | peak RSS MiB | KiB/point |")
    print("|" + "---|" * (12 + len(names) - 2))
    for r in results:
        per = 1e9 / (r["points"] * r["steps"])
        print(f"| {r['case']} | {r['points']:,} | {r['threads']} | {r['repetition']} | "
              f"{r['load_before']:.1f}, {r['idle_before']:.0f}% | {r['sorts']}/{r['steps']} | {r['loop_seconds']:.3g} | "
              f"**{r['ns_per_particle_step']:.0f}** | "
              + " | ".join(f"{per * r['phases_seconds'][p]:.0f}" for p in names)
              + f" | {r['peak_rss_kib'] / 1024:.0f} | {r['kib_per_point']:.2f} |")

    pairs = [(a, b) for a in results for b in results
             if a["case"] == b["case"] and a["repetition"] == b["repetition"]
             and a["threads"] == 1 and b["threads"] == 2]
    if pairs:
        print("\nSpeed-up from 1 to 2 threads (time with 1 / time with 2):\n")
        print("| case | run | loop | " + " | ".join(SHORT[p] for p in names) + " |")
        print("|" + "---|" * (3 + len(names)))
        for a, b in pairs:
            ratio = lambda x, y: f"{x / y:.2f}" if y > 0 else "–"
            print(f"| {a['case']} | {a['repetition']} | "
                  f"**{ratio(a['loop_seconds'], b['loop_seconds'])}** | "
                  + " | ".join(ratio(a["phases_seconds"][p], b["phases_seconds"][p])
                               for p in names) + " |")

    # the fixed part of the memory (program, libraries, grid of the
    # smallest case) against the part that grows with the problem
    ones = sorted((r for r in results if r["threads"] == 1 and r["repetition"] == 1),
                  key=lambda r: (r["dim"], r["points"]))
    for a, b in zip(ones, ones[1:]):
        if a["dim"] == b["dim"]:
            print(f"\nPeak RSS growth from {a['case']} to {b['case']}: "
                  f"{(b['peak_rss_kib'] - a['peak_rss_kib']) / (b['points'] - a['points']):.2f} "
                  f"KiB per added point (the grid grows with the points)")

    for case in dict.fromkeys(r["case"] for r in results):
        runs = [r for r in results if r["case"] == case]
        same = all(r["statistics"] == runs[0]["statistics"] for r in runs)
        print(f"{case}: statistics.csv {'identical' if same else 'DIFFERENT'} "
              f"in all {len(runs)} runs (threads {sorted({r['threads'] for r in runs})})")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--problem", choices=["floor", "box"], default="floor")
    parser.add_argument("--sizes", nargs="+", type=parse_size,
                        default=[parse_size(s) for s in ["10k", "100k", "400k", "3d-260k"]],
                        help="point counts, e.g. 10k 100k 400k 3d-260k (the default)")
    parser.add_argument("--threads", nargs="+", type=positive, default=[1, 2])
    parser.add_argument("--steps", type=positive,
                        help="steps per run (default: floor 1000, box 200)")
    parser.add_argument("--repetitions", type=positive, default=1,
                        help="runs of every case; the thread counts alternate within one")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="build directory holding the sable program (default: build/)")
    parser.add_argument("--work", help="directory for the runs' outputs and logs, kept "
                        "(default: a temporary directory, removed at the end)")
    parser.add_argument("--quiet-wait", type=float, default=0, metavar="SECONDS",
                        help="before each run wait up to this long for a second with at "
                        "least 90%% idle CPU (default 0: just measure it)")
    parser.add_argument("--json", help="write every run's numbers to this file")
    parser.add_argument("--set", action="append", default=[], metavar="'Sec/Entry=value'",
                        help="passed on to every run (e.g. 'Solver/Update scheme=usl')")
    args = parser.parse_args()
    if args.steps is None:
        args.steps = DEFAULT_STEPS[args.problem]
    args.sable = os.path.join(os.path.abspath(args.build), "sable")
    if not os.access(args.sable, os.X_OK):
        parser.error(f"--build {args.build}: no sable program in it ({args.sable})")

    work = os.path.abspath(args.work) if args.work else tempfile.mkdtemp(prefix="throughput-")
    os.makedirs(work, exist_ok=True)
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True).stdout.strip()
        model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
                      if l.startswith("model name")), "?")
        print(f"# {args.problem}, {args.steps} steps, commit {commit or '?'}, "
              f"{model}, {os.cpu_count()} cores, sable {args.sable}", flush=True)
        results = []
        for case in args.sizes:
            for repetition in range(1, args.repetitions + 1):
                for threads in args.threads:
                    results.append(run_case(args, case, threads, repetition, work))
                    print_run(results[-1])
        print_tables(results)
        if args.json:
            with open(args.json, "w") as f:
                json.dump(results, f, indent=1)
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
