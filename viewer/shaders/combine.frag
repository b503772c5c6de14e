// Pass one of the render-to-texture loop: the height of every grid vertex, one texel each (texel x =
// segment, y = ring), so pass two displaces with a single plain fetch.
uniform mat4 uViewProj;
uniform bool uFrustumBranch;
uniform vec2 uGuardBand;
uniform int uSegments;
uniform int uRings;

layout(location = 0) out float outHeight;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float angle = 6.28318530717958647692 * float(texel.x) / float(uSegments);
    vec2 xy = gridWorldXY(vec2(cos(angle), sin(angle)), float(texel.y));
    float d = distance(vec3(xy, uWaterLevel), uCameraPos);
    vec4 flatClip = uViewProj * vec4(xy, uWaterLevel, 1.0);
    bool visible = all(lessThan(abs(flatClip.xyz), flatClip.www * uGuardBand.x + uGuardBand.y));
    float lod;
    outHeight = (!uFrustumBranch || visible) ? waterHeight(xy, d, lod) : 0.0;
}
