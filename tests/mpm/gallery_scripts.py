#!/usr/bin/python3
"""The picture scripts of doc/gallery.md and doc/tutorial.md run on a real
run's output and write their PNG: contrib/gallery/snapshots.py on a short
2D collision with particle output (its PNG is a picture: a PNG header and
more than 10 kB), with --grid and --color body on the first steps of
prm/gallery_adaptive.prm, with --mesh on those of prm/gallery_gear.prm;
contrib/gallery/force_network.py on the final state of prm/qusgm_demo.prm;
contrib/gallery/gear_mesh.py writes prm/gear.msh byte for byte; and the
scripts name what is missing when given a directory without output (or
--grid a run without grid output) instead of a traceback."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_test import SABLE, WORK, check, finish, run  # noqa: E402

SOURCE = os.environ.get("SABLE_SOURCE", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
GALLERY = os.path.join(SOURCE, "contrib", "gallery")


def script(name, *args):
    result = subprocess.run(["/usr/bin/python3", os.path.join(GALLERY, name)] + list(args),
                            capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def is_picture(path):
    if not os.path.exists(path):
        return False
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 10000


disk = {"Shape": "disk", "Radius": 0.2, "Particles per cell direction": 2,
        "Young's modulus": 1e6, "Poisson's ratio": 0.3, "Density": 1000}
run("collision", {"Dimension": 2, "Time/End time": 0.1, "Grid/Lower corner": "0, 0", "Grid/Upper corner": "2, 1",
                  "Grid/Subdivisions": "40, 20", "Contact/Model": "bardenhagen 2001",
                  "Output/Particle output interval": 0.02},
    [dict(disk, Center="0.7, 0.5", Velocity="2, 0"), dict(disk, Center="1.3, 0.5", Velocity="-2, 0")])
output = os.path.join(WORK, "collision", "output")
png = os.path.join(WORK, "snapshots.png")
code, text = script("snapshots.py", output, "--times", "0,0.05,0.1", "--png", png)
check("snapshots.py writes a picture of a 2D run", code == 0 and is_picture(png), text.strip()[-200:])



def run_prm(name, *settings):
    """Run prm/<name>.prm into WORK/<name>/output with --set settings."""
    output = os.path.join(WORK, name, "output")
    os.makedirs(os.path.dirname(output), exist_ok=True)
    command = [SABLE, os.path.join(SOURCE, "prm", name + ".prm"), "--overwrite", "--set", f"Output directory={output}"]
    for setting in settings:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    check(f"prm/{name}.prm runs", result.returncode == 0, (result.stdout + result.stderr).strip()[-200:])
    return output


# the adaptive grid: the grid as refined at each output, points by body
output = run_prm("gallery_adaptive", "Time/End time=0.04")
png = os.path.join(WORK, "adaptive.png")
code, text = script("snapshots.py", output, "--times", "0,0.02,0.04", "--grid", "--color", "body", "--png", png)
check("snapshots.py --grid --color body writes a picture of an adaptive run", code == 0 and is_picture(png),
      text.strip()[-200:])
code, text = script("snapshots.py", os.path.join(WORK, "collision", "output"), "--grid")
check("snapshots.py --grid on a run without grid output: an error naming grid.pvd, no traceback",
      code != 0 and "grid.pvd" in text and "Traceback" not in text, text.strip()[-200:])

# the gear: its mesh written again as committed, its cells over its points
gear = os.path.join(WORK, "gear.msh")
code, text = script("gear_mesh.py", gear)
with open(gear) as f, open(os.path.join(SOURCE, "prm", "gear.msh")) as g:
    check("gear_mesh.py writes prm/gear.msh as committed", code == 0 and f.read() == g.read(), text.strip()[-200:])
output = run_prm("gallery_gear", "Time/End time=0.02", "Output/Particle output interval=0.01")
png = os.path.join(WORK, "gear.png")
code, text = script("snapshots.py", output, "--times", "0,0.02", "--mesh", gear, "--mesh-scale", "0.2",
                    "--mesh-translation", "0.3,0.201", "--png", png)
check("snapshots.py --mesh writes a picture of a body from a mesh file", code == 0 and is_picture(png),
      text.strip()[-200:])

directory = os.path.join(WORK, "qusgm_demo")
os.makedirs(directory, exist_ok=True)
result = subprocess.run([SABLE, os.path.join(SOURCE, "prm", "qusgm_demo.prm"), "--overwrite",
                         "--set", f"Output directory={directory}/output"], capture_output=True, text=True)
check("prm/qusgm_demo.prm runs", result.returncode == 0, (result.stdout + result.stderr).strip()[-200:])
png = os.path.join(WORK, "force_network.png")
code, text = script("force_network.py", os.path.join(directory, "output", "final_state"), "--png", png)
check("force_network.py writes a picture of the final state", code == 0 and is_picture(png), text.strip()[-200:])

empty = os.path.join(WORK, "empty")
os.makedirs(empty, exist_ok=True)
for name in ("snapshots.py", "force_network.py"):
    code, text = script(name, empty)
    check(f"{name} on a directory without output: an error, no traceback",
          code != 0 and "Traceback" not in text, text.strip()[-200:])
finish()
