#!/usr/bin/env bash
# Proof that a change altered no output: builds heightpack and heightpack-view at REV (default: the
# first parent of HEAD) in a temporary worktree, runs the demo's outputs (scripts/demo_outputs.sh) with
# that build and with this tree's build/, and compares every file byte for byte.
#   scripts/same_outputs.sh [REV]      exit 0: every file identical; 1: a file differs or is missing
# Needs what the demo needs (scripts/install-deps.sh) and Xvfb for the viewer's screenshots.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-HEAD~1}
work=$(mktemp -d /tmp/heightpack-same.XXXXXX)
trap 'git worktree remove --force "$work/tree" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT

build_viewer() {  # SOURCE BUILD
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEIGHTPACK_BUILD_TESTS=OFF \
    -DHEIGHTPACK_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$2" --target heightpack heightpack-view >/dev/null
}
# HEIGHTPACK_SAME_BUILD: a build folder of REV made earlier, to skip building it again.
before_build=${HEIGHTPACK_SAME_BUILD:-}
if [ -z "$before_build" ]; then
  echo "same_outputs: building $rev"
  git worktree add --detach "$work/tree" "$rev" >/dev/null
  before_build=$work/tree/build
  build_viewer "$work/tree" "$before_build"
fi
echo "same_outputs: building this tree"
build_viewer . build

# Both runs write to the same folder (files record their inputs' paths), moved aside after each.
bash scripts/demo_outputs.sh "$before_build" "$work/out" >"$work/before.log" 2>&1
mv "$work/out" "$work/before"
bash scripts/demo_outputs.sh build "$work/out" >"$work/after.log" 2>&1
mv "$work/out" "$work/after"

(cd "$work/before" && find . -type f | sort) >"$work/before.list"
(cd "$work/after" && find . -type f | sort) >"$work/after.list"
status=0
if ! diff -u "$work/before.list" "$work/after.list"; then
  echo "same_outputs: the two runs wrote different files" >&2
  status=1
fi
# A build's state file records each output's cache key, which changes when the key's text does (a new
# option, a new spelling): that costs one rebuild, not a different output. Such files are compared with
# the keys left out, and counted apart.
without_keys() { sed -E 's/"(key|checked)": *"[0-9a-f]*"/"\1": ""/g' "$1"; }
same=0
keys_only=0
while read -r f; do
  if cmp -s "$work/before/$f" "$work/after/$f"; then
    same=$((same + 1))
  elif [ "$(basename "$f")" = .heightpack-build.json ] &&
    cmp -s <(without_keys "$work/before/$f") <(without_keys "$work/after/$f"); then
    echo "same_outputs: cache keys changed (the next build rebuilds once), all else identical: $f"
    keys_only=$((keys_only + 1))
  else
    echo "same_outputs: differs: $f" >&2
    status=1
  fi
done <"$work/before.list"
echo "same_outputs: $same of $(wc -l <"$work/before.list") files byte-identical between $rev and this tree" \
  "($keys_only build state files differ in their cache keys alone)"
exit $status
