// Per-pixel water shading: four normal-map octaves, back-side tilt, Fresnel ramp, sky, sun glint, foam.
in vec3 vWorld;
in float vHeight;
in float vLod;
in vec2 vGrid;

uniform int uView;                  // 0 shaded, 1 height as grey, 2 LOD as colour
uniform vec2 uHeightRange;          // heights mapped to grey in view 1
uniform bool uHasNormalMap;
uniform sampler2D uNormalMap;       // xyz in [-1, 1] (RGB or RGBA), or xy alone (RG); float, half or 16-bit
uniform vec2 uNormalDecode;         // texels to components: x + y * sampled (a 16-bit normalised map's range)
uniform float uNormalGreen;         // +1: green along +v; -1: an OpenGL map (green toward row 0)
uniform vec4 uNormalOctave[4];      // tiles per metre, scroll u, scroll v, strength
uniform bool uHasFresnel;
uniform sampler2D uFresnel;         // rgb water colour, a reflectance, indexed by N.V
uniform vec2 uFresnelDecode;        // texels to values: x + y * sampled
uniform float uFresnelIndexScale;   // 1 for N.V, 2 for saturate(2 N.V)
uniform float uIor;
uniform vec3 uDeep, uShallow;
uniform float uTilt;                // how far back-facing normals lean toward the viewer
uniform vec2 uFoamRange;            // H0, Hmax
uniform bool uHasFoam;
uniform sampler2D uFoam;
uniform float uFoamScale;           // tiles per metre
// Synth's baked foam coverage (pack --foam): every frame of a map's coverage as one one-channel array in
// its file's type, layer f = frame f as in the heights' arrays (uLayerFrame picks this frame and the next),
// filtered in hardware (the fragment has derivatives, so a pixel sees its footprint's mean foam).
uniform sampler2DArray uFoamCoverage[kMaxLayers];
uniform vec4 uCoverageDecode[kMaxLayers];  // as uLayerDecode, for the coverage: applied after the filtering
uniform float uCoverageOn[kMaxLayers];  // 1 for a map whose baked coverage is shown

layout(location = 0) out vec4 outColour;


vec3 normalFromHeights(vec2 xy, float d) {
    float e = max(0.02, d * uPixelAngle);
    float lod;
    float hx = waterHeight(xy + vec2(e, 0.0), d, lod) - waterHeight(xy - vec2(e, 0.0), d, lod);
    float hy = waterHeight(xy + vec2(0.0, e), d, lod) - waterHeight(xy - vec2(0.0, e), d, lod);
    return normalize(vec3(-hx, -hy, 2.0 * e));
}

// With choppy maps the surface is P(u) = (u + shift(u), H(u)) over the grid point u: its normal is the
// cross product of P's differences along x and y (a fold turns it over; it is kept facing up).
vec3 surfacePoint(vec2 u, float d) {
    float lod;
    return vec3(u + waterShift(u, d), waterHeight(u, d, lod));
}

vec3 normalFromSurface(vec2 u, float d) {
    float e = max(0.02, d * uPixelAngle);
    vec3 n = cross(surfacePoint(u + vec2(e, 0.0), d) - surfacePoint(u - vec2(e, 0.0), d),
                   surfacePoint(u + vec2(0.0, e), d) - surfacePoint(u - vec2(0.0, e), d));
    return normalize(n.z < 0.0 ? -n : n);
}

// The surface's own slope from the displaced heights, plus the detail of four normal-map octaves. The
// octaves add each map's x and y, as the ATI shader does, so a normal's z never enters: a two-channel
// (xy) map shades exactly as the three-channel map it came from, with no z to rebuild.
vec3 normalFromMap(vec2 xy, vec3 base) {
    vec3 sum = vec3(base.xy / base.z, 0.0);
    for (int k = 0; k < 4; ++k) {
        vec2 uv = xy * uNormalOctave[k].x + uNormalOctave[k].yz * uTime;
        if (k % 2 == 1) uv = uv.yx;  // the ATI shader's swap: the two scrolling maps never line up
        vec2 n = uNormalDecode.x + uNormalDecode.y * texture(uNormalMap, uv).xy;
        sum += vec3(n.x, uNormalGreen * n.y, 0.0) * uNormalOctave[k].w;
    }
    return normalize(vec3(sum.xy, 1.0));
}

// Map k's coverage at the grid point u (before its horizontal shift: synth's foam, like its heights, belongs
// to the point u carries), at the map's tile size and scroll, this frame blended into the next.
float layerCoverage(int k, sampler2DArray coverage, vec2 u) {
    vec2 uv = layerUv(k, u);
    vec4 decode = uCoverageDecode[k];
    float c = decode.x + decode.y * texture(coverage, vec3(uv, float(uLayerFrame[k].x))).r;
    if (uLayerBlend[k] > 0.0)
        c = mix(c, decode.z + decode.w * texture(coverage, vec3(uv, float(uLayerFrame[k].y))).r, uLayerBlend[k]);
    return clamp(c, 0.0, 1.0);  // a sharp filter's ringing can leave 0..1 in the mip levels
}

float foamPattern(vec2 xy) {
    if (uHasFoam) return texture(uFoam, xy * uFoamScale).r;
    vec2 p = xy * 3.0;  // procedural: interfering ripples
    return clamp(0.5 + 0.25 * (sin(p.x * 1.7 + sin(p.y * 2.3)) + sin(p.y * 1.3 + sin(p.x * 2.9))), 0.0, 1.0);
}

vec3 lodColour(float lod) {
    const vec3 palette[6] = vec3[6](vec3(0.9, 0.1, 0.1), vec3(0.9, 0.6, 0.1), vec3(0.8, 0.9, 0.1),
                                    vec3(0.1, 0.8, 0.2), vec3(0.1, 0.6, 0.9), vec3(0.5, 0.2, 0.9));
    int level = int(floor(lod));
    return mix(palette[level % 6], palette[(level + 1) % 6], fract(lod));
}

void main() {
    if (uView == 1) {
        float g = clamp((vHeight - uHeightRange.x) / (uHeightRange.y - uHeightRange.x), 0.0, 1.0);
        outColour = vec4(vec3(0.1 + 0.8 * g), 1.0);
        return;
    }
    if (uView == 2) {
        outColour = vec4(lodColour(vLod), 1.0);
        return;
    }
    vec3 toEye = uCameraPos - vWorld;
    float d = length(toEye);
    vec3 v = toEye / d;
    vec3 n = anyChoppy() ? normalFromSurface(vGrid, d) : normalFromHeights(vWorld.xy, d);
    if (uHasNormalMap) n = normalFromMap(vWorld.xy, n);
    // 18.2.4, back sides of waves: lighting assumes a flat surface, so normals facing away from the viewer
    // are tilted toward it.
    float facing = dot(n, v);
    if (facing < uTilt) n = normalize(n + v * (uTilt - facing));
    float nv = clamp(dot(n, v), 0.0, 1.0);
    vec3 waterColour;
    float fresnel;
    if (uHasFresnel) {
        vec4 ramp = uFresnelDecode.x + uFresnelDecode.y * texture(uFresnel, vec2(clamp(nv * uFresnelIndexScale, 0.0, 1.0), 0.5));
        waterColour = ramp.rgb;
        fresnel = ramp.a;
    } else {
        float r0 = (uIor - 1.0) / (uIor + 1.0);
        r0 *= r0;
        fresnel = r0 + (1.0 - r0) * pow(1.0 - nv, 5.0);
        waterColour = mix(uShallow, uDeep, nv);
    }
    vec3 r = reflect(-v, n);
    r.z = abs(r.z);
    vec3 colour = mix(waterColour, sky(r), fresnel);
    // Baked foam: where the sea's Jacobian put it. The maps' coverages combine as independent ones; a foam
    // texture, when given, still breaks it up, and without one the coverage is the foam.
    float clear = 1.0;  // the chance that no map's foam covers the point
    if (uCoverageOn[0] > 0.5) clear *= 1.0 - layerCoverage(0, uFoamCoverage[0], vGrid);
    if (uCoverageOn[1] > 0.5) clear *= 1.0 - layerCoverage(1, uFoamCoverage[1], vGrid);
    if (uCoverageOn[2] > 0.5) clear *= 1.0 - layerCoverage(2, uFoamCoverage[2], vGrid);
    if (uCoverageOn[3] > 0.5) clear *= 1.0 - layerCoverage(3, uFoamCoverage[3], vGrid);
    if (uCoverageOn[0] > 0.5 || uCoverageOn[1] > 0.5 || uCoverageOn[2] > 0.5 || uCoverageOn[3] > 0.5) {
        colour = mix(colour, vec3(0.92), (1.0 - clear) * (uHasFoam ? foamPattern(vWorld.xy) : 1.0));
    } else {
        float foam = clamp((vHeight - uFoamRange.x) / max(uFoamRange.y - uFoamRange.x, 1e-4), 0.0, 1.0);
        colour = mix(colour, vec3(0.92), foam * foamPattern(vWorld.xy));
    }
    colour = mix(colour, sky(normalize(vec3(-v.xy, 0.02))), 1.0 - exp(-d / 30000.0));  // haze toward the horizon
    outColour = vec4(pow(colour, vec3(1.0 / 2.2)), 1.0);
}
