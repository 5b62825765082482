#!/usr/bin/python3
"""Checkpoint and restart: two elastic disks colliding with frictional
contact (Bardenhagen 2001, mu = 0.3) for N = 200 steps in one go, and the
same scene stopped at step 100 (checkpoints every 50 steps and at the end),
resumed to 150, then - as if that run had been killed after step 150 before
its next checkpoint - resumed once more from the step-100 checkpoint to N.
statistics.csv (every column, 1e-12 relative to the largest value of its
kind: energies, momenta, positions, ...)
and the particle output series must equal those of the uninterrupted run:
rows written after the checkpoint by the stopped runs are not repeated, and
the row of step 100, which only the stopped run writes (Statistics interval
3), is gone. The last resume finds a partially written `checkpoint` and
must fall back to `checkpoint.old`; its own checkpoints then replace the
incomplete one. --resume without a usable checkpoint
fails with a message naming the output directory, and so does a parameter
file with another number of bodies. The same on an adaptive grid (the
checkpoint carries the refined mesh) to 1e-11. On one rank also a block
sliding on a 45 degree staircase wedge with mu = 0.6, stopped at step 1700
and resumed to 2000 (to 1e-10): its contact carries pulling impulses from
step to step, which the checkpoint keeps.

Usage: checkpoint_restart.py [ranks] (default 1). With 2 ranks it also
resumes the 2-rank checkpoint on 1 rank (the mesh is repartitioned) and
compares with the 1-rank run to the 1e-10 of test mpi_consistency, and
checks that a resume on 2 ranks balances the material points again. On one
rank also with the default statistics schedule (rows with the particle
output): the row of a stop step is kept exactly when the uninterrupted run
has it.

The disks are seeded on the lattice, whose points have equal masses: a
resumed run adds them in another order and still agrees to 1e-12. Seeded
clipped (the default), the points at the surface carry unequal masses and
the same comparison agrees to about 1e-11 (9.4e-12 measured; 2e-10 on
the adaptive grid and from two ranks to one), round-off all the same."""
import os
import re
import shutil
import sys
from scene_test import *

n_ranks = int(sys.argv[1]) if len(sys.argv) > 1 else 1
tag = f"np{n_ranks}"
ranks = n_ranks if n_ranks > 1 else 0  # one rank: no mpirun
N = 200
elastic = {"Bulk modulus": 1e6, "Shear modulus": 5e5, "Density": 1000, "Particles per cell direction": 2}
entries = {
    "Dimension": 2, "Time/End time": 1, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
    "Output/Statistics interval": 3, "Output/Progress interval": 1000, "Output/Particle output interval": 0.02,
}
bodies = [dict(elastic, Shape="disk", Center="0.745, 0.5", Radius=0.2, Velocity="5, 0", Seeding="lattice"),
          dict(elastic, Shape="disk", Center="1.255, 0.56", Radius=0.2, Velocity="-5, 0", Seeding="lattice")]


def scene(steps, checkpoints=0):
    return dict(entries, **{"Time/Maximum number of steps": steps, "Output/Checkpoint interval": checkpoints})


def compare(what, rows, reference, tolerance):
    check(f"{what}: same steps in statistics.csv",
          [r["step"] for r in rows] == [r["step"] for r in reference],
          f"{len(rows)} rows, expected {len(reference)}")
    # a column that is zero up to round-off (total momentum) is compared
    # with the scale of its kind, as in test mpi_consistency; energy_drift
    # is already a fraction of the energy the scene holds
    def kind(column):
        if column.endswith("energy") or column in ("boundary_work", "contact_heat", "wall_heat",
                                                    "impact_loss", "plastic_work"):
            return "energy"
        if column == "energy_drift":
            return "fraction"
        if column.startswith("momentum"):
            return "momentum"
        if column.startswith("body"):
            return "velocity" if "_v" in column else "omega" if "omega" in column else "position"
        if column.startswith("contact"):
            return "force"
        return column
    scales = {"fraction": 1.0}
    for column in reference[0]:
        if kind(column) == "fraction":
            continue
        scales[kind(column)] = max(scales.get(kind(column), 0.0), max(abs(r[column]) for r in reference))
    worst, where = 0.0, ""
    for column in reference[0]:
        scale = scales[kind(column)] or 1.0
        for a, b in zip(rows, reference):
            error = abs(a.get(column, float("nan")) - b[column]) / scale
            if not error <= worst:
                worst, where = error, f"{column} at step {int(b['step'])}"
    check(f"{what}: every column within {tolerance:g} relative", worst <= tolerance,
          f"largest difference {worst:.2e} ({where})")


def message(output):
    """The program's own error line."""
    return next((l for l in output.splitlines() if l.startswith("sable:")), "(no message)")


def pvd_entries(directory):
    with open(os.path.join(directory, "output", "particles.pvd")) as f:
        return re.findall(r'timestep="([^"]*)"[^>]*file="([^"]*)"', f.read())


full_name, name = f"full_{tag}", f"restart_{tag}"
_, _, full = run(full_name, scene(N), bodies, ranks=ranks)
check("uninterrupted run has the rows it should", len(full) == 1 + N // 3 + 1, f"{len(full)} rows")

# stop at step 100 (the last step always gets a row: 100 is not a multiple of 3)
_, output, rows = run(name, scene(100, 50), bodies, ranks=ranks)
directory = os.path.join(WORK, name)
out = os.path.join(directory, "output")
checkpoint = os.path.join(out, "checkpoint")
check("stopped run wrote row 100", rows[-1]["step"] == 100)
check("a checkpoint, and no .tmp or .old left over",
      os.path.isfile(os.path.join(checkpoint, "manifest")) and
      not os.path.exists(checkpoint + ".tmp") and not os.path.exists(checkpoint + ".old"),
      str(sorted(os.listdir(out))))
size = sum(os.path.getsize(os.path.join(checkpoint, f)) for f in os.listdir(checkpoint))
print(f"checkpoint: {size} bytes, {sorted(os.listdir(checkpoint))}")
saved = os.path.join(directory, "checkpoint_step100")
shutil.rmtree(saved, ignore_errors=True)
shutil.copytree(checkpoint, saved)

# resume to 150, which writes rows 101..150 and a checkpoint at 150
_, output, rows = run(name, scene(150, 50), bodies, ranks=ranks, args=["--resume"], fresh=False)
check("resumed run says where it resumed", "resumed from" in output and "step 100" in output,
      output.strip().splitlines()[0])
check("resumed run continued to 150", rows[-1]["step"] == 150)
if n_ranks > 1:
    # the loaded mesh is split by cells; the resume balances the points again:
    # the work per rank may differ by what p4est cannot split at the cut, a
    # family of 4 cells (it keeps siblings together) of 100 + 600 x 4 points
    # each on either side, not by the empty cells' share
    m = re.search(r"work per rank.*: (\d+) \.\. (\d+)", output)
    fewest, most = (int(g) for g in m.groups()) if m else (0, 10**9)
    check("resumed on 2 ranks: work per rank balanced again", most - fewest <= 2 * 4 * 2500,
          f"{fewest} .. {most}")

# as if the run had been killed while replacing the step-100 checkpoint:
# checkpoint.old is complete, checkpoint is not
shutil.rmtree(checkpoint)
shutil.copytree(saved, checkpoint + ".old")
shutil.copytree(saved, checkpoint)
variable = os.path.join(checkpoint, "triangulation_variable.data")
with open(variable, "r+b") as f:
    f.truncate(os.path.getsize(variable) // 2)
_, output, rows = run(name, scene(N, 50), bodies, ranks=ranks, args=["--resume"], fresh=False)
check("falls back to checkpoint.old and says so",
      "checkpoint.old" in output and "triangulation_variable.data" in output,
      next((l for l in output.splitlines() if "Note" in l), "(no note)"))
compare("stopped at 100, resumed to 150, resumed from 100 to 200", rows, full, 1e-12)
check("the next checkpoints replaced the incomplete one, no .tmp or .old left over",
      os.path.isfile(os.path.join(checkpoint, "manifest")) and
      not os.path.exists(checkpoint + ".tmp") and not os.path.exists(checkpoint + ".old"),
      str(sorted(os.listdir(out))))
check("same particle output series as the uninterrupted run",
      pvd_entries(directory) == pvd_entries(os.path.join(WORK, full_name)),
      f"{len(pvd_entries(directory))} vs {len(pvd_entries(os.path.join(WORK, full_name)))} entries")

def vtu_pieces(directory):
    """The particle .vtu files without the line that holds the time of writing."""
    out = os.path.join(directory, "output")
    pieces = {}
    for piece in sorted(f for f in os.listdir(out) if f.endswith(".vtu")):
        with open(os.path.join(out, piece)) as f:
            pieces[piece] = [l for l in f if "was generated" not in l]
    return pieces


# the particle files hold every point's id and properties: on one rank (a
# deterministic order of operations) they are the same, byte for byte
same = vtu_pieces(directory) == vtu_pieces(os.path.join(WORK, full_name))
if n_ranks == 1:
    check("particle files identical to the uninterrupted run's (ids, all fields)", same)
else:
    print(f"particle files identical to the uninterrupted run's: {same}")

if n_ranks == 2:
    # the 2-rank checkpoint on 1 rank: p4est repartitions the mesh
    one = f"restart_np2_on_np1"
    run(one, scene(100, 50), bodies, ranks=0)  # creates the directory and prm
    shutil.rmtree(os.path.join(WORK, one, "output"))
    shutil.copytree(out, os.path.join(WORK, one, "output"), ignore=shutil.ignore_patterns("checkpoint*"))
    shutil.copytree(saved, os.path.join(WORK, one, "output", "checkpoint"))
    _, _, rows = run(one, scene(N), bodies, ranks=0, args=["--resume"], fresh=False)
    _, _, full_np1 = run("full_np1_reference", scene(N), bodies, ranks=0)
    compare("2-rank checkpoint resumed on 1 rank", rows, full_np1, 1e-10)

# an adaptive grid (refined at the disks' surfaces and the contact, adapted
# every 7 steps): the checkpoint carries the refined mesh and the adaptation
# counter. Cells are visited in another order after loading than on a mesh
# with a history of adaptations, so sums round differently: measured 3e-13.
adaptive = {"Grid/Subdivisions": "20, 10", "Mesh refinement/Criteria": "body surface, contact",
            "Mesh refinement/Maximum level": 1, "Mesh refinement/Refinement interval": 7}
_, _, adaptive_full = run(f"adaptive_full_{tag}", dict(scene(N), **adaptive), bodies, ranks=ranks)
run(f"adaptive_{tag}", dict(scene(100, 50), **adaptive), bodies, ranks=ranks)
_, output, rows = run(f"adaptive_{tag}", dict(scene(N), **adaptive), bodies, ranks=ranks, args=["--resume"],
                      fresh=False)
check("adaptive grid: resumed on the refined mesh", "resumed from" in output and
      re.search(r"step 100, t = [0-9.e-]+: (\d+) cells", output) is not None and
      int(re.search(r"step 100, t = [0-9.e-]+: (\d+) cells", output).group(1)) > 200,
      output.strip().splitlines()[0])
compare("adaptive grid, stopped at 100 and resumed", rows, adaptive_full, 1e-11)

# a block sliding on a 45 degree wedge (mu = 0.6; both faces staircases of
# points): the contact carries pulling impulses from step to step into the
# friction cap, and the checkpoint must carry them too (without them the
# contact force differed by a fifth of its largest value within 300 steps)
if n_ranks == 1:
    wedge_dir = os.path.abspath(os.path.join(WORK, "wedge_meshes"))
    os.makedirs(wedge_dir, exist_ok=True)

    def write_quad(path, corners):
        with open(path, "w") as f:
            f.write("4 1 0 0 0\n")
            for i, (x, y) in enumerate(corners):
                f.write(f"{i + 1} {x!r} {y!r} 0\n")
            f.write("1 0 quad 1 2 3 4\n")

    c = 0.5 ** 0.5
    write_quad(os.path.join(wedge_dir, "wedge.inp"), [(0, 0), (2, 0), (2, 0.1), (0, 2.1)])
    corner = (0.3 * c, 2.1 - 0.3 * c)
    write_quad(os.path.join(wedge_dir, "block.inp"),
               [corner, (corner[0] + 0.2 * c, corner[1] - 0.2 * c), (corner[0] + 0.4 * c, corner[1]),
                (corner[0] + 0.2 * c, corner[1] + 0.2 * c)])
    wedge_scene = {"Dimension": 2, "Gravity": "0, -9.81", "Time/End time": 1, "Grid/Lower corner": "0, 0",
                   "Grid/Upper corner": "2, 2.575", "Grid/Subdivisions": "80, 103",
                   "Boundary conditions/Types": "0: slip, 2: fixed", "Contact/Model": "bardenhagen 2001",
                   "Contact/Friction coefficient": 0.6, "Output/Statistics interval": 1,
                   "Output/Progress interval": 1000}
    wedge_bodies = [{"Shape": "mesh", "Mesh file": os.path.join(wedge_dir, f), "Young's modulus": 1e7,
                     "Poisson's ratio": 0.3, "Density": 1000, "Particles per cell direction": 2}
                    for f in ("wedge.inp", "block.inp")]
    _, _, wedge_full = run("wedge_full", dict(wedge_scene, **{"Time/Maximum number of steps": 2000}),
                           wedge_bodies)
    run("wedge_restart", dict(wedge_scene, **{"Time/Maximum number of steps": 1700,
                                              "Output/Checkpoint interval": 1000000}), wedge_bodies)
    _, _, rows = run("wedge_restart", dict(wedge_scene, **{"Time/Maximum number of steps": 2000}),
                     wedge_bodies, args=["--resume"], fresh=False)
    # measured 1.9e-11, in energy_drift when it was compared on the scale
    # of its own small values (with the pulling impulses left out of the
    # checkpoint the contact force differs by 0.2)
    compare("block on a staircase wedge, stopped at 1700 and resumed", rows, wedge_full, 1e-10)

# a parameter file that does not describe the saved scene
with open(os.path.join(out, "statistics.csv")) as f:
    before = f.read()
code, output, _ = run(name, scene(N), bodies[:1], ranks=ranks, args=["--resume"], fresh=False, expect_success=False)
check("another number of bodies: non-zero exit, message names the entry",
      code != 0 and "Number of bodies" in output, message(output))
with open(os.path.join(out, "statistics.csv")) as f:
    check("... statistics.csv untouched", f.read() == before)

# no complete checkpoint at all: a clear error naming the directory
shutil.rmtree(checkpoint + ".old", ignore_errors=True)
with open(os.path.join(checkpoint, "manifest"), "w") as f:
    f.write("garbage\n")
code, output, _ = run(name, scene(N), bodies, ranks=ranks, args=["--resume"], fresh=False, expect_success=False)
check("broken checkpoint, no checkpoint.old: non-zero exit", code != 0, f"exit code {code}")
check("... the message names both directories and what is wrong",
      "checkpoint'" in output and "checkpoint.old" in output and "manifest" in output,
      message(output))

code, output, _ = run(f"no_checkpoint_{tag}", scene(N), bodies, ranks=ranks, args=["--resume"], expect_success=False)
check("--resume without a checkpoint: non-zero exit", code != 0, f"exit code {code}")
check("... the message names the output directory",
      "no complete checkpoint" in output and "'output'" in output,
      message(output))
check("... and nothing was written", not os.path.exists(os.path.join(WORK, f"no_checkpoint_{tag}", "output")))

if n_ranks == 1:
    # the default schedule (Statistics interval 0: rows with the particle
    # output): a run stopped at a step without output writes that step's
    # row, its resume drops it; stopped at an output step, the row stays
    default = {"Output/Statistics interval": 0}
    _, _, full = run("full_default", dict(scene(120), **default), bodies)
    output_steps = [int(r["step"]) for r in full]
    for stop in (next(s for s in range(50, 100) if s not in output_steps),
                 next(s for s in output_steps if s >= 50)):
        what = f"default statistics, stopped at step {stop} ({'with' if stop in output_steps else 'without'} output)"
        _, _, rows = run("restart_default", dict(scene(stop, 1000), **default), bodies)
        check(f"{what}: the stopped run wrote its last row", int(rows[-1]["step"]) == stop)
        _, _, rows = run("restart_default", dict(scene(120, 1000), **default), bodies, args=["--resume"], fresh=False)
        compare(what, rows, full, 1e-12)
finish()
