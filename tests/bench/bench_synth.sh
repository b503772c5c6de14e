#!/usr/bin/env bash
# heightpack synth against issue 15's targets: one 4096x4096 frame of heights alone (about 4 s before the
# issue), the same frame with displacement and foam (target: under 2x that), and a 60-frame 512x512
# looping sequence with everything (swell, depth, Donelan-Banner, displacement, foam, report; target:
# under 20 s on two cores). Prints the median seconds and peak memory of RUNS runs of each, on THREADS
# threads. Other work on the machine shows in the figures: note the load average it prints.
#   tests/bench/bench_synth.sh [BUILD_DIR] [RUNS] [THREADS]
set -euo pipefail
build=${1:-build}
runs=${2:-3}
threads=${3:-2}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_synth: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_synth: needs GNU time (apt-get install time)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "$(nproc) cores, --threads $threads, $runs runs each; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

median() { sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
# bench NAME ARGS...: RUNS runs of synth with ARGS; prints and remembers the median seconds as $last.
bench() {
  local name=$1
  shift
  : >"$work/log"
  for _ in $(seq "$runs"); do
    /usr/bin/time -f "%e %M" -o "$work/t" "$hp" synth "$@" --threads "$threads" -q -o "$work/out.exr" >/dev/null
    cat "$work/t" >>"$work/log"
    rm -f "$work"/out*.exr
  done
  last=$(cut -d' ' -f1 "$work/log" | median)
  printf '%-44s %7.2f s  %6d MiB peak\n' "$name" "$last" "$(( $(cut -d' ' -f2 "$work/log" | sort -n | tail -1) / 1024 ))"
}

wind=(--spectrum jonswap --wind 14m/s --fetch 200km)
bench "4096x4096, heights only" "${wind[@]}" --tile-size 1024m --size 4096
heights=$last
bench "4096x4096, displacement and foam" "${wind[@]}" --tile-size 1024m --size 4096 --displacement --foam
full=$last
bench "512x512 x 60 frames, everything" "${wind[@]}" --swell 2.5m,12s,250deg --depth 30m --spreading donelan-banner \
  --tile-size 256m --size 512 --loop 20s --frames 60 --displacement --foam --report
sequence=$last
awk -v h="$heights" -v f="$full" -v s="$sequence" 'BEGIN {
  # The issue says "under 2x that" of a heights-only run it put at about 4 s: judged both ways, the ratio on
  # this machine now and the 8 s it meant, as the two part when heights alone get faster.
  printf "displacement and foam / heights only: %.2fx (target under 2x: %s); %.2f s (under 8 s, 2x the ~4 s before issue 15: %s)\n", f / h, (f < 2 * h ? "met" : "missed"), f, (f < 8 ? "met" : "missed");
  printf "60-frame 512x512 sequence: %.2f s (target under 20 s: %s)\n", s, (s < 20 ? "met" : "missed") }'
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
