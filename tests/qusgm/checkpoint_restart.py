#!/usr/bin/python3
"""QuSGM checkpoint/restart: the demo scene (preparation, then ten
uniaxial-strain increments) run without a stop, against runs stopped after
five increments of the load path with 'Checkpoint interval = 2' (so the
last checkpoint is after increment four and the fifth row of the stopped
run must be cut from increments.csv) and resumed with `--resume` to ten:

- stopped on 2 ranks, resumed on 1;
- stopped on 1 rank, resumed on 2;
- stopped on 1 rank, the newest checkpoint damaged (its state file cut
  short) with a complete 'checkpoint.old' beside it: the resume names the
  damage and continues from the old one.

Each resumed increments.csv and final pack must agree with the
uninterrupted run to 1e-12 relative (the issue's bound; a checkpoint holds
the equilibrium and every contact's reference loads, so the runs agree
bit for bit). Resuming where no checkpoint exists is refused with a
message naming the directory and the parameter that writes checkpoints."""
import csv
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mpm"))
from scene_test import SABLE, WORK, MPIEXEC, check, failures  # noqa: E402

SOURCE = os.environ.get("SABLE_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))


def write_scene(directory, increments):
    with open(os.path.join(SOURCE, "prm", "qusgm_demo.prm")) as f:
        scene = f.read()
    scene = re.sub(r"set Number of increments = \d+", f"set Number of increments = {increments}", scene)
    scene = scene.replace("subsection Output\n", "subsection Output\n  set Checkpoint interval = 2\n", 1)
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write("set Output directory = output\n" + scene)


def run(name, increments, ranks=1, resume=False, expect_success=True):
    directory = os.path.join(WORK, name)
    if not resume:
        shutil.rmtree(directory, ignore_errors=True)
        os.makedirs(directory)
    write_scene(directory, increments)
    command = [SABLE, "scene.prm"] + (["--resume"] if resume else [])
    if ranks > 1:
        command = [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    result = subprocess.run(command, cwd=directory, capture_output=True, text=True, timeout=500)
    output = result.stdout + result.stderr
    if expect_success and result.returncode != 0:
        print(output)
        raise SystemExit(f"[FAIL] {name}: sable exited with {result.returncode}")
    return result.returncode, output, os.path.join(directory, "output")


def table(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def compare(what, reference_output, output):
    reference = table(os.path.join(reference_output, "increments.csv"))
    rows = table(os.path.join(output, "increments.csv"))
    check(f"{what}: as many rows as the uninterrupted run", len(rows) == len(reference),
          f"{len(rows)} vs {len(reference)}")
    worst, where = 0.0, ""
    for a, b in zip(reference, rows):
        if a["stage"] != b["stage"]:
            worst, where = float("inf"), f"stage at increment {a['increment']}"
            break
        for k in a:
            if k in ("stage", "wall_time", "stopped_by"):
                continue
            if a[k] == "" or b[k] == "":  # undefined: on both sides
                if a[k] != b[k]:
                    worst, where = float("inf"), f"{k} undefined on one side at increment {a['increment']}"
                continue
            x, y = float(a[k]), float(b[k])
            if x != x and y != y:
                continue
            error = abs(x - y) / max(abs(x), 1e-300) if x != y else 0.0
            if error > worst:
                worst, where = error, f"{k} at increment {a['increment']}"
    check(f"{what}: increments.csv within 1e-12 of the uninterrupted run", worst <= 1e-12,
          f"largest relative difference {worst:.2e} {where}")
    for name in ("grains", "contacts", "wall_contacts"):
        a, b = (table(os.path.join(d, "final_state", name + ".csv")) for d in (reference_output, output))
        same = len(a) == len(b) and all(
            abs(float(p[k]) - float(q[k])) <= 1e-12 * abs(float(p[k]))
            for p, q in zip(a, b) for k in p if k != "wall")
        check(f"{what}: final state {name} within 1e-12", same)


_, _, reference = run("uninterrupted", 10)

# no checkpoint yet: a clear refusal
directory = os.path.join(WORK, "nothing")
shutil.rmtree(directory, ignore_errors=True)
os.makedirs(directory)
write_scene(directory, 10)
result = subprocess.run([SABLE, "scene.prm", "--resume"], cwd=directory, capture_output=True, text=True)
message = result.stdout + result.stderr
check("resume without a checkpoint: refused, naming the directory and 'Checkpoint interval'",
      result.returncode != 0 and "no complete checkpoint" in message and "Checkpoint interval" in message,
      message.strip().splitlines()[-1] if message.strip() else "(no message)")

for stop_ranks, resume_ranks in ((2, 1), (1, 2)):
    name = f"stop_np{stop_ranks}_resume_np{resume_ranks}"
    _, _, output = run(name, 5, ranks=stop_ranks)
    check(f"{name}: the stopped run wrote five load-path rows past the checkpoint's four",
          len(table(os.path.join(output, "increments.csv"))) ==
          len(table(os.path.join(reference, "increments.csv"))) - 5)
    _, log, output = run(name, 10, ranks=resume_ranks, resume=True)
    check(f"{name}: resumed after increment 4 of the load path",
          "after 4 increment(s) of the load path" in log)
    compare(name, reference, output)

# a damaged newest checkpoint beside a complete old one
name = "damaged"
_, _, output = run(name, 5)
checkpoint = os.path.join(output, "checkpoint")
shutil.copytree(checkpoint, checkpoint + ".old")
state = os.path.join(checkpoint, "qusgm.state")
with open(state, "r+b") as f:
    f.truncate(os.path.getsize(state) // 2)
_, log, output = run(name, 10, resume=True)
check("damaged: the resume names the damaged file and uses checkpoint.old",
      "qusgm.state" in log and "checkpoint.old" in log, log.splitlines()[0] if log else "")
compare(name, reference, output)

sys.exit(1 if failures else 0)
