#!/usr/bin/env bash
# Issue 26's and 37's figures: a synthesised sea of FRAMES frames x 3 cascades (SIZE^2 each) built into
# fresh folders: `heightpack build --jobs N`, `ninja -f PLAN -j N` on the plan of `build --plan ninja`,
# `heightpack build` of a second folder from a shared cache the first filled, and, with bazel and nginx
# installed, `bazel build --jobs N` of the `--plan bazel` workspace (sandboxed, filling an HTTP cache that
# nginx serves) and of a second workspace with another output base from that cache. Bazel's times are
# the whole command in --batch mode (its JVM's start included; Bazel's own "Elapsed time" in brackets).
# Prints seconds and whether every output is byte-identical to the plain build's.
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
trap 'if [ -s "$work/nginx/nginx.pid" ]; then kill "$(cat "$work/nginx/nginx.pid")"; fi; chmod -R u+w "$work"; rm -rf "$work"' EXIT
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

if ! command -v bazel >/dev/null || ! command -v nginx >/dev/null; then
  echo "bazel: not measured (apt-get install bazel-bootstrap nginx)"
  exit 0
fi
# nginx's WebDAV module on a free port as Bazel's HTTP cache (as tests/cli/bazel_plan_test.cpp starts it).
# Under root, nginx's workers run as nobody: they must reach and write the store.
chmod go+x "$work" && mkdir -p nginx/store nginx/tmp && chmod 777 nginx/store nginx/tmp
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])' 2>/dev/null ||
  echo $((20000 + RANDOM % 20000)))
cat >nginx/nginx.conf <<CONF
daemon on; worker_processes 1; pid $work/nginx/nginx.pid; error_log $work/nginx/error.log;
events { worker_connections 64; }
http {
  access_log off; client_max_body_size 0; client_body_temp_path $work/nginx/tmp;
  server { listen 127.0.0.1:$port; root $work/nginx/store;
           location / { dav_methods PUT DELETE MKCOL; create_full_put_path on; } }
}
CONF
nginx -p "$work/nginx" -e "$work/nginx/error.log" -c "$work/nginx/nginx.conf"
mkdir ws other
cp sea.toml ws/
(cd ws && "$hp" build --plan bazel-workspace >WORKSPACE && "$hp" build sea.toml -o out/sea --plan bazel >BUILD.bazel)
cp ws/WORKSPACE ws/BUILD.bazel ws/sea.toml other/
# bazelrun FOLDER OUTPUT_BASE: prints the whole command's seconds and Bazel's own elapsed time and processes.
bazelrun() {
  local start end
  start=$(date +%s.%N)
  (cd "$1" && bazel --nohome_rc --noworkspace_rc --batch --output_user_root="$work/bazel-root" \
    --output_base="$work/$2" --host_jvm_args=-Xmx1g build //... --jobs "$jobs" \
    --remote_cache="http://127.0.0.1:$port/hp" --repository_cache="$work/bazel-repositories" >"$work/$2.log" 2>&1)
  end=$(date +%s.%N)
  echo "$(echo "$end - $start" | bc -l) $(grep -o 'Elapsed time: [0-9.]*s' "$work/$2.log" | tail -1 | cut -d' ' -f3)" \
    "$(grep -o '[0-9]* processes: .*' "$work/$2.log" | tail -1)"
}
sameBazel() { diff -rq --exclude=.heightpack-synth plain "$1/bazel-bin/out/sea" >/dev/null && echo "identical" || echo "DIFFERENT"; }
read -r sandboxed sandboxedOwn sandboxedWhat <<<"$(bazelrun ws base1)"
read -r fromCache fromCacheOwn fromCacheWhat <<<"$(bazelrun other base2)"
printf "bazel build --jobs %s         %7.2f s  [%s]  (%s; %s)\n" "$jobs" "$sandboxed" "$sandboxedOwn" "$(sameBazel ws)" "$sandboxedWhat"
printf "bazel, a second workspace     %7.2f s  [%s]  (%s; %s)\n" "$fromCache" "$fromCacheOwn" "$(sameBazel other)" "$fromCacheWhat"
