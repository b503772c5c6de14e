#!/usr/bin/env bash
# Issue 14's figures for the GPU containers, run by hand (not by ctest):
#  1. the time pack takes to write one 4096x4096 packed float chain (its own "write" timing: encoding and
#     writing, not loading or mip-mapping) as .exr (zip), .ktx2 and .dds (uncompressed), each against
#     `cp` of a file of the same bytes into the same folder, medians of RUNS runs;
#  2. issue 24's ratios, whole `pack` runs alternating (float, half, uint16, read, cp, ...), medians of
#     wall and CPU (user + system) seconds and peak memory: per container, half and uint16 against float
#     (at most 1), and float against its floor, `heightpack info` (start-up, read, decode) plus `cp` of the
#     float file (writing the same bytes) (at most 1.3), and against `info` plus `cp` and `sync` of the copy
#     (writing the same bytes to the disk, as pack does before it moves its output into place). Every run
#     starts after a `sync`, so that none waits on the disk for the files of the runs before it;
#  3. per example map, layout and pixel type: the GPU bytes of the whole chain and the worst packed-
#     lookup error (pack --json), heights with the example manifest's amplitude as --height (ripple:
#     stored units), and ripple's normal map in rgb and xy (normal units).
#  4. issue 24's peak memory of pack (float; the default zip EXR, .ktx2, .dds) above start-up, the peak of
#     `heightpack info` on a 16x16 map, in MiB and bytes a texel (at most 8 at 8192^2), medians of RUNS.
#  With OLD_HEIGHTPACK (an older binary), sections 2 and 4 also run it, alternating: in section 2 every
#  pixel type, each run just before this build's of the same type (float: its ratios to the same floors;
#  half and uint16: to its own float), in section 4 float (its peak), for a before and after measured
#  side by side.
#   tests/bench/bench_containers.sh [BUILD_DIR] [RUNS] [SIZE] [SECTIONS] [OLD_HEIGHTPACK]
#   (SECTIONS: default "1 2 3 4")
# Needs jq, and heightpack_make_bench_map (configure with -DHEIGHTPACK_BUILD_BENCHMARKS=ON).
set -euo pipefail
build=${1:-build}
runs=${2:-5}
size=${3:-4096}
sections=${4:-1 2 3 4}
old=${5:-}
section() { [[ " $sections " == *" $1 "* ]]; }
hp="$build/heightpack"
make_map="$build/tests/bench/heightpack_make_bench_map"
examples="$(dirname "$0")/../../examples/maps"
[ -x "$hp" ] || { echo "bench_containers: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x "$make_map" ] || { echo "bench_containers: no $make_map; configure with -DHEIGHTPACK_BUILD_BENCHMARKS=ON" >&2; exit 2; }
command -v jq >/dev/null || { echo "bench_containers: needs jq (apt-get install jq)" >&2; exit 2; }
[ -z "$old" ] || [ -x "$old" ] || { echo "bench_containers: no older binary $old" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/bench_containers.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$make_map" "$size" "$size" "$work/in.png"
. "$(dirname "$0")/measure.sh"
now() { date +%s.%N; }

if section 1; then
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
fi

if section 2; then
echo
echo "2. whole pack runs, ${size}x${size}, median of $runs alternating runs (wall s, CPU s, peak MiB)"
printf '%-5s %-10s %8s %8s %8s %10s %10s\n' container type wall CPU MiB "wall ratio" "CPU ratio"
for ext in ktx2 dds; do
  for log in float half uint16 read cp cpsync old_float old_half old_uint16; do : >"$work/$log"; done
  for ((i = 0; i < runs; i++)); do
    for type in float half uint16; do
      if [ -n "$old" ]; then
        rm -f "$work/old.$ext"
        sync
        measure "$work/old_$type" "$old" pack "$work/in.png" --pixel-type "$type" -q -o "$work/old.$ext"
      fi
      rm -f "$work/$type.$ext"
      sync
      measure "$work/$type" "$hp" pack "$work/in.png" --pixel-type "$type" -q -o "$work/$type.$ext"
    done
    sync
    measure "$work/read" "$hp" info "$work/in.png"
    rm -f "$work/copy.$ext"
    sync
    measure "$work/cp" cp "$work/float.$ext" "$work/copy.$ext"
    rm -f "$work/copy.$ext"
    sync
    measure "$work/cpsync" sh -c 'cp "$1" "$2" && sync "$2"' sh "$work/float.$ext" "$work/copy.$ext"
  done
  read -r fw fc fm < <(medians "$work/float")
  for type in float half uint16; do
    read -r w c m < <(medians "$work/$type")
    printf '%-5s %-10s %8.2f %8.2f %8d %10s %10s\n' "$ext" "$type" "$w" "$c" "$m" "$(ratio "$w" "$fw")" "$(ratio "$c" "$fc")"
  done
  read -r rw rc rm < <(medians "$work/read")
  read -r cw cc cm < <(medians "$work/cp")
  floor_wall=$(awk -v a="$rw" -v b="$cw" 'BEGIN { print a + b }')
  floor_cpu=$(awk -v a="$rc" -v b="$cc" 'BEGIN { print a + b }')
  printf '%-5s %-10s %8.2f %8.2f %8d %10s %10s  (info %.2f s + cp %.2f s; float / floor)\n' "$ext" floor \
    "$floor_wall" "$floor_cpu" "$rm" "$(ratio "$fw" "$floor_wall")" "$(ratio "$fc" "$floor_cpu")" "$rw" "$cw"
  read -r sw sc sm < <(medians "$work/cpsync")
  synced_wall=$(awk -v a="$rw" -v b="$sw" 'BEGIN { print a + b }')
  synced_cpu=$(awk -v a="$rc" -v b="$sc" 'BEGIN { print a + b }')
  printf '%-5s %-10s %8.2f %8.2f %8d %10s %10s  (info + cp and sync %.2f s; float / floor on disk)\n' "$ext" "floor+s" \
    "$synced_wall" "$synced_cpu" "$rm" "$(ratio "$fw" "$synced_wall")" "$(ratio "$fc" "$synced_cpu")" "$sw"
  if [ -n "$old" ]; then
    read -r ow oc om < <(medians "$work/old_float")
    printf '%-5s %-10s %8.2f %8.2f %8d %10s %10s  (older binary, float / floor; / floor on disk %s wall)\n' "$ext" old \
      "$ow" "$oc" "$om" "$(ratio "$ow" "$floor_wall")" "$(ratio "$oc" "$floor_cpu")" "$(ratio "$ow" "$synced_wall")"
    for type in half uint16; do
      read -r w c m < <(medians "$work/old_$type")
      printf '%-5s %-10s %8.2f %8.2f %8d %10s %10s  (older binary, / its float)\n' "$ext" "old $type" "$w" "$c" "$m" \
        "$(ratio "$w" "$ow")" "$(ratio "$c" "$oc")"
    done
  fi
done
echo "(issue 24: half and uint16 at most 1.00 of float; float at most 1.30 of its floor)"
fi

if section 4; then
echo
echo "4. peak memory of pack above start-up, ${size}x${size} float, median of $runs runs"
"$make_map" 16 16 "$work/tiny.png"
: >"$work/startup"
for ((i = 0; i < runs; i++)); do measure "$work/startup" "$hp" info "$work/tiny.png"; done
read -r _ _ startup < <(medians "$work/startup")
perTexel() { awk -v m="$(($1 - startup))" -v n="$size" 'BEGIN { print m * 1048576 / (n * n) }'; }
for ext in exr ktx2 dds; do
  : >"$work/peak"
  : >"$work/oldpeak"
  for ((i = 0; i < runs; i++)); do
    rm -f "$work/peak.$ext"
    measure "$work/peak" "$hp" pack "$work/in.png" -q -o "$work/peak.$ext"
    if [ -n "$old" ]; then
      rm -f "$work/peak.$ext"
      measure "$work/oldpeak" "$old" pack "$work/in.png" -q -o "$work/peak.$ext"
    fi
  done
  read -r _ _ peak < <(medians "$work/peak")
  printf '%-5s %6d MiB, %6d MiB above start-up (%d MiB): %5.2f bytes a texel\n' "$ext" "$peak" \
    "$((peak - startup))" "$startup" "$(perTexel "$peak")"
  if [ -n "$old" ]; then
    read -r _ _ oldpeak < <(medians "$work/oldpeak")
    printf '%-5s %6d MiB, %6d MiB above start-up: %5.2f bytes a texel (older binary)\n' "$ext" "$oldpeak" \
      "$((oldpeak - startup))" "$(perTexel "$oldpeak")"
  fi
done
echo "(issue 24: at most 8 bytes a texel above start-up at 8192^2)"
fi

section 3 || exit 0
echo
echo "3. GPU bytes of the whole chain and worst packed-lookup error, pack/normal --json, .ktx2 outputs"
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
