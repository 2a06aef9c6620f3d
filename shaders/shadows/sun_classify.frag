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
    float z = texelFetch(depth, ivec2(gl_FragCoord.xy), 0).r;
    // rgCascadeOf without its loop: the splits ascend, so the cascade is how many of the used ones
    // lie at or before the pixel's view distance.
    vec4 used = step(vec4(0.5, 1.5, 2.5, 3.5), vec4(rgCascades.c.info.x));
    float passed = dot(step(rgCascades.c.splitFar, vec4(rgViewDistance(z))), used);
    bool inside = z < 1.0 && passed < rgCascades.c.info.x - 0.5;
    gl_FragDepth = inside ? (passed + 1.0) * 0.125 : 1.0;
}
