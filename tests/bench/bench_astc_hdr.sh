#!/usr/bin/env bash
# Whether ASTC HDR serves heightpack's heights: on each map of the family (the corpus's height maps, the
# example seas, 64x64 crops of the seas), plain heights at --height HEIGHT, per block size:
#   ldr, hdr   heightpack's own astc-NxN and astc-hdr-NxN (values normalised to the chain's range, as
#              heightpack stores them): level 0's worst and RMS error and the chain's worst (what
#              --pixel-type auto weighs against --tolerance), from the files' records, in metres;
#   hdr-m      ARM's command line on the heights in metres as they are (no normalisation): `astcenc -ch` of
#              the float level 0 heightpack writes, decoded by `astcenc -dh`, worst and RMS in metres.
# The last lines count the maps where HDR's figure is below LDR's of the same size (same bytes).
#   tests/bench/bench_astc_hdr.sh [BUILD_DIR] [HEIGHT_IN_METRES]
# Needs jq, oiiotool (OpenImageIO's tools) and astcenc (Debian's astcenc).
set -euo pipefail
build=${1:-build}
height=${2:-1.5}
hp="$build/heightpack"
here="$(dirname "$0")"
root="$here/../.."
[ -x "$hp" ] || { echo "bench_astc_hdr: no $hp; build first (cmake --build $build --target heightpack)" >&2; exit 2; }
for tool in jq oiiotool astcenc; do
  command -v "$tool" >/dev/null || { echo "bench_astc_hdr: needs $tool" >&2; exit 2; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_astc_hdr.XXXXXX")
trap 'rm -rf "$work"' EXIT

maps=()
for name in tests/corpus/trigger_grass_heightmap.png tests/corpus/trigger_greenland_heightmap.png \
  tests/corpus/trigger_mud_heightmap.png tests/corpus/trigger_altitude_heightmap.png \
  examples/maps/swell.png examples/maps/choppy.png examples/maps/ripple.png; do
  maps+=("$root/$name")
done
for sea in swell choppy ripple; do
  for cut in 64x64+131+77 64x64+170+150; do  # inside the 256x256 seas
    oiiotool "$root/examples/maps/$sea.png" --cut "$cut" -o "$work/${sea}_crop_${cut%%+*}_${cut#*+}.png"
    maps+=("$work/${sea}_crop_${cut%%+*}_${cut#*+}.png")
  done
done

# record FILE: "level0worst level0rms chainworst" in metres from the file's record.
record() {
  "$hp" info --json "$1" | jq -r --argjson h "$height" '.attributes as $a
    | ($a["heightpack:lookupError"] | split(",") | map(tonumber)) as $w
    | ($a["heightpack:rmsError"] | split(",") | map(tonumber)) as $r
    | "\($w[0] * $h) \($r[0] * $h) \($w | max * $h)"'
}
# raw_hdr SIDE: astcenc -ch / -dh of level 0 in metres as they are: "worst rms".
raw_hdr() {
  astcenc -ch "$work/m.exr" "$work/raw.astc" "$1x$1" -medium -silent >/dev/null
  astcenc -dh "$work/raw.astc" "$work/raw.exr" -silent >/dev/null
  { oiiotool "$work/raw.exr" --ch R "$work/m.exr" --ch R --diff 2>/dev/null || true; } |
    awk '/RMS error/ {rms = $NF} /Max error/ {worst = $4} END {printf "%.4g %.4g\n", worst, rms}'
}

printf '%-30s %-4s %28s %28s %20s\n' map size "ldr: L0 worst, rms; chain" "hdr: L0 worst, rms; chain" "hdr-m: L0 worst, rms"
declare -A lowerRms lowerWorst lowerChain
for size in 4 6 8; do lowerRms[$size]=0; lowerWorst[$size]=0; lowerChain[$size]=0; done
count=0
for map in "${maps[@]}"; do
  count=$((count + 1))
  "$hp" pack "$map" --layout plain --height "${height}m" --pixel-type float --quiet -o "$work/f.exr"
  # The float chain's values are the map's 0..1 (the height recorded beside them): level 0 in metres.
  oiiotool "$work/f.exr" --ch 0,0,0 --chnames R,G,B --ch R,G,B,A=1.0 --mulc "$height,$height,$height,1" -d float \
    -o "$work/m.exr"
  for size in 4 6 8; do
    "$hp" pack "$map" --layout plain --height "${height}m" --pixel-type "astc-${size}x${size}" --quiet -o "$work/l.ktx2"
    "$hp" pack "$map" --layout plain --height "${height}m" --pixel-type "astc-hdr-${size}x${size}" --quiet -o "$work/h.ktx2"
    read -r lw lr lc < <(record "$work/l.ktx2")
    read -r hw hr hc < <(record "$work/h.ktx2")
    read -r mw mr < <(raw_hdr "$size")
    printf '%-30s %-4s %28s %28s %20s\n' "$(basename "$map")" "${size}x${size}" \
      "$(printf '%.4f %.5f; %.4f' "$lw" "$lr" "$lc")" "$(printf '%.4f %.5f; %.4f' "$hw" "$hr" "$hc")" "$mw $mr"
    awk -v a="$hr" -v b="$lr" 'BEGIN {exit !(a < b)}' && lowerRms[$size]=$((lowerRms[$size] + 1))
    awk -v a="$hw" -v b="$lw" 'BEGIN {exit !(a < b)}' && lowerWorst[$size]=$((lowerWorst[$size] + 1))
    awk -v a="$hc" -v b="$lc" 'BEGIN {exit !(a < b)}' && lowerChain[$size]=$((lowerChain[$size] + 1))
  done
done
echo
for size in 4 6 8; do
  echo "${size}x${size}: HDR below LDR on $count maps: level-0 RMS ${lowerRms[$size]}, level-0 worst ${lowerWorst[$size]}, chain worst ${lowerChain[$size]}"
done
