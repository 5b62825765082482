#!/usr/bin/python3
"""Grain packs, bodies from a grain file and scene A5's small variant
(prm/granular_shear_small.prm).

contrib/packs/disk_pack.py:
- the same arguments and seed write the same file, and prm/granular_shear_
  small_pack.csv is what its comment's command writes (byte for byte);
- a 2D pack (periodic in y, grains crossing the x faces) and a 3D pack:
  no two grains closer than the gap (1% of the smaller radius, across the
  periodic seam too), diameters within the range, every centre inside the
  box, grains inside the box along the other axes; the area (volume)
  fraction the file states is the one recomputed here (to 1e-4), at least
  0.6 of a target of 0.7 in 2D; the mean diameter of the 2D pack (about 380
  grains) within 4 standard errors of the distribution's 57 um (the sample
  standard deviation over sqrt(n)). The gap is checked to 1e-6 (of the
  smaller radius): the file's 10 significant digits round positions by
  about 1e-13 m, 1e-8 of the smallest radius.

Bodies file: a missing file, a bad header, a row that is not a number, a
grain centred outside the grid, a grain reaching beyond a face that holds
no grains (on the scene made not periodic), a bad template entry, grains
held by a face of the periodic axis and grains that overlap (side by side,
or across the periodic seam) stop sable before any work with a message
naming the file, line and entry.

The scene (43 von Mises grains, mu = 0.3, 30% shear, periodic in y, one
rank: contact on a periodic grid is refused on several, see
periodic_boundaries):
- it ends at its end time with finite statistics, and statistics.csv has
  no per-body columns for the bodies of the file;
- the grains held by the walls move exactly with them: at every output
  every point of a left grain has velocity 0 and its initial position,
  every point of a right grain velocity (0, 100 m/s) and its initial
  position + (0, 100 m/s) t (to the nearest image across the seam), to the
  single precision of the VTU files;
- no grain passes into another: at every output no material point is
  closer than s/5 to a point of another grain, across the seam too (s =
  h/2, the point spacing). Points of one body are seeded s apart and
  contact keeps two grains' outer points about s apart; a grain passing
  into another brings points to 0. Contact here does not keep them s/2
  apart: at 100 m/s the grains of the moving wall (rigid drivers) press
  into their neighbours to 0.22-0.24 s, and free grains reach 0.35-0.41 s
  (measured with either contact model, and before the grid was periodic
  too); the least value at each output is printed;
- contrib/validation/a5_shear.py runs on the output: at 30% shear the
  column-averaged vertical displacement, as a fraction of the wall's, is
  within 0.05 of 0 in the column at the fixed wall and between 0.9 and
  1.05 at the moving wall (those columns hold mostly the walls' grains),
  and between -0.05 and 1.05 everywhere; its pictures are written;
- total momentum along y (the wall axis: the slip walls at the x faces
  push only along x, the periodic faces not at all) changes only by the
  impulse the walls' grains gave the others (driver_impulse_y), to 1e-6 of
  that impulse: a driver enters contact with its mass times 1e9, so its
  impulse, that mass times a velocity change of 1e-9 of the velocities,
  keeps about 7 of 16 digits (measured 7e-8);
- plastic work and contact friction work are positive and never decrease
  (both are dissipation: a decrease beyond round-off, 1e-12 of the final
  value, would be energy made from nothing)."""
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_test import MPIEXEC, SABLE, WORK, check, finish, read_csv  # noqa: E402

try:
    import numpy as np
    from particle_output import closest_other_body, particle_files
except ImportError as error:
    sys.exit(f"granular_shear_small.py: {error.name} is missing (python3-numpy, python3-meshio)")

SOURCE = os.environ.get("SABLE_SOURCE",
                        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
PACK = os.path.join(SOURCE, "contrib", "packs", "disk_pack.py")
SCENE = os.path.join(SOURCE, "prm", "granular_shear_small.prm")
SCENE_PACK = os.path.join(SOURCE, "prm", "granular_shear_small_pack.csv")
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)


def pack(path, *args):
    result = subprocess.run(["/usr/bin/python3", PACK, path] + [str(a) for a in args],
                            capture_output=True, text=True)
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        raise SystemExit(f"[FAIL] disk_pack.py {' '.join(map(str, args))}")
    return result.stdout


def read_pack(path):
    with open(path) as f:
        lines = f.readlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    axes = [a for a in "xyz" if a in rows[0]]
    centres = np.array([[float(r[a]) for a in axes] for r in rows])
    radii = np.array([float(r["radius"]) for r in rows])
    return comments, centres, radii


# --- the pack script -------------------------------------------------------
first, second = os.path.join(WORK, "a.csv"), os.path.join(WORK, "b.csv")
for path in (first, second):
    pack(path, "--box", 4e-4, 4e-4, "--fraction", 0.7, "--max-diameter", 125e-6, "--cross", "x",
         "--periodic", "y", "--seed", 3)
check("disk_pack.py: the same seed writes the same file", open(first).read() == open(second).read())
check("prm/granular_shear_small_pack.csv is what its command writes", open(first).read() == open(SCENE_PACK).read())


def check_pack(name, path, dim, box, periodic, cross, target, largest, gap=0.01):
    comments, centres, radii = read_pack(path)
    n = len(radii)
    delta = centres[:, None, :] - centres[None, :, :]
    for d in range(dim):
        if "xyz"[d] in periodic:
            delta[:, :, d] -= box[d] * np.round(delta[:, :, d] / box[d])
    distance = np.linalg.norm(delta, axis=2)
    rmin = np.minimum(radii[:, None], radii[None, :])
    surface_gap = (distance - radii[:, None] - radii[None, :]) / rmin
    np.fill_diagonal(surface_gap, np.inf)
    check(f"{name}: no two grains closer than {gap} of the smaller radius",
          surface_gap.min() >= gap - 1e-6, f"least gap {surface_gap.min():.6f}")
    check(f"{name}: diameters within 31-{largest * 1e6:.0f} um",
          2 * radii.min() >= 31e-6 and 2 * radii.max() <= largest,
          f"{2 * radii.min() * 1e6:.1f}-{2 * radii.max() * 1e6:.1f} um")
    inside = True
    for d in range(dim):
        inside &= bool(np.all(centres[:, d] >= 0) and np.all(centres[:, d] <= box[d]))
        if "xyz"[d] not in periodic + cross:
            inside &= bool(np.all(centres[:, d] - radii >= 0) and np.all(centres[:, d] + radii <= box[d]))
    check(f"{name}: grains inside the box (centres; wholly along the wall axes)", inside)
    # the fraction: whole grains less the caps beyond crossed faces
    measure = math.pi * radii**2 if dim == 2 else 4 / 3 * math.pi * radii**3
    for d in range(dim):
        if "xyz"[d] in cross:
            for depth in (radii - centres[:, d], centres[:, d] + radii - box[d]):
                depth = np.clip(depth, 0, None)
                if dim == 2:
                    c = radii - depth
                    cap = radii**2 * np.arccos(np.clip(c / radii, -1, 1)) - c * np.sqrt(np.clip(radii**2 - c**2, 0, None))
                else:
                    cap = math.pi * depth**2 * (3 * radii - depth) / 3
                measure = measure - np.where(depth > 0, cap, 0)
    fraction = measure.sum() / np.prod(box)
    stated = float(comments[-1].split("fraction")[1].split()[0])
    check(f"{name}: the stated fraction is the recomputed one", abs(stated - fraction) <= 1e-4,
          f"stated {stated}, recomputed {fraction:.5f}, target {target}")
    return n, fraction, radii


large = os.path.join(WORK, "large.csv")
print(pack(large, "--box", 1.2e-3, 1.2e-3, "--fraction", 0.75, "--cross", "x", "--periodic", "y", "--seed", 1).strip())
n, fraction, radii = check_pack("2D pack", large, 2, [1.2e-3, 1.2e-3], "y", "x", 0.75, 250e-6)
check("2D pack: fraction at least 0.6", fraction >= 0.6, f"{fraction:.4f}")
diameters = 2 * radii
error = diameters.std(ddof=1) / math.sqrt(n)
check("2D pack: mean diameter within 4 standard errors of 57 um", abs(diameters.mean() - 57e-6) <= 4 * error,
      f"{n} grains, mean {diameters.mean() * 1e6:.2f} um, standard error {error * 1e6:.2f} um")
small3d = os.path.join(WORK, "spheres.csv")
print(pack(small3d, "--dim", 3, "--box", 3e-4, 3e-4, 3e-4, "--fraction", 0.4, "--max-diameter", 1e-4,
           "--seed", 2).strip())
check_pack("3D pack", small3d, 3, [3e-4, 3e-4, 3e-4], "", "", 0.4, 1e-4)

# --- bad input -------------------------------------------------------------


def sable(directory, args, ranks=0):
    command = [SABLE] + args
    if ranks:
        command = [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    result = subprocess.run(command, cwd=directory, capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


bad = os.path.join(WORK, "bad")
os.makedirs(bad)
shutil.copy(SCENE, os.path.join(bad, "scene.prm"))
header = "x,y,radius\n"
cases = [
    ("missing file", None, "nothing.csv", ["Bodies file/File", "nothing.csv", "cannot open"]),
    ("bad header", "x,y,r\n1e-4,1e-4,2e-5\n", "g.csv", ["g.csv, line 1, column 3 = r", "x, y, radius"]),
    ("not a number", header + "1e-4,1e-4,2e-5\n1e-4,abc,2e-5\n", "g.csv", ["g.csv, line 3, column 2 (y)", "abc"]),
    ("centre outside", header + "1e-4,1e-4,2e-5\n\n5e-4,1e-4,2e-5\n", "g.csv", ["g.csv, line 4", "inside the grid"]),
    ("crossing a free face", header + "2e-4,1e-5,2e-5\n", "g.csv",
     ["g.csv, line 2 (radius)", "Lower y wall velocity is empty"]),
    ("overlapping grains", header + "1e-4,2e-4,4e-5\n2e-4,3e-4,3e-5\n1.5e-4,2e-4,4e-5\n", "g.csv",
     ["g.csv, line 2", "g.csv, line 4", "overlap", "quarter of its spacing"]),
    ("overlapping across the periodic seam", header + "2e-4,1e-5,4e-5\n2e-4,3.8e-4,4e-5\n", "g.csv",
     ["g.csv, line 2", "g.csv, line 3", "overlap"]),
]
# the scene is periodic in y; the face checks need a grid that is not
NOT_PERIODIC = ["--set", "Grid/Periodic axes=", "--set", "Boundary conditions/Types=0: slip, 1: slip, 2: slip, 3: slip"]
for name, text, filename, expected in cases:
    if text is not None:
        with open(os.path.join(bad, filename), "w") as f:
            f.write(text)
    code, output = sable(bad, ["scene.prm", "--set", f"Bodies file/File={filename}", "--set", "Output directory=out"] +
                         (NOT_PERIODIC if name == "crossing a free face" else []))
    check(f"bad input, {name}: refused naming {expected}",
          code != 0 and all(e in output for e in expected) and not os.path.exists(os.path.join(bad, "out")),
          output.strip().splitlines()[-1] if output.strip() else "(no output)")
code, output = sable(bad, ["scene.prm", "--set", f"Bodies file/File={SCENE_PACK}",
                           "--set", "Bodies file/Particles per cell direction=7", "--set", "Output directory=out"])
check("bad input, template entry: refused naming Bodies file/Particles per cell direction",
      code != 0 and "Bodies file/Particles per cell direction" in output and "1..4" in output,
      output.strip().splitlines()[-1] if output.strip() else "(no output)")
code, output = sable(bad, ["scene.prm", "--set", f"Bodies file/File={SCENE_PACK}",
                           "--set", "Bodies file/Lower y wall velocity=0, 0", "--set", "Output directory=out"])
check("bad input, grains held by a periodic face: refused naming Bodies file/Lower y wall velocity",
      code != 0 and "Bodies file/Lower y wall velocity" in output and "periodic" in output,
      output.strip().splitlines()[-1] if output.strip() else "(no output)")

# --- the scene ---------------------------------------------------------------
_, centres, radii = read_pack(SCENE_PACK)
width, v_wall = 4e-4, 100.0
left = set(np.nonzero(centres[:, 0] - radii < 0)[0])
right = set(np.nonzero(centres[:, 0] + radii > width)[0])
h = 8e-6
spacing = h / 2


PERIOD = 4e-4  # the grid is periodic in y


if True:
    directory = os.path.join(WORK, "scene")
    os.makedirs(directory)
    code, output = sable(directory, [SCENE, "--set", "Output directory=output", "--set", "Output/Statistics interval=10"])
    if code != 0:
        print(output)
        raise SystemExit(f"[FAIL] the scene exited with {code}")
    rows = read_csv(os.path.join(directory, "output", "statistics.csv"))
    check("scene: ends at its end time", abs(rows[-1]["time"] - 1.2e-6) <= 1e-15, f"t = {rows[-1]['time']}")
    check("scene: statistics finite", all(math.isfinite(v) for r in rows for v in r.values()))
    check("scene: no per-body columns for the file's bodies", not any(k.startswith("body") for k in rows[0]))
    files = list(particle_files(os.path.join(directory, "output")))
    t0, start = files[0]
    held_ok, worst = True, 0.0
    for t, fields in files:
        body = fields["body"].ravel().astype(int)
        for grains, velocity in ((left, (0.0, 0.0)), (right, (0.0, v_wall))):
            mask = np.isin(body, list(grains))
            held_ok &= bool(np.all(fields["velocity"][mask, 0] == velocity[0]) and
                            np.all(fields["velocity"][mask, 1] == velocity[1]))
            expected = start["x"][mask] + np.array(velocity) * (t - t0)
            error = fields["x"][mask] - expected
            error[:, 1] -= PERIOD * np.round(error[:, 1] / PERIOD)  # the nearest image
            worst = max(worst, np.abs(error).max())
    # positions are written in single precision: 6e-8 of 5e-4 m
    check("scene: the held grains move exactly with their walls",
          held_ok and worst <= 1e-10 and len(left) > 0 and len(right) > 0,
          f"{len(left)} left and {len(right)} right grains over {len(files)} outputs, position error {worst:.2e} m")
    closest = [closest_other_body(fields["x"], fields["body"].ravel().astype(int), spacing, PERIOD) / spacing
               for t, fields in files]
    print("closest points of different grains at each output, in spacings s: " +
          ", ".join(f"{c:.3f}" for c in closest))
    check("scene: no grain passes into another (closest points of two grains >= s/5 at every output)",
          min(closest) >= 0.2, f"least {min(closest):.3f} s")
    # momentum: along y only the drivers push (the slip walls act along x,
    # the periodic faces not at all)
    impulse = np.array([r["driver_impulse_y"] for r in rows])
    change = np.array([r["momentum_y"] - rows[0]["momentum_y"] for r in rows])
    scale = np.abs(impulse).max()
    check("scene: momentum along y changes only by the walls' grains' impulse (1e-6 of it: the drivers' "
          "mass factor 1e9 leaves 7 of 16 digits)",
          scale > 0 and np.abs(change - impulse).max() <= 1e-6 * scale,
          f"largest difference {np.abs(change - impulse).max():.3g} of an impulse {scale:.3g} kg m/s per m")
    plastic = np.array([r["plastic_work"] for r in rows])
    friction = np.array([r["contact_heat"] for r in rows])
    for name, series in (("plastic work", plastic), ("contact friction work", friction)):
        check(f"scene: {name} positive and never decreasing",
              series[-1] > 0 and np.all(np.diff(series) >= -1e-12 * series[-1]),
              f"final {series[-1]:.4g} J/m, largest decrease {-min(np.diff(series).min(), 0):.2g}")
    # the postprocessing script on this run
    post = os.path.join(WORK, "a5_shear")
    result = subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "contrib", "validation", "a5_shear.py"),
                             os.path.join(directory, "output"), "--work", post, "--width", str(width),
                             "--period", str(PERIOD), "--levels", "0.1", "0.3", "--bins", "10"],
                            capture_output=True, text=True)
    print(result.stdout.strip())
    check("a5_shear.py runs on the scene's output", result.returncode == 0, result.stderr.strip()[-300:])
    if result.returncode == 0:
        with open(os.path.join(post, "profiles.csv")) as f:
            profile = [(float(r["shear"]), float(r["fraction_of_wall"])) for r in csv.DictReader(f)]
        last = [fr for sh, fr in profile if abs(sh - 0.3) < 0.01]
        check("a5_shear.py: at 30% shear the profile goes from the fixed wall's 0 to the moving wall's 1 "
              "(outer columns, mostly held grains: within 0.05 and 0.1)",
              len(last) == 10 and abs(last[0]) <= 0.05 and 0.9 <= last[-1] <= 1.05 and
              all(-0.05 <= f <= 1.05 for f in last), " ".join(f"{f:.3f}" for f in last))
        check("a5_shear.py: the pictures are written",
              all(os.path.exists(os.path.join(post, n)) for n in ("profiles.png", "energy.png",
                                                                   "stress_difference_30.png")))
    print(f"energy: boundary work {rows[-1]['boundary_work']:.4g} J/m, kinetic {rows[-1]['kinetic_energy']:.4g}, "
          f"strain {rows[-1]['strain_energy']:.4g}, plastic {plastic[-1]:.4g}, friction {friction[-1]:.4g}, "
          f"energy drift {rows[-1]['energy_drift']:.4f}")

finish()
