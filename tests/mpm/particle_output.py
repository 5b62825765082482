"""Reading a run's particle output (particles.pvd and its VTU pieces) in
the scene tests, the closest approach of two bodies' points, and how far
one body's points reach into another. Needs numpy and meshio (Debian's python3-numpy, python3-meshio)."""
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


def convex_hull(points):
    """Vertices of the convex hull of 2D `points`, counter-clockwise
    (Andrew's monotone chain)."""
    pts = sorted(set(map(tuple, points)))
    if len(pts) < 3:
        return np.array(pts)

    def chain(sequence):
        out = []
        for p in sequence:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1]) -
                                     (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out[:-1]

    return np.array(chain(pts) + chain(reversed(pts)))


def deepest_in_other_hull(x, body):
    """How far the points of one body reach into the convex hull of another
    body's points (2D): the largest distance from such a point to the
    hull's nearest edge (positive inside, negative: the least clearance of
    any point outside, within a bounding box; -inf if no point comes near).
    A grain's points fill it to within a fraction of a spacing of its
    surface, so a point of another grain inside that hull lies inside the
    grain: interpenetration, whatever the seeding. For convex grains
    (disks, boxes)."""
    deepest = -math.inf
    for k in np.unique(body):
        own = x[body == k]
        hull = convex_hull(own)
        if len(hull) < 3:
            continue
        edges = np.roll(hull, -1, axis=0) - hull
        inward = np.stack([-edges[:, 1], edges[:, 0]], axis=1)
        inward /= np.linalg.norm(inward, axis=1)[:, None]
        spread = np.linalg.norm(own.max(axis=0) - own.min(axis=0))
        low, high = own.min(axis=0) - 0.1 * spread, own.max(axis=0) + 0.1 * spread
        other = x[(body != k) & np.all((x >= low) & (x <= high), axis=1)]
        if len(other) == 0:
            continue
        # distance inside each edge's line; inside the hull: the least of them
        inside = ((other[:, None, :] - hull[None, :, :]) * inward[None, :, :]).sum(axis=2).min(axis=1)
        deepest = max(deepest, inside.max())
    return deepest
