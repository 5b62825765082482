#!/usr/bin/env python3
"""Smoke test of a committed scene: parse prm/<scene>.prm and run it for a
few steps (MPM) or load increments (QuSGM), shortened on the command line
with --set, into a scratch output directory. Passes if sable exits with 0
and wrote statistics.csv (MPM) or increments.csv (QuSGM) with the rows the
shortened run must have. No numbers are checked: that is the regression
layer's job (regression.py) and the physics tests'.

    smoke.py <scene.prm>

A scene added to prm/ is covered without changes here (tests/regression/
CMakeLists.txt finds prm/*.prm when the build is configured); it runs with
the default shortening of its model unless SHORTENED below names it."""
import csv
import os
import re
import shutil
import subprocess
import sys

SABLE = os.environ.get("SABLE", "sable")
if os.sep in SABLE:  # a path: the scene runs in the scratch directory
    SABLE = os.path.abspath(SABLE)
WORK = os.environ.get("SABLE_WORK", "smoke.work")

MPM_STEPS = 5
# MPM: a few steps. Particle output (the first file is written at t = 0)
# and checkpoints stay as the scene sets them, so that their code runs too.
MPM_DEFAULT = [f"Time/Maximum number of steps={MPM_STEPS}"]
# QuSGM: the pack preparation as the scene sets it, then one increment of
# the load path.
QUSGM_DEFAULT = ["Load path/Number of increments=1"]

# Scenes that are too heavy for the defaults (each should stay under ~20 s
# on two shared cores), with the reason.
SHORTENED = {
    # 2740 grains: preparing the pack alone takes about a minute. A pack of
    # 150 grains with the scene's other entries (radii, moduli, walls,
    # preparation stages, minimiser) runs every stage in seconds.
    "g2740": ["Pack/Number of grains=150", "Preparation/Maximum activation increments=10",
              "Load path/Number of increments=1"],
}


def model_of(scene):
    """'mpm' or 'qusgm', as the program reads 'set Model' (default mpm)."""
    model = "mpm"
    with open(scene) as f:
        for line in f:
            match = re.match(r"\s*set\s+Model\s*=\s*(\w+)", line.split("#")[0])
            if match:
                model = match.group(1)
    return model


def main():
    scene = os.path.abspath(sys.argv[1])
    name = os.path.splitext(os.path.basename(scene))[0]
    model = model_of(scene)
    settings = SHORTENED.get(name, QUSGM_DEFAULT if model == "qusgm" else MPM_DEFAULT)

    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    output = os.path.join(os.path.abspath(WORK), "output")
    command = [SABLE, scene, "--set", f"Output directory={output}"]
    for setting in settings:
        command += ["--set", setting]
    print(" ".join(f"'{c}'" if " " in c else c for c in command), flush=True)
    result = subprocess.run(command, cwd=WORK, capture_output=True, text=True)
    print(result.stdout[-2000:] + result.stderr)
    if result.returncode != 0:
        sys.exit(f"[FAIL] {name}: sable exited with {result.returncode}")

    table = os.path.join(output, "increments.csv" if model == "qusgm" else "statistics.csv")
    if not os.path.exists(table):
        sys.exit(f"[FAIL] {name}: {table} not written")
    with open(table) as f:
        rows = list(csv.DictReader(f))
    if model == "qusgm":
        tested = [r for r in rows if r.get("stage") == "test"]
        ok = len(tested) == 1
        detail = f"{len(rows)} rows, {len(tested)} of the load path (expected 1)"
    else:
        steps = [int(r["step"]) for r in rows]
        # a scene may end before the step limit (End time), never after it
        ok = bool(steps) and steps[-1] <= MPM_STEPS
        detail = f"{len(rows)} rows, last step {steps[-1] if steps else None} (limit {MPM_STEPS})"
    print(("[ ok ] " if ok else "[FAIL] ") + f"{name}: {os.path.basename(table)} written, {detail}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
