#!/usr/bin/env bash
# heightpack tile against heightpack pack on the same map (issue 22 asks tile within 2x of pack), on three
# 4096x4096 16-bit maps that do not tile: a crop of a synthesised sea twice its size (what tile is for),
# a crop of the periodic sum of waves bench_pack.sh uses (a line spectrum, not a Gaussian sea: the
# re-synthesis' look is borderline there, so tile may try more), and a crop a quarter the size enlarged 4x
# with Lanczos3 (a map painted small and resized before packing: tile works at the source's size, issue 36). Each is tiled to a 16-bit PNG and packed
# to the default mip-mapped EXR. Runs alternate (tile, pack, tile, ...); prints median seconds, peak memory,
# the ratio, and what tile chose (the attempt that passed: its seed, band and look scores).
#   tests/bench/bench_tile.sh [BUILD_DIR] [RUNS] [SIZE]
set -euo pipefail
build=${1:-build}
runs=${2:-3}
size=${3:-4096}
hp="$build/heightpack"
mk="$build/tests/bench/heightpack_make_bench_map"
[ -x "$hp" ] || { echo "bench_tile: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x "$mk" ] || { echo "bench_tile: no $mk; build with -DHEIGHTPACK_BUILD_BENCHMARKS=ON" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_tile: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/measure.sh"
"$hp" synth --spectrum jonswap --wind 14m/s --tile-size 2048m --size $((2 * size)) --seed 5 -q -o "$work/sea.png"
oiiotool "$work/sea.png" --cut "${size}x${size}+0+0" -d uint16 -o "$work/sea_crop.png"
big=$((size * 5 / 4))
"$mk" "$big" "$big" "$work/big.png"
oiiotool "$work/big.png" --cut "${size}x${size}+0+0" -d uint16 -o "$work/waves_crop.png"
oiiotool "$work/sea.png" --cut "$((size / 4))x$((size / 4))+0+0" --resize:filter=lanczos3 "${size}x${size}" -d uint16 \
  -o "$work/sea_enlarged.png"
echo "inputs: ${size}x${size} 16-bit crops of a synthesised sea and of a sum of waves, and a sea crop enlarged 4x; $(nproc) cores; $runs runs each"

for map in sea_crop waves_crop sea_enlarged; do
  : >"$work/tile"
  : >"$work/pack"
  for ((i = 0; i < runs; i++)); do
    measure "$work/tile" "$hp" tile "$work/$map.png" -o "$work/tiled.png" -q
    measure "$work/pack" "$hp" pack "$work/$map.png" -o "$work/packed.exr" -q
  done
  [ -s "$work/tiled.png" ] || { echo "bench_tile: tile wrote nothing for $map" >&2; exit 1; }
  read -r tw tc tm <<<"$(medians "$work/tile")"
  read -r pw pc pm <<<"$(medians "$work/pack")"
  printf "%-10s tile %6.2f s (CPU %.2f) %5s MiB | pack %6.2f s (CPU %.2f) %5s MiB | tile / pack %s (issue 22: at most 2)\n" \
    "$map" "$tw" "$tc" "$tm" "$pw" "$pc" "$pm" "$(ratio "$tw" "$pw")"
  "$hp" info "$work/tiled.png" | grep -E "tileMethod|seed|tileMatch" | tr -s ' ' | tr '\n' ';'
  "$hp" check "$work/tiled.png" | grep -E "look" || true
  rm -f "$work/tiled.png"
done
