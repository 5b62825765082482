#!/usr/bin/env bash
# Install sable into a scratch prefix, then configure, build and run the
# embedded example against the installed package (find_package(sable)).
set -euo pipefail
build_dir="$1"
work="${SABLE_WORK}"
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$SABLE_SOURCE/contrib/examples/embedded" -B "$work/build" \
  -DCMAKE_BUILD_TYPE=Release -Dsable_DIR="$(dirname "$(find "$work/prefix" -name sableConfig.cmake)")" > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
LD_LIBRARY_PATH="$(dirname "$(find "$work/prefix" -name 'libsable.so*' | head -n 1)"):${LD_LIBRARY_PATH:-}" "$work/build/embedded"
