#!/usr/bin/python3
"""Contact-node output (Output/Contact node output): two disks colliding with
sticking contact on two MPI ranks. In the files written while they touch:
every normal is a unit vector (to the 9 digits written), the states are 0, 1 or 2, stuck nodes exist,
and the contact forces on all bodies sum to zero (at two-body nodes the two
corrections cancel) to 1e-9 of the sum of their magnitudes. The files are
read with meshio (Debian's /usr/bin/python3 with python3-meshio)."""
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


def read(pvtu):
    points = []
    for piece in ET.parse(pvtu).getroot().iter("Piece"):
        path = os.path.join(directory, piece.get("Source"))
        # a rank without contact nodes writes a piece without points, which
        # meshio 5 cannot read
        if ET.parse(path).getroot().find(".//Piece").get("NumberOfPoints") == "0":
            continue
        data = meshio.read(path).point_data
        for state, normal, force in zip(data["state"], data["normal"], data["contact_force"]):
            points.append({"state": int(state), "normal": [float(x) for x in normal],
                           "force": [float(x) for x in force]})
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
    check(f"{name}: contact forces sum to zero", math.hypot(*total) <= 1e-9 * size,
          f"|sum f| = {math.hypot(*total):.3g} N of {size:.3g} N")
check("the disks touched in some output", touching > 0, f"{touching} files with contact")
finish()
