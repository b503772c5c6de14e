#!/usr/bin/env bash
# heightpack tile against GEGL's gegl:tile-seamless and G'MIC's periodize_poisson (Debian's gegl and gmic)
# on the same maps, each result judged by `heightpack check --json`: the seams at every level, and the
# frame, blob and echo statistics (issue 22). Maps:
#   - sea-like crops: the middle of a synthesised periodic sea twice the size (several spectra and sizes),
#   - the painted example (examples/maps/painted_not_tileable.png),
#   - real textures from tests/corpus, cropped to 3/4 of their size so that none tiles (luma of colour).
# Prints one row per map and tool, then per tool: maps, seams pass, look passes, medians, and seconds.
#   tests/bench/bench_tile_look.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-test}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_tile_look: no $hp; build first" >&2; exit 2; }
for tool in gegl gmic oiiotool convert; do
  command -v "$tool" >/dev/null || { echo "bench_tile_look: needs $tool (apt-get install gegl gmic openimageio-tools imagemagick)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/in" "$work/out"

# ---- The maps ----
i=0
for spec in "phillips 12 256 256" "jonswap 9 128 512" "pierson-moskowitz 14 512 512" "jonswap 20 1024 256" \
            "phillips 7 64 256" "jonswap 12 512 1024"; do
  read -r spectrum wind tile size <<<"$spec"
  "$hp" synth --spectrum "$spectrum" --wind "${wind}m/s" --tile-size "${tile}m" --size $((2 * size)) --seed $((i + 3)) \
    -o "$work/sea$i.png" -q
  oiiotool "$work/sea$i.png" --cut "${size}x${size}+$((size / 3))+$((size / 5))" -o "$work/in/sea_${spectrum}_${size}.png"
  i=$((i + 1))
done
cp examples/maps/painted_not_tileable.png "$work/in/painted.png"
for f in tests/corpus/*.png tests/corpus/*.tga tests/corpus/*.bmp; do
  name=$(basename "${f%.*}")
  read -r w h < <(oiiotool --info "$f" | sed -nE 's/.*: *([0-9]+) x *([0-9]+).*/\1 \2/p')
  cw=$((w * 3 / 4)); ch=$((h * 3 / 4))
  # Grey 16-bit, a power of two on each side (what pack takes), cut from the top-left 3/4.
  pw=1; while ((pw * 2 <= cw)); do pw=$((pw * 2)); done
  ph=1; while ((ph * 2 <= ch)); do ph=$((ph * 2)); done
  ((pw >= 64 && ph >= 64)) || continue
  convert "$f" -colorspace Gray -crop "${pw}x${ph}+0+0" +repage -depth 16 "$work/in/corpus_$name.png"
done

# ---- Each tool on each map, judged by check ----
printf '%-34s %-10s %7s %6s %6s %6s %6s %6s\n' map tool seconds seams look frame blobs echo
: >"$work/rows"
for f in "$work"/in/*.png; do
  name=$(basename "${f%.png}")
  for tool in heightpack gegl gmic; do
    out="$work/out/${name}_$tool.png"
    start=$(date +%s.%N)
    case $tool in
      heightpack) "$hp" tile "$f" -o "$out" -q || true ;;
      gegl) gegl "$f" -o "$out" -- gegl:tile-seamless >/dev/null 2>&1 || true ;;
      gmic) gmic -v - "$f" periodize_poisson o "$out" >/dev/null 2>&1 || true ;;
    esac
    seconds=$(echo "$(date +%s.%N) - $start" | bc -l)
    if [ ! -s "$out" ]; then
      printf '%-34s %-10s %7.2f %6s\n' "$name" "$tool" "$seconds" "none" | tee -a "$work/rows"
      continue
    fi
    # --channel r: GEGL writes RGBA; a grey output's one channel stands for red.
    json=$("$hp" check "$out" --channel r --json 2>/dev/null || true)
    node -e '
      const r = JSON.parse(process.argv[1]);
      const l = r.look || {};
      const f = (v) => (typeof v === "number" ? v.toFixed(2) : "-");
      console.log([process.argv[2].padEnd(34), process.argv[3].padEnd(10), Number(process.argv[4]).toFixed(2).padStart(7),
        (r.tiles ? "pass" : "FAIL").padStart(6), (l.passes ? "pass" : "FAIL").padStart(6),
        f(l.frame).padStart(6), f(l.blobs).padStart(6), f(l.echo).padStart(6)].join(" "));
    ' "$json" "$name" "$tool" "$seconds" | tee -a "$work/rows"
  done
done

# ---- Per tool ----
echo
printf '%-10s %5s %12s %12s %13s %13s %13s %11s\n' tool maps "seams pass" "look passes" "median frame" "median blobs" "median echo" "total s"
for tool in heightpack gegl gmic; do
  awk -v tool="$tool" '$2 == tool {
      n++; s += $3
      if ($4 == "pass") seams++
      if ($5 == "pass") look++
      if ($6 != "") { fr[n] = $6; bl[n] = $7; ec[n] = $8 }
    }
    function median(a, k,   i, j, t, m) {
      m = 0; for (i in a) v[++m] = a[i]
      for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
      return m ? v[int((m + 1) / 2)] : 0
    }
    END { printf "%-10s %5d %11.0f%% %11.0f%% %13.2f %13.2f %13.2f %11.1f\n", tool, n, 100 * seams / n, 100 * look / n,
          median(fr), median(bl), median(ec), s }' "$work/rows"
done
