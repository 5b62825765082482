#!/usr/bin/env python3
"""Regression layer: run a short scene and compare its CSV output with the
reference files committed next to it, through numdiff.

    regression.py <name> [--ranks N]      run tests/regression/<name>/scene.prm
                                          and compare
    regression.py <name> --regenerate     run it and overwrite the references
                                          (a file in which only the wall
                                          time would change is kept)

The scene runs with `--set "Output directory=<scratch>"`; every reference
file in tests/regression/<name>/ (statistics.csv for MPM, increments.csv
for QuSGM) must be written again and agree with the run.

Tolerance. Two numbers agree if they differ by at most 1e-9 relative, or by
at most 1e-10 of the largest magnitude in their column of the reference
file. Why:
- The program is deterministic: on one machine a rerun, and a run with any
  number of threads, gives the same bytes. What the tolerance must absorb
  is round-off from another order of floating-point sums: another compiler
  or flags, a refactored loop, MPI ranks. Measured for the MPM scenes here,
  1 against 2 MPI ranks: at most 1.5e-11 relative for values that are not
  small compared to their column (cancelling sums such as the total
  momentum of two colliding bodies, or the spin of the 3D plate, are the
  worst), and at most 3e-13 of the column's largest magnitude for values
  that are (an angular velocity that is zero up to round-off before the
  body touches anything differs by 100% relative). 1e-9 and 1e-10 leave a
  margin of more than 60 and 300 over these (the tests
  regression_*_mpi2 run two scenes on two ranks against the same files),
  while a change of the physics shows far above them: Young's modulus of
  one disk of two_body_contact changed by a part in a million changes
  the contact force by 1e-4 relative within 100 steps.
- QuSGM gives the same bits on any number of ranks and threads, but any
  other order of its floating-point operations changes the minimiser's
  path: iteration counts and residuals change at once, and the equilibria
  at the level of the minimiser's tolerance. Such a change is not round-off to absorb:
  regenerate and explain it (README.md).
- QuSGM writes 17 significant digits (earlier 10, whose last digit may round either
  way at differences of 5e-10 relative; 1e-9 covers that too). Its
  wall_time column is excluded (every column whose name contains
  wall_time is).
- Integer columns (step, particle, cell, contact and iteration counts) must
  match within the same tolerance, that is exactly.
The environment gives SABLE, SABLE_SOURCE, SABLE_WORK and MPIEXEC (see
tests/CMakeLists.txt); NUMDIFF may name the numdiff program."""
import argparse
import csv
import os
import shutil
import subprocess
import sys

RELATIVE = 1e-9
COLUMN_FLOOR = 1e-10

HERE = os.path.dirname(os.path.abspath(__file__))
SABLE = os.environ.get("SABLE", "sable")
if os.sep in SABLE:  # a path: the scene runs in the scratch directory
    SABLE = os.path.abspath(SABLE)
WORK = os.environ.get("SABLE_WORK", "regression.work")
MPIEXEC = os.environ.get("MPIEXEC", "mpirun")
NUMDIFF = os.environ.get("NUMDIFF", "numdiff")
OUTPUT_FILES = ("statistics.csv", "increments.csv")


def run_scene(name, ranks):
    """Run tests/regression/<name>/scene.prm into WORK/output; return it."""
    output = os.path.join(os.path.abspath(WORK), "output")
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    command = [SABLE, os.path.join(HERE, name, "scene.prm"), "--set", f"Output directory={output}"]
    if ranks > 1:
        command = [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    print(" ".join(f"'{c}'" if " " in c else c for c in command), flush=True)
    result = subprocess.run(command, cwd=WORK, capture_output=True, text=True)
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        sys.exit(f"[FAIL] {name}: sable exited with {result.returncode}")
    return output


def numdiff_arguments(reference):
    """numdiff options for one CSV file as comparable() writes it:
    comma-separated fields, the relative tolerance and an absolute tolerance
    per column (a fraction of the column's largest magnitude)."""
    with open(reference) as f:
        rows = list(csv.reader(f))
    header = rows[0]
    arguments = ["-s", ",\n", "-r", f"{RELATIVE:g}"]
    for column, title in enumerate(header, start=1):
        largest = 0.0
        for row in rows[1:]:
            try:
                value = abs(float(row[column - 1]))
            except (ValueError, IndexError):
                continue
            if value == value and value != float("inf"):  # not nan or inf
                largest = max(largest, value)
        if largest > 0:
            arguments += ["-a", f"{COLUMN_FLOOR * largest:.3e}:{column}"]
    return arguments


def comparable(path, copy):
    """Write @p path to @p copy as numdiff compares it: without wall-clock
    columns, and with empty fields (undefined values) spelled 'empty'
    (numdiff merges adjacent separators, which would shift the columns)."""
    with open(copy, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(
            [[field if field != "" else "empty" for field in row] for row in without_wall_time(path)])
    return copy


def without_wall_time(path):
    """The rows of a CSV file without its wall-clock columns."""
    with open(path) as f:
        rows = list(csv.reader(f))
    keep = [i for i, title in enumerate(rows[0]) if "wall_time" not in title] if rows else []
    return [[row[i] for i in keep if i < len(row)] for row in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("name", help="a directory of tests/regression with a scene.prm")
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks (default 1)")
    parser.add_argument("--regenerate", action="store_true",
                        help="overwrite the committed reference files with this run's output")
    options = parser.parse_args()

    directory = os.path.join(HERE, options.name)
    references = [f for f in OUTPUT_FILES if os.path.exists(os.path.join(directory, f))]
    output = run_scene(options.name, options.ranks)
    written = [f for f in OUTPUT_FILES if os.path.exists(os.path.join(output, f))]

    if options.regenerate:
        for f in written:
            reference = os.path.join(directory, f)
            if os.path.exists(reference) and \
                    without_wall_time(reference) == without_wall_time(os.path.join(output, f)):
                # keep the file: only the wall time would change
                print(f"unchanged {reference}")
                continue
            shutil.copyfile(os.path.join(output, f), reference)
            print(f"wrote {reference}")
        for f in set(references) - set(written):
            os.remove(os.path.join(directory, f))
            print(f"removed {os.path.join(directory, f)} (no longer written)")
        return 0

    if not references:
        sys.exit(f"[FAIL] {options.name}: no reference file in {directory} "
                 f"(regression.py {options.name} --regenerate writes them)")
    failures = 0
    for f in references:
        reference = os.path.join(directory, f)
        produced = os.path.join(output, f)
        if not os.path.exists(produced):
            print(f"[FAIL] {f}: not written by the run")
            failures += 1
            continue
        reference = comparable(reference, produced + ".reference")
        produced = comparable(produced, produced + ".compared")
        command = [NUMDIFF] + numdiff_arguments(reference) + [reference, produced]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode == 0:
            print(f"[ ok ] {f}: equal to the reference within {RELATIVE:g} relative "
                  f"(or {COLUMN_FLOOR:g} of the column's largest value)")
        else:
            # numdiff lists each differing field with its absolute and
            # relative error
            lines = (result.stdout + result.stderr).splitlines()
            print("\n".join(lines[:60] + (["..."] if len(lines) > 60 else [])))
            print(f"[FAIL] {f}: differs from the reference {reference}")
            failures += 1
    print("all checks passed" if not failures else f"{failures} file(s) differ")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
