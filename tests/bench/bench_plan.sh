#!/usr/bin/env bash
# Issue 26's figures: a synthesised sea of FRAMES frames x 3 cascades (SIZE^2 each) built three ways into
# fresh folders: `heightpack build --jobs N`, `ninja -f PLAN -j N` on the plan of `build --plan ninja`, and
# `heightpack build` of a second folder from a shared cache the first filled. Prints seconds and whether
# every output is byte-identical to the plain build's.
#   tests/bench/bench_plan.sh [BUILD_DIR] [FRAMES] [SIZE] [JOBS]
set -euo pipefail
build=${1:-build}
frames=${2:-60}
size=${3:-256}
jobs=${4:-$(nproc)}
hp="$(cd "$build" && pwd)/heightpack"
[ -x "$hp" ] || { echo "bench_plan: no $hp; build first (cmake --build $build)" >&2; exit 2; }
command -v ninja >/dev/null || { echo "bench_plan: needs ninja (apt-get install ninja-build)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cat >sea.toml <<TOML
format = 1
name = "sea"

[[displacement]]
name = "sea"
tile_size = 256.0
synth = { wind = 12.0, size = $size, seed = 7, loop = 8.0, frames = $frames, cascades = 3 }
TOML
seconds() { local start end; start=$(date +%s.%N); "$@" >/dev/null; end=$(date +%s.%N); echo "$end - $start" | bc -l; }

plain=$(seconds "$hp" build sea.toml -o plain --jobs "$jobs" -q)
"$hp" build sea.toml -o planned --plan ninja >plan.ninja
actions=$(grep -c '^build ' plan.ninja)
planned=$(seconds ninja -f plan.ninja -j "$jobs")
"$hp" build sea.toml -o first --jobs "$jobs" --cache cache -q
restored=$(seconds "$hp" build sea.toml -o second --jobs "$jobs" --cache cache -q)
same() { diff -rq plain "$1" >/dev/null && echo "identical" || echo "DIFFERENT"; }
echo "sea: $frames frames x 3 cascades at ${size}x${size}; $(nproc) cores; $jobs jobs; $actions actions in the plan"
printf "heightpack build --jobs %s   %7.2f s\n" "$jobs" "$plain"
printf "ninja -f plan -j %s          %7.2f s  (%s)\n" "$jobs" "$planned" "$(same planned)"
printf "build from a shared cache    %7.2f s  (%s)\n" "$restored" "$(same second)"
