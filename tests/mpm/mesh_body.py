#!/usr/bin/python3
"""Bodies from a volume mesh (Shape = mesh): material points at the sub-cell
centres of the MPM grid that lie in a cell of the mesh, the same lattice as
the built-in shapes.

2D, the L-shape of three quadrilaterals in tests/mpm/meshes (Gmsh 4.1, UCD
and legacy VTK): placed on the lattice, its points fill it exactly (mass and
centroid to 1e-12), rotation is about its centroid (zero momentum);
placed off the lattice, the points are exactly those an independent test of
the L finds, and their volume is the L's area within the band the lattice
cannot resolve. A 256-gon of triangles and quadrilaterals (a mixed mesh)
seeds exactly the points of the built-in disk it approximates (seeded on
the lattice), on 1 and 2
ranks, and on a grid refined around body surfaces gets the disk's cells. 3D: the unit cube as 8 hexahedra, as 8 hexahedra with a displaced
centre vertex (warped inner faces) and as 6 tetrahedra, scaled and moved
off the lattice, seeds exactly the points of the built-in box; so does the
cube as a 12-triangle STL surface, also with its faces on the lattice's
sub-cell planes (points projecting onto its edges and diagonals); a binary
STL icosphere seeds exactly the points inside all its face planes. Bad
files and entries stop the run before any work, naming the entry and
value."""
import math
import os
import shutil
import subprocess

from scene_test import *

SOURCE = os.environ.get("SABLE_SOURCE", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
MESHES = os.path.join(SOURCE, "tests", "mpm", "meshes")

material = {"Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000}
DENSITY = 1000


def scene(dim, n, steps=1):
    return {"Dimension": dim, "Gravity": ", ".join(["0"] * dim), "Time/End time": 1,
            "Time/Maximum number of steps": steps,
            "Grid/Lower corner": ", ".join(["0"] * dim), "Grid/Upper corner": ", ".join(["1"] * dim),
            "Grid/Subdivisions": ", ".join([str(n)] * dim)}


def prepare(name, files):
    """An empty run directory with the mesh files in its subfolder meshes/:
    the body names them relative to the parameter file."""
    directory = os.path.join(WORK, name)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(os.path.join(directory, "meshes"))
    for target, text in files.items():
        with open(os.path.join(directory, "meshes", target), "w") as f:
            f.write(text)


def committed(filename):
    with open(os.path.join(MESHES, filename)) as f:
        return f.read()


def mesh_body(filename, scale, translation, **extra):
    return dict(material, **{"Shape": "mesh", "Mesh file": "meshes/" + filename, "Mesh scale": scale,
                             "Mesh translation": ", ".join(repr(t) for t in translation)}, **extra)


def run_mesh(name, entries, body, files, ranks=0):
    prepare(name, files)
    return run(name, entries, [body], ranks=ranks, fresh=False)[2][0]


# ---- 2D: the L-shape [0,2]^2 minus [1,2]^2, scaled by 0.2 -----------------
# 20 x 20 cells, 2 points per cell direction: lattice spacing s = 0.025
N, K = 20, 2
s = 1.0 / N / K
scale = 0.2
area = 3 * scale ** 2
centroid_units = (5 / 6, 5 / 6)  # of the three unit squares' centres
for filename in ("l_shape.msh", "l_shape.inp", "l_shape.vtk"):
    # corners on lattice lines: the sub-cells of the points tile the L,
    # so volume and centroid are exact; rotation about the centroid gives
    # zero momentum (about the bounding box's centre its y component would
    # be M omega (c_x - c_box,x) = 120 kg * 2/s * 0.0333 m = 8 kg m/s)
    row = run_mesh("l_aligned_" + filename.replace(".", "_"), scene(2, N),
                   mesh_body(filename, scale, (0.1, 0.1), **{"Angular velocity": 2, "Velocity": "1, 0"}),
                   {filename: committed(filename)})
    what = f"L-shape on the lattice ({filename})"
    check(f"{what}: points fill it", row["particles"] == round(area / s ** 2), f"{row['particles']:g}")
    check_relative(f"{what}: mass = density x area", row["momentum_x"], DENSITY * area, 1e-12)
    for axis, c in zip("xy", centroid_units):
        check_relative(f"{what}: centroid {axis}", row[f"body0_{axis}"], 0.1 + scale * c, 1e-12)
    check(f"{what}: rotation about the centroid (momentum_y = 0)", abs(row["momentum_y"]) < 1e-12 * DENSITY * area,
          f"{row['momentum_y']:.3g}")

# off the lattice: the points are exactly those inside the closed L
scale, shift = 0.3, (0.1137, 0.1291)
lattice = [(i + 0.5) * s for i in range(N * K)]
# no lattice coordinate on the L's edge lines, where rounding could decide
clearance = min(abs(x - t - scale * k) for x in lattice for t in shift for k in range(3))
check("L-shape off the lattice: its edges clear of the lattice lines", clearance > 1e-6, f"{clearance:.3g}")


def in_l(x, y):
    u, v = (x - shift[0]) / scale, (y - shift[1]) / scale
    return 0 <= u <= 2 and 0 <= v <= 2 and not (u > 1 and v > 1)


inside = [(x, y) for x in lattice for y in lattice if in_l(x, y)]
row = run_mesh("l_off_lattice", scene(2, N), mesh_body("l_shape.msh", scale, shift, Velocity="1, 0"),
               {"l_shape.msh": committed("l_shape.msh")})
check("L-shape off the lattice: the points inside the L, found independently",
      row["particles"] == len(inside), f"{row['particles']:g}, expected {len(inside)}")
for axis, k in zip("xy", (0, 1)):
    check_relative(f"L-shape off the lattice: centre of mass {axis} as the points'", row[f"body0_{axis}"],
                   sum(p[k] for p in inside) / len(inside), 1e-12)
# each point stands for an s x s square; the squares and the L differ only
# within s/sqrt(2) of its boundary (perimeter P = 8 x 0.3): a band of area
# at most sqrt(2) P s + pi s^2 / 2, about one lattice layer of the perimeter
area = 3 * scale ** 2
band = math.sqrt(2) * 8 * scale * s + math.pi * s ** 2 / 2
volume = row["momentum_x"] / DENSITY
check("L-shape off the lattice: volume = area within the band of the lattice spacing along its boundary",
      abs(volume - area) <= band, f"volume {volume:.6g}, area {area:.6g}, band {band:.3g}")

# ---- 2D: a 256-gon (triangle fan inside, ring of quadrilaterals) against
# the built-in disk it is inscribed in ---------------------------------------
centre, radius = (0.5, 0.45), 0.2
inner = [math.hypot(x - centre[0], y - centre[1]) for x in lattice for y in lattice]
gap = min(radius - r for r in inner if r <= radius)  # closest inside point to the circle
sides = 256
# the polygon's edges are at most the sagitta inside the circle: the point
# sets coincide if no lattice point lies in between
sagitta = radius * (1 - math.cos(math.pi / sides))
check("256-gon: no lattice point between the polygon and the circle", sagitta < gap,
      f"sagitta {sagitta:.3g}, gap {gap:.3g}")
nodes = [(0.0, 0.0)] + [(r * math.cos(2 * math.pi * i / sides), r * math.sin(2 * math.pi * i / sides))
                        for r in (0.5, 1.0) for i in range(sides)]
elements = [(2, [1, 2 + i, 2 + (i + 1) % sides]) for i in range(sides)]
elements += [(3, [2 + i, 2 + sides + i, 2 + sides + (i + 1) % sides, 2 + (i + 1) % sides]) for i in range(sides)]
polygon = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes)
polygon += "".join(f"{i + 1} {x!r} {y!r} 0\n" for i, (x, y) in enumerate(nodes))
polygon += "$EndNodes\n$Elements\n%d\n" % len(elements)
polygon += "".join(f"{e + 1} {t} 2 1 1 " + " ".join(map(str, v)) + "\n" for e, (t, v) in enumerate(elements))
polygon += "$EndElements\n"
disk = dict(material, Shape="disk", Center=f"{centre[0]}, {centre[1]}", Radius=radius, Velocity="1, 0",
            Seeding="lattice")
expected = run("polygon_builtin_disk", scene(2, N), [disk])[2][0]
for ranks in (0, 2):
    what = f"256-gon, {max(ranks, 1)} rank(s)"
    row = run_mesh(f"polygon_np{max(ranks, 1)}", scene(2, N),
                   mesh_body("polygon.msh", radius, centre, Velocity="1, 0"), {"polygon.msh": polygon}, ranks)
    check(f"{what}: the built-in disk's points", row["particles"] == expected["particles"],
          f"{row['particles']:g}, disk {expected['particles']:g}")
    check_relative(f"{what}: the built-in disk's mass", row["momentum_x"], expected["momentum_x"], 1e-12)
    for axis in "xy":
        check_relative(f"{what}: the built-in disk's centre of mass {axis}", row[f"body0_{axis}"],
                       expected[f"body0_{axis}"], 1e-12)

# the 'body surface' refinement of an adaptive grid sees the same surface:
# the same cells and points as around the built-in disk
adaptive = dict(scene(2, 10), **{"Mesh refinement/Criteria": "body surface", "Mesh refinement/Maximum level": 2})
expected = run("polygon_refined_disk", adaptive, [disk])[2][0]
row = run_mesh("polygon_refined", adaptive, mesh_body("polygon.msh", radius, centre, Velocity="1, 0"),
               {"polygon.msh": polygon})
check("256-gon on an adaptive grid: refined like the built-in disk (same cells, more than 100)",
      row["cells"] == expected["cells"] > 100, f"{row['cells']:g}, disk {expected['cells']:g}")
check("256-gon on an adaptive grid: the built-in disk's points", row["particles"] == expected["particles"],
      f"{row['particles']:g}, disk {expected['particles']:g}")

# ---- 3D: the unit cube, scaled by 0.3 and moved off the lattice, against
# the built-in box -----------------------------------------------------------
N3, K3 = 10, 4  # lattice spacing 0.025: 12 points across the box
scale, shift = 0.3, (0.1234, 0.1111, 0.1357)
box = dict(material, Shape="box", Velocity="1, 0, 0", **{"Particles per cell direction": K3,
           "Lower corner": ", ".join(map(repr, shift)),
           "Upper corner": ", ".join(repr(t + scale) for t in shift)})
expected = run("cube_builtin_box", scene(3, N3), [box])[2][0]
# the centre vertex (node 14 of 27) moved: the eight hexahedra's inner
# faces become warped (trilinear), their union is still the cube
hexes = committed("cube_hex.msh").replace("\n14 0.5 0.5 0.5\n", "\n14 0.61 0.43 0.55\n")
check("warped cube: the centre vertex moved", hexes != committed("cube_hex.msh"))
for filename, text in (("cube_hex.msh", committed("cube_hex.msh")), ("cube_warped.msh", hexes),
                       ("cube_tet.msh", committed("cube_tet.msh"))):
    what = f"3D {filename}"
    row = run_mesh("cube_" + filename.replace(".", "_"), scene(3, N3),
                   mesh_body(filename, scale, shift, Velocity="1, 0, 0", **{"Particles per cell direction": K3}),
                   {filename: text})
    check(f"{what}: the built-in box's points", row["particles"] == expected["particles"] == 12 ** 3,
          f"{row['particles']:g}, box {expected['particles']:g}")
    check_relative(f"{what}: the built-in box's mass", row["momentum_x"], expected["momentum_x"], 1e-12)
    for axis in "xyz":
        check_relative(f"{what}: the built-in box's centre of mass {axis}", row[f"body0_{axis}"],
                       expected[f"body0_{axis}"], 1e-12)

# ---- 3D: closed surfaces from STL files ---------------------------------------
import itertools
import struct


def stl_ascii(triangles):
    text = "solid test\n"
    for t in triangles:
        text += "  facet normal 0 0 0\n    outer loop\n"
        text += "".join(f"      vertex {x!r} {y!r} {z!r}\n" for x, y, z in t)
        text += "    endloop\n  endfacet\n"
    return text + "endsolid test\n"


def cube_triangles():
    """The unit cube's 12 triangles, each face cut along a diagonal."""
    triangles = []
    for axis in range(3):
        for side in (0, 1):
            corners = []
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                v = [0, 0, 0]
                v[axis], v[(axis + 1) % 3], v[(axis + 2) % 3] = side, a, b
                corners.append(tuple(float(c) for c in v))
            triangles += [(corners[0], corners[1], corners[2]), (corners[0], corners[2], corners[3])]
    return triangles


# the cube on the lattice's sub-cell planes (0.1 + 0.3 = 0.4): many points
# project onto the faces' diagonals and edges, where a ray test without a
# consistent rule counts two triangles or none
for name, shift_cube in (("aligned", (0.1, 0.1, 0.1)), ("off_lattice", shift)):
    box_here = dict(box, **{"Lower corner": ", ".join(map(repr, shift_cube)),
                            "Upper corner": ", ".join(repr(t + scale) for t in shift_cube)})
    expected = run(f"stl_builtin_box_{name}", scene(3, N3), [box_here])[2][0]
    row = run_mesh(f"stl_cube_{name}", scene(3, N3),
                   mesh_body("cube.stl", scale, shift_cube, Velocity="1, 0, 0", **{"Particles per cell direction": K3}),
                   {"cube.stl": stl_ascii(cube_triangles())})
    what = f"3D cube.stl (ASCII), {name.replace('_', ' ')}"
    check(f"{what}: the built-in box's points", row["particles"] == expected["particles"] == 12 ** 3,
          f"{row['particles']:g}, box {expected['particles']:g}")
    for axis in "xyz":
        check_relative(f"{what}: the built-in box's centre of mass {axis}", row[f"body0_{axis}"],
                       expected[f"body0_{axis}"], 1e-12)


def icosphere(levels):
    """Triangles of a sphere of radius 1: an icosahedron, each triangle cut
    into four `levels` times, the new vertices pushed onto the sphere."""
    p = (1 + 5 ** 0.5) / 2
    v = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
         (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    unit = lambda a: tuple(c / math.sqrt(sum(x * x for x in a)) for c in a)
    triangles = [tuple(unit(v[i]) for i in t) for t in f]
    for _ in range(levels):
        finer = []
        for a, b, c in triangles:
            ab, bc, ca = (unit(tuple((x + y) / 2 for x, y in zip(m, n))) for m, n in ((a, b), (b, c), (c, a)))
            finer += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        triangles = finer
    return triangles


# a convex 1280-triangle sphere (binary STL) against an independent test:
# inside every face's plane
sphere = icosphere(3)
radius, centre3 = 0.2, (0.5013, 0.4987, 0.5021)
binary = b"binary STL of a sphere".ljust(80, b" ") + struct.pack("<I", len(sphere))
for t in sphere:
    binary += struct.pack("<12fH", 0, 0, 0, *[c for vertex in t for c in vertex], 0)
planes = []
for a, b, c in sphere:
    a, b, c = (tuple(float(struct.unpack("<f", struct.pack("<f", x))[0]) for x in p) for p in (a, b, c))
    n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
         (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
         (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
    planes.append((n, a))
lattice3 = [(i + 0.5) / N3 / K3 for i in range(N3 * K3)]
inside, clearance = 0, 1.0
for x, y, z in itertools.product(lattice3, repeat=3):
    u = [(q - o) / radius for q, o in zip((x, y, z), centre3)]
    if sum(c * c for c in u) > 1 + 1e-6:  # outside the sphere the polyhedron is inscribed in
        continue
    distances = [sum(n_ * (u_ - a_) for n_, u_, a_ in zip(n, u, a)) / math.sqrt(sum(c * c for c in n))
                 for n, a in planes]  # outward normals: inside means all <= 0
    inside += max(distances) < 0
    clearance = min(clearance, abs(max(distances)))
check("STL sphere: no lattice point on a face plane", clearance > 1e-6, f"{clearance:.3g}")
prepare("stl_sphere", {})
with open(os.path.join(WORK, "stl_sphere", "meshes", "sphere.stl"), "wb") as f:
    f.write(binary)
row = run("stl_sphere", scene(3, N3),
          [mesh_body("sphere.stl", radius, centre3, Velocity="1, 0, 0", **{"Particles per cell direction": K3})],
          fresh=False)[2][0]
check("STL sphere (binary, 1280 triangles): the points inside every face, found independently",
      row["particles"] == inside, f"{row['particles']:g}, expected {inside}")

# ---- a relative path is read from the parameter file's folder, whatever
# the working directory --------------------------------------------------------
name = "relative_path"
prepare(name, {"l_shape.msh": committed("l_shape.msh")})
entries = dict(scene(2, N), **{"Output directory": os.path.join(WORK, name, "output"), "Output/Statistics interval": 1})
with open(os.path.join(WORK, name, "scene.prm"), "w") as f:
    f.write(prm_text(entries, [mesh_body("l_shape.msh", 0.2, (0.1, 0.1))]))
result = subprocess.run([SABLE, os.path.join(name, "scene.prm")], cwd=WORK, capture_output=True, text=True)
check("mesh file found next to the parameter file, run from another folder", result.returncode == 0,
      (result.stdout + result.stderr).strip()[-300:])

# ---- bad input: refused before any work, naming the entry and value ---------
square = committed("l_shape.msh")
bad = {
    "missing file": ("2", {"Mesh file": "meshes/part.msh"}, {}, ["Body 0/Mesh file = meshes/part.msh", "cannot open"]),
    "no file name": ("2", {"Mesh file": ""}, {}, ["Body 0/Mesh file = '", "name of a mesh file"]),
    "unknown suffix": ("2", {"Mesh file": "meshes/part.obj"}, {"part.obj": "v 0 0 0\n"},
                       ["Body 0/Mesh file = meshes/part.obj", "*.msh"]),
    "STL in 2D": ("2", {"Mesh file": "meshes/part.stl"}, {"part.stl": stl_ascii(cube_triangles())},
                  ["Body 0/Mesh file = meshes/part.stl", "2D volume mesh", "3D surface"]),
    "open STL surface": ("3", {"Mesh file": "meshes/part.stl"}, {"part.stl": stl_ascii(cube_triangles()[1:])},
                         ["Body 0/Mesh file = meshes/part.stl", "closed surface", "3 of its 18 edges"]),
    "not a mesh": ("2", {"Mesh file": "meshes/part.msh"}, {"part.msh": "this is not a mesh\n"},
                   ["Body 0/Mesh file = meshes/part.msh", "2D volume mesh", "cannot read it"]),
    "3D mesh in 2D": ("2", {"Mesh file": "meshes/cube_hex.msh"}, {"cube_hex.msh": committed("cube_hex.msh")},
                      ["Body 0/Mesh file = meshes/cube_hex.msh", "2D volume mesh", "this is a 3D mesh"]),
    "2D mesh in 3D": ("3", {"Mesh file": "meshes/l_shape.msh"}, {"l_shape.msh": square},
                      ["Body 0/Mesh file = meshes/l_shape.msh", "3D volume mesh", "this is a 2D mesh"]),
    "outside the grid": ("2", {"Mesh file": "meshes/l_shape.msh", "Mesh translation": "0.7, 0.1"},
                         {"l_shape.msh": square}, ["Body 0/Mesh file = meshes/l_shape.msh", "inside the grid"]),
    "scale zero": ("2", {"Mesh file": "meshes/l_shape.msh", "Mesh scale": 0}, {"l_shape.msh": square},
                   ["Body 0/Mesh scale = 0", "> 0"]),
}
for what, (dim, changes, files, words) in bad.items():
    name = "bad_" + what.replace(" ", "_")
    prepare(name, files)
    body = dict(mesh_body("l_shape.msh", 0.2, (0.1,) * int(dim)), **changes)
    code, output, rows = run(name, scene(int(dim), N3), [body], expect_success=False, fresh=False)
    check(f"{what}: refused, naming {words}", code != 0 and all(w in output for w in words),
          output.strip()[-300:])
    check(f"{what}: no step taken, nothing written", "step " not in output and
          not os.path.exists(os.path.join(WORK, name, "output")), output.strip()[-100:])
finish()
