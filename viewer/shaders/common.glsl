// Shared by every pass: the height field H(x, y, t) of chapter 18, a sum of scrolling height maps, read
// through 4-neighbour packed textures (one nearest fetch per level), or through plain one-channel
// textures: hardware bilinear filtering (the reference) or textureGather (GL 4.0) and the filter here.
// The viewer puts "#version 400 core" and HEIGHTPACK_GATHER 1 before this where the context is 4.0 or
// newer, else "#version 330 core" and HEIGHTPACK_GATHER 0 (and never asks for the gather lookup).

// Every map the scene names, up to four: synth --cascades makes as many tiles of one sea. Renderer's
// kMaxLayers is this number, and the calls in waterHeight and waterShift name each sampler once.
const int kMaxLayers = 4;

uniform int uLayerCount;
// Every height texture is in its file's type (32-bit float, half, 16-bit normalised); uLayerDecode maps
// what they sample back to the file's values. Each is an array texture holding every frame of a map's
// sequence, frame f in layer f, so blending this frame into the next costs no sampler of its own. One
// sampler a map holds its heights in whichever form uLookup reads (the renderer binds the packed chain,
// the plain chain or the gather atlas to it), and one its Dx, Dy: the vertex stage reads nine samplers
// with the combine target, the fragment stage fifteen with the shading textures and foam coverage, of
// the sixteen GL 3.3 promises a stage, whatever the lookup.
//   packed (uLookup 0, 1): RGBA, nearest, mip-mapped: R=H(i,j) G=H(i+1,j) B=H(i,j+1) A=H(i+1,j+1)
//   reference (2, 3): R, GL_LINEAR, mip-mapped
//   gather (4, 5): R atlas, one level, nearest (GL 4.0 only)
uniform sampler2DArray uHeights[kMaxLayers];
uniform ivec2 uLayerFrame[kMaxLayers];  // the layers of this frame and the next (0, 0 for a single map)
uniform float uLayerBlend[kMaxLayers];  // how far between this frame and the next (0 for a single map)
uniform vec4 uLayerDecode[kMaxLayers];  // stored = x + y * sampled for this frame, z + w * sampled for the next
uniform vec4 uLayerXform[kMaxLayers];   // tiles per metre, scroll u and v (tiles per second), amplitude (m)
uniform vec2 uLayerStored[kMaxLayers];  // the stored value of a mid height (subtracted), and 1 if clamp-wrapped
uniform int uLayerLevels[kMaxLayers];   // mip levels in each layer's chain
uniform int uLookup;                    // bilinear (even) or trilinear (odd): 0, 1 packed; 2, 3 reference; 4, 5 gather
uniform vec2 uBands;                    // Listing 18-3's snapped LOD band, (0.3, 0.7)
uniform float uPixelAngle;              // radians a pixel subtends, for the LOD from distance
uniform float uTime;
uniform float uWaterLevel;

// Explosions (18.2.5): I(r) = I0 sin(k r + w t) exp(-b t) / r^2, several at once, with r taken as
// s = sqrt(r^2 + R^2), R = 1 m: the chapter's formula wherever r >> R, and smooth at the centre, where
// 1 / r^2 is infinite (clamping r at 1 m left a flat-topped spike with a kink around it). w < 0: the
// rings run outward.
const int kMaxExplosions = 8;
uniform int uExplosionCount;
uniform vec4 uExplosion[kMaxExplosions];  // centre x, y, start time, strength I0
uniform vec3 uExplosionShape;             // k, w, b

uniform ivec2 uLayerSize[kMaxLayers];  // level 0 size of each layer

// The size of a level, from level 0's: textureSize with a level that differs between vertices of one
// SIMD batch is not reliable on every driver (llvmpipe's vertex stage), so it is not used.
vec2 levelSize(int layer, int level) {
    return vec2(max(ivec2(1), uLayerSize[layer] >> level));
}

// Listing 18-2 with the design's lookup: p = uv * size - 0.5, one nearest fetch at floor(p).
float packedBilinear(sampler2DArray tex, int layer, int frame, vec2 uv, int level, bool clampMode) {
    vec2 size = levelSize(layer, level);
    vec2 p = (clampMode ? clamp(uv, 0.0, 1.0) : fract(uv)) * size - 0.5;  // fract keeps far coordinates precise
    if (clampMode) p = clamp(p, vec2(0.0), size - 1.0);
    vec2 i = floor(p);
    vec2 f = p - i;
    vec4 t = texelFetch(tex, ivec3(mod(i, size), frame), level);
    return mix(mix(t.r, t.g, f.x), mix(t.b, t.a, f.x), f.y);
}

float referenceBilinear(sampler2DArray tex, int frame, vec2 uv, int level, bool clampMode) {
    return textureLod(tex, vec3(clampMode ? uv : fract(uv), float(frame)), float(level)).r;
}

#if HEIGHTPACK_GATHER
// textureGather reads only a texture's base level, so the plain chain is one atlas per map: level l's
// texel (0, 0) at uGatherOrigin[layer * kMaxLevels + l], each level followed by a column and a row of
// its wrapped neighbours, so the 2x2 footprint below never leaves the level.
const int kMaxLevels = 16;
uniform ivec2 uGatherOrigin[kMaxLayers * kMaxLevels];
uniform vec2 uGatherSize[kMaxLayers];   // the atlas in texels

// The packed lookup's arithmetic on the four texels one gather returns.
float gatherBilinear(sampler2DArray atlas, int layer, int frame, vec2 uv, int level, bool clampMode) {
    vec2 size = levelSize(layer, level);
    vec2 p = (clampMode ? clamp(uv, 0.0, 1.0) : fract(uv)) * size - 0.5;
    if (clampMode) p = clamp(p, vec2(0.0), size - 1.0);
    vec2 i = floor(p);
    vec2 f = p - i;
    // The corner shared by texels i and i + 1: the bilinear footprint there is exactly those four,
    // half a texel from any rounding that could pick another.
    vec2 corner = vec2(uGatherOrigin[layer * kMaxLevels + level]) + mod(i, size) + 1.0;
    vec4 t = textureGather(atlas, vec3(corner / uGatherSize[layer], float(frame)));  // (i,j+1) (i+1,j+1) (i+1,j) (i,j)
    return mix(mix(t.w, t.z, f.x), mix(t.x, t.y, f.x), f.y);
}
#endif

// heights: the map's texture for the current lookup (uHeights' comment).
float levelLookup(sampler2DArray heights, int layer, int frame, vec2 uv, int level, bool clampMode) {
#if HEIGHTPACK_GATHER
    if (uLookup >= 4) return gatherBilinear(heights, layer, frame, uv, level, clampMode);
#endif
    return uLookup >= 2 ? referenceBilinear(heights, frame, uv, level, clampMode)
                        : packedBilinear(heights, layer, frame, uv, level, clampMode);
}

// Listing 18-3: one level below the band, the next above it, a blend inside it.
float layerHeight(sampler2DArray heights, int layer, int frame, vec2 uv, float lod, bool clampMode) {
    int last = uLayerLevels[layer] - 1;
    if (uLookup % 2 == 0) return levelLookup(heights, layer, frame, uv, 0, clampMode);
    lod = clamp(lod, 0.0, float(last));
    int level = min(int(floor(lod)), last);
    float fr = lod - float(level);
    if (level == last || fr < uBands.x) return levelLookup(heights, layer, frame, uv, level, clampMode);
    float coarse = levelLookup(heights, layer, frame, uv, level + 1, clampMode);
    if (fr > uBands.y) return coarse;
    float fine = levelLookup(heights, layer, frame, uv, level, clampMode);
    return mix(fine, coarse, (fr - uBands.x) / (uBands.y - uBands.x));
}

// The level of detail of layer k seen from distance d: log2 of texels per pixel.
float layerLod(int k, float d) {
    float texelsPerMetre = uLayerXform[k].x * float(uLayerSize[k].x);
    return log2(max(d * uPixelAngle * texelsPerMetre, 1.0));
}

vec2 layerUv(int k, vec2 world) {
    return world * uLayerXform[k].x + uLayerXform[k].yz * uTime;
}

// Layer k's height above its mean at xy, seen from distance d: this frame, blended into the next frame
// of a sequence; lod receives the layer's level of detail. Every lookup is a weighted mean of texels,
// so a normalised map's scale and offset apply once, after it.
float layerContribution(int k, sampler2DArray heights, vec2 xy, float d, out float lod) {
    lod = layerLod(k, d);
    vec2 uv = layerUv(k, xy);
    bool clampMode = uLayerStored[k].y > 0.5;
    vec4 decode = uLayerDecode[k];
    float stored = decode.x + decode.y * layerHeight(heights, k, uLayerFrame[k].x, uv, lod, clampMode);
    if (uLayerBlend[k] > 0.0) {
        float next = decode.z + decode.w * layerHeight(heights, k, uLayerFrame[k].y, uv, lod, clampMode);
        stored = mix(stored, next, uLayerBlend[k]);
    }
    return uLayerXform[k].w * (stored - uLayerStored[k].x);
}

// Tessendorf's choppy waves: maps that carry Dx, Dy move each point sideways as well as up. Their Dx, Dy
// are packed as the heights are and read with the same lookup, at the same level and LOD band, so a
// vertex's shift belongs to the very height it is given.
uniform sampler2DArray uShifts[kMaxLayers];  // layer 2f: Dx, layer 2f + 1: Dy of frame f (RGBA packed)
uniform float uLayerChop[kMaxLayers];   // choppiness of each map with Dx, Dy; 0 for a map without them
uniform vec4 uShiftDecode[kMaxLayers];  // as uLayerDecode, for Dx and Dy (the type their file stored them in)

vec2 packedShiftBilinear(sampler2DArray tex, int layer, int frame, vec2 uv, int level, bool clampMode) {
    vec2 size = levelSize(layer, level);
    vec2 p = (clampMode ? clamp(uv, 0.0, 1.0) : fract(uv)) * size - 0.5;
    if (clampMode) p = clamp(p, vec2(0.0), size - 1.0);
    vec2 i = floor(p);
    vec2 f = p - i;
    ivec2 at = ivec2(mod(i, size));
    vec4 x = texelFetch(tex, ivec3(at, 2 * frame), level);
    vec4 y = texelFetch(tex, ivec3(at, 2 * frame + 1), level);
    return vec2(mix(mix(x.r, x.g, f.x), mix(x.b, x.a, f.x), f.y), mix(mix(y.r, y.g, f.x), mix(y.b, y.a, f.x), f.y));
}

// layerHeight's levels and band for D (the reference and gather lookups are for heights: D stays packed).
vec2 layerShiftAt(sampler2DArray tex, int layer, int frame, vec2 uv, float lod, bool clampMode) {
    int last = uLayerLevels[layer] - 1;
    if (uLookup % 2 == 0) return packedShiftBilinear(tex, layer, frame, uv, 0, clampMode);
    lod = clamp(lod, 0.0, float(last));
    int level = min(int(floor(lod)), last);
    float fr = lod - float(level);
    if (level == last || fr < uBands.x) return packedShiftBilinear(tex, layer, frame, uv, level, clampMode);
    vec2 coarse = packedShiftBilinear(tex, layer, frame, uv, level + 1, clampMode);
    if (fr > uBands.y) return coarse;
    vec2 fine = packedShiftBilinear(tex, layer, frame, uv, level, clampMode);
    return mix(fine, coarse, (fr - uBands.x) / (uBands.y - uBands.x));
}

// Layer k's horizontal shift at xy: x + choppiness A D, synth's D = i k/|k| h pointing toward the crests
// (a Gerstner wave's sharpening for positive choppiness); frames blended as the heights are.
vec2 layerShift(int k, sampler2DArray tex, vec2 xy, float d) {
    float lod = layerLod(k, d);
    vec2 uv = layerUv(k, xy);
    bool clampMode = uLayerStored[k].y > 0.5;
    vec4 decode = uShiftDecode[k];  // after the lookup, a weighted mean of texels, as for the heights
    vec2 D = decode.x + decode.y * layerShiftAt(tex, k, uLayerFrame[k].x, uv, lod, clampMode);
    if (uLayerBlend[k] > 0.0)
        D = mix(D, decode.z + decode.w * layerShiftAt(tex, k, uLayerFrame[k].y, uv, lod, clampMode), uLayerBlend[k]);
    return uLayerChop[k] * uLayerXform[k].w * D;
}

bool anyChoppy() {
    for (int k = 0; k < kMaxLayers; ++k)
        if (k < uLayerCount && uLayerChop[k] != 0.0) return true;
    return false;
}

// GLSL 3.30 indexes an array of samplers with constant expressions only, so each map's call is written out.
// Where the grid point at xy moves sideways, seen from distance d (the same d as its height).
vec2 waterShift(vec2 xy, float d) {
    vec2 s = vec2(0.0);
    if (uLayerCount > 0 && uLayerChop[0] != 0.0) s += layerShift(0, uShifts[0], xy, d);
    if (uLayerCount > 1 && uLayerChop[1] != 0.0) s += layerShift(1, uShifts[1], xy, d);
    if (uLayerCount > 2 && uLayerChop[2] != 0.0) s += layerShift(2, uShifts[2], xy, d);
    if (uLayerCount > 3 && uLayerChop[3] != 0.0) s += layerShift(3, uShifts[3], xy, d);
    return s;
}

// Height above the water level at world position xy, seen from distance d; lod0 receives layer 0's LOD.
float waterHeight(vec2 xy, float d, out float lod0) {
    float h = 0.0;
    lod0 = 0.0;
    float lod;
    if (uLayerCount > 0) h += layerContribution(0, uHeights[0], xy, d, lod0);
    if (uLayerCount > 1) h += layerContribution(1, uHeights[1], xy, d, lod);
    if (uLayerCount > 2) h += layerContribution(2, uHeights[2], xy, d, lod);
    if (uLayerCount > 3) h += layerContribution(3, uHeights[3], xy, d, lod);
    for (int e = 0; e < kMaxExplosions; ++e) {
        if (e >= uExplosionCount) break;
        float age = uTime - uExplosion[e].z;
        if (age < 0.0) continue;
        vec2 toCentre = xy - uExplosion[e].xy;
        float s2 = dot(toCentre, toCentre) + 1.0;
        float s = sqrt(s2);
        h += uExplosion[e].w * sin(uExplosionShape.x * s + uExplosionShape.y * age) * exp(-uExplosionShape.z * age) / s2;
    }
    return h;
}

// The radial grid (Listing 18-1): ring i at r = a0 + a1 i^4 around the camera, segment j at angle 2 pi j / M.
uniform vec2 uGridRadius;   // a0, a1
uniform vec3 uCameraPos;

vec2 gridWorldXY(vec2 direction, float ring) {
    return uCameraPos.xy + direction * (uGridRadius.x + uGridRadius.y * pow(ring, 4.0));
}

// The procedural sky the water reflects: a gradient from a pale horizon to a deeper zenith, and a sun.
uniform vec3 uSunDir;
uniform vec3 uSunColour;

vec3 sky(vec3 dir) {
    float up = clamp(dir.z, 0.0, 1.0);
    vec3 base = mix(vec3(0.62, 0.72, 0.82), vec3(0.16, 0.33, 0.62), pow(up, 0.5));
    float sun = max(dot(dir, uSunDir), 0.0);
    return base + uSunColour * (pow(sun, 900.0) * 8.0 + pow(sun, 12.0) * 0.15);
}
