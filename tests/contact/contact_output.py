#!/usr/bin/python3
"""Contact-node output (Output/Contact node output): two disks colliding with
sticking contact on two MPI ranks. In the files written while they touch:
every normal is a unit vector, the states are 0, 1 or 2, stuck nodes exist,
and the contact forces on all bodies sum to zero (at two-body nodes the two
corrections cancel). The files hold single-precision values (deal.II's
output patches), each rounded to within 2^-24 = 6e-8 of itself, so the sum
is zero to 1e-7 of the sum of the force magnitudes, and a unit normal has
length 1 to 1e-6. The files are read through meshio.

The same disks on one rank with mu = 0.3, once with 'Contact/Round pair
normals = line of centres': at every file where they touch, all nodes that
act carry one normal, the line between the disks' centres (the directions
agree to 1e-6, the files' precision); with the default fitted planes the
normal turns from node to node (measured: by up to 0.22 rad), which shows
the check can fail."""
import glob
import math
import os
import sys
import xml.etree.ElementTree as ET

import meshio

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "mpm"))
from scene_test import WORK, check, finish, run  # noqa: E402

disk = {"Shape": "disk", "Radius": 0.2, "Young's modulus": 1e6, "Poisson's ratio": 0.3,
        "Density": 1000, "Particles per cell direction": 2}
code, output, rows = run("contact_output", {
    "Dimension": 2, "Time/End time": 0.04, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
    "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": "stick",
    "Output/Particle output interval": 0.005, "Output/Contact node output": "true",
}, [dict(disk, Center="0.745, 0.5", Velocity="5, 0"), dict(disk, Center="1.255, 0.52", Velocity="-5, 0")], ranks=2)

directory = os.path.join(WORK, "contact_output", "output")
files = sorted(glob.glob(os.path.join(directory, "contact_nodes_*.pvtu")))
check("a contact-node file per particle output", len(files) == len(glob.glob(os.path.join(directory, "particles_*.pvtu"))),
      f"{len(files)} files")
check("a contact_nodes.pvd series", os.path.exists(os.path.join(directory, "contact_nodes.pvd")))


def read(pvtu, directory=directory):
    points = []
    for piece in ET.parse(pvtu).getroot().iter("Piece"):
        path = os.path.join(directory, piece.get("Source"))
        if ET.parse(path).getroot().find(".//Piece").get("NumberOfPoints") == "0":
            continue  # a rank without contact nodes (meshio cannot read an empty piece)
        mesh = meshio.read(path)
        data = mesh.point_data
        for i in range(len(mesh.points)):
            points.append({"state": int(round(data["state"][i])), "body": int(round(data["body"][i])),
                           "normal": [float(x) for x in data["normal"][i]],
                           "force": [float(x) for x in data["contact_force"][i]]})
    return points


touching = 0
for pvtu in files:
    points = read(pvtu)
    if not any(p["state"] for p in points):
        continue
    touching += 1
    name = os.path.basename(pvtu)
    acting = [p for p in points if p["state"]]
    check(f"{name}: acting normals are unit vectors",
          all(abs(math.hypot(*p["normal"]) - 1) < 1e-6 for p in acting))
    check(f"{name}: states in 0..2", all(p["state"] in (0, 1, 2) for p in points))
    check(f"{name}: stuck nodes present", any(p["state"] == 1 for p in points))
    total = [sum(p["force"][d] for p in points) for d in range(2)]
    size = sum(math.hypot(*p["force"][:2]) for p in points)
    check(f"{name}: contact forces sum to zero", math.hypot(*total) <= 1e-7 * size,
          f"|sum f| = {math.hypot(*total):.3g} N of {size:.3g} N")
check("the disks touched in some output", touching > 0, f"{touching} files with contact")


def largest_turn(pair_normals):
    """The largest angle between two acting nodes' normals (body 0's, or
    body 1's reversed) in any file where the disks touch, one rank."""
    code, output, rows = run(f"contact_output_{pair_normals.split()[0]}", {
        "Dimension": 2, "Time/End time": 0.04, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
        "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001", "Contact/Friction coefficient": 0.3,
        "Contact/Round pair normals": pair_normals,
        "Output/Particle output interval": 0.005, "Output/Contact node output": "true",
    }, [dict(disk, Center="0.745, 0.5", Velocity="5, 0"), dict(disk, Center="1.255, 0.52", Velocity="-5, 0")])
    where = os.path.join(WORK, f"contact_output_{pair_normals.split()[0]}", "output")
    turn, files_touching = 0.0, 0
    for pvtu in sorted(glob.glob(os.path.join(where, "contact_nodes_*.pvtu"))):
        normals = [p["normal"][:2] if p["body"] == 0 else [-x for x in p["normal"][:2]]
                   for p in read(pvtu, where) if p["state"]]
        if not normals:
            continue
        files_touching += 1
        angles = [math.atan2(n[1], n[0]) for n in normals]
        turn = max(turn, max(angles) - min(angles))
    return code, turn, files_touching


code, turn, n = largest_turn("line of centres")
check("line of centres: in every file where the disks touch, all acting nodes carry one normal (to 1e-6 rad)",
      code == 0 and n > 0 and turn < 1e-6, f"{n} files, largest turn {turn:.2e} rad")
code, turn, n = largest_turn("fitted plane")
check("fitted planes (the default): the normal turns from node to node (by more than 1e-3 rad)",
      code == 0 and n > 0 and turn > 1e-3, f"{n} files, largest turn {turn:.2e} rad")
finish()
