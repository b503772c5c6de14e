#!/usr/bin/env bash
# The README as a newcomer types it (issue 35): every heightpack, heightpack-view and ninja command in the
# README's and docs/'s command blocks (and the oiiotool lines that make their inputs) runs, in the order
# the pages give them, in one empty folder that holds only a copy of examples/, with a home of its own.
# Each must exit as its comment says ("exit N"; 0 where it says none). The viewer's commands draw at
# 320x180 (Mesa's software renderer takes seconds a frame at 1280x720), its windows under the caller's
# X server (xvfb-run) for a few frames (--frames), as a person would close them.
# Prints each command and its exit code, then "N passed, M failed"; exits 1 when any fails.
#   tests/readme/readme_walk.sh BUILD_DIR [SOURCE_DIR]
set -u
BUILD=$(realpath "$1")
SRC=$(realpath "${2:-$(dirname "$0")/../..}")
HP="$BUILD/heightpack"
VIEW="$BUILD/viewer/heightpack-view"
[ -x "$HP" ] || { echo "no heightpack in $BUILD" >&2; exit 2; }
ROOT=$(mktemp -d "${TMPDIR:-/tmp}/heightpack-readme.XXXXXX")
trap 'rm -rf "$ROOT"' EXIT
cp -r "$SRC/examples" "$ROOT/examples"
mkdir -p "$ROOT/bin"
ln -s "$HP" "$ROOT/bin/heightpack"
[ -x "$VIEW" ] && ln -s "$VIEW" "$ROOT/bin/heightpack-view"
export PATH="$ROOT/bin:$PATH"
# ~/.cache/heightpack in the README is this folder's; Mesa's compiled shaders stay where they were.
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/mesa_shader_cache}"
# As the viewer tests run llvmpipe (tests/viewer/viewer_support.cpp): the cache's keys include this, so the
# walk finds the shaders the test loop compiled.
export GALLIVM_PERF="${GALLIVM_PERF:-nopt}"
export HOME="$ROOT/home"
unset XDG_CACHE_HOME HEIGHTPACK_CACHE HEIGHTPACK_CACHE_MODE HEIGHTPACK_CACHE_TOKEN
mkdir -p "$HOME"

# The command lines of the plain (unlabelled) fenced blocks, continuation lines joined, in page order.
commands() {
    awk '
        /^```/ { if (fenced) { fenced = 0; plain = 0 } else { fenced = 1; plain = ($0 == "```") } next }
        !plain { next }
        { line = (pending != "") ? pending " " $0 : $0; pending = "" }
        line ~ /\\$/ { sub(/\\$/, "", line); pending = line; next }
        line ~ /^(HEIGHTPACK_[A-Z_]+=[^ ]+ )?(heightpack|heightpack-view|ninja|oiiotool) / { print line }
    ' "$@"
}

cd "$ROOT" || exit 2
passed=0
failed=0
n=0
while IFS= read -r line; do
    n=$((n + 1))
    comment=""
    command=$line
    if [[ $line == *" # "* ]]; then
        command=${line%% # *}
        comment=${line#* # }
    fi
    expected=0
    [[ $comment =~ exit\ ([0-9]+) ]] && expected=${BASH_REMATCH[1]}
    if [[ $command == heightpack-view* ]]; then
        command=$(sed -E 's/ --size [0-9]+x[0-9]+//' <<<"$command")" --size 320x180"
        # A window: a few frames, then it closes.
        if [[ $command != *--screenshot* && $command != *--bench* && $command != *--grid-heights* ]]; then
            command="$command --frames 3"
        fi
    fi
    start=$EPOCHREALTIME
    eval "$command" > "$ROOT/last.out" 2> "$ROOT/last.err" < /dev/null
    code=$?
    seconds=$(awk "BEGIN { print $EPOCHREALTIME - $start }")
    if [ "$code" -eq "$expected" ]; then
        passed=$((passed + 1))
        printf 'ok   %3d  %5.1fs  %s\n' "$n" "$seconds" "$command"
    else
        failed=$((failed + 1))
        printf 'FAIL %3d  %5.1fs  %s\n      exit %d, expected %d: %s\n' "$n" "$seconds" "$command" "$code" "$expected" \
            "$(head -c 400 "$ROOT/last.err" | tr '\n' ' ')"
    fi
done < <(commands "$SRC/README.md" "$SRC"/docs/*.md)
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
