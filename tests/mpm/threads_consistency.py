#!/usr/bin/python3
"""Threads do not change MPM results: a scene run with one thread, with
`--threads 2` and with SABLE_THREADS=3 writes byte-identical statistics.csv.
The threaded loops are the particle-to-grid scatter and the search for
contact nodes (blocks of cells coloured so that no two blocks of a colour
share a node; every node adds its contributions colour by colour, block by
block, whatever the number of threads), the contact node loop (sums over
nodes formed in fixed chunks), the nodal updates, the grid-to-particle
gather and the stress update (each point's own data only).

1. Two plastic disks colliding with frictional contact (history variables,
   per-body fields, two-body contact nodes).
2. A pile of four bodies (a box on a friction floor, two plastic disks on it
   side by side, a third disk dropped between them) under gravity, on a grid
   refined at body surfaces and contacts every 4 steps, so that cells with
   hanging nodes scatter through the folded shape functions, and nodes with
   three bodies occur; pair forces of all six pairs are reported. The
   same pile with 'Contact/Normals = logistic regression', with
   'fitted at edges' and with 'Solver/Update scheme = USAVG' (one and two
   threads).

A bad thread count stops with a message naming the option."""
import csv
import math
import io
import os
import shutil
import subprocess

from scene_test import *

entries = {
    "Dimension": 2, "Time/End time": 0.03, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
    "Output directory": "output",
}
plastic = {"Material": "von Mises", "Young's modulus": 1e6, "Poisson's ratio": 0.3, "von Mises/Yield stress": 2e3,
           "von Mises/Hardening modulus": 1e4, "Density": 1000, "Particles per cell direction": 2}
bodies = [dict(plastic, Shape="disk", Center="0.745, 0.5", Radius=0.2, Velocity="5, 0"),
          dict(plastic, Shape="disk", Center="1.255, 0.56", Radius=0.2, Velocity="-5, 0")]


def run_with(name, arguments, environment, scene=(entries, bodies)):
    directory = os.path.join(WORK, name)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write(prm_text(*scene))
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
# 2. a pile of four bodies on an adapted grid
pile_entries = {
    "Dimension": 2, "Gravity": "0, -9.81", "Time/End time": 0.03, "Grid/Lower corner": "0, 0",
    "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20",
    "Boundary conditions/Types": "0: slip, 1: slip, 2: friction",
    "Boundary conditions/Friction coefficients": "2: 0.3",
    "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
    "Mesh refinement/Criteria": "body surface, contact", "Mesh refinement/Maximum level": 2,
    "Mesh refinement/Refinement interval": 4, "Output directory": "output",
}
elastic = {"Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000,
           "Particles per cell direction": 2}
pile = [dict(elastic, Shape="box", **{"Lower corner": "0.1, 0.0", "Upper corner": "0.9, 0.3"}),
        dict(plastic, Shape="disk", Center="0.33, 0.45", Radius=0.15, Velocity="0.5, -2"),
        dict(plastic, Shape="disk", Center="0.67, 0.45", Radius=0.15, Velocity="-0.5, -2"),
        dict(elastic, Shape="disk", Center="0.5, 0.72", Radius=0.12, Velocity="0, -5")]
pile_scene = (pile_entries, pile)
code, output, one = run_with("pile_one", [], {"SABLE_THREADS": ""}, pile_scene)
check("pile, one thread: runs", code == 0 and "1 thread(s) per rank" in output, output[-300:])
rows = list(csv.DictReader(io.StringIO(one)))
cells = {int(r["cells"]) for r in rows}
check("pile: the grid is adapted (more than the 400 coarse cells, changing)",
      min(cells) > 400 and len(cells) > 1, f"cell counts {sorted(cells)}")
# the size of each pair's contact force (side by side, the normal force is
# along x)
forces = [max(math.hypot(float(r[f"contact{a}_{b}_fx"]), float(r[f"contact{a}_{b}_fy"])) for r in rows)
          for a, b in ((0, 1), (1, 2), (1, 3), (2, 3))]
check("pile: bodies 0-1, 1-2, 1-3 and 2-3 are in contact", all(f > 0 for f in forces), f"{forces}")
for name, arguments, environment in (("pile_two", ["--threads", "2"], {}),
                                     ("pile_three", [], {"SABLE_THREADS": "3"})):
    code, output, text = run_with(name, arguments, environment, pile_scene)
    check(f"pile, {name[5:]} threads: same statistics.csv as one thread", code == 0 and text == one,
          output[-300:])
# the same pile with the planes fitted between the bodies' points: each
# node's samples come colour by colour, so their order, and the fit, does
# not depend on the threads either; with 'fitted at edges' only where two
# bodies meet at an edge, which the nodes decide from their complete mass
# gradients; and with the stress updated in two halves (USAVG), whose
# first half each cell's points take or not by the contact nodes and the
# friction floor's nodes it reaches
for variant, tag in ((("Contact/Normals", "logistic regression"), "fitted"),
                     (("Contact/Normals", "fitted at edges"), "edges"),
                     (("Solver/Update scheme", "USAVG"), "usavg")):
    scene = (dict(pile_entries, **{variant[0]: variant[1]}), pile)
    what = f"{variant[0].split('/')[1]} = {variant[1]}"
    code, output, one = run_with(f"{tag}_one", [], {"SABLE_THREADS": ""}, scene)
    check(f"pile, {what}, one thread: runs", code == 0, output[-300:])
    code, output, text = run_with(f"{tag}_two", ["--threads", "2"], {}, scene)
    check(f"pile, {what}, two threads: same statistics.csv as one thread",
          code == 0 and text == one and one.count("\n") > 20, output[-300:])

code, output, _ = run_with("bad", ["--threads", "two"], {})
check("--threads two: refused with exit code 2", code == 2 and "--threads" in output and "two" in output,
      output[-300:])
finish()
