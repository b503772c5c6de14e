#!/usr/bin/env bash
# heightpack synth against issue 24's targets, at 4096x4096 on THREADS threads, RUNS runs of each command
# alternating (so all see the same machine), medians of wall seconds and of CPU (user + sys) seconds:
#   - heights only, against its floor: start-up (synth --size 4) + one float inverse DFT of a 4096^2 field
#     (heightpack_bench_kernels' BM_SeaInverseDft, CPU time on THREADS threads) + writing the file's bytes
#     (cat of the output into a new file); target within 3x;
#   - heights only against `pack` of a 4096^2 16-bit map (zip, the default): target faster;
#   - with --shift --foam against heights only: target within 2x;
#   - peak memory with shift and foam above start-up, in bytes a texel: target at most 24;
#   - and issue 15's 60-frame 512x512 looping sequence with everything (target under 20 s).
# With BEFORE (a heightpack binary from an earlier build, e.g. main's), its runs alternate with these and
# the same figures are printed for it. The default output compression of each binary is used (zip before
# issue 24, none after). Other work on the machine shows in the wall figures: compare the CPU seconds.
#   tests/bench/bench_synth.sh [BUILD_DIR] [RUNS] [THREADS] [BEFORE]
set -euo pipefail
build=${1:-build}
runs=${2:-5}
threads=${3:-2}
before=${4:-}
hp="$build/heightpack"
kernels="$build/tests/bench/heightpack_bench_kernels"
for tool in "$hp" "$kernels" "$build/tests/bench/heightpack_make_bench_map"; do
  [ -x "$tool" ] || { echo "bench_synth: no $tool; build first (cmake --build $build)" >&2; exit 2; }
done
[ -x /usr/bin/time ] || { echo "bench_synth: needs GNU time (apt-get install time)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "$(nproc) cores, --threads $threads, $runs runs each; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$build/tests/bench/heightpack_make_bench_map" 4096 4096 "$work/map.png"

median() { sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
# run LOG COMMAND...: appends "wall cpu peakKiB" of one run to LOG.
run() {
  local log=$1
  shift
  /usr/bin/time -f "%e %U %S %M" -o "$work/t" "$@" >/dev/null 2>&1
  awk '{printf "%s %.3f %s\n", $1, $2 + $3, $4}' "$work/t" >>"$log"
}
# stat LOG FIELD: the median of field FIELD (1 wall, 2 cpu, 3 peak KiB).
stat() { cut -d' ' -f"$2" "$1" | median; }

wind=(--spectrum jonswap --wind 14m/s --fetch 200km --tile-size 1024m --size 4096)
binaries=(after)
[ -n "$before" ] && binaries=(before after)
for ((i = 0; i < runs; i++)); do
  for b in "${binaries[@]}"; do
    exe=$hp
    [ "$b" = before ] && exe=$before
    run "$work/$b.startup" "$exe" synth "${wind[@]:0:8}" --size 4 --threads "$threads" -q -o "$work/s.exr"
    run "$work/$b.heights" "$exe" synth "${wind[@]}" --threads "$threads" -q -o "$work/h.exr"
    run "$work/$b.write" sh -c "cat '$work/h.exr' > '$work/copy.exr'"
    rm -f "$work/copy.exr"
    run "$work/$b.full" "$exe" synth "${wind[@]}" --shift --foam --threads "$threads" -q -o "$work/f.exr"
    run "$work/$b.pack" "$exe" pack "$work/map.png" --threads "$threads" -q -o "$work/p.exr"
    rm -f "$work"/h.exr "$work"/f.exr "$work"/p.exr "$work"/s.exr
  done
done
# One float inverse DFT of a 4096^2 field (the floor's transform); CPU ms of the transform on THREADS threads.
fft=$("$kernels" --benchmark_filter="BM_SeaInverseDft/$threads/" --benchmark_format=csv 2>/dev/null |
  awk -F, '/BM_SeaInverseDft/ {print $3 / 1000}')
fft=${fft:-0.1}

for b in "${binaries[@]}"; do
  exe=$hp
  [ "$b" = before ] && exe=$before
  bench=(startup heights write full pack)
  declare -A wall cpu peak
  for n in "${bench[@]}"; do
    wall[$n]=$(stat "$work/$b.$n" 1)
    cpu[$n]=$(stat "$work/$b.$n" 2)
    peak[$n]=$(stat "$work/$b.$n" 3)
  done
  echo "== $b: $exe"
  for n in heights full pack; do
    printf '%-28s wall %6.2f s  cpu %6.2f s  peak %6d MiB\n' "$n" "${wall[$n]}" "${cpu[$n]}" "$((${peak[$n]} / 1024))"
  done
  awk -v s="${wall[startup]}" -v sm="${peak[startup]}" -v w="${wall[write]}" -v f="$fft" -v h="${wall[heights]}" \
      -v hc="${cpu[heights]}" -v full="${wall[full]}" -v fullc="${cpu[full]}" -v fm="${peak[full]}" \
      -v p="${wall[pack]}" -v pc="${cpu[pack]}" 'BEGIN {
    floor = s + f + w
    printf "floor: start-up %.2f s + one FFT %.3f s + write %.2f s = %.2f s\n", s, f, w, floor
    printf "heights / floor: %.2fx (target within 3x: %s)\n", h / floor, (h <= 3 * floor ? "met" : "missed")
    printf "heights / pack: wall %.2fx, cpu %.2fx (target under 1: %s)\n", h / p, hc / pc, (h < p ? "met" : "missed")
    printf "shift and foam / heights: wall %.2fx, cpu %.2fx (target within 2x: %s)\n", full / h, fullc / hc,
           (full <= 2 * h ? "met" : "missed")
    perTexel = (fm - sm) * 1024 / (4096 * 4096)
    printf "shift and foam peak above start-up: %.1f bytes a texel (target at most 24: %s)\n", perTexel,
           (perTexel <= 24 ? "met" : "missed") }'
done

: >"$work/seq"
for ((i = 0; i < runs; i++)); do
  run "$work/seq" "$hp" synth --spectrum jonswap --wind 14m/s --fetch 200km --swell 2.5m,12s,250deg --depth 30m \
    --spreading donelan-banner --tile-size 256m --size 512 --loop 20s --frames 60 --shift --foam --report \
    --threads "$threads" -q -o "$work/seq.exr"
  rm -f "$work"/seq*.exr
done
awk -v s="$(stat "$work/seq" 1)" -v c="$(stat "$work/seq" 2)" 'BEGIN {
  printf "60-frame 512x512 sequence: wall %.2f s, cpu %.2f s (target under 20 s: %s)\n", s, c, (s < 20 ? "met" : "missed") }'
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
