// The sky behind the water, from the same function the water reflects.
in vec2 vUv;
uniform mat4 uInverseViewProj;

layout(location = 0) out vec4 outColour;

void main() {
    vec4 near = uInverseViewProj * vec4(vUv * 2.0 - 1.0, -1.0, 1.0);
    vec4 far = uInverseViewProj * vec4(vUv * 2.0 - 1.0, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - near.xyz / near.w);
    outColour = vec4(pow(sky(dir), vec3(1.0 / 2.2)), 1.0);
}
