#!/usr/bin/env bash
# heightpack pack vs OpenImageIO's oiiotool making the same 4-channel float, periodic, mip-mapped EXR
# from one SIZExSIZE (default 4096) 16-bit periodic map, at equal compression. Runs alternate (heightpack,
# oiiotool, heightpack, ...) so both see the same machine state; prints median wall seconds, median CPU
# (user + sys) seconds, peak memory, and their ratios. On a machine shared with other work the CPU ratio is
# the steadier. With BEFORE (a heightpack binary of an earlier build, e.g. main's), its runs alternate with
# the others and its line is printed too, so before and after are measured side by side.
#   tests/bench/bench_pack.sh [BUILD_DIR] [RUNS] [SIZE] [BEFORE]
set -euo pipefail
build=${1:-build}
runs=${2:-3}
size=${3:-4096}
before=${4:-}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_pack: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -z "$before" ] || [ -x "$before" ] || { echo "bench_pack: no heightpack binary $before" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_pack: needs GNU time (apt-get install time)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_pack: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/tests/bench/heightpack_make_bench_map" "$size" "$size" "$work/in.png"
echo "input: ${size}x${size} 16-bit periodic PNG, $(du -h "$work/in.png" | cut -f1); $(nproc) cores; $runs runs each;" \
  "load average $(cut -d' ' -f1-3 /proc/loadavg)"

# Appends "seconds peakKiB cpuSeconds" of one command to the file named first.
measure() {
  local log=$1
  shift
  /usr/bin/time -f "%e %M %U %S" -o "$work/t" "$@" >/dev/null 2>&1
  awk '{printf "%s %s %.3f\n", $1, $2, $3 + $4}' "$work/t" >>"$log"
}
median() { sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
# field LOG N: the median of field N (1 wall seconds, 2 peak KiB, 3 CPU seconds).
field() { cut -d' ' -f"$2" "$1" | median; }

for compression in zip none; do
  : >"$work/hp"
  : >"$work/before"
  : >"$work/oiio"
  for ((i = 0; i < runs; i++)); do
    measure "$work/hp" "$hp" pack "$work/in.png" --compression "$compression" -q -o "$work/hp.exr"
    [ -z "$before" ] || measure "$work/before" "$before" pack "$work/in.png" --compression "$compression" -q -o "$work/before.exr"
    measure "$work/oiio" oiiotool "$work/in.png" --ch R=Y,G=Y,B=Y,A=Y -d float --compression "$compression" \
      -otex:wrap=periodic "$work/oiio.exr"
  done
  names=(hp)
  [ -z "$before" ] || names=(before hp)
  for name in "${names[@]}"; do
    label=heightpack
    [ "$name" = before ] && label="before    "
    awk -v c="$compression" -v l="$label" \
        -v hs="$(field "$work/$name" 1)" -v os="$(field "$work/oiio" 1)" \
        -v hc="$(field "$work/$name" 3)" -v oc="$(field "$work/oiio" 3)" \
        -v hm="$(field "$work/$name" 2)" -v om="$(field "$work/oiio" 2)" \
        -v hz="$(du -h "$work/$name.exr" | cut -f1)" -v oz="$(du -h "$work/oiio.exr" | cut -f1)" 'BEGIN {
      printf "%-5s %s %5.2f s (cpu %5.2f s) %5.0f MiB | oiiotool %5.2f s (cpu %5.2f s) %5.0f MiB | time ratio %.2f, cpu ratio %.2f, memory ratio %.2f | files %s vs %s\n",
        c, l, hs, hc, hm / 1024, os, oc, om / 1024, hs / os, hc / oc, hm / om, hz, oz }'
  done
done
[ -z "$before" ] || { cmp -s "$work/hp.exr" "$work/before.exr" && echo "the last outputs of both builds: byte-identical" ||
  echo "the last outputs of both builds differ"; }
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
