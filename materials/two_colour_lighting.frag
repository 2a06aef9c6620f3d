#version 460
// Lighting of the two-colour path (seed 000 tbl:3, fig:14): the `two_colour` G-buffer unpacked to
// the standard lighting inputs — diffuse colour and f0 colour as stored — then the standard BRDF
// and light loop of shaders/passes/deferred_lighting.frag, over the tile's lights.
#include "lib/lighting.glsl"
#include "lib/exposure.glsl"
#include "lib/ibl.glsl"
#include "gbuffer_two_colour.glsl"

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
    GBuffer_two_colour g = unpackGBuffer_two_colour(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0),
                                                    texelFetch(GB3, p, 0));
    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    vec3 V = rgViewDirection(position);
    float linearRoughness = 1.0 - g.smoothness;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(p);
    float sun = rgSunVisibility(position, g.normal);  // the sun's shadow (RG_SHADOWS), once
    for (uint k = 0u; k < list.count; ++k) {
        RgLightSample s = rgEvaluateLight(rgListLight(list, k), position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, g.diffuseColor, g.f0, linearRoughness);
    }
    luminance += rgStandardIbl(position, g.normal, V, g.diffuseColor, g.f0, linearRoughness, rgAmbientOcclusion(g.ao));  // the probes (RG_IBL, RG_REFLECTION)
    color = vec4(luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}
