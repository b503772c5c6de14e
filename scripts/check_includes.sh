#!/usr/bin/env bash
# Every source file of the library, the command line and the viewer compiles on its own, as in a project
# that builds heightpack without HEIGHTPACK_UNITY_BUILD (the test builds are unity builds, where a file
# can lean on the includes of the one before it). Parses each file (no code generation) in build-includes/.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build-includes
cmake -S . -B "$dir" -G Ninja -DHEIGHTPACK_UNITY_BUILD=OFF -DHEIGHTPACK_BUILD_BENCHMARKS=OFF \
  -DCMAKE_BUILD_TYPE=Release -DHEIGHTPACK_WERROR=ON -DCMAKE_CXX_COMPILER_LAUNCHER="$PWD/scripts/syntax_only.sh" >/dev/null
mapfile -t objects < <(ninja -C "$dir" -t targets all | grep -E '\.cpp\.o:' | grep -v '^tests/' | cut -d: -f1)
ninja -C "$dir" "${objects[@]}"
echo "check_includes: ${#objects[@]} files compile on their own"
