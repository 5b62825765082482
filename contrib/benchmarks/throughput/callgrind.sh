#!/usr/bin/env bash
# Instruction counts of the MPM step under valgrind's callgrind, which do
# not depend on the load of a shared machine. Two 2D scenes, linear elastic,
# 2x2 points per cell, MUSL, output off, one thread, 20 steps (or the
# number given):
#   box:   run.sh's box at 64^2 cells filling the grid, slip walls
#          (16,384 points)
#   floor: a 1 m square dropped on a fixed floor under gravity in a 2 m grid
#          of 256^2 cells, three quarters of it empty (65,536 points)
# Prints the instructions of the whole run, of Simulator::advance() (the
# steps), of the statistics (their first row included) and of deal.II's
# particle sort, and the instructions per particle-step. Each scene runs
# with 'Statistics interval' 1 (every step) and 0 (the default).
# Usage: contrib/benchmarks/throughput/callgrind.sh [build dir] [steps]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="${1:-$root/build}"
steps="${2:-20}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

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

scene box "1, 1" "64, 64" "1, 1" "0, 0" "0: slip, 1: slip, 2: slip, 3: slip" \
  "Velocity = 0.1, 0.05" > "$work/box.prm"
scene floor "2, 2" "256, 256" "1, 1" "0, -9.81" "2: fixed" "Density = 1000" > "$work/floor.prm"
for name in box floor; do
  for interval in 1 0; do
    sed -i "s/Statistics interval = .*/Statistics interval = $interval/" "$work/$name.prm"
    rm -rf "$work/out_$name" # sable refuses to write over an earlier run's results
    DEAL_II_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$work/$name.out" \
      "$build/sable" "$work/$name.prm" > "$work/$name.log" 2>&1 ||
      { echo "$name, statistics interval $interval: $(grep -m1 'sable:' "$work/$name.log")"; continue; }
    callgrind_annotate --inclusive=yes --threshold=100 "$work/$name.out" > "$work/$name.txt" 2> /dev/null
    count() { grep -E '^ *[0-9,]+ ' "$work/$name.txt" | grep -F -m1 "$1" | awk '{print $1}' | tr -d , || true; }
    total=$(grep -o "summary: [0-9]*" "$work/$name.out" | awk '{print $2}')
    advance=$(count "Simulator<2>::advance() [")
    statistics=$(count "Simulator<2>::compute_statistics() const [")
    sort=$(count "sort_particles_into_subdomains_and_cells() [")
    particles=$(grep -o '[0-9]* material points' "$work/$name.log" | cut -d' ' -f1)
    echo "$name, statistics interval $interval: $particles points, $steps steps: total $total," \
      "advance ${advance:-0}, statistics ${statistics:-0}, deal.II sort ${sort:-0} instructions;" \
      "per particle-step $(( ${advance:-0} / (particles * steps) )) (advance)," \
      "$(( (${advance:-0} + ${statistics:-0}) / (particles * steps) )) (with the statistics);" \
      "$(grep -o 'Particle sort in .* steps' "$work/$name.log" || echo 'sorted every step')"
  done
done
