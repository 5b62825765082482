#!/usr/bin/env bash
# Build sable (installing what is missing) and run the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/contrib/setup.sh"
cd "$root/build"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ctest --output-on-failure -j "${SABLE_TEST_JOBS:-2}" "$@"
