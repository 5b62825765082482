#!/usr/bin/env bash
# MPM threads within one rank, 1 against 2 threads, the repetitions
# alternating (1, 2, 1, 2, ...): the TimerOutput sections of the phases
# that run threaded and the time loop, in seconds, for
#  - box:  a linear-elastic box filling a 2D grid of 256^2 cells, 2x2
#          points per cell (262,144 points), slip walls, 50 steps (as ../throughput/run.py --problem box);
#  - pile: the same grid and points split into 32 x 32 square grains (8 x 8
#          cells each) that tile it, each with its own velocity (contact
#          nodes between all neighbours, nodes with up to four bodies),
#          Bardenhagen 2001 contact with mu = 0.3, 40 steps.
# Usage: contrib/benchmarks/scaling/threads.sh [build dir] [repetitions = 3]
# With QUIET_WAIT=<seconds>, each 1-thread/2-thread pair first waits up to
# that long for a second of at least 90% idle CPU and prints what it saw.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/machine.sh"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
repeats="${2:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

common() { # steps
  cat <<PRM
set Dimension = 2
set Output directory = $work/out
subsection Time
  set End time = 100
  set Maximum number of steps = $1
  set CFL number = 0.5
end
subsection Grid
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 256, 256
end
subsection Boundary conditions
  set Types = 0: slip, 1: slip, 2: slip, 3: slip
end
subsection Output
  set Statistics interval = $1
  set Progress interval = $1
end
PRM
}

box() {
  common 50
  cat <<PRM
set Number of bodies = 1
subsection Body 0
  set Shape = box
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Particles per cell direction = 2
  set Young's modulus = 1e6
  set Poisson's ratio = 0.3
  set Velocity = 0.1, 0.05
end
PRM
}

pile() { # 32 x 32 grains, velocities from a fixed formula (no RNG)
  common 40
  python3 - <<'PY'
n = 32
print(f"set Number of bodies = {n * n}")
print("subsection Contact\n  set Model = bardenhagen 2001\n  set Friction coefficient = 0.3\n"
      "  set Reported pairs = none\nend")
for i in range(n):
    for j in range(n):
        b = i * n + j
        vx, vy = 0.2 * ((7 * b) % 11 - 5) / 5, 0.2 * ((5 * b) % 13 - 6) / 6
        print(f"subsection Body {b}\n  set Shape = box\n"
              f"  set Lower corner = {i / n}, {j / n}\n  set Upper corner = {(i + 1) / n}, {(j + 1) / n}\n"
              f"  set Particles per cell direction = 2\n  set Young's modulus = 1e6\n"
              f"  set Poisson's ratio = 0.3\n  set Velocity = {vx}, {vy}\nend")
PY
}

section() { # log, name: the wall time of a TimerOutput section
  grep -E "^\| $2 " "$1" | awk -F'|' '{gsub(/ /, "", $4); sub(/s$/, "", $4); print $4}' | head -1
}

echo "# $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg);" \
  "commit $(git -C "$root" rev-parse --short HEAD)"
for scene in box pile; do
  "$scene" > "$work/$scene.prm"
  for r in $(seq "$repeats"); do
    echo "# $scene run $r: load $(cut -d' ' -f1 /proc/loadavg), $(wait_quiet) before"
    for t in 1 2; do
      "$build/sable" --overwrite --threads "$t" "$work/$scene.prm" > "$work/log"
      echo "$scene run $r, $t thread(s) (load $(cut -d' ' -f1 /proc/loadavg)):" \
        "particles to grid $(section "$work/log" 'particles to grid') s" \
        "(finding contact nodes $(section "$work/log" 'find contact nodes \(in particles to grid\)') s)," \
        "contact $(section "$work/log" 'contact \(in grid update\)') s," \
        "grid update $(section "$work/log" 'grid update and boundaries') s," \
        "grid to particles $(section "$work/log" 'grid to particles and stresses') s," \
        "sort $(section "$work/log" 'sort particles') s," \
        "time loop $(seconds "$work/log") s"
    done
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
