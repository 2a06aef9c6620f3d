// Shading of the two-colour path (seed 000 tbl:3, fig:14): the `two_colour` G-buffer's diffuse
// colour and f0 colour, as stored, through the standard BRDF, light loop and probes
// (materials/standard_shading.glsl's). Deferred (materials/two_colour_lighting.frag) and forward.
vec3 rgShade(GBuffer_two_colour g, vec3 position, vec3 V, ivec2 pixel) {
    float linearRoughness = 1.0 - g.smoothness;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);
    float sun = rgSunVisibility(position, g.normal);  // the sun's shadow (RG_SHADOWS), once
    for (uint k = 0u; k < list.count; ++k) {
        RgLightSample s = rgEvaluateLight(rgListLight(list, k), position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, g.diffuseColor, g.f0, linearRoughness);
    }
    luminance += rgStandardIbl(position, g.normal, V, g.diffuseColor, g.f0, linearRoughness, rgAmbientOcclusion(g.ao, position));  // the probes (RG_IBL, RG_REFLECTION)
    return luminance;
}
