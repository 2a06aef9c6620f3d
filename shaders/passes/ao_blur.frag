#version 460
// The half-resolution AO (gtao.frag) brought to full resolution: a 4×4 box of half-resolution
// texels around the pixel (it averages the 4×4 rotation pattern), each weighted by how close its
// view distance (kept by gtao beside the AO) is to the pixel's (a bilateral filter: no AO bleeding across silhouettes).
#include "lib/scene.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_half;
layout(set = 0, binding = 1) uniform sampler2D depth;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth, p, 0).r;
    if (z >= 1.0) { color = vec4(1.0); return; }
    float d0 = rgViewDistance(z);
    ivec2 h = p / 2;
    ivec2 halfSize = textureSize(ao_half, 0);
    float sum = 0.0, weight = 0.0;
    float falloff = 1.0 / (0.05 * d0 + 0.05);  // loose enough for a floor at grazing view
    for (int j = -2; j < 2; ++j)
        for (int i = -2; i < 2; ++i) {
            vec2 aoDepth = texelFetch(ao_half, clamp(h + ivec2(i, j), ivec2(0), halfSize - 1), 0).rg;  // gtao: AO, view distance
            float w = exp(-abs(aoDepth.g - d0) * falloff) + 1e-4;
            sum += aoDepth.r * w;
            weight += w;
        }
    color = vec4(vec3(sum / weight), 1.0);
}
