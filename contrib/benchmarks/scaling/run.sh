#!/usr/bin/env bash
# Strong scaling from one to two cores, by MPI ranks and by threads:
#  - MPM: a linear-elastic box filling the grid (as throughput/run.py --problem box), 2D
#    256^2 cells and 3D 32^3 cells with 2^dim points per cell (262,144
#    points), 50 steps, output off; wall time of the time loop for
#    1 rank x 1 thread, 2 ranks x 1 thread, 1 rank x 2 threads, the triple
#    repeated; ratios within each repetition and of the fastest of each
#    configuration over all repetitions (on a shared machine the minimum is
#    the time least disturbed by other jobs);
#  - MPM load balance: the same grid with the points in one quarter
#    (2D, 128^2 of the 256^2 cells), 2 ranks with and without
#    'Solver/Balance particles across ranks';
#  - the cell and particle costs behind the partition weights: the full box
#    against a box in 1/16 of the same grid, one rank;
#  - QuSGM: one evaluation of Pi and grad Pi and one increment with 1 and 2
#    threads (qusgm_benchmark threads), bit-identity of the results; the
#    same on 1 and 2 MPI ranks (qusgm_benchmark ranks, after the threads
#    runs have put the pack in the cache).
# Usage: contrib/benchmarks/scaling/run.sh [build dir] [QuSGM grains = 2740]
#        [QuSGM pack cache = /tmp/qusgm-cache] [repetitions = 3]
# With QUIET_WAIT=<seconds>, each repetition first waits up to that long for
# a second of at least 90% idle CPU (other users' jobs) and prints what it saw.
# Needs the `benchmarks` target built (cmake --build build --target benchmarks).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/machine.sh"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
grains="${2:-2740}"
cache="${3:-/tmp/qusgm-cache}"
repeats="${4:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mpirun=(mpirun --allow-run-as-root --oversubscribe)

scene() { # dim cells-per-direction fraction-of-the-grid-filled balance
  local dim=$1 n=$2 fill=$3 balance=${4:-true}
  local lower upper body_upper cells vel
  if [ "$dim" = 2 ]; then lower="0, 0"; upper="1, 1"; body_upper="$fill, $fill"
    cells="$n, $n"; vel="0.1, 0.05"
  else lower="0, 0, 0"; upper="1, 1, 1"; body_upper="$fill, $fill, $fill"
    cells="$n, $n, $n"; vel="0.1, 0.05, 0"; fi
  cat <<PRM
set Dimension = $dim
set Output directory = $work/out
set Number of bodies = 1
subsection Time
  set End time = 100
  set Maximum number of steps = 50
  set CFL number = 0.5
end
subsection Solver
  set Balance particles across ranks = $balance
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
  set Statistics interval = 50
  set Progress interval = 50
end
subsection Body 0
  set Shape = box
  set Lower corner = $lower
  set Upper corner = $body_upper
  set Particles per cell direction = 2
  set Young's modulus = 1e6
  set Poisson's ratio = 0.3
  set Velocity = $vel
end
PRM
}

ratio() { python3 -c "print(f'{$1/$2:.2f}')"; }
minimum() { python3 -c "import sys; print(min(map(float, sys.argv[1:])))" "$@"; }
split() { # the TimerOutput rows of a log, as "name time"
  grep -E '^\| (particles to grid|grid to particles|stress update|grid update|sort particles)' "$1" |
    awk -F'|' '{gsub(/^ +| +$/, "", $2); gsub(/s$/, "", $4); printf "%s=%s  ", $2, $4}'
}

echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores;" \
  "load before: $(cut -d' ' -f1-3 /proc/loadavg); commit $(git -C "$root" rev-parse --short HEAD)"

for case in "2 256" "3 32"; do
  set -- $case
  scene "$1" "$2" 1 > "$work/s.prm"
  all_a=(); all_b=(); all_c=()
  for r in $(seq "$repeats"); do
    l="$(load), $(wait_quiet)"
    "$build/sable" --overwrite --threads 1 "$work/s.prm" > "$work/a.log"
    "${mpirun[@]}" -np 2 "$build/sable" --overwrite --threads 1 "$work/s.prm" > "$work/b.log"
    "$build/sable" --overwrite --threads 2 "$work/s.prm" > "$work/c.log"
    a=$(seconds "$work/a.log"); b=$(seconds "$work/b.log"); c=$(seconds "$work/c.log")
    all_a+=("$a"); all_b+=("$b"); all_c+=("$c")
    echo "MPM ${1}D run $r (load $l): 1x1 $a s, 2 ranks $b s (x$(ratio "$a" "$b")), 2 threads $c s (x$(ratio "$a" "$c"))"
    echo "  1x1:       $(split "$work/a.log")"
    echo "  2 ranks:   $(split "$work/b.log")"
    echo "  2 threads: $(split "$work/c.log")"
  done
  a=$(minimum "${all_a[@]}"); b=$(minimum "${all_b[@]}"); c=$(minimum "${all_c[@]}")
  echo "MPM ${1}D fastest of $repeats: 1x1 $a s, 2 ranks $b s (x$(ratio "$a" "$b")), 2 threads $c s (x$(ratio "$a" "$c"))"
  grep 'particles per rank' "$work/b.log" | sed 's/^/  2 ranks: /'
done

# load balance: points in one quarter of the grid
for r in $(seq "$repeats"); do
  q="$(load), $(wait_quiet)"
  scene 2 256 0.5 true > "$work/s.prm"
  "$build/sable" --overwrite "$work/s.prm" > "$work/a.log"
  "${mpirun[@]}" -np 2 "$build/sable" --overwrite "$work/s.prm" > "$work/b.log"
  scene 2 256 0.5 false > "$work/s.prm"
  "${mpirun[@]}" -np 2 "$build/sable" --overwrite "$work/s.prm" > "$work/c.log"
  a=$(seconds "$work/a.log"); b=$(seconds "$work/b.log"); c=$(seconds "$work/c.log")
  echo "MPM 2D, points in a quarter, run $r (load $q): 1 rank $a s; 2 ranks balanced $b s (x$(ratio "$a" "$b")), unbalanced $c s (x$(ratio "$a" "$c"))"
  [ "$r" = 1 ] && grep 'particles per rank' "$work/b.log" | sed 's/^/  balanced:   /' &&
    grep 'particles per rank' "$work/c.log" | sed 's/^/  unbalanced: /'
done

# cost per cell and per material point (one rank, one thread): the full
# box (65,536 cells, 262,144 points) and a box in 1/16 of it (16,384 points)
for r in $(seq "$repeats"); do
  scene 2 256 1 > "$work/s.prm"; "$build/sable" --overwrite "$work/s.prm" > "$work/a.log"
  scene 2 256 0.25 > "$work/s.prm"; "$build/sable" --overwrite "$work/s.prm" > "$work/b.log"
  a=$(seconds "$work/a.log"); b=$(seconds "$work/b.log")
  python3 - "$a" "$b" <<'PY'
import sys
full, small = map(float, sys.argv[1:])
cells, p_full, p_small, steps = 65536, 262144, 16384, 50
per_particle = (full - small) / (p_full - p_small) / steps
per_cell = (small / steps - per_particle * p_small) / cells
print(f"cost per step: {1e6*per_cell:.3f} us per cell, {1e6*per_particle:.3f} us per material point"
      f" (ratio {per_particle/per_cell:.1f}); full box {full} s, 1/16 box {small} s")
PY
done

# QuSGM with threads
for r in $(seq "$repeats"); do
  echo "# QuSGM run $r (load $(load), $(wait_quiet))"
  "$build/contrib/benchmarks/qusgm_benchmark" threads "$cache" "$grains" 2
done

# QuSGM on MPI ranks (Pi, |grad Pi| and the stress change must be the same)
for r in $(seq "$repeats"); do
  echo "# QuSGM ranks run $r (load $(load), $(wait_quiet))"
  for np in 1 2; do
    "${mpirun[@]}" -np "$np" "$build/contrib/benchmarks/qusgm_benchmark" ranks "$cache" "$grains" | tail -n 1
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
