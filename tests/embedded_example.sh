#!/usr/bin/env bash
# Install sable into a scratch prefix, then build the embedded example as
# the README says (find_package(sable) + target_link_libraries(app
# sable::sable), no deal.II macros, no environment variables), in Debug and
# in Release, and run it. Checks: the installed `sable` and the example run
# without LD_LIBRARY_PATH, the example's own loop wrote statistics and
# particle files, and sable::sable passed no optimisation or NDEBUG on.
set -euo pipefail
build_dir="$1"
work="${SABLE_WORK}"
rm -rf "$work" && mkdir -p "$work"
clean_env=(env -u LD_LIBRARY_PATH -u CMAKE_PREFIX_PATH -u DEAL_II_DIR -u deal.II_DIR)
fail() { echo "[FAIL] $*"; exit 1; }

cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
"${clean_env[@]}" "$work/prefix/bin/sable" --help > "$work/help.log" 2>&1 \
  || { cat "$work/help.log"; fail "the installed bin/sable does not run"; }
echo "[ ok ] installed bin/sable runs without LD_LIBRARY_PATH"

for type in Debug Release; do
  b="$work/build-$type"
  "${clean_env[@]}" cmake -S "$SABLE_SOURCE/contrib/examples/embedded" -B "$b" \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=$type > "$work/configure-$type.log" 2>&1 \
    || { cat "$work/configure-$type.log"; fail "$type: configure"; }
  "${clean_env[@]}" cmake --build "$b" > "$work/build-$type.log" 2>&1 \
    || { tail -n 40 "$work/build-$type.log"; fail "$type: build"; }
  flags="$b/CMakeFiles/embedded.dir/flags.make"
  # the program's own flags are CMake's for its build type (Release:
  # -O3 -DNDEBUG); none may come from sable::sable
  if grep -E -e '^CXX_DEFINES.*-D|-funroll|-Wall|-pedantic' "$flags"; then
    fail "$type: sable::sable passed build flags on to the program ($flags)"
  fi
  out="$work/output-$type"
  (cd "$work" && "${clean_env[@]}" "$b/embedded" "$out") || fail "$type: the example failed"
  rows=$(($(wc -l < "$out/statistics.csv") - 1))
  [ "$rows" -gt 10 ] || fail "$type: statistics.csv has $rows rows"
  [ -f "$out/particles.pvd" ] && ls "$out"/particles_*.pvtu > /dev/null \
    || fail "$type: no particle files in $out"
  echo "[ ok ] $type: built as the README says, ran, wrote $rows statistics rows and particle files"
done
