#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz) with clang, ASan and UBSan into build-fuzz/ and runs each
# for SECONDS (default 30) from its seed corpus and dictionary. Fails on any finding: the input that
# found it is left in build-fuzz/findings/, and becomes a regression test in tests/.
#   scripts/fuzz.sh [SECONDS] [FUZZER...]     e.g. scripts/fuzz.sh 600 fuzz_manifest
# The fuzzers run side by side, one per core. scripts/fuzz_long.sh runs them all for minutes, by hand.
# New inputs that reach new code stay in build-fuzz/corpus/NAME, so a later run starts from there.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-30}
shift || true
fuzzers=("$@")
if ((${#fuzzers[@]} == 0)); then fuzzers=(fuzz_png_fast fuzz_load_image fuzz_manifest fuzz_material fuzz_gpu_texture); fi

# clang and libFuzzer's runtime are Debian packages; the rest comes with the main build's dependencies.
bash scripts/install-deps.sh
fuzz_packages=(clang libclang-rt-14-dev)
missing=()
for p in "${fuzz_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  as_root=()
  if [ "$(id -u)" -ne 0 ]; then as_root=(sudo); fi
  echo "fuzz: installing ${missing[*]}"
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# -O1 and line tables only: quick to build, and asserts stay on (no NDEBUG) so toml++'s fire too.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DHEIGHTPACK_WERROR=ON -DHEIGHTPACK_BUILD_FUZZERS=ON \
  -DHEIGHTPACK_BUILD_TESTS=OFF -DHEIGHTPACK_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz --target "${fuzzers[@]}"

export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp:print_suppressions=0"
mkdir -p build-fuzz/findings build-fuzz/logs
# One fuzzer: runs it, then prints its summary line, or FINDING and the report. Exits 1 on a finding.
# Every fuzzer fails on out-of-memory too (-rss_limit_mb): since issue 21 heightpack judges every header
# before a reader underneath allocates for it, so a reader that runs out of memory is a finding.
run_one() {
  local f=$1 log="build-fuzz/logs/$1.log" rc=0
  mkdir -p "build-fuzz/corpus/$f"
  # The first corpus folder receives what the run finds; the seeds in the repo are only read.
  build-fuzz/tests/fuzz/"$f" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict="tests/fuzz/$f.dict" -artifact_prefix="build-fuzz/findings/$f-" \
    "build-fuzz/corpus/$f" "tests/fuzz/corpus/$f" >"$log" 2>&1 || rc=$?
  if ((rc == 0)); then
    # "#N DONE cov: C ft: F corp: K/SIZE ..."
    local summary
    summary=$(grep -E '^#[0-9]+' "$log" | tail -1)
    field() { sed -nE "s/.*$1:? ([0-9]+).*/\1/p" <<<"$summary"; }
    echo "fuzz: $f: ok in ${seconds}s: $(sed -nE 's/^#([0-9]+).*/\1/p' <<<"$summary") executions," \
      "$(field cov) edges covered, $(field ft) features, corpus $(field corp)"
  else
    echo "fuzz: $f: FINDING (log: $log)"
    grep -E 'ERROR|SUMMARY|runtime error|Assertion|Test unit written|^    #[0-9]' "$log" | head -30 || true
    return 1
  fi
}

# As many fuzzers at once as there are cores; each is one process on one core.
jobs=$(nproc)
for f in "${fuzzers[@]}"; do
  while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
  run_one "$f" > "build-fuzz/logs/$f.summary" 2>&1 &
done
wait
failed=()
for f in "${fuzzers[@]}"; do
  cat "build-fuzz/logs/$f.summary"
  if ! grep -q "^fuzz: $f: ok" "build-fuzz/logs/$f.summary"; then failed+=("$f"); fi
done
if ((${#failed[@]} > 0)); then
  echo "fuzz: findings in ${failed[*]}; reproduce with build-fuzz/tests/fuzz/NAME build-fuzz/findings/NAME-*"
  exit 1
fi
