#!/usr/bin/env bash
# The demo's outputs, made with the heightpack and heightpack-view of a build folder:
#   scripts/demo_outputs.sh BUILD_DIR OUT_DIR
# scripts/demo.sh calls it with build/ and out/; scripts/same_outputs.sh calls it for two builds and
# compares what they wrote.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "$1")
OUT=$2

# The pipeline's step: every texture of each material manifest, and material.json. A second run has
# nothing to do.
"$BUILD"/heightpack build examples/ocean.toml examples/lagoon.toml -o "$OUT" --jobs 2
"$BUILD"/heightpack build examples/ocean.toml examples/lagoon.toml -o "$OUT" --jobs 2
xvfb-run -a -s "-screen 0 1280x1024x24" "$BUILD"/viewer/heightpack-view "$OUT"/ocean/material.json \
  --screenshot "$OUT"/view.png --size 1280x720 --time 12.5 --camera 0,0,8,30,-10

# Each command on its own.
mkdir -p "$OUT"
for map in examples/maps/*.png; do
  name=$(basename "$map" .png)
  "$BUILD"/heightpack pack "$map" -o "$OUT/$name.exr" --emit-plain "$OUT/${name}_plain.exr"
  # A picture of level 0 (R = the height) for people without an EXR viewer.
  oiiotool "$OUT/$name.exr" --ch R --ch R,R,R -d uint8 -o "$OUT/${name}_preview.png"
done

# Normal maps in world units (tile width, and how many metres a stored 1.0 stands above 0.0), and the
# Fresnel / water-colour ramp the water shader indexes by N.V.
# The same sizes as examples/ocean.toml gives the maps (swell 64 m, 1.5 m; choppy 16 m, 0.4 m).
"$BUILD"/heightpack normal examples/maps/swell.png --tile-size 64m --height 1.5m -o "$OUT"/swell_n.exr
"$BUILD"/heightpack normal examples/maps/choppy.png --tile-size 16m --height 0.4m -o "$OUT"/choppy_n.exr
"$BUILD"/heightpack normal examples/maps/ripple.png --tile-size 8m --height 0.05m -o "$OUT"/ripple_n.exr
for name in swell choppy ripple; do
  oiiotool "$OUT/${name}_n.exr" --mulc 0.5 --addc 0.5 -d uint8 -o "$OUT/${name}_n_preview.png"
done
"$BUILD"/heightpack fresnel --ior 1.333 --deep 0.02,0.10,0.16 --shallow 0.10,0.40,0.45 -o "$OUT"/fresnel.exr
"$BUILD"/heightpack fresnel --ior 1.333 --format png8 -o "$OUT"/fresnel.png
# The 256x1 ramp stretched into two strips a person can see: the colour, and the reflectance as grey.
oiiotool "$OUT"/fresnel.exr --ch R,G,B --resize 256x32 --colorconvert linear sRGB "$OUT"/fresnel.exr --ch A,A,A \
  --resize 256x32 --mosaic 1x2 -d uint8 -o "$OUT"/fresnel_preview.png

# Does a map tile? The painting does not (exit 1, a verdict per edge); the periodic + smooth method fixes
# it; the previews show both tiled 2x2, failing seams marked.
"$BUILD"/heightpack check examples/maps/painted_not_tileable.png --preview "$OUT"/painted_check_before.png || true
"$BUILD"/heightpack tile examples/maps/painted_not_tileable.png -o "$OUT"/painted_tiled.png
"$BUILD"/heightpack check "$OUT"/painted_tiled.png --preview "$OUT"/painted_check_after.png
"$BUILD"/heightpack check examples/maps/swell.png --quiet && echo "examples/maps/swell.png tiles"

# A material made entirely of synthesised maps: a JONSWAP swell the manifest synthesises itself
# ([displacement.synth]) and a Phillips chop from `synth` (heights in metres; the normal map needs a
# file), built from a manifest into OUT/synth and rendered.
"$BUILD"/heightpack synth --spectrum phillips --wind 7m/s --direction 40 --tile-size 32m --size 256 --seed 5 \
  -o "$OUT"/synth_chop.exr
# The material's manifest synthesises the swell and points at the chop (heights in metres, so amplitude 1); its
# normal-map octaves use scales that share no small ratio, so the chop's tile does not repeat visibly.
cat >"$OUT"/synth_sea.toml <<'TOML'
format = 1
name = "synth_sea"

[[displacement]]
name = "swell"
tile_size = 256.0
scroll = [0.002, 0.001]

[displacement.synth]
spectrum = "jonswap"
wind = 14.0
fetch = 200000.0
direction = 20.0
size = 512
seed = 3

[[displacement]]
name = "chop"
source = "synth_chop.exr"
tile_size = 32.0
scroll = [-0.01, 0.006]

[normals]
name = "chop_n"
source = "synth_chop.exr"
tile_size = 32.0
height = 1.0

[[normals.octave]]
tile_size = 32.0
scroll = [-0.01, 0.006]

[[normals.octave]]
tile_size = 13.7
scroll = [0.012, 0.01]
strength = 0.6

[[normals.octave]]
tile_size = 5.3
scroll = [0.03, -0.02]
strength = 0.35

[[normals.octave]]
tile_size = 2.1
scroll = [-0.05, -0.04]
strength = 0.2

[fresnel]
ior = 1.333
TOML
"$BUILD"/heightpack build "$OUT"/synth_sea.toml -o "$OUT"/synth
xvfb-run -a -s "-screen 0 1280x1024x24" "$BUILD"/viewer/heightpack-view "$OUT"/synth/material.json \
  --screenshot "$OUT"/synth_view.png --size 1280x720 --time 4 --camera 0,0,12,20,-8
# And the seams a 3x3 tiling shows, before and after tile.
xvfb-run -a "$BUILD"/viewer/heightpack-view examples/maps/painted_not_tileable.png --tiled 3x3 --size 768x768 \
  --screenshot "$OUT"/painted_tiled3x3.png
xvfb-run -a "$BUILD"/viewer/heightpack-view "$OUT"/painted_tiled.png --tiled 3x3 --size 768x768 \
  --screenshot "$OUT"/painted_fixed_tiled3x3.png

echo
"$BUILD"/heightpack info "$OUT"/swell.exr
echo
echo "demo: packed textures and previews are in $OUT/:"
ls -1 "$OUT"
