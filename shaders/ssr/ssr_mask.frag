#version 460
// Which of SSR's half-resolution pixels trace a ray (scripts/ssr.lua): depth 0 where ssr.frag
// would march — something drawn at the full-resolution pixel it traces (ssr_pixel.glsl; with
// RG_SSR_TEMPORAL at any pixel of the block), smooth enough (linear roughness ≤
// Params.ssr_max_roughness) — and 1 where it returns 0 at once. The ssr pass
// then draws at depth 0.5 with a greater-than test, so lavapipe's early depth test drops every
// block with no ray before shading it (a branch in the shader cannot: both sides run for a
// block); those keep the cleared 0, what ssr.frag writes there. The default scene's floor
// (linear roughness 0.65) and sky trace none: at 1280×720 `ssr` 8.6 → 4.0 ms, this mask 1.5
// (the same runs; the image the same, frame by frame).
#include "lib/scene.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"
#include "ssr_pixel.glsl"

layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2) uniform Params { float ssr_max_roughness; } params;

bool traces(ivec2 p) {
    p = min(p, textureSize(depth, 0) - 1);  // an odd width or height: its last pixel again
    return texelFetch(depth, p, 0).r < 1.0 && !(1.0 - rgGBufferSmoothnessAt(p) > params.ssr_max_roughness);
}

void main() {
#ifdef RG_SSR_TEMPORAL
    // The block, not this frame's corner: `ssr_temporal` draws over the same mask, and a block
    // whose corners differ accumulates them all (its rough or empty corners as misses).
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    bool any = traces(p) || traces(p + ivec2(1, 0)) || traces(p + ivec2(0, 1)) || traces(p + ivec2(1, 1));
#else
    bool any = traces(rgSsrTracedPixel(ivec2(gl_FragCoord.xy), textureSize(depth, 0)));
#endif
    gl_FragDepth = any ? 0.0 : 1.0;
}
