#!/usr/bin/env bash
# Throughput of the single-field MPM step: a linear-elastic box of about
# 262k material points (2D: 256^2 cells x 2^2 points; 3D: 32^3 cells x 2^3
# points), output off, 200 steps, one MPI rank. Prints particle-steps per
# second (whole step, sorting included), peak memory and the TimerOutput
# split. Usage: contrib/benchmarks/throughput/run.sh [build dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="${1:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

scene() { # dim cells-per-direction upper-corner
  local dim=$1 n=$2
  local lower upper cells vel
  if [ "$dim" = 2 ]; then lower="0, 0"; upper="1, 1"; cells="$n, $n"; vel="0.1, 0.05"
  else lower="0, 0, 0"; upper="1, 1, 1"; cells="$n, $n, $n"; vel="0.1, 0.05, 0"; fi
  cat <<PRM
set Dimension = $dim
set Output directory = $work/out$dim
set Number of bodies = 1
subsection Time
  set End time = 100
  set Maximum number of steps = 200
  set CFL number = 0.5
end
subsection Grid
  set Lower corner = $lower
  set Upper corner = $upper
  set Subdivisions = $cells
end
subsection Boundary conditions
  set Types = 0: slip, 1: slip, 2: slip, 3: slip
end
subsection Output
  set Statistics interval = 200
  set Progress interval = 200
end
subsection Body 0
  set Shape = box
  set Lower corner = $lower
  set Upper corner = $upper
  set Particles per cell direction = 2
  set Young's modulus = 1e6
  set Poisson's ratio = 0.3
  set Velocity = $vel
end
PRM
}

for case in "2 256" "3 32"; do
  set -- $case
  scene "$1" "$2" > "$work/scene$1.prm"
  /usr/bin/time -v "$build/sable" --overwrite "$work/scene$1.prm" > "$work/log$1" 2> "$work/time$1"
  particles=$(grep -o '[0-9]* material points' "$work/log$1" | cut -d' ' -f1)
  seconds=$(grep -o 'in [0-9.e+-]* s wall time' "$work/log$1" | awk '{print $2}')
  memory=$(grep 'Maximum resident' "$work/time$1" | awk '{print $NF}')
  echo "${1}D: $particles material points, 200 steps in $seconds s:" \
    "$(python3 -c "print(f'{$particles*200/$seconds/1e6:.2f}')") M particle-steps/s, peak memory $((memory / 1024)) MiB"
  grep -E '^\| (particles|grid|sort|statistics|initialize)' "$work/log$1"
done
