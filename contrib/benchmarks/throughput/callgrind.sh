#!/usr/bin/env bash
# Instruction counts of the MPM step under valgrind's callgrind, which do
# not depend on the load of a shared machine. Two 2D scenes, linear elastic,
# 2x2 points per cell, MUSL (or the scheme given), output off, one thread, 20 steps (or the
# number given):
#   box:   run.sh's box at 64^2 cells filling the grid, slip walls
#          (16,384 points)
#   floor: a 1 m square dropped on a fixed floor under gravity in a 2 m grid
#          of 256^2 cells, three quarters of it empty (65,536 points)
#   grains: a 1 m square of 128^2 cells cut into 50 x 50 square grains of
#          25-26 points (65,536 points; the grain size of issue 13's
#          10,000 grains), each with its own velocity, frictional contact
#          (Bardenhagen 2001, mu = 0.3), slip walls
# Prints the instructions of the whole run, of Simulator::advance() (the
# steps), of the statistics (their first row included), of deal.II's
# particle sort and of finding the contact nodes, and the instructions per
# particle-step. box and floor run with 'Statistics interval' 1 (every
# step) and 0 (the default), grains with 0.
# With a third argument, every scene runs with that 'Solver/Update scheme'
# (USL, MUSL or USAVG) instead of the default.
# Usage: contrib/benchmarks/throughput/callgrind.sh [build dir] [steps] [update scheme]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="${1:-$root/build}"
steps="${2:-20}"
scheme="${3:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
source "$root/contrib/benchmarks/callgrind_functions.sh"

scene() { # name grid-upper-corner cells body-upper-corner gravity walls body-entry
  cat <<PRM
set Dimension = 2
set Output directory = $work/out_$1
set Number of bodies = 1
set Gravity = $5
subsection Time
  set End time = 100
  set Maximum number of steps = $steps
  set CFL number = 0.5
end
subsection Grid
  set Lower corner = 0, 0
  set Upper corner = $2
  set Subdivisions = $3
end
subsection Boundary conditions
  set Types = $6
end
subsection Output
  set Statistics interval = 1
  set Progress interval = 1000000
end
subsection Body 0
  set Shape = box
  set Lower corner = 0, 0
  set Upper corner = $4
  set Particles per cell direction = 2
  set Young's modulus = 1e6
  set Poisson's ratio = 0.3
  set $7
end
PRM
}

# half-open grains (upper corner 1e-12 short), so that each point is in one
grains() {
  cat <<PRM
set Dimension = 2
set Output directory = $work/out_grains
set Number of bodies = 2500
subsection Time
  set End time = 100
  set Maximum number of steps = $steps
  set CFL number = 0.5
end
subsection Grid
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 128, 128
end
subsection Boundary conditions
  set Types = 0: slip, 1: slip, 2: slip, 3: slip
end
subsection Contact
  set Model = bardenhagen 2001
  set Friction coefficient = 0.3
end
subsection Output
  set Statistics interval = 0
  set Progress interval = 1000000
end
PRM
  awk 'BEGIN { srand(42); w = 0.02
    for (i = 0; i < 50; ++i) for (j = 0; j < 50; ++j) {
      printf "subsection Body %d\n  set Shape = box\n", 50 * i + j
      printf "  set Lower corner = %.17g, %.17g\n", i * w, j * w
      printf "  set Upper corner = %.17g, %.17g\n", (i + 1) * w - 1e-12, (j + 1) * w - 1e-12
      printf "  set Particles per cell direction = 2\n  set Density = 1000\n"
      printf "  set Young\047s modulus = 1e6\n  set Poisson\047s ratio = 0.3\n"
      printf "  set Velocity = %.3f, %.3f\nend\n", rand() - 0.5, rand() - 0.5 } }'
}

scene box "1, 1" "64, 64" "1, 1" "0, 0" "0: slip, 1: slip, 2: slip, 3: slip" \
  "Velocity = 0.1, 0.05" > "$work/box.prm"
scene floor "2, 2" "256, 256" "1, 1" "0, -9.81" "2: fixed" "Density = 1000" > "$work/floor.prm"
grains > "$work/grains.prm"
if [ -n "$scheme" ]; then
  for name in box floor grains; do
    printf 'subsection Solver\n  set Update scheme = %s\nend\n' "$scheme" >> "$work/$name.prm"
  done
fi
for run in box:1 box:0 floor:1 floor:0 grains:0; do
  name=${run%:*} interval=${run#*:}
  sed -i "s/Statistics interval = .*/Statistics interval = $interval/" "$work/$name.prm"
  rm -rf "$work/out_$name" # sable refuses to write over an earlier run's results
  callgrind_run "$work/$name.out" "$work/$name.log" "$build/sable" "$work/$name.prm" ||
    { echo "$name, statistics interval $interval: $(grep -m1 'sable:' "$work/$name.log")"; continue; }
  total=$(grep -o "summary: [0-9]*" "$work/$name.out" | awk '{print $2}')
  advance=$(callgrind_count "$work/$name.out" "Simulator<2>::advance() [")
  statistics=$(callgrind_count "$work/$name.out" "Simulator<2>::compute_statistics() const [")
  sort=$(callgrind_count "$work/$name.out" "sort_particles_into_subdomains_and_cells() [")
  contact=$(callgrind_count "$work/$name.out" "MultiBodyContact<2>::mark_contact_nodes(")
  particles=$(material_points "$work/$name.log")
  echo "$name, statistics interval $interval: $particles points, $steps steps: total $total," \
    "advance ${advance:-0}, statistics ${statistics:-0}, deal.II sort ${sort:-0}," \
    "contact nodes ${contact:-0} instructions;" \
    "per particle-step $(( ${advance:-0} / (particles * steps) )) (advance)," \
    "$(( (${advance:-0} + ${statistics:-0}) / (particles * steps) )) (with the statistics);" \
    "$(grep -o 'Particle sort in .* steps' "$work/$name.log" || echo 'sorted every step')"
done
