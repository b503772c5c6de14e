// Displaces the radial grid: one vertex per (ring, segment), packed as (cos, sin, ring) as in Listing 18-1.
layout(location = 0) in vec3 aGrid;

uniform mat4 uViewProj;
uniform bool uFrustumBranch;   // skip texturing outside the guard-banded clip volume
uniform vec2 uGuardBand;       // C0, C1
uniform bool uUseCombined;     // two-pass mode: the height was computed per vertex in the combine pass
uniform sampler2D uCombined;   // RGBA32F, M x N: texel (segment, ring): height, horizontal shift
uniform int uSegments;

out vec3 vWorld;
out float vHeight;
out float vLod;
out vec2 vGrid;                // the point before its horizontal shift, where the fragment finds its normal

void main() {
    vec2 xy = gridWorldXY(aGrid.xy, aGrid.z);
    float d = distance(vec3(xy, uWaterLevel), uCameraPos);
    vec4 flatClip = uViewProj * vec4(xy, uWaterLevel, 1.0);
    bool visible = all(lessThan(abs(flatClip.xyz), flatClip.www * uGuardBand.x + uGuardBand.y));
    float h = 0.0;
    float lod = 0.0;
    vec2 shift = vec2(0.0);
    if (uUseCombined) {
        vec4 combined = texelFetch(uCombined, ivec2(gl_VertexID % uSegments, gl_VertexID / uSegments), 0);
        h = combined.r;
        shift = combined.gb;
        lod = uLayerCount > 0 ? layerLod(0, d) : 0.0;
    } else if (!uFrustumBranch || visible) {
        h = waterHeight(xy, d, lod);
        if (anyChoppy()) shift = waterShift(xy, d);
    }
    vGrid = xy;
    vWorld = vec3(xy + shift, uWaterLevel + h);
    vHeight = h;
    vLod = lod;
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
