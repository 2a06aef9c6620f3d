#version 460
// Deferred lighting of the toon path: the `toon` G-buffer unpacked and shaded by
// toon_shading.glsl, on the pixels of stencil class lit_toon.
#include "lib/lighting.glsl"
#include "lib/exposure.glsl"
#include "lib/ibl.glsl"
#include "gbuffer_toon.glsl"
#include "toon_shading.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D GB3;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(set = 0, binding = 5, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 6) uniform Params { float initial_ev100; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    GBuffer_toon g = unpackGBuffer_toon(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0), texelFetch(GB3, p, 0));
    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    color = vec4(rgShade(g, position, rgViewDirection(position), p) * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}
