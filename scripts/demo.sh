#!/usr/bin/env bash
# The main job on the bundled examples: installs what is missing, builds, builds the example water
# materials (examples/*.toml) into out/ocean and out/lagoon, renders the ocean with the viewer, and
# runs every command on examples/maps into out/. Open out/view.png and out/*_preview.png to look.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target heightpack heightpack-view
bash scripts/demo_outputs.sh build out

