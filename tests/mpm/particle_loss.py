#!/usr/bin/python3
"""No material point is lost silently, and unstable runs stop with where
and when.

- A disk bouncing in a closed box keeps its particle count in every row.
- A disk flying out through a free boundary stops the run with a message
  giving the step, the time and the position; with 'Allow outflow' the run
  finishes, reports the loss, and the count falls.
- USL at CFL 0.5 on a spinning box is unstable (doc/mpm.md): the run stops
  with the step, time and a position instead of writing NaN."""
from scene_test import *

grid = {"Dimension": 2, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "1, 1", "Grid/Subdivisions": "20, 20"}
disk = {"Shape": "disk", "Center": "0.5, 0.5", "Radius": 0.2, "Young's modulus": 1e6,
        "Poisson's ratio": 0.3, "Density": 1000, "Particles per cell direction": 2}

_, _, rows = run("closed", dict(grid, **{"Time/End time": 0.3, "Gravity": "2, -9.81",
                                         "Boundary conditions/Types": "0: slip, 1: slip, 2: slip, 3: slip"}),
                 [dict(disk, Velocity="3, 2")])
counts = {r["particles"] for r in rows}
check("closed domain: particle count constant", len(counts) == 1 and rows[0]["particles"] > 0, f"counts {sorted(counts)}")

code, output, rows = run("leaving", dict(grid, **{"Time/End time": 0.3}), [dict(disk, Velocity="5, 0")],
                         expect_success=False)
message = output.strip().splitlines()[-1]
check("leaving: non-zero exit", code != 0, f"exit code {code}")
check("leaving: message says what, when and where",
      all(w in message for w in ("left the grid", "at step", "time", "position", "Allow outflow")), message)

code, output, rows = run("outflow", dict(grid, **{"Time/End time": 0.3, "Output/Allow outflow": "true"}),
                         [dict(disk, Velocity="5, 0")], expect_success=False)
check("outflow allowed: run finishes", code == 0, f"exit code {code}")
check("outflow allowed: loss reported", "left the grid" in output)
check("outflow allowed: count falls", rows[-1]["particles"] < rows[0]["particles"],
      f"{rows[0]['particles']:.0f} -> {rows[-1]['particles']:.0f}")

code, output, rows = run("unstable", dict(grid, **{"Time/End time": 0.5, "Solver/Update scheme": "USL"}),
                         [{"Shape": "box", "Lower corner": "0.3, 0.3", "Upper corner": "0.7, 0.7", "Young's modulus": 1e6,
                           "Poisson's ratio": 0.3, "Density": 1000, "Angular velocity": 2}], expect_success=False)
message = output.strip().splitlines()[-1]
check("unstable: non-zero exit", code != 0, f"exit code {code}")
check("unstable: message gives step, time and position",
      all(w in message for w in ("unstable at step", "time", "(")), message)
check("unstable: no NaN written", all(all(v == v for v in r.values()) for r in rows))
finish()
