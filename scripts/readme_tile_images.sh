#!/usr/bin/env bash
# Remakes the README's pictures of `tile` (docs/images/tile_3x3.jpg, tile_shaded.jpg, tile_before.jpg,
# tile_after.jpg) from the bundled painting, with the heightpack in BUILD_DIR. Needs ImageMagick
# (apt-get install imagemagick).
#   scripts/readme_tile_images.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-test}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "readme_tile_images: no $hp; build first" >&2; exit 2; }
command -v convert >/dev/null || { echo "readme_tile_images: needs ImageMagick's convert" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
map=examples/maps/painted_not_tileable.png
cp "$map" "$work/painting.png"
"$hp" tile "$map" -o "$work/periodic.png" -q
# Moisan alone kinks the slopes at the edges (check fails it): a threshold that lets it through, for the picture.
"$hp" tile "$map" --method moisan --threshold 1000000 --force -o "$work/moisan.png" -q
"$hp" tile "$map" --method crossfade -o "$work/crossfade.png" -q
# tiled N x N, grey as stored
tiled() {
  local row=() col=()
  for _ in $(seq "$2"); do row+=("$1"); done
  convert "${row[@]}" +append "$work/row.png"
  for _ in $(seq "$2"); do col+=("$work/row.png"); done
  convert "${col[@]}" -append "$3"
}
# lit from the upper left, as a normal map would show it
# (16-bit first, so 8-bit terraces do not become the picture; one fixed contrast for all, so they compare).
shaded() { tiled "$1" 2 "$work/s.png"; convert "$work/s.png" -depth 16 -blur 0x1 -shade 120x30 -level 35%,75% "$2"; }

tiled "$work/painting.png" 3 "$work/a.png"
tiled "$work/periodic.png" 3 "$work/b.png"
convert "$work/a.png" "$work/b.png" -bordercolor white -border 6 +append -resize 1536x -quality 88 docs/images/tile_3x3.jpg
for m in painting moisan crossfade periodic; do
  shaded "$work/$m.png" "$work/$m-shaded.png"
done
convert "$work/painting-shaded.png" "$work/moisan-shaded.png" "$work/crossfade-shaded.png" "$work/periodic-shaded.png" \
  -resize 512x -bordercolor white -border 4 +append -quality 88 docs/images/tile_shaded.jpg
"$hp" check "$map" --preview "$work/before.png" -q || true
"$hp" check "$work/periodic.png" --preview "$work/after.png" -q
convert "$work/before.png" -resize 384x384 -quality 85 docs/images/tile_before.jpg
convert "$work/after.png" -resize 384x384 -quality 85 docs/images/tile_after.jpg
echo "wrote docs/images/tile_3x3.jpg, tile_shaded.jpg, tile_before.jpg and tile_after.jpg"
