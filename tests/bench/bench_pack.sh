#!/usr/bin/env bash
# heightpack pack vs OpenImageIO's oiiotool making the same 4-channel float, periodic, mip-mapped EXR
# from one 4096x4096 16-bit periodic map, at equal compression. Runs alternate (heightpack, oiiotool,
# heightpack, ...) so both see the same machine state; prints median seconds, peak memory, and ratios.
#   tests/bench/bench_pack.sh [BUILD_DIR] [RUNS] [SIZE]
set -euo pipefail
build=${1:-build}
runs=${2:-3}
size=${3:-4096}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_pack: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_pack: needs GNU time (apt-get install time)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_pack: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/tests/bench/heightpack_make_bench_map" "$size" "$size" "$work/in.png"
echo "input: ${size}x${size} 16-bit periodic PNG, $(du -h "$work/in.png" | cut -f1); $(nproc) cores; $runs runs each"

# Appends "seconds peakKiB" of one command to the file named first.
measure() {
  local log=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >/dev/null 2>&1
  cat "$work/t" >>"$log"
}
median() { sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

for compression in zip none; do
  : >"$work/hp"
  : >"$work/oiio"
  for ((i = 0; i < runs; i++)); do
    measure "$work/hp" "$hp" pack "$work/in.png" --compression "$compression" -q -o "$work/hp.exr"
    measure "$work/oiio" oiiotool "$work/in.png" --ch R=Y,G=Y,B=Y,A=Y -d float --compression "$compression" \
      -otex:wrap=periodic "$work/oiio.exr"
  done
  awk -v c="$compression" \
      -v hs="$(cut -d' ' -f1 "$work/hp" | median)" -v os="$(cut -d' ' -f1 "$work/oiio" | median)" \
      -v hm="$(cut -d' ' -f2 "$work/hp" | median)" -v om="$(cut -d' ' -f2 "$work/oiio" | median)" \
      -v hz="$(du -h "$work/hp.exr" | cut -f1)" -v oz="$(du -h "$work/oiio.exr" | cut -f1)" 'BEGIN {
    printf "%-5s heightpack %6.2f s %5.0f MiB | oiiotool %6.2f s %5.0f MiB | time ratio %.2f, memory ratio %.2f | files %s vs %s\n",
      c, hs, hm / 1024, os, om / 1024, hs / os, hm / om, hz, oz }'
done
