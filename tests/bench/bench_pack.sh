#!/usr/bin/env bash
# heightpack pack vs OpenImageIO's oiiotool making the same 4-channel float, periodic, mip-mapped EXR
# from one SIZExSIZE (default 4096) 16-bit periodic map, at equal compression (issue 24: zip at most 0.4x
# oiiotool's time at 4096^2 and 8192^2). Runs alternate (heightpack, oiiotool, heightpack, ...) so both see
# the same machine state; prints median wall seconds, median CPU (user + sys) seconds, peak memory and the
# ratios (on a machine shared with other work the CPU ratio is the steadier). With BEFORE (a heightpack
# binary of an earlier build, e.g. main's), its runs alternate with the others and its line is printed
# too, so before and after are measured side by side.
#   tests/bench/bench_pack.sh [BUILD_DIR] [RUNS] [SIZE] [BEFORE]
set -euo pipefail
. "$(dirname "$0")/measure.sh"
before=${4:-}
[ -z "$before" ] || [ -x "$before" ] || { echo "bench_pack: no heightpack binary $before" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_pack: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 2; }
bench_map bench_pack "${1:-build}" "${2:-3}" "${3:-4096}"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

for compression in zip none; do
  : >"$work/after"
  : >"$work/before"
  : >"$work/oiio"
  for ((i = 0; i < runs; i++)); do
    measure "$work/after" "$hp" pack "$work/in.png" --compression "$compression" -q -o "$work/after.exr"
    [ -z "$before" ] || measure "$work/before" "$before" pack "$work/in.png" --compression "$compression" -q -o "$work/before.exr"
    measure "$work/oiio" oiiotool "$work/in.png" --ch R=Y,G=Y,B=Y,A=Y -d float --compression "$compression" \
      -otex:wrap=periodic "$work/oiio.exr"
  done
  read -r ow oc om <<<"$(medians "$work/oiio")"
  names=(after)
  [ -z "$before" ] || names=(before after)
  for name in "${names[@]}"; do
    read -r hw hc hm <<<"$(medians "$work/$name")"
    label=heightpack
    [ "$name" = before ] && label="before    "
    printf '%-5s %s %5.2f s (cpu %5.2f s) %5d MiB | oiiotool %5.2f s (cpu %5.2f s) %5d MiB | time ratio %s, cpu ratio %s, memory ratio %s | files %s vs %s\n' \
      "$compression" "$label" "$hw" "$hc" "$hm" "$ow" "$oc" "$om" "$(ratio "$hw" "$ow")" "$(ratio "$hc" "$oc")" \
      "$(ratio "$hm" "$om")" "$(du -h "$work/$name.exr" | cut -f1)" "$(du -h "$work/oiio.exr" | cut -f1)"
  done
  if [ -n "$before" ]; then
    cmp -s "$work/after.exr" "$work/before.exr" && echo "$compression: both builds wrote the same bytes" ||
      echo "$compression: the two builds' outputs differ"
  fi
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
