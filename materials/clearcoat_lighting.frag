#version 460
// Lighting of the clear-coat path: for each light, the base (the standard BRDF) attenuated by
// the coat's Fresnel, plus the coat's own GGX lobe (f0 = 0.04, an IOR of 1.5; roughness from
// coatSmoothness). The lights are evaluated for both lobes: "lit twice".
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
    vec3 N = g.normal;
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    float coatStrength = float(g.materialData) / 31.0;
    float coatRoughness = 1.0 - g.reserved;
    float coatAlpha = max(coatRoughness * coatRoughness, 1e-3);
    float NdotV = abs(dot(N, V)) + 1e-5;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(p);  // the tile's lights (lib/light_tiles.glsl)
    float sun = rgSunVisibility(position, N);  // the sun's shadow (RG_SHADOWS), once for both lobes
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        // Each lobe sees the light from its own representative point (area lights): evaluated
        // with the base's roughness and with the coat's.
        RgLightSample s = rgEvaluateLight(i, position, N, V, linearRoughness, sun);
        RgLightSample c = rgEvaluateLight(i, position, N, V, coatRoughness, sun);
        vec3 H = rgSafeNormalize(V + c.Ls, N);
        float NdotL = clamp(dot(N, c.Ls), 0.0, 1.0);
        float NdotH = clamp(dot(N, H), 0.0, 1.0);
        float LdotH = clamp(dot(c.Ls, H), 0.0, 1.0);
        float Fc = F_Schlick(0.04, 1.0, LdotH) * coatStrength;
        float coat = D_GGX(NdotH, coatAlpha) * V_SmithGGXCorrelated(NdotL, NdotV, coatAlpha) * Fc / RG_PI * NdotL;
        vec3 base = rgStandardLighting(s, N, V, diffuseColor, f0, linearRoughness);
        luminance += base * (1.0 - Fc) + vec3(coat) * c.specularIlluminance * c.specularNormalisation;
    }
#ifdef RG_IBL
    // The distant probe, both lobes: the base attenuated by the coat's Fresnel at the view angle,
    // the coat's own split-sum lobe (f0 0.04, f90 1) with its specular occlusion.
    float FcView = F_Schlick(0.04, 1.0, NdotV) * coatStrength;
    float ao = rgAmbientOcclusion(g.ao);
    RgIbl coatIbl = rgEvaluateIbl(position, N, V, vec3(0.04), 1.0, coatRoughness);
    luminance += rgStandardIbl(position, N, V, diffuseColor, f0, linearRoughness, ao) * (1.0 - FcView) +
                 coatIbl.specular * coatStrength * rgSpecularOcclusion(NdotV, ao, coatRoughness * coatRoughness);
#endif
    color = vec4(luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}
