#!/usr/bin/env bash
# Issue 14's figures for the GPU containers, run by hand (not by ctest):
#  1. the time pack takes to write one 4096x4096 packed float chain (its own "write" timing: encoding and
#     writing, not loading or mip-mapping) as .exr (zip), .ktx2 and .dds (uncompressed), each against
#     `cp` of a file of the same bytes into the same folder, medians of RUNS runs;
#  2. per example map, layout and pixel type: the GPU bytes of the whole chain and the worst packed-
#     lookup error (pack --json), heights with the example manifest's amplitude as --height (ripple:
#     stored units), and ripple's normal map in rgb and xy (normal units).
#   tests/bench/bench_containers.sh [BUILD_DIR] [RUNS] [SIZE]
# Needs jq, and heightpack_make_bench_map (configure with -DHEIGHTPACK_BUILD_BENCHMARKS=ON).
set -euo pipefail
build=${1:-build}
runs=${2:-5}
size=${3:-4096}
hp="$build/heightpack"
make_map="$build/tests/bench/heightpack_make_bench_map"
examples="$(dirname "$0")/../../examples/maps"
[ -x "$hp" ] || { echo "bench_containers: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x "$make_map" ] || { echo "bench_containers: no $make_map; configure with -DHEIGHTPACK_BUILD_BENCHMARKS=ON" >&2; exit 2; }
command -v jq >/dev/null || { echo "bench_containers: needs jq (apt-get install jq)" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/bench_containers.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$make_map" "$size" "$size" "$work/in.png"
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
now() { date +%s.%N; }

echo "1. writing a ${size}x${size} packed float chain (every level, RGBA32F), $(nproc) cores, median of $runs runs"
printf '%-5s %-6s %12s %10s %10s %10s\n' container codec bytes "write s" "cp s" "write/cp"
exr_seconds=""
for ext in exr ktx2 dds; do
  codec=none
  [ "$ext" = exr ] && codec=zip
  : >"$work/write"
  : >"$work/cp"
  for ((i = 0; i < runs; i++)); do
    rm -f "$work/out.$ext" "$work/copy.$ext"
    sync  # both start with no dirty pages of the other waiting to be written back
    "$hp" pack "$work/in.png" --json -o "$work/out.$ext" | jq '.timings.write' >>"$work/write"
    sync
    start=$(now)
    cp "$work/out.$ext" "$work/copy.$ext"
    end=$(now)
    awk -v a="$start" -v b="$end" 'BEGIN { print b - a }' >>"$work/cp"
  done
  w=$(median <"$work/write")
  c=$(median <"$work/cp")
  [ "$ext" = exr ] && exr_seconds=$w
  printf '%-5s %-6s %12d %10.3f %10.3f %10.2f\n' "$ext" "$codec" "$(stat -c %s "$work/out.$ext")" "$w" "$c" \
    "$(awk -v w="$w" -v c="$c" 'BEGIN { print w / c }')"
done
echo "(write/cp: 1 would be writing as fast as cp copies the finished file; exr zip write: $exr_seconds s)"

echo
echo "2. GPU bytes of the whole chain and worst packed-lookup error, pack/normal --json, .ktx2 outputs"
printf '%-8s %-11s %-7s %12s %14s %s\n' map layout type "gpu bytes" "worst error" units
row() {  # map layout type json
  printf '%-8s %-11s %-7s %12d %14.3g %s\n' "$1" "$2" "$3" "$(jq '.gpuBytes' <<<"$4")" \
    "$(jq '.lookupError.worst' <<<"$4")" "$(jq -r '.lookupError.units' <<<"$4")"
}
for entry in swell:1.5m choppy:0.4m ripple:; do
  map=${entry%%:*}
  height=${entry#*:}
  for layout in neighbour4 plain; do
    for type in float half uint16; do
      args=(pack "$examples/$map.png" --layout "$layout" --pixel-type "$type" --json -o "$work/t.ktx2")
      [ -n "$height" ] && args+=(--height "$height")
      row "$map" "$layout" "$type" "$("$hp" "${args[@]}")"
    done
  done
done
for layout in rgb xy; do
  for type in float half uint16; do
    row ripple "normal $layout" "$type" "$("$hp" normal "$examples/ripple.png" --tile-size 8m --height 0.05m \
      --layout "$layout" --pixel-type "$type" --json -o "$work/n.ktx2")"
  done
done
