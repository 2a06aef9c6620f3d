// Shading of the clear-coat path: for each light, the base (the standard BRDF, f0 4 % or a metal's
// base colour) attenuated by the coat's Fresnel, plus the coat's own GGX lobe (f0 = 0.04, an IOR of
// 1.5; strength, smoothness and normal from the clearcoat layout, materials/clearcoat.lua) about
// the coat's normal. The lights are evaluated for both lobes: "lit twice" (seed 000 §3.2.2), each
// with its own normal and roughness. Deferred (the generated lighting_path_clearcoat.frag) and
// forward.
vec3 rgShade(GBuffer_clearcoat g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    vec3 Nc = g.coatNormal;
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(0.5)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    float coatStrength = g.coatWeight;
    float coatRoughness = 1.0 - g.coatGloss;
    float coatAlpha = max(coatRoughness * coatRoughness, 1e-3);
    float NcdotV = abs(dot(Nc, V)) + 1e-5;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);  // the tile's lights (lib/light_tiles.glsl)
    float sun = rgSunVisibility(position, N);  // the sun's shadow (RG_SHADOWS), once for both lobes
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        // Each lobe sees the light from its own representative point (area lights): evaluated
        // with the base's normal and roughness and with the coat's.
        RgLightSample s = rgEvaluateLight(i, position, N, V, linearRoughness, sun);
        RgLightSample c = rgEvaluateLight(i, position, Nc, V, coatRoughness, sun);
        vec3 H = rgSafeNormalize(V + c.Ls, Nc);
        float NdotL = clamp(dot(Nc, c.Ls), 0.0, 1.0);
        float NdotH = clamp(dot(Nc, H), 0.0, 1.0);
        float LdotH = clamp(dot(c.Ls, H), 0.0, 1.0);
        float Fc = F_Schlick(0.04, 1.0, LdotH) * coatStrength;
        float coat = D_GGX(NdotH, coatAlpha) * V_SmithGGXCorrelated(NdotL, NcdotV, coatAlpha) * Fc / RG_PI * NdotL;
        vec3 base = rgStandardLighting(s, N, V, diffuseColor, f0, linearRoughness);
        luminance += base * (1.0 - Fc) + vec3(coat) * c.specularIlluminance * c.specularNormalisation;
    }
#ifdef RG_IBL
    // The distant probe, both lobes: the base attenuated by the coat's Fresnel at the view angle,
    // the coat's own split-sum lobe (f0 0.04, f90 1) with its specular occlusion.
    float FcView = F_Schlick(0.04, 1.0, NcdotV) * coatStrength;
    float ao = rgAmbientOcclusion(g.ao, position);
    RgIbl coatIbl = rgEvaluateIbl(position, Nc, V, vec3(0.04), 1.0, coatRoughness);
    luminance += rgStandardIbl(position, N, V, diffuseColor, f0, linearRoughness, ao) * (1.0 - FcView) +
                 coatIbl.specular * coatStrength * rgSpecularOcclusion(NcdotV, ao, coatRoughness * coatRoughness);
#endif
    return luminance;
}
