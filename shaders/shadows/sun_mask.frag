#version 460
// The sun's shadow mask (scripts/shadows.lua): the sun's visibility (lib/shadows.glsl's PCSS) at
// each pixel of cascade RG_SUN_CASCADE — the pixels whose code sun_classify.frag wrote, which the
// pass's equal depth test selects — from that cascade's map, at the G-buffer's position and normal,
// into `sun_visibility`; the deferred lighting passes read it (RG_SUN_MASK) instead of the maps.
// With RG_SUN_MASK_HALF (the `sun_mask_halfN` passes) the same at half resolution, into
// `sun_visibility_half`: a quarter of the PCSS lookups, the mask's cost.
// One pass per cascade, right after its map is drawn: the map is dead once its pixels are filtered,
// and the next cascade's map takes its memory (3 × 8 MiB at 2048² d16 → 8 MiB live at a time).
#define RG_SHADOWS 1
#define RG_SUN_MASK_WRITER 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"

#ifndef RG_SUN_CASCADE
#define RG_SUN_CASCADE 0
#endif

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 1) uniform sampler2D depth;

void main() {
#ifdef RG_SUN_MASK_HALF
    // Texel h of the half-resolution mask: full-resolution pixel 2h, its view distance beside it
    // for the lighting's depth-aware upsample (lib/upsample.glsl).
    ivec2 q = ivec2(gl_FragCoord.xy) * 2;
    float z = texelFetch(depth, q, 0).r;
    vec3 P = rgWorldPosition((vec2(q) + 0.5) * camera.viewport.zw, z);
    vec3 N = rgGBufferNormalAt(q);
    color = vec4(rgSunShadowIn(sun_shadow, RG_SUN_CASCADE, P, N), rgViewDistance(z), 0.0, 1.0);
#else
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 P = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    vec3 N = rgGBufferNormalAt(p);
    color = vec4(rgSunShadowIn(sun_shadow, RG_SUN_CASCADE, P, N));
#endif
}
