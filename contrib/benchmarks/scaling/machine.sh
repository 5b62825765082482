# Shell functions the scaling scripts share (sourced, not run): the state
# of a shared machine and the wall time of a sable run.

load() { cut -d' ' -f1 /proc/loadavg; }

idle() { # percentage of idle CPU time over the next second, all cores
  local a b
  a=($(head -1 /proc/stat)); sleep 1; b=($(head -1 /proc/stat))
  local total=0 i
  for i in 1 2 3 4 5 6 7 8; do total=$((total + b[i] - a[i])); done
  echo $(( 100 * (b[4] - a[4]) / (total > 0 ? total : 1) ))
}

wait_quiet() { # on a shared machine: wait up to QUIET_WAIT s (default 0)
  # for a second with at least 90% idle CPU; print the idle percentage seen
  local waited=0 i
  i=$(idle)
  while [ "$i" -lt 90 ] && [ "$waited" -lt "${QUIET_WAIT:-0}" ]; do
    sleep 4; waited=$((waited + 5)); i=$(idle)
  done
  echo "$i% idle"
}

seconds() { grep -o 'in [0-9.e+-]* s wall time' "$1" | awk '{print $2}'; }
