#!/usr/bin/env bash
# The main job on the bundled examples: installs what is missing, builds, packs every map in
# examples/maps into out/, and prints what it wrote. Open out/*_preview.png to look at the results.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEIGHTPACK_BUILD_TESTS=OFF -DHEIGHTPACK_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build --target heightpack

mkdir -p out
for map in examples/maps/*.png; do
  name=$(basename "$map" .png)
  ./build/heightpack pack "$map" -o "out/$name.exr" --emit-plain "out/${name}_plain.exr"
  # A picture of level 0 (R = the height) for people without an EXR viewer.
  oiiotool "out/$name.exr" --ch R --ch R,R,R -d uint8 -o "out/${name}_preview.png"
done
echo
./build/heightpack info out/swell.exr
echo
echo "demo: packed textures and previews are in out/:"
ls -1 out
