#!/usr/bin/env python3
"""The command line option --set "Subsection/Entry=value" (also --set=...,
repeatable) changes entries of a scene after its file is read.

1. A setting that names no entry of the scene (an unknown entry or
   subsection, a body beyond 'Number of bodies'), a value outside the
   entry's pattern or outside what sable allows, and a malformed or missing
   argument stop the program before any work: non-zero exit, a message
   naming the setting, and no output written (an existing statistics.csv
   is left untouched).
2. Good settings change the run: a step limit, the gravity (the last of two
   settings of an entry wins), a second body added with 'Number of bodies'
   and its 'Body 1' entries (read in the program's second pass), the same
   for MPM with --set=; for QuSGM (prm/qusgm_demo.prm with a smaller pack)
   the number of load increments, and a bad QuSGM entry is refused the same
   way."""
import os
import subprocess

from scene_test import *

SOURCE = os.environ.get("SABLE_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
g = -9.81
entries = {"Dimension": 2, "Gravity": f"0, {g}", "Time/End time": 0.01,
           "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "10, 10"}
body = {"Shape": "disk", "Center": "0.3, 0.5", "Radius": 0.15, "Young's modulus": 1e6,
        "Poisson's ratio": 0.3, "Density": 1000}

# 1. bad settings: (name, arguments, words the message must contain)
cases = [
    ("unknown_entry", ["--set", "Time/Frobnication=1"],
     ["Time/Frobnication = 1", "--set", "no entry 'Frobnication' in subsection 'Time'"]),
    ("unknown_subsection", ["--set", "Tme/End time=1"], ["Tme/End time", "no subsection 'Tme'"]),
    ("unknown_top_level", ["--set=Frobnication=1"], ["Frobnication", "no entry 'Frobnication' at the top level"]),
    ("body_beyond_count", ["--set", "Body 1/Radius=0.1"], ["Body 1/Radius", "no subsection 'Body 1'"]),
    ("pattern", ["--set", "Time/End time=soon"], ["Time/End time = soon", "Double"]),
    ("dimension", ["--set", "Dimension=4"], ["Dimension = 4", "Integer range 2...3"]),
    ("checked_by_sable", ["--set", "Body 0/Density=-5"], ["Density", "-5", "> 0"]),
    ("no_equal_sign", ["--set", "Time/End time"], ["--set", "Time/End time", "Entry=value"]),
    ("empty_name", ["--set", "Time//End time=1"], ["--set", "Time//End time=1"]),
    ("missing_argument", ["--set"], ["--set", "(missing)"]),
]
for name, arguments, words in cases:
    directory = os.path.join(WORK, name)
    os.makedirs(os.path.join(directory, "output"), exist_ok=True)
    sentinel = os.path.join(directory, "output", "statistics.csv")
    with open(sentinel, "w") as f:
        f.write("previous run\n")
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write(prm_text(dict(entries, **{"Output directory": "output"}), [body]))
    command = [SABLE, "scene.prm"] + arguments
    result = subprocess.run(command, cwd=directory, capture_output=True, text=True)
    message = result.stdout + result.stderr
    check(f"{name}: non-zero exit", result.returncode != 0, f"exit code {result.returncode}")
    missing = [w for w in words if w not in message]
    check(f"{name}: message names {words}", not missing,
          message.strip().splitlines()[-1] if message.strip() else "(no message)")
    check(f"{name}: no step taken", "step " not in result.stdout)
    with open(sentinel) as f:
        check(f"{name}: existing output untouched", f.read() == "previous run\n")
    check(f"{name}: nothing else written", os.listdir(os.path.join(directory, "output")) == ["statistics.csv"])

# 2. good settings
_, _, full = run("full", entries, [body])
check("without --set: the scene runs to its End time, past step 3", len(full) > 5, f"{len(full)} rows")

_, out, rows = run("step_limit", entries, [body], args=["--set", "Time/Maximum number of steps=3"])
check("--set 'Time/Maximum number of steps=3': three steps",
      [int(r["step"]) for r in rows] == [0, 1, 2, 3], f"steps {[int(r['step']) for r in rows]}")
check("the step-limited run matches the full one where they overlap",
      all(a == b for a, b in zip(rows, full)))

_, out, rows = run("gravity", entries, [body], args=["--set", "Gravity=0, -5", "--set=Gravity = 0, -20"])
worst = max(abs(r["body0_vy"] - (-20) * r["time"]) for r in rows)
check("--set Gravity twice: the last one (g = -20) acts, v = g t", worst < 1e-9 * 20 * rows[-1]["time"],
      f"max |v_y - g t| = {worst:.3g}")

second = {"Shape": "disk", "Center": "0.7, 0.5", "Radius": "0.1", "Young's modulus": "1e6",
          "Poisson's ratio": "0.3", "Density": "2000", "Velocity": "0, 1"}
arguments = ["--set", "Number of bodies=2"]
for key, value in second.items():
    arguments += ["--set", f"Body 1/{key}={value}"]
_, out, rows = run("second_body", entries, [body], args=arguments)
check("--set 'Number of bodies=2' with 'Body 1/...' settings: a second body",
      rows and "body1_vy" in rows[0] and abs(rows[0]["body1_vy"] - 1) < 1e-12,
      f"columns {sorted(rows[0])[:6] if rows else None}..., body1_vy(0) = {rows[0].get('body1_vy') if rows else None}")

# QuSGM: the demo scene with a smaller pack, shortened on the command line
scene = os.path.join(SOURCE, "prm", "qusgm_demo.prm")
smaller = ["--set", "Pack/Number of grains=60", "--set", "Preparation/Target confining stress=2e6",
           "--set", "Preparation/Maximum activation increments=5"]
for increments in (1, 2):
    directory = os.path.join(WORK, f"qusgm_{increments}")
    result = subprocess.run([SABLE, scene, "--overwrite", "--set", f"Output directory={directory}",
                             "--set", f"Load path/Number of increments={increments}"] + smaller,
                            capture_output=True, text=True)
    tested = []
    if result.returncode == 0:
        with open(os.path.join(directory, "increments.csv")) as f:
            tested = [line for line in f if ",test," in line]
    check(f"QuSGM --set 'Load path/Number of increments={increments}': that many increments",
          result.returncode == 0 and len(tested) == increments, f"exit {result.returncode}, {len(tested)} increments")
directory = os.path.join(WORK, "qusgm_bad")
result = subprocess.run([SABLE, scene, "--set", f"Output directory={directory}",
                         "--set", "Load path/Number of increment=1"], capture_output=True, text=True)
check("QuSGM: unknown entry refused before any work",
      result.returncode != 0 and "no entry 'Number of increment' in subsection 'Load path'" in result.stderr
      and not os.path.exists(directory), result.stderr.strip())
finish()
