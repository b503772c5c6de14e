#!/usr/bin/env bash
# Start-up (issue 37): the median wall time of `heightpack --version`, `info` of a 16x16 EXR and of a
# 16x16 PNG (no OpenImageIO), and `info` of a 16x16 TIFF (loads the OpenImageIO module), with the number of
# shared objects each maps (LD_DEBUG=files). Given a second heightpack (an older build), it is timed on the
# same files, runs alternating.
#   tests/bench/bench_startup.sh [BUILD_DIR] [RUNS] [OTHER_HEIGHTPACK]
set -euo pipefail
build=${1:-build}
runs=${2:-21}
other=${3:-}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_startup: no $hp; build first (cmake --build $build)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_startup: needs oiiotool (openimageio-tools) for the TIFF" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$hp" synth -o "$work/small.exr" --size 16 --wind 8 --tile-size 16m >/dev/null
"$hp" synth -o "$work/small.png" --size 16 --wind 8 --tile-size 16m >/dev/null
oiiotool "$work/small.png" -o "$work/small.tif"

# ms PROGRAM ARGS...: one run's wall milliseconds.
ms() {
  local t0 t1
  t0=$(date +%s%N)
  "$@" >/dev/null 2>&1 || true
  t1=$(date +%s%N)
  echo $(((t1 - t0) / 1000))
}
median() { sort -n | awk '{a[NR] = $1} END {printf "%.1f", ((NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2) / 1000}'; }
objects() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -c 'calling fini: /' || true; }

printf '%-22s %12s %8s' "command" "this (ms)" "objects"
[ -n "$other" ] && printf ' %12s %8s' "other (ms)" "objects"
printf '\n'
for name in version exr png tiff; do
  case $name in
    version) args=(--version) ;;
    exr) args=(info "$work/small.exr") ;;
    png) args=(info "$work/small.png") ;;
    tiff) args=(info "$work/small.tif") ;;
  esac
  : >"$work/this"
  : >"$work/other"
  for ((i = 0; i < runs; i++)); do
    ms "$hp" "${args[@]}" >>"$work/this"
    [ -n "$other" ] && ms "$other" "${args[@]}" >>"$work/other"
  done
  printf '%-22s %12s %8s' "${args[0]} ${name}" "$(median <"$work/this")" "$(objects "$hp" "${args[@]}")"
  [ -n "$other" ] && printf ' %12s %8s' "$(median <"$work/other")" "$(objects "$other" "${args[@]}")"
  printf '\n'
done
