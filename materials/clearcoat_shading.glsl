// Shading of the clear-coat path: for each light, the base (the standard BRDF) attenuated by
// the coat's Fresnel, plus the coat's own GGX lobe (f0 = 0.04, an IOR of 1.5; roughness from
// coatSmoothness, in the disney layout's spare GB2.r; strength in MaterialData). The lights are
// evaluated for both lobes: "lit twice" (seed 000 §3.2.2). Deferred
// (materials/clearcoat_lighting.frag) and forward.
vec3 rgShade(GBuffer_disney g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    float coatStrength = float(g.materialData) / 31.0;
    float coatRoughness = 1.0 - g.reserved;
    float coatAlpha = max(coatRoughness * coatRoughness, 1e-3);
    float NdotV = abs(dot(N, V)) + 1e-5;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);  // the tile's lights (lib/light_tiles.glsl)
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
    float ao = rgAmbientOcclusion(g.ao, position);
    RgIbl coatIbl = rgEvaluateIbl(position, N, V, vec3(0.04), 1.0, coatRoughness);
    luminance += rgStandardIbl(position, N, V, diffuseColor, f0, linearRoughness, ao) * (1.0 - FcView) +
                 coatIbl.specular * coatStrength * rgSpecularOcclusion(NdotV, ao, coatRoughness * coatRoughness);
#endif
    return luminance;
}
