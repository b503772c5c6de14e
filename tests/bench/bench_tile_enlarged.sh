#!/usr/bin/env bash
# heightpack tile on enlarged maps (issue 36): the bundled painting, game textures of tests/corpus and a
# synthesised sea crop, each enlarged 2x, 4x and 8x (to at least 1024 a side) by oiiotool with nearest
# (box), bilinear (triangle), bicubic (catmull-rom) and Lanczos3 filters, 16-bit. Per map: the method
# tile chose (periodic: re-synthesis; quilt; a crossfade is the last resort none should reach), its look
# scores, wall seconds and peak memory; then how many maps reached each method.
#   tests/bench/bench_tile_enlarged.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_tile_enlarged: no $hp; build first (cmake --build $build)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "bench_tile_enlarged: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/measure.sh"
"$hp" synth --spectrum jonswap --wind 14m/s --tile-size 1024m --size 1024 --seed 5 -q -o "$work/sea.png"
oiiotool "$work/sea.png" --cut 256x256+0+0 -o "$work/sea256.png"
sources="$root/examples/maps/painted_not_tileable.png $work/sea256.png"
for name in trigger_grass_heightmap.png trigger_mud_heightmap.png etr_rock.png gl117_redsand1.tga; do
  sources="$sources $root/tests/corpus/$name"
done
printf "%-28s %-7s %-12s %-40s %7s %6s\n" map enlarge method look seconds MiB
: >"$work/methods"
for src in $sources; do
  side=$(oiiotool --info "$src" | sed -E 's/.*: *([0-9]+) x.*/\1/')
  base=$(basename "${src%.*}")
  for factor in 2 4 8; do
    size=$((side * factor))
    [ "$size" -ge 1024 ] && [ "$size" -le 4096 ] || continue
    for filter in box triangle catmull-rom lanczos3; do
      oiiotool "$src" --ch 0 --resize:filter=$filter "${size}x${size}" -d uint16 -o "$work/in.png"
      : >"$work/log"
      measure "$work/log" "$hp" tile "$work/in.png" -o "$work/out.png" -q
      read -r wall _ peak _ <"$work/log"
      if [ -s "$work/out.png" ]; then
        method=$("$hp" info "$work/out.png" | sed -nE 's/.*tileMethod[^a-z]*([a-z+]+).*/\1/p' | head -1)
        look=$("$hp" check "$work/out.png" | grep -oE "frame [0-9.]+, blobs [0-9.]+, echo [0-9.-]+" | head -1)
        method=${method:-none}  # the map tiled already: copied
      else
        method="(nothing)" look=""
      fi
      echo "$method" >>"$work/methods"
      printf "%-28s %-7s %-12s %-40s %7.2f %6d\n" "$base" "${factor}x-$filter" "$method" "$look" "$wall" "$((peak / 1024))"
      rm -f "$work/out.png"
    done
  done
done
echo "methods: $(sort "$work/methods" | uniq -c | tr -s ' ' | tr '\n' ';')"
