#!/usr/bin/env python3
"""Threads do not change MPM results: the same scene (two plastic disks
colliding with frictional contact, so history variables and per-body fields
are used) run with one thread, with `--threads 2` and with SABLE_THREADS=3
writes byte-identical statistics.csv (each material point's stress update
depends only on its own data). A bad thread count stops with a message
naming the option."""
import os
import subprocess

from scene_test import *

entries = {
    "Dimension": 2, "Time/End time": 0.03, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
    "Output directory": "output",
}
plastic = {"Material": "von Mises", "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Yield stress": 2e3,
           "Hardening modulus": 1e4, "Density": 1000, "Particles per cell direction": 2}
bodies = [dict(plastic, Shape="disk", Center="0.745, 0.5", Radius=0.2, Velocity="5, 0"),
          dict(plastic, Shape="disk", Center="1.255, 0.56", Radius=0.2, Velocity="-5, 0")]


def run_with(name, arguments, environment):
    directory = os.path.join(WORK, name)
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write(prm_text(entries, bodies))
    env = dict(os.environ, **environment)
    result = subprocess.run([SABLE] + arguments + ["scene.prm"], cwd=directory, capture_output=True,
                            text=True, env=env)
    output = result.stdout + result.stderr
    statistics = os.path.join(directory, "output", "statistics.csv")
    text = open(statistics).read() if result.returncode == 0 and os.path.exists(statistics) else ""
    return result.returncode, output, text


code, output, one = run_with("one", [], {"SABLE_THREADS": ""})
check("one thread: runs", code == 0 and "1 thread(s) per rank" in output, output[-300:])
check("one thread: statistics written", one.count("\n") > 20)
code, output, two = run_with("two", ["--threads", "2"], {})
check("--threads 2: runs with two threads", code == 0 and "2 thread(s) per rank" in output, output[-300:])
check("--threads 2: same statistics.csv as one thread", two == one)
code, output, three = run_with("three", [], {"SABLE_THREADS": "3"})
check("SABLE_THREADS=3: runs with three threads", code == 0 and "3 thread(s) per rank" in output,
      output[-300:])
check("SABLE_THREADS=3: same statistics.csv as one thread", three == one)
code, output, _ = run_with("bad", ["--threads", "two"], {})
check("--threads two: refused with exit code 2", code == 2 and "--threads" in output and "two" in output,
      output[-300:])
finish()
