#version 460
// Which of SSR's half-resolution pixels trace a ray (scripts/ssr.lua): depth 0 where ssr.frag
// would march — something drawn at the pixel's top-left full-resolution pixel, smooth enough
// (linear roughness ≤ Params.ssr_max_roughness) — and 1 where it returns 0 at once. The ssr pass
// then draws at depth 0.5 with a greater-than test, so lavapipe's early depth test drops every
// block with no ray before shading it (a branch in the shader cannot: both sides run for a
// block); those keep the cleared 0, what ssr.frag writes there. The default scene's floor
// (linear roughness 0.65) and sky trace none: at 1280×720 `ssr` 8.6 → 4.0 ms, this mask 1.5
// (the same runs; the image the same, frame by frame).
#include "lib/scene.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"

layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2) uniform Params { float ssr_max_roughness; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    float z = texelFetch(depth, p, 0).r;
    bool traces = z < 1.0 && !(1.0 - rgGBufferSmoothnessAt(p) > params.ssr_max_roughness);
    gl_FragDepth = traces ? 0.0 : 1.0;
}
