// Pass one of the render-to-texture loop: the height of every grid vertex, one texel each (texel x =
// segment, y = ring), with its horizontal shift when a map is choppy, so pass two displaces with a single
// plain fetch.
uniform mat4 uViewProj;
uniform bool uFrustumBranch;
uniform vec2 uGuardBand;
uniform int uSegments;
uniform int uRings;

layout(location = 0) out vec4 outCombined;  // height, then the horizontal shift of choppy maps

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float angle = 6.28318530717958647692 * float(texel.x) / float(uSegments);
    vec2 xy = gridWorldXY(vec2(cos(angle), sin(angle)), float(texel.y));
    float d = distance(vec3(xy, uWaterLevel), uCameraPos);
    vec4 flatClip = uViewProj * vec4(xy, uWaterLevel, 1.0);
    bool visible = all(lessThan(abs(flatClip.xyz), flatClip.www * uGuardBand.x + uGuardBand.y));
    float lod;
    bool sampled = !uFrustumBranch || visible;
    outCombined = vec4(sampled ? waterHeight(xy, d, lod) : 0.0, sampled && anyChoppy() ? waterShift(xy, d) : vec2(0.0), 0.0);
}
