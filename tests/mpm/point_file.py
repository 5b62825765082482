#!/usr/bin/python3
"""Bodies from a points file (Shape = points): a CSV of the points the
built-in disk seeds on the lattice (Seeding = lattice: sub-cell centres of a 20 x 20 grid within the radius,
each with a quarter of a cell's area) gives the same number of points,
mass (momentum at 1 m/s) and centre of mass as the disk itself, to 1e-12
relative (sums of the same numbers in another order), on 1 and 2 ranks; a
velocity column replaces 'Velocity'; a relative file name is read from the
parameter file's folder; points on cell faces and on the grid's upper
bounds are seeded once (2 ranks); unknown or missing columns and bad rows stop the
run naming the file, line and column."""
import os
import shutil

from scene_test import *

N, K = 20, 2  # cells per direction of the unit square, points per cell direction
h = 1.0 / N
centre, radius = (0.5, 0.45), 0.2
points = []
for i in range(N * K):
    for j in range(N * K):
        x, y = (i + 0.5) * h / K, (j + 0.5) * h / K
        if (x - centre[0]) ** 2 + (y - centre[1]) ** 2 <= radius ** 2:
            points.append((x, y))
volume = h * h / (K * K)

scene = {"Dimension": 2, "Gravity": "0, 0", "Time/End time": 1e-3, "Time/Maximum number of steps": 2,
         "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": f"{N}, {N}"}
material = {"Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000, "Velocity": "1, 0"}
disk = dict(material, **{"Shape": "disk", "Center": f"{centre[0]}, {centre[1]}", "Radius": radius,
                         "Particles per cell direction": K, "Seeding": "lattice"})


def write_points(name, text):
    directory = os.path.join(WORK, name)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    with open(os.path.join(directory, "disk.csv"), "w") as f:
        f.write(text)


def from_file(name):
    return dict(material, **{"Shape": "points", "Points file": "disk.csv"})


_, _, reference = run("points_builtin_disk", scene, [disk])
expected = reference[0]
rows_csv = "".join(f"{volume!r},{x!r},{y!r}\n" for x, y in points)
for ranks in (0, 2):
    name = f"points_disk_np{max(ranks, 1)}"
    write_points(name, "# the points of the built-in disk\nvolume,x,y\n" + rows_csv)
    _, _, rows = run(name, scene, [from_file(name)], ranks=ranks, fresh=False)
    row = rows[0]
    what = f"{max(ranks, 1)} rank(s)"
    check(f"{what}: as many points as the built-in disk", row["particles"] == expected["particles"] == len(points),
          f"{row['particles']:g}, disk {expected['particles']:g}, file {len(points)}")
    check_relative(f"{what}: mass (momentum at 1 m/s) as the built-in disk's", row["momentum_x"],
                   expected["momentum_x"], 1e-12)
    for axis in "xy":
        check_relative(f"{what}: centre of mass {axis} as the built-in disk's", row[f"body0_{axis}"],
                       expected[f"body0_{axis}"], 1e-12)

# points on cell faces, corners and the grid's upper bound: each seeded
# once, also where the faces are those between the ranks' cells
name = "points_on_faces"
faces = [(0.5, 0.5), (0.25, 0.5), (0.5, 0.3), (1.0, 0.5), (0.5, 1.0), (1.0, 1.0), (0.0, 0.0)]
write_points(name, "x,y,volume\n" + "".join(f"{x},{y},{volume!r}\n" for x, y in faces))
_, _, rows = run(name, dict(scene, **{"Grid/Subdivisions": "4, 4"}), [dict(from_file(name), Velocity="0, 0")], ranks=2, fresh=False)
check("2 ranks: points on faces, corners and the grid's bounds seeded once each",
      rows[0]["particles"] == len(faces), f"{rows[0]['particles']:g} of {len(faces)}")

# velocities from the file
name = "points_velocity"
write_points(name, "x,y,volume,vx,vy\n" + "".join(f"{x!r},{y!r},{volume!r},2,-1\n" for x, y in points))
_, _, rows = run(name, scene, [from_file(name)], fresh=False)
check_relative("velocity columns: momentum_x = 2 m/s times the mass", rows[0]["momentum_x"],
               2 * expected["momentum_x"], 1e-12)
check_relative("velocity columns: momentum_y = -1 m/s times the mass", rows[0]["momentum_y"],
               -expected["momentum_x"], 1e-12)

# bad files: the message names file, line and column
bad = {
    "unknown column": ("x,y,vol\n0.5,0.5,0.001\n", ["disk.csv, line 1, column 3", "vol", "volume"]),
    "missing volume": ("x,y\n0.5,0.5\n", ["disk.csv, line 1", "a column 'volume'"]),
    "repeated column": ("x,y,x,volume\n", ["disk.csv, line 1, column 3", "each column once"]),
    "half a velocity": ("x,y,volume,vx\n", ["disk.csv, line 1", "all velocity columns"]),
    "not a number": ("x,y,volume\n0.5,0.5,0.001\n0.5,0.5a,0.001\n", ["disk.csv, line 3, column 2 (y)", "a number"]),
    "too few fields": ("x,y,volume\n0.5,0.5\n", ["disk.csv, line 2", "3 fields"]),
    "zero volume": ("x,y,volume\n0.5,0.5,0\n", ["disk.csv, line 2, column 3 (volume)", "> 0"]),
    "outside the grid": ("x,y,volume\n1.5,0.5,0.001\n", ["Body 0/Points file", "inside the grid"]),
}
for what, (text, words) in bad.items():
    name = "points_bad_" + what.replace(" ", "_")
    write_points(name, text)
    code, output, _ = run(name, scene, [from_file(name)], expect_success=False, fresh=False)
    check(f"{what}: refused, naming {words}", code != 0 and all(w in output for w in words), output.strip()[-300:])
finish()
