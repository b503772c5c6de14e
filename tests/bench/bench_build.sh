#!/usr/bin/env bash
# heightpack build over a material of N maps against what a pipeline without it runs: one `heightpack
# check` and one `heightpack pack` process per map. Then the incremental cases: a second build (nothing
# to do) and a build after touching every map (hashes only). Median seconds of RUNS, and ratios.
#   tests/bench/bench_build.sh [BUILD_DIR] [RUNS] [MAPS] [SIZE]
set -euo pipefail
build=${1:-build}
runs=${2:-3}
maps=${3:-8}  # a material holds at most 8 displacement maps
size=${4:-1024}
hp="$build/heightpack"
[ -x "$hp" ] || { echo "bench_build: no $hp; build first (cmake --build $build)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/tests/bench/heightpack_make_bench_map" "$size" "$size" "$work/map.png"
{
  echo "format = 1"
  echo "name = \"bench\""
  for ((i = 0; i < maps; i++)); do
    cp "$work/map.png" "$work/map$i.png"
    printf '[[displacement]]\nname = "map%d"\nsource = "map%d.png"\ntile_size = 64\n' "$i" "$i"
  done
} >"$work/bench.toml"
echo "material: $maps maps of ${size}x${size} 16-bit; $(nproc) cores; $runs runs each"

seconds() { local s; s=$(date +%s.%N); "$@" >/dev/null 2>&1; awk -v a="$s" -v b="$(date +%s.%N)" 'BEGIN {print b - a}'; }
median() { sort -n | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
per_map() {
  for ((i = 0; i < maps; i++)); do
    "$hp" check "$work/map$i.png" -q && "$hp" pack "$work/map$i.png" -q -o "$work/loose/map$i.exr"
  done
}
mkdir -p "$work/loose"
: >"$work/loose.t"; : >"$work/j1.t"; : >"$work/j2.t"; : >"$work/noop.t"; : >"$work/touch.t"
for ((r = 0; r < runs; r++)); do
  seconds per_map >>"$work/loose.t"
  rm -rf "$work/out"; seconds "$hp" build "$work/bench.toml" -o "$work/out" --jobs 1 >>"$work/j1.t"
  rm -rf "$work/out"; seconds "$hp" build "$work/bench.toml" -o "$work/out" --jobs 2 >>"$work/j2.t"
  seconds "$hp" build "$work/bench.toml" -o "$work/out" >>"$work/noop.t"
  touch "$work"/map*.png
  seconds "$hp" build "$work/bench.toml" -o "$work/out" >>"$work/touch.t"
done
loose=$(median <"$work/loose.t")
for case in j1 j2 noop touch; do
  t=$(median <"$work/$case.t")
  case $case in
    j1) what="build --jobs 1" ;;
    j2) what="build --jobs 2" ;;
    noop) what="build, nothing changed" ;;
    touch) what="build, every map touched" ;;
  esac
  printf '%-28s %7.2f s   ratio to check+pack per map (%.2f s): %.2f\n' "$what" "$t" "$loose" "$(awk -v a="$t" -v b="$loose" 'BEGIN {print a / b}')"
done
