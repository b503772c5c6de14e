#!/usr/bin/env bash
# `heightpack check` against reading the same map (issue 24: within 1.5x of one decode): a SIZExSIZE
# 16-bit periodic PNG (the map bench_pack.sh uses), checked and read by `heightpack info` (start-up, read,
# decode and the level's statistics), runs alternating (check, info, check, ...). Prints median wall and
# CPU (user + system) seconds, peak memory and the ratios.
#   tests/bench/bench_check.sh [BUILD_DIR] [RUNS] [SIZE]
set -euo pipefail
. "$(dirname "$0")/measure.sh"
bench_map bench_check "$@"

: >"$work/check"
: >"$work/read"
for ((i = 0; i < runs; i++)); do
  measure "$work/check" "$hp" check "$work/in.png"
  measure "$work/read" "$hp" info "$work/in.png"
done
# The verdict is not what is timed: check exits 1 on a seam, and that is still a finished run.
if awk '$4 > 1 { bad = 1 } END { exit !bad }' "$work/check"; then
  echo "bench_check: heightpack check failed (exit codes: $(cut -d' ' -f4 "$work/check" | tr '\n' ' '))" >&2
  exit 1
fi
read -r cw cc cm < <(medians "$work/check")
read -r rw rc rm < <(medians "$work/read")
printf 'check %6.2f s wall %6.2f s CPU %5d MiB | read (info) %6.2f s wall %6.2f s CPU %5d MiB\n' \
  "$cw" "$cc" "$cm" "$rw" "$rc" "$rm"
echo "check / read: wall $(ratio "$cw" "$rw"), CPU $(ratio "$cc" "$rc") (issue 24: at most 1.5)"
