#!/usr/bin/env bash
# Installs what is missing, builds heightpack with warnings as errors, and runs every test.
#   scripts/test.sh             release build in build-test/
#   scripts/test.sh --sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
if [ "${1:-}" = "--sanitize" ]; then
  dir=build-asan
  # -O1 with line tables only: half the compile time of -O2 -g under ASan (CI builds everything twice on
  # two cores), and reports still name file and line. A unity build, as the release one: that each file
  # compiles on its own is scripts/check_includes.sh's to say, which .ci/run runs.
  flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
    -DHEIGHTPACK_SANITIZE=address,undefined -DHEIGHTPACK_BUILD_BENCHMARKS=OFF)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # use_tls=0: LeakSanitizer does not scan thread-local storage, where GCC 12's crashes at exit on that of a
  # library loaded after start-up (OpenImageIO, loaded when a file needs it). It can only report more that
  # way, never less: what third-party libraries keep in theirs is suppressed in lsan.supp.
  export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0:use_tls=0"
  jobs=2
  # The README walk, Bazel's, the HTTP cache server tests and three.js in Chromium (labels walk, bazel,
  # server and browser) are left out here: what they add is other programs (Bazel, nginx, Chromium, Mesa's
  # shader compiler) driving the same commands, and this build does not build their programs.
  labels=(-LE 'walk|bazel|server|browser')
else
  dir=build-test
  # The benchmark programs are not tests: .ci/run builds them after this, outside the loop's four minutes.
  flags=(-DCMAKE_BUILD_TYPE=Release -DHEIGHTPACK_BUILD_BENCHMARKS=OFF)
  # One test more than the two cores: the viewer, kill and signal tests wait on Xvfb, timers and other
  # processes for part of their time (170 s against 180 s at -j 2 on two cores).
  jobs=3
  labels=()
fi
cmake -S . -B "$dir" -G Ninja -DHEIGHTPACK_WERROR=ON "${flags[@]}"
cmake --build "$dir"
# The tests' independent KTX2 reader and three.js (whose KTX2Loader the browser test runs), pinned, into the
# build folder (never needed to build or run).
npm install --prefix "$dir/npm" --no-save --no-audit --no-fund ktx-parse@2.0.0 three@0.180.0 >/dev/null
# Every test (under the sanitizers, all but the labels above).
ctest --test-dir "$dir" --output-on-failure -j "$jobs" "${labels[@]}"
