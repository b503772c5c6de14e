#!/usr/bin/env bash
# The rules of the three floors (issue 13), checked on the source tree:
#   1. each floor only looks down: core includes no io or bake header and no image, EXR, TOML or JSON
#      library; io includes no bake header and no TOML or JSON library;
#   2. the library never names a command-line flag in what it says (its errors carry a reason that each
#      shell words in its own flags or manifest keys);
#   3. a source file outside tests/ over 400 lines is named as a warning: split it by concept (a folder
#      per subject, core/tile, core/sea, bake/build), not to meet a count.
# Prints every breach and exits 1 if there is any; warnings do not fail.
#   tests/layout/floor_rules.sh [SOURCE_DIR]
set -uo pipefail
cd "${1:-$(dirname "$0")/../..}"
breaches=0
breach() { echo "floor_rules: $*"; breaches=$((breaches + 1)); }

# files_of FLOOR: the sources and public headers of one floor.
files_of() { find "libpack/$1" "libpack/include/heightpack/$1" -name '*.cpp' -o -name '*.hpp' | sort; }

forbidden_core='#include *[<"](heightpack/(io|bake)/|OpenImageIO/|OpenEXR/|Imath/|toml\+\+/|nlohmann/|libdeflate|xxhash)'
forbidden_io='#include *[<"](heightpack/bake/|toml\+\+/|nlohmann/)'
for f in $(files_of core); do
  grep -nE "$forbidden_core" "$f" | while IFS= read -r line; do echo "floor_rules: $f:$line: core includes a floor above or a file library"; done
  grep -qE "$forbidden_core" "$f" && breaches=$((breaches + 1))
done
for f in $(files_of io); do
  grep -nE "$forbidden_io" "$f" | while IFS= read -r line; do echo "floor_rules: $f:$line: io includes the bake floor or a manifest library"; done
  grep -qE "$forbidden_io" "$f" && breaches=$((breaches + 1))
done

# A flag inside a string literal: "... --word" (comments are not what the library says). A line marked
# "// floor_rules: data" writes such text into a file as data (KTX2's KTXwriterScParams), not as a hint.
for f in $(find libpack -name '*.cpp' -o -name '*.hpp' | sort); do
  said=$(sed -e 's|.*// floor_rules: data$||' -e 's|//.*$||' "$f") || { breach "cannot read $f"; continue; }
  hits=$(grep -nE '"([^"]*[ (])?--[a-z][a-z-]*' <<<"$said" || true)
  if [ -n "$hits" ]; then
    while IFS= read -r line; do echo "floor_rules: $f:$line: the library names a command-line flag"; done <<<"$hits"
    breaches=$((breaches + 1))
  fi
done

for f in $(find libpack tools viewer -name '*.cpp' -o -name '*.hpp' | sort); do
  n=$(wc -l <"$f")
  [ "$n" -gt 400 ] && echo "floor_rules: warning: $f has $n lines (over 400: is it one concern?)"
done

if [ "$breaches" -gt 0 ]; then
  echo "floor_rules: $breaches breach(es)"
  exit 1
fi
echo "floor_rules: every floor looks only down and the library names no flag"
