#!/usr/bin/env bash
# What each contact option costs per step, as instruction counts under
# valgrind's callgrind (they do not depend on the load of a shared machine).
# Scene: 64 elastic disks (R = 0.05 m, 8 cells per diameter, 2x2 points per
# cell) in a square lattice, each touching its neighbours, on a fixed floor
# under gravity, 2D, the default update scheme (USAVG where bodies touch),
# one thread, output off, 20 steps (or the number given). Variants: the
# defaults, each contact option changed alone, the update schemes USL and
# MUSL, the disks seeded conforming or on the
# lattice (the default seeds them clipped), the floor a friction wall
# (either contact criterion), the GIMP functions (with the default scheme, with USL, with USL and the
# affine transfers), and contact 'none' (one velocity field: the
# single-field step, under MUSL, the default for a scene without contact).
# Prints the instructions of Simulator::advance() (the steps) per variant
# and its ratio to the default.
# Usage: contrib/benchmarks/contact_options/callgrind.sh [build dir] [steps]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="${1:-$root/build}"
steps="${2:-20}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
source "$root/contrib/benchmarks/callgrind_functions.sh"

scene() { # contact entries, body entries, boundary entries, other entries
  cat <<PRM
set Dimension = 2
set Output directory = $work/out
set Number of bodies = 64
set Gravity = 0, -9.81
subsection Time
  set End time = 100
  set Maximum number of steps = $steps
end
subsection Grid
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 80, 80
end
subsection Boundary conditions
  set Types = 2: fixed
$3
end
subsection Output
  set Progress interval = 1000000
end
subsection Contact
  set Model = bardenhagen 2001
  set Friction coefficient = 0.3
$1
end
$4
PRM
  for i in $(seq 0 63); do
    printf 'subsection Body %d\n  set Shape = disk\n  set Radius = 0.05\n' "$i"
    awk -v i="$i" 'BEGIN { printf "  set Center = %g, %g\n", 0.1 + 0.1 * (i % 8), 0.05 + 0.1 * int(i / 8) }'
    printf "  set Particles per cell direction = 2\n  set Young's modulus = 1e7\n  set Density = 1000\n%s\nend\n" "$2"
  done
}

variants=("defaults|"
          "Detection = shared nodes|  set Detection = shared nodes"
          "Normals = largest mass|  set Normals = largest mass"
          "Normals = mass weighted|  set Normals = mass weighted"
          "Normals = fitted at edges|  set Normals = fitted at edges"
          "Normals = logistic regression|  set Normals = logistic regression"
          "Round pair normals = line of centres|  set Round pair normals = line of centres"
          "Round body moments = kept|  set Round body moments = kept"
          "Nodes with three or more bodies = centre of mass|  set Nodes with three or more bodies = centre of mass"
          "Model = bardenhagen 2000|  set Model = bardenhagen 2000"
          "Friction coefficient = 0|  set Friction coefficient = 0"
          "Impulse scaling = off|  set Impulse scaling = off"
          "Passes = momentum update|  set Passes = momentum update"
          "Update scheme = USL|||| subsection Solver\n  set Update scheme = USL\nend"
          "Update scheme = MUSL|||| subsection Solver\n  set Update scheme = MUSL\nend"
          "Seeding = conforming||  set Seeding = conforming"
          "Seeding = lattice||  set Seeding = lattice"
          "floor: friction wall, surface position|||  set Types = 2: friction\n  set Friction coefficients = 2: 0.3"
          "floor: friction wall, material|||  set Types = 2: friction\n  set Friction coefficients = 2: 0.3\n  set Friction wall contact = material"
          "Shape functions = gimp|||| subsection Grid\n  set Shape functions = gimp\nend"
          "Shape functions = gimp, Update scheme = USL|||| subsection Grid\n  set Shape functions = gimp\nend\nsubsection Solver\n  set Update scheme = USL\nend"
          "Shape functions = gimp, Update scheme = USL, Affine transfers|||| subsection Grid\n  set Shape functions = gimp\nend\nsubsection Solver\n  set Update scheme = USL\n  set Affine transfers = true\nend"
          "Model = none (single field)|  set Model = none")
reference=0
for variant in "${variants[@]}"; do
  IFS='|' read -r name contact_entries body_entries boundary_entries other_entries <<< "$variant"
  scene "$contact_entries" "$body_entries" "$(printf '%b' "$boundary_entries")" \
    "$(printf '%b' "$other_entries")" > "$work/scene.prm"
  rm -rf "$work/out"
  callgrind_run "$work/callgrind.out" "$work/log" "$build/sable" "$work/scene.prm" ||
    { echo "$name: $(grep -m1 'sable:' "$work/log")"; continue; }
  advance=$(callgrind_count "$work/callgrind.out" "Simulator<2>::advance() [")
  if [ "$reference" -eq 0 ]; then reference=$advance; fi
  points=$(material_points "$work/log")
  echo "$name: $points points, $steps steps: advance $advance instructions," \
    "$(( advance / (points * steps) )) per particle-step, $(awk -v a="$advance" -v r="$reference" 'BEGIN { printf "%.3f", a / r }') x the defaults"
done
