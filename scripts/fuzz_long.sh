#!/usr/bin/env bash
# Runs every fuzzer (tests/fuzz) for MINUTES each (default 5), by hand: CI runs them for seconds only.
# Fails on any finding, leaving its input in build-fuzz/findings/; new coverage stays in build-fuzz/corpus/.
#   scripts/fuzz_long.sh [MINUTES]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-5}
bash scripts/fuzz.sh $((minutes * 60))
