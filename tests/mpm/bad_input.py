#!/usr/bin/python3
"""Every kind of bad input stops the program before any step: non-zero exit,
a message naming the entry, the value and what is allowed, and no output
written (an existing statistics.csv is left untouched). Bodies seeded into
each other are refused; bodies that touch are not."""
import os
import subprocess
from scene_test import *

good_entries = {"Dimension": 2, "Time/End time": 0.01,
                "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "10, 10"}
good_body = {"Shape": "disk", "Center": "0.5, 0.5", "Radius": 0.2, "Young's modulus": 1e6,
             "Poisson's ratio": 0.3, "Density": 1000}

# (name, entry changes, body changes (a list: one body each), words the
# message must contain)
cases = [
    ("unknown_entry", {"Time/Frobnication": 1}, {}, ["Frobnication"]),
    ("wrong_type", {"Time/End time": "soon"}, {}, ["End time", "soon"]),
    ("density_zero", {}, {"Density": 0}, ["Density", "0", "> 0"]),
    ("density_negative", {}, {"Density": -5}, ["Density", "-5", "> 0"]),
    ("poisson_half", {}, {"Poisson's ratio": 0.5}, ["Poisson's ratio", "0.5", "(-1, 0.5)"]),
    ("poisson_minus_one", {}, {"Poisson's ratio": -1}, ["Poisson's ratio", "-1", "(-1, 0.5)"]),
    ("cfl_zero", {"Time/CFL number": 0}, {}, ["CFL number", "0", "(0, 1]"]),
    ("cfl_large", {"Time/CFL number": 1.5}, {}, ["CFL number", "1.5", "(0, 1]"]),
    ("settling_tolerance", {"Solver/Settling steps": 100, "Solver/Settling tolerance": 1},
     {}, ["Settling tolerance", "1", "(0, 1)"]),
    ("settling_gravity", {"Solver/Settling steps": 100, "Solver/Settling gravity": "-9.81"},
     {}, ["Solver/Settling gravity", "-9.81", "2 comma-separated numbers"]),
    ("ppc_zero", {}, {"Particles per cell direction": 0}, ["Particles per cell direction", "0", "1..4"]),
    ("ppc_five", {}, {"Particles per cell direction": 5}, ["Particles per cell direction", "5", "1..4"]),
    ("body_outside", {}, {"Center": "0.9, 0.5"}, ["Body 0/Center", "0.9, 0.5", "inside the grid"]),
    ("no_bodies", {"Number of bodies": 0}, {}, ["Number of bodies", "0"]),
    ("radius_zero", {}, {"Radius": 0}, ["Radius", "0", "> 0"]),
    ("friction_negative", {"Boundary conditions/Types": "2: friction",
                           "Boundary conditions/Friction coefficients": "2: -0.1"}, {}, ["Friction coefficients", "-0.1", ">= 0"]),
    ("group_friction_unknown_group", {"Contact/Model": "bardenhagen 2001", "Contact/Group friction": "0-5: 0.3"}, {},
     ["Contact/Group friction", "0-5", "groups the bodies belong to"]),
    ("group_friction_twice", {"Contact/Model": "bardenhagen 2001", "Contact/Group friction": "0-0: 0.3, 0-0: 0.5"},
     {}, ["Contact/Group friction", "given twice"]),
    ("moving_without_velocity", {"Boundary conditions/Types": "2: moving"}, {},
     ["Wall velocities", "moving", "id 2 has none"]),
    ("yield_missing", {}, {"Material": "von Mises"}, ["Body 0/von Mises/Yield stress", "0", "> 0"]),
    ("refinement_levels", {"Mesh refinement/Criteria": "body surface", "Mesh refinement/Minimum level": 3,
                           "Mesh refinement/Maximum level": 2}, {}, ["Minimum level", "3", "<= 'Maximum level' = 2"]),
    ("refinement_nothing", {"Mesh refinement/Criteria": "contact", "Mesh refinement/Maximum level": 0}, {},
     ["Maximum level", "0", "above 'Minimum level'"]),
    ("boundary_id_unknown", {"Boundary conditions/Types": "0: slip, 7: slip"}, {},
     ["Boundary conditions/Types", "7: slip", "0, 1, 2, 3"]),
    ("boundary_id_renumbered", {"Grid/Boundary ids": "0, 0, 5, 5", "Boundary conditions/Types": "2: fixed"}, {},
     ["Boundary conditions/Types", "2: fixed", "0, 5"]),
    ("grid_beyond_memory", {"Grid/Subdivisions": "1000000, 1000000"}, {},
     ["Grid/Subdivisions", "1000000, 1000000", "fits into memory", "GB", "available"]),
    ("refinement_criterion", {"Mesh refinement/Criteria": "curvature"}, {}, ["Criteria", "curvature"]),
    ("refinement_region", {"Mesh refinement/Criteria": "region", "Mesh refinement/Region lower corner": "0.5, 0.5",
                           "Mesh refinement/Region upper corner": "0.6, 0.4"}, {}, ["Region upper corner", "larger"]),
    ("gimp_refinement", {"Grid/Shape functions": "gimp", "Mesh refinement/Criteria": "body surface",
                         "Mesh refinement/Maximum level": 1}, {},
     ["Grid/Shape functions", "gimp", "Mesh refinement"]),
    ("shape_functions", {"Grid/Shape functions": "quadratic"}, {}, ["Shape functions", "quadratic"]),
    ("affine_linear", {"Solver/Affine transfers": "true", "Solver/Update scheme": "USL"}, {},
     ["Solver/Affine transfers", "true", "Grid/Shape functions = gimp", "USL"]),
    ("affine_musl", {"Solver/Affine transfers": "true", "Grid/Shape functions": "gimp"}, {},
     ["Solver/Affine transfers", "true", "Grid/Shape functions = gimp", "USL"]),
    # bodies seeded into each other (cells of 0.1 m, points 0.05 m apart):
    # a disk reaching 0.1 m into a box, two spheres 0.15 m into each other
    ("bodies_overlap", {}, [{}, {"Shape": "box", "Lower corner": "0.6, 0.3", "Upper corner": "0.9, 0.7"}],
     ["Body 0 and Body 1 overlap", "inside Body", "quarter of its spacing"]),
    ("spheres_overlap", {"Dimension": 3, "Grid/Lower corner": "0, 0, 0", "Grid/Upper corner": "1, 1, 1",
                         "Grid/Subdivisions": "10, 10, 10"},
     [{"Center": "0.3, 0.5, 0.5"}, {"Center": "0.65, 0.5, 0.5"}], ["Body 0 and Body 1 overlap", "inside Body"]),
]

for name, entries, body_changes, words in cases:
    directory = os.path.join(WORK, name)
    os.makedirs(os.path.join(directory, "output"), exist_ok=True)
    sentinel = os.path.join(directory, "output", "statistics.csv")
    with open(sentinel, "w") as f:
        f.write("previous run\n")
    e = dict(good_entries, **entries)
    e["Output directory"] = "output"
    # no bodies at all: neither 'Body k' subsections nor a bodies file; a
    # list of changes: one body each
    if entries.get("Number of bodies") == 0:
        bodies = []
    elif isinstance(body_changes, list):
        bodies = [dict(good_body, **changes) for changes in body_changes]
    else:
        bodies = [dict(good_body, **body_changes)]
    text = prm_text(e, bodies)
    if "Number of bodies" in entries:
        text = text.replace("set Number of bodies = 1\n", "")
    with open(os.path.join(directory, "scene.prm"), "w") as f:
        f.write(text)
    result = subprocess.run([SABLE, "scene.prm"], cwd=directory, capture_output=True, text=True)
    message = result.stdout + result.stderr
    check(f"{name}: non-zero exit", result.returncode != 0, f"exit code {result.returncode}")
    missing = [w for w in words if w not in message]
    check(f"{name}: message names {words}", not missing, message.strip().splitlines()[-1] if message.strip() else "(no message)")
    check(f"{name}: no step taken", "step " not in result.stdout)
    with open(sentinel) as f:
        check(f"{name}: existing output untouched", f.read() == "previous run\n")
    check(f"{name}: nothing else written", os.listdir(os.path.join(directory, "output")) == ["statistics.csv"])

missing_file = subprocess.run([SABLE, os.path.join(WORK, "does_not_exist.prm")], capture_output=True, text=True)
check("unreadable file: non-zero exit", missing_file.returncode != 0)
check("unreadable file: message names the file", "does_not_exist.prm" in missing_file.stderr, missing_file.stderr.strip())

# Bodies may touch: a disk against a box's face, and a disk 0.01 m into it
# (less than a quarter of the 0.05 m point spacing, so no point of either
# lies that deep in the other), run. On two ranks the overlap is refused
# with the one-rank message, whichever rank holds the deepest point.
box = dict(good_body, **{"Shape": "box", "Lower corner": "0.5, 0.3", "Upper corner": "0.8, 0.7"})
for name, centre in (("touching", "0.3, 0.5"), ("touching_within_a_quarter_spacing", "0.31, 0.5")):
    code, output, rows = run(name, good_entries, [dict(good_body, Center=centre), box], expect_success=False)
    check(f"{name}: runs", code == 0 and len(rows) > 1, output.strip().splitlines()[-1] if output.strip() else "")
deep = [good_body, dict(box, **{"Lower corner": "0.6, 0.3", "Upper corner": "0.9, 0.7"})]
messages = [run(f"overlap_ranks_{ranks}", good_entries, deep, ranks=ranks, expect_success=False)[1]
            for ranks in (0, 2)]
refusal = [next((line for line in m.splitlines() if "overlap" in line), "") for m in messages]
check("overlap on two ranks: the one-rank message", refusal[0] != "" and refusal[0] == refusal[1],
      f"{refusal[0]!r} against {refusal[1]!r}")
# the bodies are checked before the output directory is prepared: even
# --overwrite leaves an earlier run's outputs in place
directory = os.path.join(WORK, "overlap_overwrite", "output")
os.makedirs(directory, exist_ok=True)
with open(os.path.join(directory, "statistics.csv"), "w") as f:
    f.write("previous run\n")
code, output, _ = run("overlap_overwrite", good_entries, deep, expect_success=False, args=["--overwrite"], fresh=False)
with open(os.path.join(directory, "statistics.csv")) as f:
    check("overlap with --overwrite: refused, the earlier outputs kept",
          code != 0 and "overlap" in output and f.read() == "previous run\n" and os.listdir(directory) == ["statistics.csv"],
          output.strip().splitlines()[-1] if output.strip() else "")
finish()
