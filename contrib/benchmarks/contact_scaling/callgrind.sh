#!/usr/bin/env bash
# Contact against the number of grains as instruction counts under
# valgrind's callgrind, which do not depend on the load of a shared
# machine: contact_scaling's tilings (1 to 10,000 square grains tiling a
# square of cells, 2x2 points per cell, random velocities, Bardenhagen 2001
# with mu = 0.3, against the same points in one velocity field), one thread.
# Prints per tiling the instructions of the steps (Simulator::step(), the
# warm-up step included) per particle-step for both models, their ratio,
# and for the contact run the share of the contact kernel and of finding
# the contact nodes.
# Usage: contrib/benchmarks/contact_scaling/callgrind.sh [build dir]
#            [cells per direction = 256] [steps = 3] [grains per side ...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
build="${1:-$root/build}"
cells="${2:-256}"
steps="${3:-3}"
shift $(($# < 3 ? $# : 3))
tilings=("$@")
[ ${#tilings[@]} -gt 0 ] || tilings=(1 4 10 32 100)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
source "$root/contrib/benchmarks/callgrind_functions.sh"

cmake --build "$build" --target contact_scaling > /dev/null
echo "| grains | material points | none, instructions per particle-step | bardenhagen 2001 | contact / none | contact kernel | finding contact nodes |"
echo "|---|---|---|---|---|---|---|"
for per_side in "${tilings[@]}"; do
  # one profile per call of seconds_per_step(): contact none, then 2001
  DEAL_II_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
    --dump-after='*seconds_per_step*' \
    "$build/contrib/benchmarks/contact_scaling" "$cells" "$steps" pairwise "$per_side" \
    > "$work/log" 2>&1
  points=$(grep -E "^\| $((per_side * per_side)) \|" "$work/log" | awk -F'|' '{print $3}' | tr -d ' ')
  counts=()
  for part in 1 2; do
    callgrind_annotate --inclusive=yes --threshold=100 "$work/cg.out.$part" > "$work/cg.out.$part.txt" 2> /dev/null
    counts+=("$(callgrind_count "$work/cg.out.$part" "Simulator<2>::step()")")
  done
  kernel=$(callgrind_count "$work/cg.out.2" "BardenhagenContact<2>::apply(")
  marking=$(callgrind_count "$work/cg.out.2" "MultiBodyContact<2>::mark_contact_nodes(")
  awk -v g=$((per_side * per_side)) -v p="$points" -v s=$((steps + 1)) -v a="${counts[0]}" \
      -v b="${counts[1]}" -v k="${kernel:-0}" -v m="${marking:-0}" 'BEGIN {
    printf "| %d | %d | %.0f | %.0f | %.3f | %.1f%% | %.1f%% |\n", g, p, a / (p * s), b / (p * s),
      b / a, 100 * k / b, 100 * m / b }'
done
