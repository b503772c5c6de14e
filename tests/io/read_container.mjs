// The tests' independent reader of the KTX2 and DDS files heightpack writes. Prints one JSON document:
// the format, level 0's size, the layer count (1 unless an array texture), the key/values, and per level
// its size, the SHA-256 of its bytes (as stored, after inflating) and its values decoded to numbers. An
// array's level holds every layer's image in turn, layer 0 first (as a KTX2 level stores them; a DDS
// stores each layer's whole chain in turn, gathered here level by level).
//   node read_container.mjs FILE.ktx2 NPM_DIR   KTX2 through ktx-parse (npm); zstd levels through the
//                                               zstd command-line tool (Debian's zstd package)
//   node read_container.mjs FILE.dds NPM_DIR    DDS: the header through nvddsinfo (NVIDIA Texture Tools,
//                                               Debian's libnvtt-bin), the levels by Microsoft's DX10
//                                               layout, decoded here
// Decoding here is written from the formats' definitions, not from heightpack's code.
import { readFileSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { execFileSync } from 'node:child_process';
import { pathToFileURL } from 'node:url';
import { join } from 'node:path';

const [file, npmDir] = process.argv.slice(2);
const bytes = readFileSync(file);

// binary16 to number, from IEEE 754's definition.
function half(h) {
  const sign = h & 0x8000 ? -1 : 1;
  const exponent = (h >> 10) & 0x1f;
  const fraction = h & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

// kind: f32, f16, unorm16, snorm16. unorm16 values are the raw integers u; the test maps them.
function decode(data, kind) {
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  const out = [];
  const step = kind === 'f32' ? 4 : 2;
  for (let at = 0; at + step <= data.byteLength; at += step) {
    if (kind === 'f32') out.push(view.getFloat32(at, true));
    else if (kind === 'f16') out.push(half(view.getUint16(at, true)));
    else if (kind === 'unorm16') out.push(view.getUint16(at, true));
    else out.push(Math.max(view.getInt16(at, true) / 32767, -1));
  }
  return out;
}

const sha256 = (data) => createHash('sha256').update(data).digest('hex');

// Vulkan and DXGI codes of the formats, from the Vulkan registry and Microsoft's DXGI_FORMAT list.
const vk = {
  109: ['VK_FORMAT_R32G32B32A32_SFLOAT', 'f32', 4], 97: ['VK_FORMAT_R16G16B16A16_SFLOAT', 'f16', 4],
  91: ['VK_FORMAT_R16G16B16A16_UNORM', 'unorm16', 4], 103: ['VK_FORMAT_R32G32_SFLOAT', 'f32', 2],
  83: ['VK_FORMAT_R16G16_SFLOAT', 'f16', 2], 77: ['VK_FORMAT_R16G16_UNORM', 'unorm16', 2],
  78: ['VK_FORMAT_R16G16_SNORM', 'snorm16', 2],
  100: ['VK_FORMAT_R32_SFLOAT', 'f32', 1], 76: ['VK_FORMAT_R16_SFLOAT', 'f16', 1], 70: ['VK_FORMAT_R16_UNORM', 'unorm16', 1],
  139: ['VK_FORMAT_BC4_UNORM_BLOCK', 'bc4', 1], 141: ['VK_FORMAT_BC5_UNORM_BLOCK', 'bc5', 2],
  // ASTC: RGBA in every block; which channels hold values the file's KTXswizzle says.
  157: ['VK_FORMAT_ASTC_4x4_UNORM_BLOCK', 'astc4', 4], 165: ['VK_FORMAT_ASTC_6x6_UNORM_BLOCK', 'astc6', 4],
  171: ['VK_FORMAT_ASTC_8x8_UNORM_BLOCK', 'astc8', 4],
  // ASTC HDR (VK_EXT_texture_compression_astc_hdr): the same blocks, decoded as half floats.
  1000066000: ['VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT', 'astc4', 4], 1000066004: ['VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT', 'astc6', 4],
  1000066007: ['VK_FORMAT_ASTC_8x8_SFLOAT_BLOCK_EXT', 'astc8', 4],
};
const dxgi = {
  R32G32B32A32_FLOAT: ['f32', 4], R16G16B16A16_FLOAT: ['f16', 4], R16G16B16A16_UNORM: ['unorm16', 4],
  R32G32_FLOAT: ['f32', 2], R16G16_FLOAT: ['f16', 2], R16G16_UNORM: ['unorm16', 2], R16G16_SNORM: ['snorm16', 2],
  R32_FLOAT: ['f32', 1], R16_FLOAT: ['f16', 1], R16_UNORM: ['unorm16', 1],
  BC4_UNORM: ['bc4', 1], BC5_UNORM: ['bc5', 2],
};

// Block formats (BC4: 8 bytes, BC5: 16 bytes a 4x4 block; ASTC 16 bytes a 4x4, 6x6 or 8x8 block) are not
// decoded here: their bytes go out as hex for a decoder of their own (the tests use nvdecompress, astcenc).
const isBlock = (kind) => kind === 'bc4' || kind === 'bc5' || kind.startsWith('astc');
const blockBytes = (kind) => (kind === 'bc4' ? 8 : 16);
const blockSide = (kind) => (kind.startsWith('astc') ? Number(kind.slice(4)) : 4);
const imageBytes = (w, h, kind, texelBytes) =>
  isBlock(kind) ? Math.ceil(w / blockSide(kind)) * Math.ceil(h / blockSide(kind)) * blockBytes(kind) : w * h * texelBytes;
const valuesOf = (data, kind) => (isBlock(kind) ? [] : decode(data, kind));
const blocksOf = (data, kind) => (isBlock(kind) ? Buffer.from(data).toString('hex') : undefined);

if (file.toLowerCase().endsWith('.ktx2')) {
  const { read } = await import(pathToFileURL(join(npmDir, 'node_modules', 'ktx-parse', 'dist', 'index.mjs')).href);
  const ktx = read(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
  const [name, kind, channels] = vk[ktx.vkFormat] ?? [`vkFormat ${ktx.vkFormat}`, 'f32', 1];
  const keyValues = {};
  for (const [key, value] of Object.entries(ktx.keyValue)) {
    const text = typeof value === 'string' ? value : new TextDecoder().decode(value);
    keyValues[key] = text.replace(/\0$/, '');
  }
  const dfd = ktx.dataFormatDescriptor[0];
  const levels = ktx.levels.map((level, i) => {
    let data = level.levelData;
    if (ktx.supercompressionScheme === 2) data = execFileSync('zstd', ['-d', '-c', '-q'], { input: data });
    return {
      width: Math.max(1, ktx.pixelWidth >> i), height: Math.max(1, ktx.pixelHeight >> i),
      byteLength: data.byteLength, uncompressedByteLength: level.uncompressedByteLength,
      sha256: sha256(data), values: valuesOf(new Uint8Array(data), kind), blocks: blocksOf(data, kind),
    };
  });
  console.log(JSON.stringify({
    reader: 'ktx-parse', format: name, channels, typeSize: ktx.typeSize, width: ktx.pixelWidth,
    height: ktx.pixelHeight, layerCount: Math.max(1, ktx.layerCount), levelCount: ktx.levelCount,
    supercompressionScheme: ktx.supercompressionScheme,
    dfd: {
      colorModel: dfd.colorModel, colorPrimaries: dfd.colorPrimaries, transferFunction: dfd.transferFunction,
      bytesPlane0: dfd.bytesPlane[0], texelBlockDimension: Array.from(dfd.texelBlockDimension),
      samples: dfd.samples.map((s) => ({ bitOffset: s.bitOffset, bitLength: s.bitLength, channelType: s.channelType,
                                          lower: s.sampleLower, upper: s.sampleUpper })),
    },
    keyValues, levels,
  }));
} else {
  const info = execFileSync('nvddsinfo', [file], { encoding: 'utf8' });
  const field = (re) => { const m = info.match(re); if (!m) throw new Error(`nvddsinfo printed no ${re}`); return m[1]; };
  const width = Number(field(/^Width: (\d+)/m)), height = Number(field(/^Height: (\d+)/m));
  const levelCount = Number(field(/^Mipmap count: (\d+)/m));
  const format = field(/DXGI Format: \d+ \((\w+)\)/);
  const [kind, channels] = dxgi[format] ?? ['f32', 1];
  const texelBytes = (kind === 'f32' ? 4 : 2) * channels;
  // DDS_HEADER_DXT10 (after the magic and the 124-byte header): dxgiFormat, resourceDimension, miscFlag,
  // arraySize, miscFlags2. nvddsinfo prints the array size too: both must agree.
  const layerCount = Math.max(1, bytes.readUInt32LE(4 + 124 + 12));
  const printedArraySize = info.match(/Array size: (\d+)/m);
  if (printedArraySize && Math.max(1, Number(printedArraySize[1])) !== layerCount)
    throw new Error(`nvddsinfo prints array size ${printedArraySize[1]}, the header holds ${layerCount}`);
  let at = 4 + 124 + 20;  // magic, DDS_HEADER, DDS_HEADER_DXT10; then each layer's chain, level 0 first, rows packed
  const parts = Array.from({ length: levelCount }, () => []);
  for (let layer = 0; layer < layerCount; ++layer) {
    for (let i = 0; i < levelCount; ++i) {
      const w = Math.max(1, width >> i), h = Math.max(1, height >> i);
      const n = imageBytes(w, h, kind, texelBytes);
      const data = bytes.subarray(at, at + n);
      if (data.byteLength !== n) throw new Error(`layer ${layer} level ${i} is truncated`);
      parts[i].push(data);
      at += data.byteLength;
    }
  }
  if (at !== bytes.byteLength) throw new Error(`${bytes.byteLength - at} bytes after the last level`);
  const levels = parts.map((layers, i) => {
    const data = Buffer.concat(layers);
    return { width: Math.max(1, width >> i), height: Math.max(1, height >> i), byteLength: data.byteLength,
             sha256: sha256(data), values: valuesOf(data, kind), blocks: blocksOf(data, kind) };
  });
  // heightpack's record in dwReserved1 (docs/formats.md, "GPU containers"): 'HPCK', version 1, then the layout
  // code and the wrap code, and in word 6 the flags: bit 1 the uint16 normalisation in words 7 and 8,
  // bits 2 and 3 the layers after the heights (Dx, Dy; Foam). Read from the header's bytes as
  // documented, not through heightpack.
  const keyValues = {};
  const header = new DataView(bytes.buffer, bytes.byteOffset + 4, 124);
  const reserved = (i) => header.getUint32(4 * (7 + i), true);
  if (reserved(0) === 0x4b435048 && reserved(1) === 1) {
    const layouts = [undefined, 'neighbour4', 'plain', 'normal', 'fresnel', 'normalXY'];
    const wraps = [undefined, 'periodic', 'clamp'];
    if (layouts[reserved(2)]) keyValues['heightpack:layout'] = layouts[reserved(2)];
    if (wraps[reserved(3)]) keyValues['heightpack:wrap'] = wraps[reserved(3)];
    const flags = reserved(6);
    if (flags & 2) {  // the normalisation: value = offset + scale * u / 65535 (uint16), offset + scale * u (blocks)
      keyValues['heightpack:normalisedOffset'] = String(header.getFloat32(4 * (7 + 7), true));
      keyValues['heightpack:normalisedScale'] = String(header.getFloat32(4 * (7 + 8), true));
    }
    if (layerCount > 1) {
      const names = ['heights', ...(flags & 4 ? ['Dx', 'Dy'] : []), ...(flags & 8 ? ['Foam'] : [])];
      if (names.length === layerCount) keyValues['heightpack:layers'] = names.join(',');
    }
  }
  console.log(JSON.stringify({ reader: 'nvddsinfo', format: `DXGI_FORMAT_${format}`, channels, width, height,
                               layerCount, levelCount, keyValues, levels }));
}
