#version 460
// Deferred lighting of the standard material (seed 000 §3.1, §4): the `disney` G-buffer, every
// light of the scene (shaders/lib/lighting.glsl: punctual, sun and area lights, the diffuse lobe
// from the light's illuminance, the specular lobe from its representative point), the distant
// light probe (lib/ibl.glsl, with RG_IBL), emissive (GB3),
// written as pre-exposed luminance. Runs only on the pixels of its stencil class (the pass's stencil test).
#include "lib/lighting.glsl"
#include "lib/exposure.glsl"
#include "lib/ibl.glsl"
#include "gbuffer_disney.glsl"

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
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0),
                                            texelFetch(GB3, p, 0));
    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    vec3 V = rgViewDirection(position);
    // §3.2.1: metals take their f0 from the base colour, dielectrics 0.16 · reflectance².
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(p);  // the tile's lights (lib/light_tiles.glsl)
    float sun = rgSunVisibility(position, g.normal);  // the sun's shadow (RG_SHADOWS), once
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        RgLightSample s = rgEvaluateLight(i, position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, diffuseColor, f0, linearRoughness);
    }
    luminance += rgStandardIbl(position, g.normal, V, diffuseColor, f0, linearRoughness, rgAmbientOcclusion(g.ao));  // the probes (RG_IBL, RG_PROBES)
    color = vec4(luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}
