// Shading of the sheen path (materials/sheen.lua): per light, the standard BRDF of the base scaled
// by 1 − max(sheen colour) · E(N·V), plus the sheen lobe — sheen colour × D_Charlie × V_Neubelt
// (lib/brdf.glsl) from the light's diffuse direction and illuminance (a broad lobe, lit as the
// diffuse one is: the cosine and the horizon in the illuminance); the probes the same way, the
// sheen lit by the distant probe's irradiance / π times E (exact for a uniform environment: E is
// the lobe's albedo). E is the DFG table's w (rgSheenAlbedo), so without RG_IBL the base is not
// scaled. Deferred (the generated lighting_path_sheen.frag) and forward.
vec3 rgShade(GBuffer_sheen g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(0.5)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    float sheenAlpha = rgSheenAlpha(g.sheenRoughness);
    float NdotV = clamp(dot(N, V), 1e-4, 1.0);
    // What the sheen takes from the base.
    float scaling = rgSheenScaling(g.sheenColor, rgSheenAlbedo(NdotV, g.sheenRoughness));
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);  // the tile's lights (lib/light_tiles.glsl)
    float sun = rgSunVisibility(position, N);  // the sun's shadow (RG_SHADOWS), once
    for (uint k = 0u; k < list.count; ++k) {
        RgLightSample s = rgEvaluateLight(rgListLight(list, k), position, N, V, linearRoughness, sun);
        vec3 H = rgSafeNormalize(V + s.Ld, N);
        float NdotL = clamp(dot(N, s.Ld), 0.0, 1.0);
        vec3 sheen = rgSheenBrdf(g.sheenColor, clamp(dot(N, H), 0.0, 1.0), NdotL, NdotV, sheenAlpha);
        luminance += rgStandardLighting(s, N, V, diffuseColor, f0, linearRoughness) * scaling +
                     sheen * s.diffuseIlluminance;
    }
    float ao = rgAmbientOcclusion(g.ao, position);
    luminance += rgStandardIbl(position, N, V, diffuseColor, f0, linearRoughness, ao) * scaling;  // the probes (RG_IBL, RG_REFLECTION)
#if defined(RG_IBL) && !(defined(RG_SCENE_LIGHTMAP) && RG_SCENE_LIGHTMAP)
    luminance += g.sheenColor * rgSheenAlbedo(NdotV, g.sheenRoughness) * rgShIrradiance(rgEnvSh.coefficients, N) / RG_PI * ao;
#endif
    return luminance;
}
