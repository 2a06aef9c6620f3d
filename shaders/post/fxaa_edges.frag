#version 460
// FXAA's edge mask (scripts/post.lua): depth 0 where fxaa.frag's contrast test finds an edge, 1
// elsewhere. The fxaa pass then draws at depth 1 with a greater-than test, so lavapipe's early
// depth test drops every block without an edge pixel before shading it — a branch in the shader
// cannot (both sides run for a block): at 1280×720 the filter costs ~2.2 ms instead of ~12.5,
// this mask ~3.0 and the tone mapping's copy ~1.3 (−6 ms). The same image: a pixel outside the mask keeps the tone mapping's copy, which is
// what fxaa.frag writes for a pixel without an edge.
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1) uniform Params { float fxaa_threshold; } params;
#include "fxaa_contrast.glsl"

void main() {
    pixel = ivec2(gl_FragCoord.xy);
    last = textureSize(source, 0) - 1;
    gl_FragDepth = fxaaEdge(fxaaCross(luma(texelFetch(source, pixel, 0).rgb)), params.fxaa_threshold) ? 0.0 : 1.0;
}
