#!/usr/bin/env bash
# Build sable (installing what is missing) and run one scene, replacing the
# outputs of its earlier run (sable --overwrite) unless given --resume.
# Usage: contrib/run.sh [scene.prm [sable options]]   (default: prm/quick_demo.prm)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/prm/quick_demo.prm}"
# the scene as an absolute path: the run starts in the project root
[ -e "$scene" ] && scene="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")"
"$root/contrib/setup.sh"
cd "$root"
# --overwrite unless the run is to be resumed
mode=--overwrite
for argument in "${@:2}"; do [ "$argument" = --resume ] && mode=; done
exec "$root/build/sable" "$scene" ${mode:+"$mode"} "${@:2}"
