"""Reading a run's particle output (particles.pvd and its VTU pieces) in
the scene tests, and the closest approach of two bodies' points. Needs
numpy and meshio (Debian's python3-numpy, python3-meshio)."""
import math
import os
from xml.etree import ElementTree

import meshio
import numpy as np


def particle_files(directory, names=("id", "body", "velocity")):
    """(time, fields) of every particle output in `directory`: the point
    data `names` and the positions "x" (2D), all pieces joined, the points
    sorted by id."""
    root = ElementTree.parse(os.path.join(directory, "particles.pvd")).getroot()
    for dataset in root.iter("DataSet"):
        pvtu = os.path.join(directory, dataset.get("file"))
        pieces = [os.path.join(os.path.dirname(pvtu), p.get("Source"))
                  for p in ElementTree.parse(pvtu).getroot().iter("Piece")]
        meshes = [meshio.read(p) for p in pieces]
        meshes = [m for m in meshes if len(m.points)]
        fields = {name: np.concatenate([m.point_data[name] for m in meshes]) for name in names}
        fields["x"] = np.concatenate([m.points[:, :2] for m in meshes]).astype(float)
        order = np.argsort(fields["id"].ravel())
        yield float(dataset.get("timestep")), {k: v[order] for k, v in fields.items()}


def closest_other_body(x, body, width, period=None):
    """Least distance from a point to a point of another body, found in cell
    lists of `width` (two points closer than it are in neighbouring cells;
    farther pairs may be missed, and none found gives infinity); with
    `period`, across a periodic seam along y too (the points within two
    widths of it also at their images)."""
    if period is not None:
        low, high = x[:, 1] < 2 * width, x[:, 1] > period - 2 * width
        x = np.concatenate([x, x[low] + [0, period], x[high] - [0, period]])
        body = np.concatenate([body, body[low], body[high]])
    keys = np.floor(x / width).astype(int)
    cells = {}
    for i, key in enumerate(map(tuple, keys)):
        cells.setdefault(key, []).append(i)
    best = math.inf
    for (i, j), members in cells.items():
        near = [m for di in (-1, 0, 1) for dj in (-1, 0, 1) for m in cells.get((i + di, j + dj), [])]
        a, b = np.array(members), np.array(near)
        d = np.linalg.norm(x[a][:, None, :] - x[b][None, :, :], axis=2)
        d[body[a][:, None] == body[b][None, :]] = np.inf
        best = min(best, d.min())
    return best
