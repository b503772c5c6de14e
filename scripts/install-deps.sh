#!/usr/bin/env bash
# Installs heightpack's build, test and demo dependencies from Debian 12's packages (apt-get, as root or
# through sudo). Installs only what is missing, so a second run is quick.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config              # build
  libopenimageio-dev openimageio-tools          # reading images; oiiotool for previews and the benchmark
  libopenexr-dev libdeflate-dev                 # writing tiled, mip-mapped EXRs; fast deflate for zip tiles
  libcli11-dev nlohmann-json3-dev               # command line, --json
  libtomlplusplus-dev                           # material manifests (heightpack build)
  libcurl4-openssl-dev                          # heightpack build's shared cache on an HTTP server
  libxxhash-dev zlib1g-dev                      # pixel hashes; CRCs in tests
  libzstd-dev                                   # Zstandard supercompression of KTX2 levels
  strace                                        # tests: which files a command opens (io_safety_test)
  zstd libnvtt-bin                              # tests' independent readers: the zstd tool for supercompressed
                                                # KTX2 levels, nvddsinfo for DDS (ktx-parse under Node: below)
  libopencv-core-dev                            # the DFT behind `tile` (periodic + smooth)
  libastcenc-dev astcenc                        # ASTC output (ARM's encoder, Apache-2.0); tests: astcenc -dl decodes
  libglfw3-dev libglm-dev libepoxy-dev          # heightpack-view: window and GL context, maths, GL loader
  libimgui-dev libstb-dev                       # heightpack-view: the panel (imgui.pc requires stb)
  xvfb xauth libgl1-mesa-dri                    # headless screenshots and viewer tests (Mesa llvmpipe)
  libegl-dev libegl-mesa0                       # heightpack-view --headless: EGL headers for libepoxy, Mesa's
                                                # EGL (surfaceless platform) loaded at run time
  libgtest-dev libgmock-dev libbenchmark-dev    # tests and benchmarks
  libsquish-dev                                 # tests and tests/bench only: a second BC4/BC5 encoder to
                                                # judge heightpack's against (MIT; never linked into libpack)
  time                                          # peak memory in tests/bench/bench_pack.sh
  bazel-bootstrap nginx                         # the Bazel plan's test (label bazel): Bazel 4.2.3, and nginx's
                                                # WebDAV module as its HTTP cache
  groff-base                                    # tests: rendering the man pages (tests/manual)
  chromium                                      # the browser test (label browser): three.js's KTX2Loader in
                                                # headless Chromium, WebGL 2 on its SwiftShader
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node and npm run the tests' KTX2 reader (ktx-parse). Debian's nodejs and npm, unless a Node with its own
# npm is there already (NodeSource's nodejs package bundles npm and conflicts with Debian's).
if ! command -v node >/dev/null 2>&1; then missing+=(nodejs); fi
if ! command -v npm >/dev/null 2>&1; then missing+=(npm); fi
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present, and Node with npm"
  exit 0
fi
as_root=()
if [ "$(id -u)" -ne 0 ]; then as_root=(sudo); fi
echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
