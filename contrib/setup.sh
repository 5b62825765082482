#!/usr/bin/env bash
# Shared set-up for run.sh and test.sh: install the Debian packages sable needs
# (only those missing), then configure and build a Release build in build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(libdeal.ii-dev cmake g++ make numdiff ccache openmpi-bin python3 python3-matplotlib python3-numpy python3-meshio python3-h5py)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "sable: installing Debian packages: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

jobs="${SABLE_BUILD_JOBS:-$(nproc)}"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release > "$root/build.configure.log" 2>&1 \
  || { cat "$root/build.configure.log"; exit 1; }
rm -f "$root/build.configure.log"
cmake --build "$root/build" -j "$jobs"
