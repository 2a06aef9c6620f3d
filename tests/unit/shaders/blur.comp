#version 460
#include "lib/common.glsl"

#ifndef GROUP_X
#define GROUP_X 8
#endif
#ifndef RADIUS
#define RADIUS 2
#endif

layout(local_size_x = GROUP_X, local_size_y = 4, local_size_z = 1) in;

layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D outImage;
layout(set = 0, binding = 1) uniform sampler2D inTex;
layout(set = 0, binding = 2) uniform sampler2D luts[3];

layout(set = 1, binding = 0, std140) uniform Params {
    vec4 tint;       // offset 0
    float exposure;  // offset 16
    int steps;       // offset 20
    vec2 texel;      // offset 24
    mat4 transform;  // offset 32, size 64
} params;

layout(set = 1, binding = 1, std430) readonly buffer Weights {
    uint count;
    float weights[];
} weightBuf;

layout(push_constant) uniform Push {
    uvec2 size;  // offset 0
    float time;  // offset 8
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), pc.size))) return;
    vec2 uv = (vec2(p) + 0.5) * params.texel;
    vec4 sum = vec4(0.0);
    for (int i = -RADIUS; i <= RADIUS; ++i) {
        uint k = min(uint(i + RADIUS), weightBuf.count - 1u);
        sum += texture(inTex, uv + vec2(float(i), 0.0) * params.texel) * weightBuf.weights[k];
    }
    sum.rgb *= texture(luts[1], vec2(luminance(sum.rgb), 0.5)).rgb * params.exposure;
    sum *= params.tint * (0.5 + 0.5 * sin(pc.time * kPi));
    imageStore(outImage, p, params.transform * sum);
}
