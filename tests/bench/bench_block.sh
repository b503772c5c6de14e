#!/usr/bin/env bash
# Issue 39's figures for the block formats (BC4, BC5, ASTC), run by hand (not by ctest):
#  1. bytes a texel of a whole chain per pixel type (pack --json's gpuBytes over the chain's texels), plain
#     heights and xy normals of examples/maps/swell.png;
#  2. the error against nvcompress -bc4/-bc5 and libsquish's kBc4/kBc5 on the same values, per map of the
#     test family (the corpus's grey maps, the example seas, crops of them; tests/io/block_format_test.cpp
#     prints the table and the rates of maps where heightpack's is worse);
#  3. the encode time of a SIZE x SIZE chain: whole `pack --layout plain` runs (load, mips, encode, write) in
#     bc4 and uint16, and `nvcompress -bc4` (load, its own mips, encode, write) of the same 8-bit PNG, and
#     `normal --layout xy` in bc5 against `nvcompress -bc5` of an RG PNG; libsquish's of the same PNGs
#     (tests/bench/squish_chain.cpp: load, 2x2 box mips, encode on one thread, write); medians of RUNS, wall
#     and CPU. The whole commands do different work around the encoding (heightpack makes the normals from
#     the heights, filters its mips with a wider kernel and measures each level's decoded error; the others
#     read an RG image and box-filter it), so the "encode" rows take from each block run the same tool's
#     run without the encoding: heightpack's uint16 output of the same chain, `nvcompress -rgb`, squish_chain
#     raw (differences of the medians);
#  4. ASTC 4x4, 6x6, 8x8 against ARM's astcenc command line at the same preset (-medium) on the same
#     SIZE x SIZE 8-bit map: level 0's worst and RMS error (units of the map's 0..1 values), both files'
#     blocks decoded by `astcenc -dl`, and the encode time (heightpack: the whole chain; astcenc: level 0).
#   tests/bench/bench_block.sh [BUILD_DIR] [RUNS] [SIZE]
# Needs jq, GNU time, oiiotool (OpenImageIO's tools), nvcompress (libnvtt-bin), astcenc, and the container
# tests and heightpack_squish_chain built (libsquish-dev; -DHEIGHTPACK_BUILD_BENCHMARKS=ON).
set -euo pipefail
build=${1:-build}
runs=${2:-3}
size=${3:-4096}
hp="$build/heightpack"
here="$(dirname "$0")"
examples="$here/../../examples/maps"
squish="$build/tests/bench/heightpack_squish_chain"
[ -x "$hp" ] || { echo "bench_block: no $hp; build first (cmake --build $build)" >&2; exit 2; }
[ -x "$squish" ] || { echo "bench_block: no $squish; install libsquish-dev, build with -DHEIGHTPACK_BUILD_BENCHMARKS=ON" >&2; exit 2; }
for tool in jq oiiotool nvcompress astcenc; do
  command -v "$tool" >/dev/null || { echo "bench_block: needs $tool" >&2; exit 2; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_block.XXXXXX")
trap 'rm -rf "$work"' EXIT
. "$here/measure.sh"

echo "1. bytes a texel of the whole chain (examples/maps/swell.png, 512x512, every level)"
printf '%-8s %-8s %12s %10s\n' output type "gpu bytes" "B/texel"
texels=$(( (512 * 512 * 4 - 1) / 3 ))  # 512^2 + 256^2 + ... + 1
for type in float half uint16 bc4 astc-4x4 astc-6x6 astc-8x8; do
  bytes=$("$hp" pack "$examples/swell.png" --layout plain --pixel-type "$type" --json -o "$work/s.ktx2" | jq '.gpuBytes')
  printf '%-8s %-8s %12s %10s\n' heights "$type" "$bytes" "$(ratio "$bytes" "$texels")"
done
for type in float half uint16 bc5 astc-4x4 astc-6x6 astc-8x8; do
  bytes=$("$hp" normal "$examples/swell.png" --tile-size 8m --height 0.5m --layout xy --pixel-type "$type" --json \
          -o "$work/n.ktx2" | jq '.gpuBytes')
  printf '%-8s %-8s %12s %10s\n' normals "$type" "$bytes" "$(ratio "$bytes" "$texels")"
done

echo
echo "2. error against nvcompress and squish on the same values (units of each map's range; degrees for normals)"
"$build/tests/heightpack_container_tests" --gtest_filter='BlockFormats.Bc*' | grep -E ' ours |^bc[45] maps'

echo
echo "3. encode time of a ${size}x${size} chain, $(nproc) cores, median of $runs runs (wall s, CPU s)"
oiiotool --pattern noise:type=gaussian:mean=0.5:stddev=0.15 "${size}x${size}" 1 --blur 9x9 --ch 0 -d uint8 -o "$work/map.png"
oiiotool "$work/map.png" "$work/map.png" --chappend --ch 0,1,0 -d uint8 -o "$work/rg.png"
printf '%-34s %10s %10s\n' run wall cpu
# row KEY NAME COMMAND...: the medians of RUNS runs of COMMAND, printed and kept as wall_KEY and cpu_KEY.
declare -A wall_of cpu_of
row() {
  local key=$1 name=$2
  shift 2
  : >"$work/log"
  for ((i = 0; i < runs; i++)); do measure "$work/log" "$@"; done
  read -r wall cpu _ < <(medians "$work/log")
  wall_of[$key]=$wall cpu_of[$key]=$cpu
  printf '%-34s %10s %10s\n' "$name" "$wall" "$cpu"
}
# encode NAME WITH WITHOUT: the difference of two rows' medians, the encoding's own time.
encode() {
  printf '%-34s %10s %10s\n' "$1" "$(awk -v a="${wall_of[$2]}" -v b="${wall_of[$3]}" 'BEGIN { printf "%.2f", a - b }')" \
    "$(awk -v a="${cpu_of[$2]}" -v b="${cpu_of[$3]}" 'BEGIN { printf "%.2f", a - b }')"
}
row hu "heightpack pack uint16" "$hp" pack "$work/map.png" --layout plain --pixel-type uint16 --quiet -o "$work/u.ktx2"
row h4 "heightpack pack bc4" "$hp" pack "$work/map.png" --layout plain --pixel-type bc4 --quiet -o "$work/b.ktx2"
row nr "nvcompress -rgb" nvcompress -rgb "$work/map.png" "$work/nvr.dds"
row n4 "nvcompress -bc4" nvcompress -bc4 "$work/map.png" "$work/nv4.dds"
row sr "squish raw (no encoding)" "$squish" raw "$work/map.png" "$work/sqr.bin"
row s4 "squish bc4 (one thread)" "$squish" bc4 "$work/map.png" "$work/sq4.bin"
row hnu "heightpack normal xy uint16" "$hp" normal "$work/map.png" --tile-size 8m --height 0.5m --layout xy \
  --pixel-type uint16 --quiet -o "$work/nu.ktx2"
row hn5 "heightpack normal xy bc5" "$hp" normal "$work/map.png" --tile-size 8m --height 0.5m --layout xy --pixel-type bc5 \
  --quiet -o "$work/n.ktx2"
row nrr "nvcompress -rgb (RG image)" nvcompress -rgb "$work/rg.png" "$work/nvrr.dds"
row n5 "nvcompress -bc5" nvcompress -bc5 "$work/rg.png" "$work/nv5.dds"
row srr "squish raw (RG image)" "$squish" raw "$work/rg.png" "$work/sqrr.bin"
row s5 "squish bc5 (one thread)" "$squish" bc5 "$work/rg.png" "$work/sq5.bin"
echo "encode alone (block run less the same tool's run without encoding):"
encode "  heightpack bc4 (- uint16)" h4 hu
encode "  nvcompress -bc4 (- -rgb)" n4 nr
encode "  squish bc4 (- raw)" s4 sr
encode "  heightpack bc5 (- uint16)" hn5 hnu
encode "  nvcompress -bc5 (- -rgb)" n5 nrr
encode "  squish bc5 (- raw)" s5 srr

echo
echo "4. ASTC against astcenc -cl ... -medium on the same ${size}x${size} map (level 0, decoded by astcenc -dl;"
echo "   error in units of the map's 0..1 values; time: heightpack the whole chain, astcenc level 0), median of $runs runs"
# le64 FILE OFFSET: the little-endian 64-bit word at OFFSET.
le64() { od -An -t u8 -j "$2" -N 8 "$1" | tr -d ' '; }
# astc_file SIDE WIDTH HEIGHT BLOCKS OUT: ARM's .astc header (magic, block size, 24-bit sizes) before BLOCKS.
astc_file() {
  local side=$1 w=$2 h=$3
  printf '\x13\xab\xa1\x5c' >"$5"
  printf "\\x$(printf %02x "$side")\\x$(printf %02x "$side")\\x01" >>"$5"
  for v in "$w" "$h" 1; do
    printf "\\x$(printf %02x $((v & 255)))\\x$(printf %02x $((v >> 8 & 255)))\\x$(printf %02x $((v >> 16 & 255)))" >>"$5"
  done
  cat "$4" >>"$5"
}
# errors DECODED.exr SCALE OFFSET: "worst rms" of OFFSET + SCALE * R against the map's values.
errors() {
  { oiiotool "$1" --ch R --mulc "$2" --addc "$3" "$work/map.png" --ch 0 --diff 2>/dev/null || true; } |
    awk '/RMS error/ {rms = $NF} /Max error/ {worst = $4} END {printf "%.5f %.5f", worst, rms}'
}
printf '%-10s %22s %22s %20s %20s\n' size "heightpack worst, rms" "astcenc worst, rms" "heightpack wall/cpu" "astcenc wall/cpu"
for side in 4 6 8; do
  type="astc-${side}x${side}"
  "$hp" pack "$work/map.png" --layout plain --pixel-type "$type" --quiet -o "$work/a.ktx2"
  kv=$("$hp" info --json "$work/a.ktx2")
  scale=$(jq -r '.attributes["heightpack:normalisedScale"]' <<<"$kv")
  offset=$(jq -r '.attributes["heightpack:normalisedOffset"]' <<<"$kv")
  dd if="$work/a.ktx2" of="$work/level0.bin" bs=1 skip="$(le64 "$work/a.ktx2" 80)" count="$(le64 "$work/a.ktx2" 88)" 2>/dev/null
  astc_file "$side" "$size" "$size" "$work/level0.bin" "$work/ours.astc"
  astcenc -dl "$work/ours.astc" "$work/ours.exr" -silent >/dev/null
  astcenc -cl "$work/map.png" "$work/cli.astc" "${side}x${side}" -medium -silent >/dev/null
  astcenc -dl "$work/cli.astc" "$work/cli.exr" -silent >/dev/null
  ours=$(errors "$work/ours.exr" "$scale" "$offset")
  theirs=$(errors "$work/cli.exr" 1 0)
  : >"$work/log"
  for ((i = 0; i < runs; i++)); do
    measure "$work/log" "$hp" pack "$work/map.png" --layout plain --pixel-type "$type" --quiet -o "$work/a.ktx2"
  done
  read -r hwall hcpu _ < <(medians "$work/log")
  : >"$work/log"
  for ((i = 0; i < runs; i++)); do
    measure "$work/log" astcenc -cl "$work/map.png" "$work/cli.astc" "${side}x${side}" -medium -silent
  done
  read -r awall acpu _ < <(medians "$work/log")
  printf '%-10s %22s %22s %20s %20s\n' "$type" "$ours" "$theirs" "$hwall / $hcpu" "$awall / $acpu"
done
