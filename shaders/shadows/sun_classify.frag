#version 460
// The sun's shadow mask, first step (scripts/shadows.lua): each pixel's cascade as a depth code in
// `sun_cascade_mask` — (i + 1) / 8 for cascade i, 1 for the sky and beyond the shadow distance
// (`sun_visibility_clear` has set the mask itself to 1, lit). Each mask pass then draws at its
// cascade's code with an equal test, so lavapipe's early depth test keeps the blocks of other
// cascades from being shaded at all (a branch in the shader cannot: both sides run for a block).
// The codes are multiples of 1/8, exact in the d32f target and in the triangle's depth.
#define RG_SHADOWS 1
#define RG_SUN_CASCADES_ONLY 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"

layout(location = 0) in vec2 uv;
layout(set = 0, binding = 0) uniform sampler2D depth;

void main() {
#ifdef RG_SUN_MASK_HALF
    float z = texelFetch(depth, ivec2(gl_FragCoord.xy) * 2, 0).r;  // half resolution: texel h samples pixel 2h
#else
    float z = texelFetch(depth, ivec2(gl_FragCoord.xy), 0).r;
#endif
    int ci = z < 1.0 ? rgCascadeOf(rgViewDistance(z)) : RG_MAX_CASCADES;
    gl_FragDepth = ci < RG_MAX_CASCADES ? float(ci + 1) * 0.125 : 1.0;
}
