#!/usr/bin/python3
"""The fields of the particle output (doc/mpm.md, "Particle fields"), read
back with meshio (VTU) and h5py (HDF5), on an elastic box that slides on a
slip floor under gravity (it bounces on the floor, so its stress is not
zero; it slides at 1 m/s, so its displacement grows), in 2D on 2 ranks and
in 3D on 1 rank:

- F and stress are 9-component tensors in VTU, velocity and displacement 3-
  component vectors; in 2D (plane strain) F is padded with F_zz = 1 and
  zeros, the stress is symmetric and its zz component is not zero;
- pressure = -(s_xx + s_yy + s_zz)/3 and von Mises = sqrt(3/2 s':s') of the
  written stress components, to 1e-6 of the largest stress component (each
  value is rounded to single precision, 6e-8 relative: a sum of three
  components is off by at most 3 such roundings, the von Mises norm by a
  few more);
- displacement = position - the position at time 0 (matched by id), to
  3e-7 m: positions, initial positions and displacements are each rounded
  to single precision, 6e-8 of coordinates below 1 m, and 0.1 m moved;
- the mass-weighted mean displacement = the change of the centre of mass in
  statistics.csv, to 1e-6 relative (single-precision masses and
  displacements);
- HDF5 writes the tensors as 9 scalars each (stress_xx, stress_xy, ...,
  deal.II 9.4's HDF5 writer keeps 3 components of a vector), with the same
  pressure and von Mises relations; without 'Output/Displacement output'
  there is no displacement field;
- 'Output/Displacement output' cannot change on --resume (it changes what a
  checkpoint holds)."""
import glob
import os
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np

from scene_test import *

STRESS_TOLERANCE = 1e-6  # of the largest stress component
POSITION_TOLERANCE = 3e-7  # m
g = -9.81


def scene(dim, output_format="vtu", displacement=True):
    upper = "1, 0.5" if dim == 2 else "1, 0.5, 0.5"
    return {
        "Dimension": dim, "Gravity": f"0, {g}" + (", 0" if dim == 3 else ""),
        "Time/End time": 0.1, "Time/CFL number": 0.5,
        "Grid/Lower corner": "0, 0" + (", 0" if dim == 3 else ""), "Grid/Upper corner": upper,
        "Grid/Subdivisions": "20, 10" if dim == 2 else "10, 5, 5",
        "Boundary conditions/Types": "2: slip",
        "Output/Particle output interval": 0.025, "Output/Output format": output_format,
        "Output/Displacement output": "true" if displacement else "false",
    }


def box(dim):
    return [{"Shape": "box",
             "Lower corner": "0.2, 0" + (", 0.1" if dim == 3 else ""),
             "Upper corner": "0.5, 0.15" + (", 0.4" if dim == 3 else ""),
             "Velocity": "1, 0" + (", 0" if dim == 3 else ""),
             "Young's modulus": 1e5, "Poisson's ratio": 0.3, "Density": 1000,
             "Particles per cell direction": 2}]


def pvd_series(out):
    """(time, [piece .vtu paths]) per particle output, from particles.pvd."""
    result = []
    for entry in ET.parse(os.path.join(out, "particles.pvd")).getroot().iter("DataSet"):
        pvtu = os.path.join(out, entry.get("file"))
        result.append((float(entry.get("timestep")), sorted(glob.glob(pvtu[:-len(".pvtu")] + ".*.vtu"))))
    return result


def read_vtu(pieces):
    """Points and point data of all pieces of one output."""
    meshes = [meshio.read(p) for p in pieces]
    points = np.concatenate([m.points for m in meshes]).astype(float)
    data = {name: np.concatenate([m.point_data[name] for m in meshes]).astype(float)
            for name in meshes[0].point_data}
    return points, data


def check_stress_relations(what, stress, pressure, von_mises):
    """stress: (n, 9) row-major components."""
    scale = max(np.abs(stress).max(), 1e-300)
    s = stress.reshape(-1, 3, 3)
    trace = s[:, 0, 0] + s[:, 1, 1] + s[:, 2, 2]
    error = np.abs(pressure.reshape(-1) + trace / 3).max() / scale
    check(f"{what}: pressure = -tr(stress)/3", error <= STRESS_TOLERANCE,
          f"largest error {error:.2e} of the largest stress component {scale:.4g} Pa")
    deviator = s - trace[:, None, None] / 3 * np.eye(3)
    expected = np.sqrt(1.5 * np.einsum("pij,pij->p", deviator, deviator))
    error = np.abs(von_mises.reshape(-1) - expected).max() / scale
    check(f"{what}: von Mises = sqrt(3/2 s':s')", error <= STRESS_TOLERANCE,
          f"largest error {error:.2e} of the largest stress component")
    symmetric = np.abs(s - s.transpose(0, 2, 1)).max() / scale
    check(f"{what}: the stress is symmetric", symmetric == 0, f"{symmetric:.2e}")
    return scale


def vtu_run(dim, ranks):
    what = f"{dim}D, {ranks} rank(s)"
    name = f"particle_fields_{dim}d"
    _, _, rows = run(name, scene(dim), box(dim), ranks=ranks)
    out = os.path.join(WORK, name, "output")
    outputs = pvd_series(out)
    check(f"{what}: 5 particle outputs, each in {ranks} piece(s)",
          len(outputs) == 5 and all(len(pieces) == ranks for _, pieces in outputs),
          str([(t, len(p)) for t, p in outputs]))
    initial = {}
    for t, pieces in outputs:
        points, data = read_vtu(pieces)
        row = min(rows, key=lambda r: abs(r["time"] - t))
        label = f"{what}, t = {t:.4g}"
        shapes = {k: data[k].shape[1:] for k in ("F", "stress", "velocity", "displacement")}
        check(f"{label}: F and stress have 9 components, velocity and displacement 3",
              shapes == {"F": (9,), "stress": (9,), "velocity": (3,), "displacement": (3,)}, str(shapes))
        scalars = ("id", "body", "mass", "initial_volume", "pressure", "von_mises")
        check(f"{label}: {', '.join(scalars)} are scalars",
              all(data[k].size == len(points) for k in scalars))
        check(f"{label}: as many points as statistics.csv", len(points) == row["particles"])
        scale = check_stress_relations(label, data["stress"], data["pressure"], data["von_mises"])
        F = data["F"].reshape(-1, 3, 3)
        if dim == 2:
            padding = np.abs(F[:, 2, :2]).max() + np.abs(F[:, :2, 2]).max() + np.abs(F[:, 2, 2] - 1).max()
            check(f"{label}: plane strain F has F_zz = 1 and no other z entries", padding == 0)
            if t > 0:
                zz = np.abs(data["stress"][:, 8]).max() / scale
                check(f"{label}: plane strain stress_zz is written", zz > 0.1, f"max |stress_zz| {zz:.3f} of the largest")
        ids = data["id"].reshape(-1).astype(int)
        if t == 0:
            initial = dict(zip(ids, points))
            check(f"{label}: displacement 0 at time 0", np.abs(data["displacement"]).max() == 0)
            continue
        x0 = np.array([initial[i] for i in ids])
        error = np.abs(data["displacement"] - (points - x0)).max()
        check(f"{label}: displacement = x - x(0) by id", error <= POSITION_TOLERANCE,
              f"largest difference {error:.2e} m, largest displacement {np.abs(data['displacement']).max():.4f} m")
        mass = data["mass"].reshape(-1)
        mean = (mass[:, None] * data["displacement"]).sum(axis=0) / mass.sum()
        axes = "xyz"[:dim]
        expected = np.array([row[f"body0_{a}"] - rows[0][f"body0_{a}"] for a in axes])
        error = np.abs(mean[:dim] - expected).max() / np.abs(expected).max()
        check(f"{label}: mass-weighted mean displacement = centre-of-mass change", error <= 1e-6,
              f"{mean[:dim]} against {expected}, relative error {error:.2e}")


vtu_run(2, 2)
vtu_run(3, 1)

# HDF5: the tensors as scalars; no displacement unless asked
name = "particle_fields_hdf5"
run(name, scene(2, "hdf5", displacement=False), box(2))
out = os.path.join(WORK, name, "output")
files = sorted(glob.glob(os.path.join(out, "particles_*.h5")))
with h5py.File(files[-1], "r") as f:
    components = [f"{n}_{a}{b}" for n in ("F", "stress") for a in "xyz" for b in "xyz"]
    missing = [c for c in components + ["pressure", "von_mises", "velocity", "id"] if c not in f]
    check("hdf5: 9 scalar datasets each for F and stress, pressure, von_mises", not missing, f"missing {missing}")
    check("hdf5: no displacement without 'Output/Displacement output'", "displacement" not in f)
    if not missing:
        stress = np.concatenate([f[f"stress_{a}{b}"][()] for a in "xyz" for b in "xyz"], axis=1).astype(float)
        check_stress_relations("hdf5", stress, f["pressure"][()].astype(float), f["von_mises"][()].astype(float))

# what a checkpoint holds may not change on resume
name = "particle_fields_resume"
short = dict(scene(2, displacement=False), **{"Time/Maximum number of steps": 5, "Output/Checkpoint interval": 5})
run(name, short, box(2))
code, output, _ = run(name, dict(short, **{"Output/Displacement output": "true", "Time/Maximum number of steps": 10}),
                      box(2), args=["--resume"], fresh=False, expect_success=False)
check("resume with another 'Output/Displacement output' is refused, naming the entry",
      code != 0 and "Output/Displacement output: 'false' in the checkpoint, 'true' now" in output, output[-400:])
finish()
