// The flat tiled view: one map (its first frame, level 0, plain, hardware bilinear) repeated N x M, as grey
// from its min to max, with the tile lines drawn on demand. The tiles keep the map's shape (square texels):
// the block of N x M tiles is as large as the window holds, centred, and the rest is left black.
uniform sampler2DArray uMap;  // a map's frames, one a layer: frame 0 is shown
uniform vec2 uTiles;
uniform vec2 uRange;
uniform vec2 uDecode;   // the map's texels back to its values: x + y * sampled
uniform bool uSeamLines;
uniform vec2 uTilePixels;  // pixels one tile spans, across and down
uniform vec2 uOrigin;      // pixels from the window's top-left corner to the block's
uniform vec2 uViewport;

layout(location = 0) out vec4 outColour;

void main() {
    // Row 0 of the map at the top, as an image viewer shows it.
    vec2 t = (vec2(gl_FragCoord.x, uViewport.y - gl_FragCoord.y) - uOrigin) / uTilePixels;
    if (any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, uTiles))) discard;
    float h = uDecode.x + uDecode.y * textureLod(uMap, vec3(fract(t), 0.0), 0.0).r;
    float g = clamp((h - uRange.x) / (uRange.y - uRange.x), 0.0, 1.0);
    vec3 colour = vec3(g);
    if (uSeamLines) {
        vec2 distance = abs(t - floor(t + 0.5)) * uTilePixels;  // pixels to the nearest tile line
        if (min(distance.x, distance.y) < 1.0) colour = mix(colour, vec3(1.0, 0.2, 0.1), 0.6);
    }
    outColour = vec4(colour, 1.0);
}
