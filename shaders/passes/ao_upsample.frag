#version 460
// The filtered half-resolution AO (ao_blur.frag) at full resolution: the four half-resolution
// texels around the pixel, weighted bilinearly and by how close each one's view distance is to
// the pixel's (a bilateral upsample: edges keep their own side's AO).
#include "lib/scene.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_filtered;
layout(set = 0, binding = 1) uniform sampler2D depth;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth, p, 0).r;
    if (z >= 1.0) { color = vec4(1.0); return; }
    float d0 = rgViewDistance(z);
    ivec2 halfSize = textureSize(ao_filtered, 0);
    // The pixel's centre in half-resolution texel coordinates, and its four neighbours.
    vec2 f = (vec2(p) + 0.5) * 0.5 - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 w1 = f - vec2(base), w0 = 1.0 - w1;
    float falloff = 1.0 / (0.05 * d0 + 0.05);
    float sum = 0.0, weight = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            vec2 aoDepth = texelFetch(ao_filtered, clamp(base + ivec2(i, j), ivec2(0), halfSize - 1), 0).rg;
            float w = (i == 0 ? w0.x : w1.x) * (j == 0 ? w0.y : w1.y) * (exp(-abs(aoDepth.g - d0) * falloff) + 1e-4);
            sum += aoDepth.r * w;
            weight += w;
        }
    color = vec4(vec3(sum / weight), 1.0);
}
