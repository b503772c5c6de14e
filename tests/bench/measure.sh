# Sourced by the bench scripts that compare commands side by side: each run's wall seconds, CPU seconds
# (user + system: on a shared machine other processes stretch the wall time, not the CPU time) and peak
# memory, and medians over runs. Needs GNU time (apt-get install time) and a scratch folder in $work
# (bench_map makes one).
[ -x /usr/bin/time ] || { echo "$(basename "$0"): needs GNU time (apt-get install time)" >&2; exit 2; }

# measure LOG COMMAND...: runs COMMAND (output discarded) and appends "wall cpu peakKiB exit" to LOG.
measure() {
  local log=$1
  shift
  local code=0
  /usr/bin/time -f "%e %U %S %M" -o "$work/measure.t" "$@" >/dev/null 2>&1 || code=$?
  awk -v code="$code" '{ printf "%s %.2f %s %d\n", $1, $2 + $3, $4, code }' "$work/measure.t" >>"$log"
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# medians LOG: "wall cpu peakMiB", the median of each column of LOG.
medians() {
  printf '%s %s %s\n' "$(cut -d' ' -f1 "$1" | median)" "$(cut -d' ' -f2 "$1" | median)" \
    "$(cut -d' ' -f3 "$1" | median | awk '{ printf "%.0f", $1 / 1024 }')"
}

# ratio A B: A / B to two decimals.
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", (b > 0 ? a / b : 0) }'; }

# bench_map NAME [BUILD_DIR] [RUNS] [SIZE]: the scripts' common start. Sets build, runs (default 5), size
# (default 4096), hp (the CLI) and work (a scratch folder removed on exit), and makes $work/in.png, a
# SIZExSIZE 16-bit periodic map (heightpack_make_bench_map, built with -DHEIGHTPACK_BUILD_BENCHMARKS=ON).
bench_map() {
  local name=$1
  build=${2:-build}
  runs=${3:-5}
  size=${4:-4096}
  hp="$build/heightpack"
  local mk="$build/tests/bench/heightpack_make_bench_map"
  [ -x "$hp" ] || { echo "$name: no $hp; build first (cmake --build $build)" >&2; exit 2; }
  [ -x "$mk" ] || { echo "$name: no $mk; build with -DHEIGHTPACK_BUILD_BENCHMARKS=ON" >&2; exit 2; }
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  "$mk" "$size" "$size" "$work/in.png"
  echo "input: ${size}x${size} 16-bit periodic PNG, $(du -h "$work/in.png" | cut -f1); $(nproc) cores; $runs runs each"
}
