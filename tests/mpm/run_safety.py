#!/usr/bin/python3
"""Runs that never clobber or mislead:

1. a fresh run into a directory holding an earlier run's results is refused
   (naming the directory, --overwrite and --resume) and changes nothing;
   --overwrite removes the earlier outputs (stale particle files too) and
   keeps unrelated files; the same for a QuSGM run;
2. a lock file against a second run into the same directory: a running
   holder is named (process id and host), a dead holder's lock is taken
   over with a note, the lock goes on normal exit and on errors;
3. --resume refuses a scene whose materials, grid, bodies, boundaries or
   contact differ from the checkpoint's, naming each entry with both
   values, and accepts a new end time; a checkpoint of an older format is
   refused with a message saying so;
4. include lines are read relative to the including file, a missing one
   is named;
5. a scene far beyond the machine's memory is refused at once, naming the
   entry, the need and the available memory;
6. an output directory that cannot be created, a statistics file (MPM and
   QuSGM) and a checkpoint that cannot be written (a file size limit, as a
   full disk would) are reported by sable with the path; the earlier
   checkpoint survives.
(Unknown boundary ids are refused in bad_input.py.)"""
import hashlib
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import time
import zlib
from scene_test import *

entries = {"Dimension": 2, "Time/End time": 1, "Time/Maximum number of steps": 20, "Gravity": "0, -10",
           "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "10, 10",
           "Boundary conditions/Types": "2: fixed", "Output/Particle output interval": 1e-4,
           "Output/Checkpoint interval": 10}
body = {"Shape": "disk", "Center": "0.5, 0.5", "Radius": 0.2, "Young's modulus": 1e6,
        "Poisson's ratio": 0.3, "Density": 1000}


def snapshot(directory):
    """Every file below `directory` with the hash of its contents."""
    files = {}
    for root, _, names in os.walk(directory):
        for name in names:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                files[os.path.relpath(path, directory)] = hashlib.sha1(f.read()).hexdigest()
    return files


def sable(directory, args, limit=None, timeout=120):
    """Run sable in `directory` with `args`; with `limit`, files may not grow
    beyond `limit` bytes (writes fail as on a full disk)."""
    def limited():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    # MPI's shared-memory files would meet the limit before sable's: one
    # process needs none
    environment = dict(os.environ, OMPI_MCA_btl="self", PMIX_MCA_gds="hash") if limit else None
    result = subprocess.run([SABLE] + args, cwd=directory, capture_output=True, text=True, timeout=timeout,
                            preexec_fn=limited if limit else None, env=environment)
    return result.returncode, result.stdout + result.stderr


def last_line(output):
    return output.strip().splitlines()[-1] if output.strip() else "(no output)"


# --- 1. earlier results: refused, or --overwrite
name = "rerun"
directory = os.path.join(WORK, name)
out = os.path.join(directory, "output")
run(name, dict(entries, **{"Time/Maximum number of steps": 40}), [body])
particles = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".pvtu"))
with open(os.path.join(out, "notes.txt"), "w") as f:
    f.write("the user's own file\n")
before = snapshot(out)
code, output, _ = run(name, entries, [body], fresh=False, expect_success=False)
check("a fresh run into earlier results: non-zero exit", code != 0, f"exit code {code}")
check("... the message names the directory, --overwrite and --resume",
      "'output'" in output and "--overwrite" in output and "--resume" in output and "statistics.csv" in output,
      last_line(output))
check("... no step taken", "step " not in output.replace("steps", ""))
check("... nothing in the directory changed", snapshot(out) == before)

code, output, rows = run(name, entries, [body], fresh=False, args=["--overwrite"])
after = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".pvtu"))
check("--overwrite: the run starts and says what it removed",
      code == 0 and "removed the earlier outputs" in output, last_line(output))
check("... statistics.csv holds only the new run's rows", rows and rows[-1]["step"] == 20 and len(rows) == 21,
      f"{len(rows)} rows, last step {rows[-1]['step'] if rows else None}")
check("... the earlier run's later particle files are gone",
      len(particles) > len(after) and set(after) <= set(particles) and
      not os.path.exists(os.path.join(out, particles[-1])), f"{len(particles)} files before, {len(after)} after")
check("... unrelated files are kept", os.path.exists(os.path.join(out, "notes.txt")))
check("... no lock file left after a normal exit", not os.path.exists(os.path.join(out, "sable.lock")))

# the same for a QuSGM run (the demo scene, smaller)
directory = os.path.join(WORK, "qusgm")
shutil.rmtree(directory, ignore_errors=True)
os.makedirs(directory)
qusgm = [os.path.join(os.environ.get("SABLE_SOURCE", os.path.join(os.path.dirname(__file__), "..", "..")),
                      "prm", "qusgm_demo.prm"),
         "--set", "Output directory=output", "--set", "Pack/Number of grains=60",
         "--set", "Preparation/Target confining stress=2e6", "--set", "Preparation/Maximum activation increments=5",
         "--set", "Load path/Number of increments=1"]
code, output = sable(directory, qusgm)
check("QuSGM: a fresh run", code == 0, last_line(output))
before = snapshot(os.path.join(directory, "output"))
code, output = sable(directory, qusgm)
check("QuSGM: a second fresh run into its results is refused, naming increments.csv and --overwrite",
      code != 0 and "'output'" in output and "increments.csv" in output and "--overwrite" in output,
      last_line(output))
check("... nothing changed", snapshot(os.path.join(directory, "output")) == before)
code, output = sable(directory, qusgm + ["--overwrite"])
check("QuSGM: --overwrite runs", code == 0 and "removed the earlier outputs" in output, last_line(output))
code, output = sable(directory, qusgm + ["--overwrite"], limit=1000)
check("QuSGM: increments.csv beyond a file size limit: non-zero exit, naming the file and the increment",
      code != 0 and "cannot write 'output/increments.csv' (increment" in output, last_line(output))
check("... no lock left", not os.path.exists(os.path.join(directory, "output", "sable.lock")))

# QuSGM: a resume with another friction is refused, naming it; a longer
# load path is not
qusgm_checkpoints = qusgm + ["--set", "Output/Checkpoint interval=1"]
code, output = sable(directory, qusgm_checkpoints + ["--overwrite"])
code, output = sable(directory, qusgm_checkpoints + ["--resume", "--set", "Contact/Friction coefficient=0.5",
                                                     "--set", "Load path/Number of increments=2"])
check("QuSGM: --resume with another friction coefficient: refused, naming it with both values",
      code != 0 and "Contact/Friction coefficient: '0.3' in the checkpoint, '0.5' now" in output and
      "Number of increments" not in output.replace("Load path/Number of increments, the Output", ""),
      last_line(output))
code, output = sable(directory, qusgm_checkpoints + ["--resume", "--set", "Load path/Number of increments=2"])
check("QuSGM: --resume with a longer load path runs on", code == 0 and "Resumed from" in output, last_line(output))

# --- 2. the lock file
name = "lock"
directory = os.path.join(WORK, name)
out = os.path.join(directory, "output")
# a body at rest without gravity for 1000 s: runs until killed
long_run = dict(entries, **{"Time/End time": 1000, "Time/Maximum number of steps": 1, "Gravity": "0, 0",
                            "Output/Particle output interval": 0, "Output/Checkpoint interval": 0,
                            "Grid/Subdivisions": "40, 40"})
run(name, long_run, [body])
first = subprocess.Popen([SABLE, "scene.prm", "--overwrite", "--set", "Time/Maximum number of steps=0"],
                         cwd=directory, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
lock = os.path.join(out, "sable.lock")
for _ in range(600):
    if os.path.exists(lock) and os.path.getsize(lock) > 0 or first.poll() is not None:
        break
    time.sleep(0.1)
code, output = sable(directory, ["scene.prm", "--overwrite"])
check("a second run into a running run's directory: non-zero exit", code != 0, f"exit code {code}")
check("... the message names the directory, the process id and the host",
      "'output'" in output and str(first.pid) in output and socket.gethostname() in output, last_line(output))
check("... the first run still runs", first.poll() is None)
first.kill()  # as if the machine had killed it: its lock stays
first.wait()
check("a killed run leaves its lock", os.path.exists(lock))
code, output = sable(directory, ["scene.prm", "--overwrite", "--set", "Time/Maximum number of steps=5"])
check("the lock of a dead process is taken over with a note",
      code == 0 and "taking over the lock file" in output and str(first.pid) in output, last_line(output))
check("... and released at the end", not os.path.exists(lock))

# --- 3. resume with a changed scene
name = "resume"
directory = os.path.join(WORK, name)
out = os.path.join(directory, "output")
run(name, entries, [body])
with open(os.path.join(out, "statistics.csv")) as f:
    statistics = f.read()
checkpoint = snapshot(os.path.join(out, "checkpoint"))
changed = ["--set", "Body 0/Young's modulus=2e6", "--set", "Grid/Subdivisions=20, 20",
           "--set", "Contact/Friction coefficient=0.5"]
code, output = sable(directory, ["scene.prm", "--resume"] + changed)
check("--resume with another material, grid and contact: non-zero exit", code != 0, f"exit code {code}")
for entry, old, new in [("Body 0/Young's modulus", "1e+06", "2e+06"),
                        ("Grid/Subdivisions", "10, 10", "20, 20"),
                        ("Contact/Friction coefficient", "0", "0.5")]:
    line = next((l for l in output.splitlines() if l.strip().startswith(entry + ":")), "")
    check(f"... names {entry} with both values", line and f"'{old}' in the checkpoint, '{new}' now" in line,
          line.strip() or last_line(output))
check("... the lock is released after the error", not os.path.exists(os.path.join(out, "sable.lock")))
check("... statistics.csv and the checkpoint untouched",
      open(os.path.join(out, "statistics.csv")).read() == statistics and
      snapshot(os.path.join(out, "checkpoint")) == checkpoint)
code, output = sable(directory, ["scene.prm", "--resume", "--set", "Time/Maximum number of steps=30",
                                 "--set", "Output/Statistics interval=2"])
rows = read_csv(os.path.join(out, "statistics.csv"))
check("--resume with a later step limit and another statistics interval: runs on",
      code == 0 and rows and rows[-1]["step"] == 30, last_line(output))

# a checkpoint of an older format: the first number of the state archive
# after boost's header is the format
state = os.path.join(out, "checkpoint", "simulator.state")
with open(state) as f:
    text = f.read()
match = re.match(r"(\d+ serialization::archive \d+ \d+ \d+ )(\d+)", text)
check("the state archive starts with the format 11", match is not None and match.group(2) == "11", text[:60])
if match:
    with open(state, "w") as f:
        f.write(match.group(1) + "10" + text[match.end():])
    # the manifest with the new size and checksum: a complete checkpoint
    manifest = os.path.join(out, "checkpoint", "manifest")
    with open(manifest) as f:
        lines = f.read().splitlines()
    with open(state, "rb") as f:
        data = f.read()
    lines = [f"{len(data)} {zlib.crc32(data):x} simulator.state" if l.endswith(" simulator.state") else l
             for l in lines]
    with open(manifest, "w") as f:
        f.write("\n".join(lines) + "\n")
    code, output = sable(directory, ["scene.prm", "--resume", "--set", "Time/Maximum number of steps=40"])
    check("a checkpoint of format 10: refused, saying it is an older format",
          code != 0 and "format is 10" in output and "earlier version of sable" in output, last_line(output))

# --- 4. include relative to the including file
directory = os.path.join(WORK, "include")
shutil.rmtree(directory, ignore_errors=True)
os.makedirs(os.path.join(directory, "scenes", "common"))
with open(os.path.join(directory, "scenes", "common", "grid.prm"), "w") as f:
    f.write("subsection Grid\n  set Subdivisions = 12, 12\nend\n")
with open(os.path.join(directory, "scenes", "common", "all.prm"), "w") as f:
    f.write("include grid.prm\n")  # relative to scenes/common/
scene = prm_text(dict(entries, **{"Time/Maximum number of steps": 2}), [body]).replace(
    "set Dimension = 2\n", "set Dimension = 2\ninclude common/all.prm\n", 1).replace(
    "  set Subdivisions = 10, 10\n", "")
with open(os.path.join(directory, "scenes", "scene.prm"), "w") as f:
    f.write(scene)
code, output = sable(directory, ["scenes/scene.prm"])
check("include relative to the including file, run from elsewhere: runs with its grid",
      code == 0 and "144 cells" in output, last_line(output))
os.remove(os.path.join(directory, "scenes", "common", "grid.prm"))
code, output = sable(directory, ["scenes/scene.prm", "--overwrite"])
check("a missing include: non-zero exit, naming the file and where it is included",
      code != 0 and "scenes/common/grid.prm" in output and "line 1 of" in output and "all.prm" in output,
      last_line(output))

# --- 5. memory: a scene beyond the machine, refused at once
with open("/proc/meminfo") as f:
    available = next(int(l.split()[1]) * 1024 for l in f if l.startswith("MemAvailable:"))
# a box body filling the grid, 16 points per cell at 200 bytes or more
# (sable's lower bound): four times the available memory
n = int((4 * available / (16 * 200)) ** 0.5) + 1
directory = os.path.join(WORK, "memory")
box = {"Shape": "box", "Lower corner": "0, 0", "Upper corner": "1, 1", "Particles per cell direction": 4,
       "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000}
start = time.monotonic()
code, output, _ = run("memory", dict(entries, **{"Grid/Subdivisions": f"{n}, {n}"}), [box],
                      expect_success=False, timeout=60)
seconds = time.monotonic() - start
check(f"{n}^2 cells with 16 points each: non-zero exit", code != 0, f"exit code {code}")
check("... the message names the body's seeding, the need and the memory available",
      "Body 0/Particles per cell direction = 4" in output and "GB" in output and "available" in output,
      last_line(output))
# a second is the bound; the machine may be busy with other work
check("... within a few seconds", seconds < 5, f"{seconds:.2f} s")
check("... nothing written", not os.path.exists(os.path.join(directory, "output")))

# --- 6. write errors
directory = os.path.join(WORK, "unwritable")
shutil.rmtree(directory, ignore_errors=True)
os.makedirs(directory)
with open(os.path.join(directory, "file"), "w") as f:
    f.write("a file, not a directory\n")
with open(os.path.join(directory, "scene.prm"), "w") as f:
    f.write(prm_text(dict(entries, **{"Output directory": "file/output"}), [body]))
code, output = sable(directory, ["scene.prm"])
check("an output directory that cannot be created: non-zero exit, naming it",
      code != 0 and "cannot create the output directory 'file/output'" in output and "step " not in output,
      last_line(output))

name = "disk_full"
directory = os.path.join(WORK, name)
out = os.path.join(directory, "output")
# 3200 material points: a checkpoint of about 1 MB
fine = dict(entries, **{"Output/Particle output interval": 0, "Grid/Subdivisions": "40, 40"})
dense = dict(body, **{"Particles per cell direction": 4})
run(name, fine, [dense])
code, output = sable(directory, ["scene.prm", "--overwrite", "--set", "Output/Checkpoint interval=0"], limit=4000)
check("statistics.csv beyond a file size limit: non-zero exit, naming the file and the step",
      code != 0 and "cannot write 'output/statistics.csv' (step" in output, last_line(output))
check("... no lock left", not os.path.exists(os.path.join(out, "sable.lock")))
run(name, fine, [dense])
checkpoint = snapshot(os.path.join(out, "checkpoint"))
size = sum(os.path.getsize(os.path.join(out, "checkpoint", f)) for f in checkpoint)
code, output = sable(directory, ["scene.prm", "--resume", "--set", "Time/Maximum number of steps=30",
                                 "--set", "Output/Statistics interval=1000"], limit=size // 4)
check("a checkpoint beyond a file size limit: non-zero exit, sable names the checkpoint",
      code != 0 and "cannot write the checkpoint 'output/checkpoint.tmp'" in output and "ulimit" in output,
      last_line(output))
check("... the earlier checkpoint is intact", snapshot(os.path.join(out, "checkpoint")) == checkpoint)
code, output = sable(directory, ["scene.prm", "--resume", "--set", "Time/Maximum number of steps=30"])
check("... and a run resumes from it", code == 0 and "resumed from" in output and "step 20" in output,
      last_line(output))
finish()
