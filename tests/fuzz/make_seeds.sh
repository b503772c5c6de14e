#!/usr/bin/env bash
# Remakes the seed corpora under tests/fuzz/corpus (committed; run this only to change them). Small real
# files: images written by oiiotool in every format heightpack reads, PNGs with every row filter, the
# example manifests pointed at the harness's maps, and a material.json as heightpack build writes it.
set -euo pipefail
cd "$(dirname "$0")"
out=corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# fuzz_png_fast: grey and grey + alpha, 8 and 16 bits, each row filter (0-4), written by hand so every
# filter appears; and two PNGs written by libpng (oiiotool).
python3 - "$out/fuzz_png_fast" <<'PY'
import struct, sys, zlib
def chunk(t, b): return struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b) & 0xffffffff)
def paeth(a, b, c):
    p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)
def png(w, h, colour, depth, name):
    samples = 1 if colour == 0 else 2
    bpp = samples * depth // 8
    raw = [bytes((x * 37 + y * 11 + k * 5) & 0xff for x in range(w * bpp) for k in [0]) for y in range(h)]
    out, prev = b'', bytes(w * bpp)
    for y, row in enumerate(raw):
        f = y % 5
        enc = bytearray()
        for i, v in enumerate(row):
            a = row[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
            pred = [0, a, b, (a + b) // 2, paeth(a, b, c)][f]
            enc.append((v - pred) & 0xff)
        out += bytes([f]) + enc; prev = row
    data = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, depth, colour, 0, 0, 0))
    z = zlib.compress(out, 9)
    data += chunk(b'IDAT', z[:len(z) // 2]) + chunk(b'IDAT', z[len(z) // 2:]) + chunk(b'IEND', b'')
    open(f'{sys.argv[1]}/{name}', 'wb').write(data)
png(7, 5, 0, 8, 'grey8.png'); png(6, 5, 0, 16, 'grey16.png'); png(5, 5, 4, 8, 'greyalpha8.png')
png(4, 5, 4, 16, 'greyalpha16.png')
PY
oiiotool --pattern noise:type=uniform 16x16 1 -d uint8 -o "$out/fuzz_png_fast/libpng8.png"
oiiotool --pattern fill:top=0:bottom=1 8x8 2 -d uint16 -o "$out/fuzz_png_fast/libpng16.png"

# fuzz_load_image: byte 0 picks the extension (index into the harness's list), byte 1 the channel
# (0 auto, 1 r); the file follows.
exts=(png tif exr jpg bmp tga hdr pgm psd gif dds ico sgi dpx webp pfm)
seed() {  # seed NAME EXT-INDEX CHANNEL FILE
  { printf "\\x$(printf %02x "$2")\\x$(printf %02x "$3")"; cat "$4"; } >"$out/fuzz_load_image/$1"
}
i=0
for ext in "${exts[@]}"; do
  for spec in "1:uint8" "3:uint16"; do
    ch=${spec%%:*} type=${spec##*:}
    f="$tmp/s$ch.$ext"
    if oiiotool --pattern noise:type=uniform 8x8 "$ch" -d "$type" -o "$f" 2>/dev/null; then
      seed "$ext-$ch" "$i" $((ch == 1 ? 0 : 1)) "$f"
    fi
  done
  i=$((i + 1))
done
oiiotool --pattern fill:top=0:bottom=1 8x8 1 -d half --tile 4 4 --mipmap -o "$tmp/mip.exr" 2>/dev/null &&
  seed exr-tiled-mip 2 0 "$tmp/mip.exr"
oiiotool --pattern fill:top=0:bottom=1 8x8 1 -d uint16 --compression lzw -o "$tmp/lzw.tif" && seed tif-lzw 1 0 "$tmp/lzw.tif"
head -c 200 "$out/fuzz_load_image/tif-3" >"$tmp/trunc.tif" && seed tif-truncated 1 1 "$tmp/trunc.tif"

# fuzz_manifest: the examples, their sources pointed at the harness's map.png and seq.NNNN.png.
for m in ../../examples/*.toml; do
  sed -e 's#"maps/swell.png"#"seq.png"#' -e 's#"maps/[a-z_]*.png"#"map.png"#' "$m" >"$out/fuzz_manifest/$(basename "$m")"
done
cat >"$out/fuzz_manifest/every-key.toml" <<'TOML'
format = 1
name = "every-key"
threshold = 3.5
[defaults]
wrap = "clamp"
filter = "box"
compression = "piz"
resize = true
channel = "luma"
tileable = false
container = "ktx2"
pixel_type = "auto"
tolerance = 0.001
[[displacement]]
name = "a"
source = "map.png"
output = "sub/a.dds"
container = "dds"
tile_size = 10
scroll = [1, -1]
amplitude = 2
height_scale = -1
height_offset = 0.5
filter = "triangle"
layout = "plain"
allow_block_compression = true
[normals]
source = "seq.png"
tile_size = 4
height = 0.1
kernel = "scharr"
convention = "directx"
alpha = "variance"
[fresnel]
output = "f.exr"
pixel_type = "half"
ior = 1.5
index = "2nv"
size = 64
[foam]
source = "map.png"
h0 = 0
hmax = 1
tile_size = 2
TOML

# fuzz_material: material.json as heightpack build writes it (docs/manifest.md's example), and a small one.
cat >"$out/fuzz_material/ocean.json" <<'JSON'
{
  "schema": "heightpack-material",
  "version": 1,
  "name": "ocean",
  "generator": "heightpack 0.1.0",
  "manifest": "ocean.toml",
  "displacement": [
    {
      "name": "swell",
      "texture": {"file": "swell.exr", "width": 512, "height": 512, "levels": 10, "frames": 4},
      "layout": "neighbour4", "wrap": "periodic", "filter": "kaiser", "heightScale": 1.0, "heightOffset": 0.0,
      "tileSize": 64.0, "scroll": [0.01, 0.004], "amplitude": 1.5, "loopPeriod": 8.0
    },
    {
      "name": "choppy",
      "texture": {"file": "choppy.exr", "width": 256, "height": 256, "levels": 9},
      "layout": "neighbour4", "wrap": "clamp", "filter": "box", "heightScale": -2.0, "heightOffset": 0.5,
      "tileSize": 16.0, "scroll": [-0.006, 0.011], "amplitude": 0.4
    }
  ],
  "normals": {
    "name": "ripple_n",
    "texture": {"file": "ripple_n.exr", "width": 256, "height": 256, "levels": 9},
    "convention": "opengl", "alpha": "none", "tileSize": 8.0, "heightRange": 0.05,
    "octaves": [{"tileSize": 8.0, "scroll": [0.02, 0.01], "strength": 1.0},
                {"tileSize": 2.0, "scroll": [0.05, -0.03], "strength": 0.5}]
  },
  "fresnel": {
    "name": "fresnel",
    "texture": {"file": "fresnel.exr", "width": 256, "height": 1, "levels": 1},
    "ior": 1.333, "model": "exact", "index": "nv"
  },
  "foam": {"name": "foam", "texture": {"file": "foam.exr", "width": 64, "height": 64, "levels": 7},
           "h0": 1.2, "hmax": 2.2, "tileSize": 4.0}
}
JSON
cat >"$out/fuzz_material/small.json" <<'JSON'
{"schema":"heightpack-material","version":1,"name":"s","displacement":[{"name":"a","texture":{"file":"a.exr","width":1,"height":1,"levels":1},"wrap":"periodic","filter":"kaiser","heightScale":1,"heightOffset":0,"tileSize":1,"scroll":[0,0],"amplitude":1}]}
JSON
ls -l "$out"/*

# fuzz_gpu_texture: KTX2 (float; uint16 with zstd; BC4, BC5; ASTC heights 6x6 and normals 4x4; ASTC HDR heights
# 4x4) and DDS (half;
# uint16 normals; BC4, BC5) of an 8x8 16-bit map, as
# heightpack writes them (HEIGHTPACK: the binary, ../../build/heightpack by default).
hp=${HEIGHTPACK:-../../build/heightpack}
mkdir -p "$out/fuzz_gpu_texture"
oiiotool --pattern noise:type=uniform 8x8 1 -d uint16 -o "$tmp/m.png"
"$hp" pack "$tmp/m.png" -q -o "$out/fuzz_gpu_texture/packed_float.ktx2"
"$hp" pack "$tmp/m.png" -q --pixel-type uint16 --compression zstd -o "$out/fuzz_gpu_texture/packed_uint16_zstd.ktx2"
"$hp" pack "$tmp/m.png" -q --pixel-type half -o "$out/fuzz_gpu_texture/packed_half.dds"
"$hp" normal "$tmp/m.png" -q --tile-size 8m --height 1m --pixel-type uint16 -o "$out/fuzz_gpu_texture/normal_uint16.dds"
# Block streams: BC4 plain heights and BC5 xy normals, in KTX2 and DDS; ASTC heights and normals in KTX2.
"$hp" pack "$tmp/m.png" -q --layout plain --pixel-type bc4 -o "$out/fuzz_gpu_texture/plain_bc4.ktx2"
"$hp" pack "$tmp/m.png" -q --layout plain --pixel-type bc4 -o "$out/fuzz_gpu_texture/plain_bc4.dds"
"$hp" normal "$tmp/m.png" -q --tile-size 8m --height 1m --layout xy --pixel-type bc5 -o "$out/fuzz_gpu_texture/normal_bc5.ktx2"
"$hp" normal "$tmp/m.png" -q --tile-size 8m --height 1m --layout xy --pixel-type bc5 -o "$out/fuzz_gpu_texture/normal_bc5.dds"
"$hp" pack "$tmp/m.png" -q --layout plain --pixel-type astc-6x6 -o "$out/fuzz_gpu_texture/plain_astc6.ktx2"
"$hp" normal "$tmp/m.png" -q --tile-size 8m --height 1m --layout xy --pixel-type astc-4x4 \
  -o "$out/fuzz_gpu_texture/normal_astc4.ktx2"
"$hp" pack "$tmp/m.png" -q --layout plain --pixel-type astc-hdr-4x4 -o "$out/fuzz_gpu_texture/plain_astc_hdr4.ktx2"
