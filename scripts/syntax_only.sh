#!/usr/bin/env bash
# A compiler launcher for scripts/check_includes.sh: parses the file (-fsyntax-only) and leaves an empty
# object where the build expects one.
set -euo pipefail
out=""
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [ "${args[i]}" = "-o" ]; then out="${args[i + 1]}"; fi
done
"$@" -fsyntax-only
if [ -n "$out" ]; then : >"$out"; fi
