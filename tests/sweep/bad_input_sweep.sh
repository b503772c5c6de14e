#!/usr/bin/env bash
# The bad-input sweep (issue 12): every command under inputs, options and outputs that must fail, each
# checked against the command-line contract: the documented exit code, exactly one line on stderr
# ("heightpack: error: <path>: <what> (<hint>)") naming the file where there is one, nothing new or
# changed in the working folder, and no temporary file left. Prints a table and "N passed, M failed";
# exits 1 when any case fails.
#
#   tests/sweep/bad_input_sweep.sh [path/to/heightpack]      (default: build/heightpack)
#   VERBOSE=1 ...                                            prints every case
# Two shards run side by side, each in its own folder (every case starts a process; most of its time
# is loading OpenImageIO's shared libraries).
set -u
HP=$(realpath "${1:-build/heightpack}")
HOSTILE=$(realpath "$(dirname "$0")/../io/hostile")   # fuzz findings (issue 21), refused by every reader
[ -x "$HP" ] || { echo "no heightpack at $HP" >&2; exit 2; }
SHARDS=("pack normal info check" "tile synth fresnel build")
if [ -z "${SWEEP_SHARD:-}" ]; then
    out=$(mktemp -d "${TMPDIR:-/tmp}/heightpack-sweep-out.XXXXXX")
    for i in "${!SHARDS[@]}"; do SWEEP_SHARD=$i bash "$0" "$HP" > "$out/$i" 2>&1 & done
    wait
    grep -hv '^row ' "$out"/* | grep -v '^$'
    printf '\n%-8s %6s %7s\n' command cases passed
    grep -h '^row ' "$out"/* | awk '{ printf "%-8s %6d %7d\n", $2, $3, $4; c += $3; p += $4 }
        END { printf "%-8s %6d %7d\n%d passed, %d failed\n", "all", c, p, p, c - p; exit (c == p && c > 0) ? 0 : 1 }'
    status=$?
    rm -rf "$out"
    exit $status
fi
MINE=" ${SHARDS[$SWEEP_SHARD]} "
ROOT=$(mktemp -d "${TMPDIR:-/tmp}/heightpack-sweep.XXXXXX")
trap 'chmod -R u+w "$ROOT" 2>/dev/null; rm -rf "$ROOT"' EXIT
W="$ROOT/work"   # the working folder every case runs in
T="$ROOT/io"     # stdout and stderr of the case
mkdir -p "$W" "$T"
cd "$W" || exit 2

# ---- Inputs: good ones made by heightpack itself, bad ones from them or from bytes -----------------
"$HP" synth --wind 10 --tile-size 64m --size 32 -o good.png -q || exit 2
"$HP" synth --wind 10 --tile-size 64m --size 32 -o good.exr -q || exit 2
"$HP" tile good.png -o good.tif -q --depth uint16 --force || exit 2
"$HP" pack good.png -o packed.exr -q || exit 2
"$HP" fresnel --format png8 -o colour.png -q || exit 2              # 256x1 RGBA: a colour image
"$HP" synth --wind 10 --tile-size 64m --size 32 -o seq.exr --frames 2 --loop 4s -q || exit 2
cut_half() { head -c $(($(stat -c %s "$1") / 2)) "$1" > "$2"; }
cut_half good.png cut.png
cut_half good.tif cut.tif
cut_half good.exr cut.exr
head -c $(($(stat -c %s packed.exr) - 20)) packed.exr > cutmip.exr   # a mip-mapped EXR missing its last level
head -c 8 good.png > signature.png
: > empty.png
printf 'hello\n' > text.png
printf 'not an exr at all, just some text that is long enough to look like a header\n' > text.exr
printf 'II*\0garbage garbage garbage garbage\n' > text.tif
mkdir folder.png
ln -s folder.png dirlink.png
head -c 1000 /dev/zero > zeros.png
yes | head -c 4000 > yes.exr
head -c 33 good.png > header.png
head -c 300 good.exr > header.exr
head -c 16 good.tif > header.tif
mkfifo fifo.png
cp good.png seqfifo.0000.png; mkfifo seqfifo.0001.png
ln -s missing-target.png dangling.png
ln -s fifo.png fifolink.png
# Float maps as PFM (bottom-up rows of little-endian floats): NaN, infinity, a short file, a huge header.
pfm() { printf 'Pf\n2 2\n-1.0\n'; printf "$1"; }
pfm '\0\0\0\077\0\0\300\177\0\0\0\077\0\0\0\077' > nan.pfm
pfm '\0\0\0\077\0\0\200\177\0\0\0\077\0\0\0\077' > inf.pfm
pfm '\0\0\0\077' > short.pfm
printf 'Pf\n100000 100000\n-1.0\n\0\0\0\0' > hugeheader.pfm
# PNGs by hand (CRCs included): headers claiming 100000^2 and 32768^2, an IDAT run split by a text
# chunk, a damaged CRC; and an RLE8 BMP (OpenImageIO 2.4 decodes those wrongly).
b64() { printf '%s' "$1" | base64 -d > "$2"; }
b64 iVBORw0KGgoAAAANSUhEUgABhqAAAYagCAAAAACNOVQUAAAADElEQVR4nGNgoAwAAABAAAG3NHzvAAAAAElFTkSuQmCC huge.png
b64 iVBORw0KGgoAAAANSUhEUgAAgAAAAIAACAAAAADhF/yjAAAADElEQVR4nGNgoAwAAABAAAG3NHzvAAAAAElFTkSuQmCC big.png
b64 iVBORw0KGgoAAAANSUhEUgAAABAAAAAQCAAAAAA6mKC9AAAAW0lEQVR4nGNgYOcTlVHWMrSwd/MNiU7KZGDmEpSQV9M1sXbyDAiPS81hYOMVkVbSNDC3c/UJjkrMyGfgFBCXU9UxtnL08A+LTckuYuARllLU0DezdfEOikxIzytl4BeTAq6TSQAAAAN0RVh0YQBi3EmiOwAAAFxJREFUVdE2snRw9wuNSc4qrGAQklRQ1zO1cfYKjIhPyy2pZkCxs6C8jgHFzuKqRgYUO8tqWxhQ7KxsaGdAsbOmuYsBxc76tl4GFDubOicwoNjZ2jOZAcXOjv5pAAqdSwHVvGDzAAAAAElFTkSuQmCC split.png
b64 iVBORw0KGgoAAAANSUhEUgAAABAAAAAQCAAAAAA6mKC9AAAAt0lEQat4nGNgYOcTlVHWMrSwd/MNiU7KZGDmEpSQV9M1sXbyDAiPS81hYOMVkVbSNDC3c/UJjkrMyGfgFBCXU9UxtnL08A+LTckuYuARllLU0DezdfEOikxIzytl4BeTVdE2snRw9wuNSc4qrGAQklRQ1zO1cfYKjIhPyy2pZkCxs6C8jgHFzuKqRgYUO8tqWxhQ7KxsaGdAsbOmuYsBxc76tl4GFDubOicwoNjZ2jOZAcXOjv5pAAqdSwE6yUr/AAAAAElFTkSuQmCC badcrc.png
{ printf 'BM\076\004\0\0\0\0\0\0\066\004\0\0\050\0\0\0\004\0\0\0\002\0\0\0\001\0\010\0\001\0\0\0\010\0\0\0'
  printf '\023\013\0\0\023\013\0\0\0\001\0\0\0\0\0\0'
  for i in $(seq 0 255); do printf "\\$(printf %03o "$i")\\$(printf %03o "$i")\\$(printf %03o "$i")\\0"; done
  printf '\004\012\0\0\004\310\0\001'; } > rle.bmp
head -c 100 rle.bmp > cutrle.bmp
cp "$HOSTILE"/load_image-oom-* "$HOSTILE"/tiff_huge_alloc.tif "$HOSTILE"/png_text_chunk_oom.png "$HOSTILE"/exr_negative_seek.exr "$HOSTILE"/jpeg_stuffed_zero_iptc.jpg .
HOSTILE_MAPS=(load_image-oom-*.dpx load_image-oom-*.exr load_image-oom-*.png tiff_huge_alloc.tif png_text_chunk_oom.png exr_negative_seek.exr jpeg_stuffed_zero_iptc.jpg)
printf 'GIF89a\001\000\001\000\000\000\000;' > a.gif   # a format heightpack does not read
# A map whose sides are not powers of two: the first 3 rows of good.png are not a PNG, so crop via tile's
# mirror of a 1-row... simplest: synth refuses non-powers of two, so use a PFM 3x3.
{ printf 'Pf\n3 3\n-1.0\n'; for i in 1 2 3 4 5 6 7 8 9; do printf '\0\0\0\077'; done; } > odd.pfm
# Textures from pack with one header value damaged in place (issue 38; perl-base is in every Debian):
# refused by every reader as bad input naming the file (tests/cli/damaged_header_test.cpp checks the key).
"$HP" pack good.png -o packed.ktx2 -q || exit 2
damage() { perl -0777 -pe "$3" "$1" > "$2"; cmp -s "$1" "$2" && { echo "damage $2: nothing replaced" >&2; exit 2; }; }
damage packed.ktx2 layoutx.ktx2 's/neighbour4/neighbourX/'
damage packed.ktx2 scalex.ktx2 's/(heightpack:heightScale\0)1\0/${1}x\0/'
damage packed.ktx2 wrapx.ktx2 's/(heightpack:wrap\0)periodic/${1}mirrored/'
damage packed.exr layoutx.exr 's/neighbour4/neighbourX/'
damage packed.exr filterx.exr 's/(heightpack:filter\0string\0....)kaiser/${1}kaiseX/s'
damage seq.0000.exr loopx.exr 's/(heightpack:loopPeriod\0float\0....)..../${1}\0\0\200\277/s'  # -1 s
# Block streams cut short (issue 39): BC4 heights in KTX2 and DDS, the level data ending mid-block.
"$HP" pack good.png -o bc4.ktx2 --layout plain --pixel-type bc4 -q || exit 2
"$HP" pack good.png -o bc4.dds --layout plain --pixel-type bc4 -q || exit 2
# ASTC HDR heights in KTX2, cut short the same way.
"$HP" pack good.png -o hdr.ktx2 --layout plain --pixel-type astc-hdr-6x6 -q || exit 2
for f in bc4.ktx2 bc4.dds hdr.ktx2; do head -c $(( $(stat -c %s "$f") - 13 )) "$f" > "cut$f"; done
DAMAGED=(layoutx.ktx2 scalex.ktx2 wrapx.ktx2 layoutx.exr filterx.exr loopx.exr cutbc4.ktx2 cutbc4.dds cuthdr.ktx2)
# Outputs that must not be replaced.
printf 'old' > readonly.exr; chmod 444 readonly.exr
printf 'old' > target.exr; ln -s target.exr link.exr
mkfifo node.exr
mkdir outdir.exr
ln good.png hardlink.png
# Manifests for build.
cp good.png maps_a.png
manifest() { printf 'format = 1\nname = "sea"\n\n[[displacement]]\nname = "a"\nsource = "%s"\ntile_size = 64.0\n%s\n' "$1" "$2"; }

snapshot() { find "$W" -printf '%P %y %s %i %m %T@\n' | sort; }

# ---- The runner ----------------------------------------------------------------------------------
declare -A cases passed
order=()
failures=0
total=0
# expect COMMAND CODE NAMED ARGS...: runs 'heightpack COMMAND ARGS...' in the working folder; NAMED is a
# path the error line must contain ('' when the error is about an option, not a file).
expect() {
    local cmd=$1 code=$2 named=$3
    shift 3
    [[ "$MINE" == *" $cmd "* ]] || return 0
    local before after rc problems=""
    before=$(snapshot)
    timeout "${SWEEP_TIMEOUT:-30}" "$HP" "$cmd" "$@" > "$T/out" 2> "$T/err" < /dev/null
    rc=$?
    after=$(snapshot)
    [ "$rc" -eq "$code" ] || problems+="exit $rc, want $code; "
    local lines
    lines=$(wc -l < "$T/err")
    [ "$lines" -eq 1 ] || problems+="$lines lines on stderr; "
    local line
    line=$(head -n 1 "$T/err")
    [[ "$line" == "heightpack: error: "* ]] || problems+="not a heightpack error line; "
    [[ "$line" == *")" ]] || problems+="no hint in parentheses; "
    [ -z "$named" ] || [[ "$line" == *"$named"* ]] || problems+="does not name $named; "
    [ "$before" == "$after" ] || problems+="the working folder changed: $(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -3 | tr '\n' ' '); "
    find "$ROOT" -name '*.hptmp-*' | grep -q . && problems+="a temporary file was left; "
    if [ -z "${cases[$cmd]+x}" ]; then cases[$cmd]=0; passed[$cmd]=0; order+=("$cmd"); fi
    cases[$cmd]=$((cases[$cmd] + 1))
    total=$((total + 1))
    if [ -z "$problems" ]; then
        passed[$cmd]=$((passed[$cmd] + 1))
        [ -z "${VERBOSE:-}" ] || echo "ok   $cmd $*"
    else
        failures=$((failures + 1))
        echo "FAIL heightpack $cmd $* -> $problems" | cut -c1-400
        echo "     stderr: $(head -c 300 "$T/err")"
        find "$ROOT" -name '*.hptmp-*' -delete
    fi
}

# Inputs every map-reading command refuses (exit 3), each naming the file.
BAD_MAPS=(missing.png empty.png text.png signature.png cut.png cut.tif cut.exr text.exr text.tif folder.png fifo.png
          /dev/zero dangling.png fifolink.png short.pfm hugeheader.pfm huge.png big.png split.png
          badcrc.png rle.bmp cutrle.bmp zeros.png yes.exr header.png header.exr header.tif dirlink.png
          good.png/ "" "${HOSTILE_MAPS[@]}" a.gif)
# ...and those refused by commands that need heights, not by info (which describes them): colour, NaN.
HEIGHT_ONLY=(colour.png nan.pfm inf.pfm)

# ---- pack ----
for f in "${BAD_MAPS[@]}" "${HEIGHT_ONLY[@]}" odd.pfm layoutx.exr filterx.exr loopx.exr; do expect pack 3 "$f" "$f" -o out.exr; done
expect pack 2 "" good.png -o out.exr --scale nan
expect pack 2 "" good.png -o out.exr --offset inf
expect pack 2 "" good.png -o out.exr --scale 1e300
expect pack 2 "" good.png -o out.exr --filter sinc
expect pack 2 "" good.png -o out.exr --threads -1
expect pack 2 "" good.png
expect pack 2 "-o ''" good.png -o ''
expect pack 2 good.png good.png -o good.png
expect pack 2 hardlink.png good.png -o out.exr --emit-plain hardlink.png
expect pack 2 ./packed.exr packed.exr -o ./packed.exr
expect pack 2 out.png good.png -o out.png
expect pack 2 out.tif good.png -o out.tif
expect pack 2 out.exr good.png -o out.exr --emit-plain out.exr
expect pack 4 readonly.exr good.png -o readonly.exr
expect pack 4 link.exr good.png -o link.exr
expect pack 4 node.exr good.png -o node.exr
expect pack 4 outdir.exr good.png -o outdir.exr
expect pack 4 missing/out.exr good.png -o missing/out.exr
expect pack 4 /dev/full good.png -o /dev/full
# Pixel types and layouts (issue 14): auto and --tolerance need each other; a length needs --height.
expect pack 2 "" good.png -o out.ktx2 --pixel-type auto
expect pack 2 "" good.png -o out.ktx2 --pixel-type half --tolerance 0.001
expect pack 2 "" good.png -o out.ktx2 --pixel-type auto --tolerance 1mm
expect pack 2 "" good.png -o out.ktx2 --pixel-type auto --tolerance 0 --height 2m
expect pack 2 "" good.png -o out.ktx2 --layout plain --emit-plain plain.ktx2
expect pack 2 "" good.png -o out.ktx2 --layout rgb
# ASTC HDR holds plain heights in KTX2 only (issue 39).
expect pack 2 out.dds good.png -o out.dds --layout plain --pixel-type astc-hdr-4x4
expect pack 2 "" good.png -o out.ktx2 --pixel-type astc-hdr-8x8

# ---- normal ----
N=(--tile-size 8m --height 1m)
for f in "${BAD_MAPS[@]}" "${HEIGHT_ONLY[@]}" odd.pfm; do expect normal 3 "$f" "$f" "${N[@]}" -o out.exr; done
expect normal 2 "" good.png --tile-size 8m --height 1e300 -o out.exr
expect normal 2 "" good.png "${N[@]}" --layout xy --height-in-alpha -o out.ktx2
expect normal 2 "" good.png "${N[@]}" --pixel-type auto --tolerance 1furlong -o out.ktx2
expect normal 2 "" good.png "${N[@]}" --layout xy --pixel-type astc-hdr-6x6 -o out.ktx2
# Words a new user gets wrong (issue 35): a misspelt option, an option given twice; a manifest is no texture.
expect normal 2 "--tilesize" good.png --tilesize 8m --height 1m -o out.exr
expect pack 2 "--filtr" good.png --filtr lanczos3 -o out.exr
expect synth 2 "--size" --size 64 --size 128 --wind 12 --tile-size 64m -o out.exr
expect normal 2 "" good.png "${N[@]}" --layout xy -o out.png
expect normal 2 "" good.png --tile-size nan --height 1m -o out.exr
expect normal 2 "" good.png --tile-size 8m,inf --height 1m -o out.exr
expect normal 2 "" good.png --tile-size 8m --height -1m -o out.exr
expect normal 2 "" good.png --tile-size 8ft --height 1m -o out.exr
expect normal 2 "" good.png --height 1m -o out.exr
expect normal 2 out.jpg good.png "${N[@]}" -o out.jpg
expect normal 2 good.png good.png "${N[@]}" -o good.png
expect normal 2 "" good.png "${N[@]}" -o out.png --format exr
expect normal 4 readonly.exr good.png "${N[@]}" -o readonly.exr
expect normal 4 link.exr good.png "${N[@]}" -o link.exr
expect normal 4 node.exr good.png "${N[@]}" -o node.exr
expect normal 4 /dev/full good.png "${N[@]}" -o /dev/full

# ---- check ----
for f in "${BAD_MAPS[@]}" "${HEIGHT_ONLY[@]}" cutmip.exr "${DAMAGED[@]}"; do expect check 3 "$f" "$f"; done
expect check 2 "" good.png --threshold nan
expect check 2 "" good.png --threshold inf
expect check 2 "" good.png --threshold 0.5
expect check 2 "" good.png --wrap mirror
expect check 2 good.png good.png --preview good.png
expect check 2 hardlink.png good.png --preview hardlink.png
expect check 2 prev.jpg good.png --preview prev.jpg
expect check 2 "--preview ''" good.png --preview ''
expect check 4 node.exr good.png --preview node.exr
expect check 4 missing/p.png good.png --preview missing/p.png

# ---- tile ----
for f in "${BAD_MAPS[@]}" "${HEIGHT_ONLY[@]}"; do expect tile 3 "$f" "$f" -o out.png; done
expect tile 2 "" good.png -o out.png --threshold nan
expect tile 2 "" good.png -o out.png --width 0.9 --method crossfade
expect tile 2 "" good.png -o out.png --width nan --method crossfade
expect tile 2 "" good.png -o out.png --width 0.1
expect tile 2 "" good.png -o out.png --depth uint4
expect tile 2 out.jpg good.png -o out.jpg
expect tile 2 out good.png -o out
expect tile 2 good.png good.png -o good.png
expect tile 2 hardlink.png good.png -o hardlink.png --force
expect tile 4 readonly.exr good.png -o readonly.exr
expect tile 4 link.exr good.png -o link.exr
expect tile 4 node.exr good.png -o node.exr
expect tile 4 outdir.exr good.png -o outdir.exr

# ---- info ----
for f in "${BAD_MAPS[@]}" cutmip.exr "${DAMAGED[@]}"; do expect info 3 "$f" "$f"; done
expect info 2 "" good.png --threads nan
expect info 2 "" good.png --bogus
expect info 2 "" good.png packed.exr
expect info 2 ""

# ---- synth ----
S=(--tile-size 64m --size 16)
expect synth 2 "" --wind nan "${S[@]}" -o s.exr
expect synth 2 "" --wind inf "${S[@]}" -o s.exr
expect synth 2 "" --wind 1e300 "${S[@]}" -o s.exr
expect synth 2 "" --wind -3 "${S[@]}" -o s.exr
expect synth 2 "" --wind 0 "${S[@]}" -o s.exr
expect synth 2 "" --wind 12furlongs "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --direction nan "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --direction inf "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --direction 1e9 "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --gamma nan "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --gamma 0.5 "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --fetch nan "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --fetch 1e300 "${S[@]}" -o s.exr
expect synth 2 "" --wind 10 --tile-size 1e300 --size 16 -o s.exr
expect synth 2 "" --wind 10 --tile-size nan --size 16 -o s.exr
expect synth 2 "" --wind 10 --tile-size 64m --size 3 -o s.exr
expect synth 2 "" --wind 10 --tile-size 64m --size 16384 -o s.exr
expect synth 2 "" --wind 10 --tile-size 64m --size 1e300 -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --frames 2 -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --frames 0 --loop 4s -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --frames 2 --loop nan -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --spectrum pierson -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --shift -o s.png
expect synth 2 "" --wind 10 "${S[@]}" --seed abc -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --swell -1m,12s,250deg -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --spreading cos4 -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --choppiness -1 -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --foam-decay 0s -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --depth nan -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --frames 10001 --loop 1s -o s.exr
expect synth 2 "" --wind 10 "${S[@]}" --frames 2 --loop 1e300 -o s.exr
expect synth 2 "" --wind 10 --tile-size 64m,32m --size 16 -o s.exr
expect synth 2 "" --wind 10 --tile-size 64m --size 0 -o s.exr
expect synth 2 s.jpg --wind 10 "${S[@]}" -o s.jpg
expect synth 2 "-o ''" --wind 10 "${S[@]}" -o ''
expect synth 4 readonly.exr --wind 10 "${S[@]}" -o readonly.exr
expect synth 4 link.exr --wind 10 "${S[@]}" -o link.exr
expect synth 4 node.exr --wind 10 "${S[@]}" -o node.exr
expect synth 4 outdir.exr --wind 10 "${S[@]}" -o outdir.exr
expect synth 4 missing/s.exr --wind 10 "${S[@]}" -o missing/s.exr

# ---- fresnel ----
expect fresnel 2 "" --ior nan -o f.exr
expect fresnel 2 "" --ior inf -o f.exr
expect fresnel 2 "" --ior 0.5 -o f.exr
expect fresnel 2 "" --ior 1e300 -o f.exr
expect fresnel 2 "" --size 1 -o f.exr
expect fresnel 2 "" --size 1e300 -o f.exr
expect fresnel 2 "" --deep nan,0,0 -o f.exr
expect fresnel 2 "" --deep 2,0,0 -o f.exr
expect fresnel 2 "" --shallow 0.1,0.2 -o f.exr
expect fresnel 2 "" --model fancy -o f.exr
expect fresnel 2 "" --index 3nv -o f.exr
expect fresnel 2 "" --format png8 -o f.exr
expect fresnel 2 "" --size -5 -o f.exr
expect fresnel 2 "" --size abc -o f.exr
expect fresnel 2 "" --deep 0.1,0.1,0.1,0.1 -o f.exr
expect fresnel 2 "" --ior 1.333 extra.png -o f.exr
expect fresnel 2 f.jpg -o f.jpg
expect fresnel 2 f.tif -o f.tif
expect fresnel 2 f -o f
expect fresnel 2 "-o ''" -o ''
expect fresnel 2 ""
expect fresnel 2 "" -o f.exr --threads abc
expect fresnel 4 readonly.exr -o readonly.exr
expect fresnel 4 link.exr -o link.exr
expect fresnel 4 node.exr -o node.exr
expect fresnel 4 outdir.exr -o outdir.exr
expect fresnel 4 missing/f.exr -o missing/f.exr
expect fresnel 4 /dev/full -o /dev/full
expect fresnel 4 /dev/null -o /dev/null

# ---- build ----
m=0
bad_manifest() {  # bad_manifest CODE NAMED TEXT: writes the manifest and builds it (named: FILE:LINE or a source)
    m=$((m + 1))
    printf '%s' "$3" > "m$m.toml"
    expect build "$1" "${2//@/m$m.toml}" "m$m.toml" -o out
}
bad_manifest 3 "@:" ''
bad_manifest 3 "@:1" 'format = '
bad_manifest 3 "@:" '[#]'
bad_manifest 3 "@:1" 'format = 2'
bad_manifest 3 "@:" 'format = 1'
bad_manifest 3 "@:6" "$(manifest fifo.png '')"
bad_manifest 3 "@:6" "$(manifest missing.png '')"
bad_manifest 3 "@:6" "$(manifest folder.png '')"
bad_manifest 3 "@:7" "$(printf 'format = 1\nname = "sea"\n\n[[displacement]]\nname = "a"\nsource = "maps_a.png"\ntile_size = nan\n')"
bad_manifest 3 "@:7" "$(printf 'format = 1\nname = "sea"\n\n[[displacement]]\nname = "a"\nsource = "maps_a.png"\ntile_size = inf\n')"
bad_manifest 3 "@:7" "$(printf 'format = 1\nname = "sea"\n\n[[displacement]]\nname = "a"\nsource = "maps_a.png"\ntile_size = 1e300\n')"
bad_manifest 3 "@:7" "$(printf 'format = 1\nname = "sea"\n\n[[displacement]]\nname = "a"\nsource = "maps_a.png"\ntile_size = "big"\n')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'amplitude = nan')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'height_scale = 0')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'scroll = [1e9, 0]')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'output = "../escape.exr"')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'output = "a.png"')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'wrap = "mirror"')"
bad_manifest 3 "@:8" "$(manifest maps_a.png "$(head -c 200000 /dev/zero | tr '\0' k) = 1")"
bad_manifest 3 "@:12" "$(manifest maps_a.png "$(printf '\n[normals]\nsource = "maps_a.png"\ntile_size = 8.0\nheight = 1e300')")"
bad_manifest 3 "@:10" "$(manifest maps_a.png "$(printf '\n[fresnel]\nior = nan')")"
bad_manifest 3 "@:10" "$(manifest maps_a.png "$(printf '\n[fresnel]\nior = 0.5')")"
bad_manifest 3 "@:9" "$(manifest maps_a.png "$(printf '\n[normals]\nsource = "maps_a.png"\ntile_size = 8.0')")"
bad_manifest 3 "@:" "$(manifest maps_a.png "$(printf '\n[[displacement]]\nname = "a"\nsource = "maps_a.png"\ntile_size = 8.0')")"
bad_manifest 3 "@:2" "$(printf 'format = 1\nname = "a b/c"\n[[displacement]]\nsource = "maps_a.png"\ntile_size = 8.0\n')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'tile_sise = 3.0')"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'channel = "auto"')"
# Block formats (issue 39) where they cannot be: the packed layout, an EXR, ASTC in a DDS, bc5 for heights.
bad_manifest 3 "@:9" "$(manifest maps_a.png "$(printf 'container = "ktx2"\npixel_type = "bc4"')")"
bad_manifest 3 "@:9" "$(manifest maps_a.png "$(printf 'layout = "plain"\npixel_type = "bc4"')")"
bad_manifest 3 "@:10" "$(manifest maps_a.png "$(printf 'layout = "plain"\ncontainer = "dds"\npixel_type = "astc-4x4"')")"
bad_manifest 3 "@:10" "$(manifest maps_a.png "$(printf 'layout = "plain"\ncontainer = "dds"\npixel_type = "bc5"')")"
bad_manifest 3 "@:8" "$(manifest maps_a.png 'layout = "xy"')"
bad_manifest 3 "@:11" "$(manifest maps_a.png "$(printf 'container = "ktx2"\npixel_type = "auto"\ntolerance = 0.01\nallow_block_compression = true')")"
bad_manifest 3 "cut.png" "$(manifest cut.png '')"
bad_manifest 3 "seqfifo.0001.png" "$(manifest seqfifo.png '')"
bad_manifest 3 "nan.pfm" "$(manifest nan.pfm '')"
bad_manifest 3 "rle.bmp" "$(manifest rle.bmp '')"
bad_manifest 3 "huge.png" "$(manifest huge.png '')"
bad_manifest 3 "colour.png" "$(manifest colour.png '')"
manifest maps_a.png '' > ok.toml
expect build 4 good.png ok.toml -o good.png
expect info 2 ok.toml ok.toml
expect build 4 /dev/full ok.toml -o /dev/full
expect build 3 folder.png folder.png -o out
expect build 3 fifo.png fifo.png -o out
expect build 3 missing.toml missing.toml -o out
expect build 2 "" m1.toml
expect build 2 "" m1.toml -o out --jobs 0
expect build 2 "" m1.toml --check-only --depfile d.d
expect build 2 "" ok.toml -o out --cache ftp://u:pw@host/c          # a cache neither a folder nor http(s)
expect build 2 "" ok.toml -o out --cache-mode sometimes
expect build 2 "" ok.toml -o out --cache-mode read-only              # a mode without a cache
expect build 2 "" ok.toml -o out --cache http://127.0.0.1:9/hp --cache-size 1G   # a size is a folder's

# ---- This shard's rows of the table ----
for cmd in "${order[@]}"; do echo "row $cmd ${cases[$cmd]} ${passed[$cmd]}"; done
[ "$failures" -eq 0 ]
