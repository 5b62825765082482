# Shared by the callgrind benchmark scripts (sourced, not run).
#
# callgrind_run OUT LOG SABLE PRM: run sable on PRM under callgrind with one
#   thread, the profile into OUT and the program's output into LOG; then
#   annotate the profile (inclusive counts) into OUT.txt. Fails as sable does.
# callgrind_count OUT FUNCTION: the inclusive instructions of the first
#   function whose annotated name contains FUNCTION (empty if none).
# material_points LOG: the number of material points the run reported.
callgrind_run() {
  DEAL_II_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$1" "$3" "$4" > "$2" 2>&1 ||
    return 1
  callgrind_annotate --inclusive=yes --threshold=100 "$1" > "$1.txt" 2> /dev/null
}

callgrind_count() {
  # grep -m1 closes the pipe early: not a failure
  grep -E '^ *[0-9,]+ ' "$1.txt" | grep -F -m1 "$2" | awk '{print $1}' | tr -d , || true
}

material_points() {
  grep -o '[0-9]* material points' "$1" | cut -d' ' -f1
}
