"""Helpers for tests that run the `sable` program on a generated scene and
check its statistics.csv against analytic solutions.

The environment gives SABLE (program), SABLE_WORK (scratch directory) and
MPIEXEC; see tests/CMakeLists.txt."""
import csv
import os
import shutil
import subprocess
import sys

SABLE = os.environ.get("SABLE", "sable")
WORK = os.environ.get("SABLE_WORK", "scene_test.work")
MPIEXEC = os.environ.get("MPIEXEC", "mpirun")

failures = []


def prm_text(entries, bodies):
    """Build a parameter file: `entries` maps 'Subsection/Entry' (or 'Entry')
    to a value; `bodies` is a list of dicts of body entries ('Entry', or
    'Subsection/Entry' for a material model's own entries). MPM scenes get
    'Output/Statistics interval = 1' unless they set it: the checks read the
    statistics of every step (the program's default writes them only with
    particle output and progress lines)."""
    if entries.get("Model", "mpm") == "mpm" and "Output/Statistics interval" not in entries:
        entries = dict(entries, **{"Output/Statistics interval": 1})
    top = []
    sections = {}
    for key, value in entries.items():
        if "/" in key:
            section, entry = key.split("/", 1)
            sections.setdefault(section, []).append((entry, value))
        else:
            top.append((key, value))
    lines = [f"set {k} = {v}" for k, v in top]
    lines.append(f"set Number of bodies = {len(bodies)}")
    for section, items in sections.items():
        lines.append(f"subsection {section}")
        lines += [f"  set {k} = {v}" for k, v in items]
        lines.append("end")
    for b, body in enumerate(bodies):
        lines.append(f"subsection Body {b}")
        lines += [f"  set {k} = {v}" for k, v in body.items() if "/" not in k]
        # a material model's own entries: 'von Mises/Yield stress'
        nested = {}
        for key, value in body.items():
            if "/" in key:
                section, entry = key.split("/", 1)
                nested.setdefault(section, []).append((entry, value))
        for section, items in nested.items():
            lines.append(f"  subsection {section}")
            lines += [f"    set {k} = {v}" for k, v in items]
            lines.append("  end")
        lines.append("end")
    return "\n".join(lines) + "\n"


def run(name, entries, bodies, ranks=0, expect_success=True, args=(), fresh=True, timeout=None):
    """Run a scene in WORK/name (emptied first unless not `fresh`), with
    extra program arguments `args`; return (returncode, stdout+stderr, rows)."""
    directory = os.path.join(WORK, name)
    if fresh:
        shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory, exist_ok=True)
    entries = dict(entries)
    entries.setdefault("Output directory", "output")
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write(prm_text(entries, bodies))
    command = [SABLE, "scene.prm"] + list(args)
    if ranks:
        command = [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    result = subprocess.run(command, cwd=directory, capture_output=True, text=True, timeout=timeout)
    output = result.stdout + result.stderr
    if expect_success and result.returncode != 0:
        print(output)
        raise SystemExit(f"[FAIL] {name}: sable exited with {result.returncode}")
    rows = read_csv(os.path.join(directory, entries["Output directory"], "statistics.csv"))
    return result.returncode, output, rows


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def check(what, condition, detail=""):
    print(("[ ok ] " if condition else "[FAIL] ") + what + (f": {detail}" if detail else ""))
    if not condition:
        failures.append(what)


def check_relative(what, value, expected, tolerance):
    error = abs(value - expected) / max(abs(expected), 1e-300)
    check(what, error <= tolerance,
          f"value {value:.10g}, expected {expected:.10g}, relative error {error:.3g} (tolerance {tolerance:g})")


def finish():
    print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
    sys.exit(1 if failures else 0)
