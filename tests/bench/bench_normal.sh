#!/usr/bin/env bash
# `normal` against `pack` on the same map, both with their default options (issue 24: normal within 1.2x
# of pack): a SIZExSIZE 16-bit periodic PNG made into a float normal chain (.exr) and a packed float chain
# (.exr, zip). Runs alternate (normal, pack, normal, ...); prints median wall and CPU seconds, peak memory,
# the ratios, and the bytes of the normal map with each EXR compression (what the default is chosen by).
#   tests/bench/bench_normal.sh [BUILD_DIR] [RUNS] [SIZE]
set -euo pipefail
. "$(dirname "$0")/measure.sh"
bench_map bench_normal "$@"

normal=("$hp" normal "$work/in.png" --tile-size 8m --height 0.15m -q)
: >"$work/normal"
: >"$work/pack"
for ((i = 0; i < runs; i++)); do
  measure "$work/normal" "${normal[@]}" -o "$work/n.exr"
  measure "$work/pack" "$hp" pack "$work/in.png" -q -o "$work/p.exr"
done
read -r nw nc nm < <(medians "$work/normal")
read -r pw pc pm < <(medians "$work/pack")
printf 'normal %6.2f s wall %6.2f s CPU %5d MiB | pack %6.2f s wall %6.2f s CPU %5d MiB\n' "$nw" "$nc" "$nm" "$pw" "$pc" "$pm"
echo "normal / pack: wall $(ratio "$nw" "$pw"), CPU $(ratio "$nc" "$pc") (issue 24: at most 1.2)"

echo "normal map bytes and one run's CPU seconds by --compression:"
for type in float half; do
  for compression in none zip piz; do
    : >"$work/one"
    measure "$work/one" "${normal[@]}" --pixel-type "$type" --compression "$compression" -o "$work/c.exr"
    printf '  %-5s %-4s %12d bytes %6.2f s CPU\n' "$type" "$compression" "$(stat -c %s "$work/c.exr")" \
      "$(cut -d' ' -f2 "$work/one")"
  done
done
