// Shading of the skin path, deferred and forward (rgraph generates both shaders from it). Light
// that enters skin leaves it further on, red furthest: the diffuse response to a light at cosine
// c = N·L is, per colour channel, the cosine raised to a power p ≤ 1 and normalised,
//     R(c) = (p + 1) / 2 · c^p,   p = 1 − 0.75 · scatter,
// so that over the hemisphere it gathers what Lambert's c does (∫ R dω = π for every p: a white
// furnace stays white) while a smaller p moves light from where the surface faces the light to
// near the terminator. It still ends at c = 0, where the sun's mask ends the sun (rgSunVisibility
// is 0 facing away): no light wraps into the shadow the surface casts on itself. Specular: one GGX
// lobe at f0 = 0.028 (skin's reflectance, n ≈ 1.4). Ambient: the distant probe, as the standard
// path. Absolute luminance (nits). An example of a path's shading function, not a seed's model.
vec3 rgShade(GBuffer_skin g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    float linearRoughness = 1.0 - g.smoothness;
    const vec3 f0 = vec3(0.028);
    vec3 p = 1.0 - 0.75 * g.scatter;
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);
    float sun = rgSunVisibility(position, N);
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        RgLightSample s = rgEvaluateLight(i, position, N, V, linearRoughness, sun);
        // The illuminance on a surface facing the light (E⊥), shadowed as at the pixel.
        RgLightSample facing = rgEvaluateLight(i, position, s.Ld, V, 1.0, sun);
        float c = clamp(dot(N, s.Ld), 0.0, 1.0);
        vec3 response = 0.5 * (p + 1.0) * pow(vec3(c), p);
        luminance += g.baseColor / RG_PI * facing.diffuseIlluminance * response;
        luminance += rgStandardLighting(s, N, V, vec3(0.0), f0, linearRoughness);  // the specular lobe
    }
    luminance += rgStandardIbl(position, N, V, g.baseColor, f0, linearRoughness, rgAmbientOcclusion(g.ao, position));
    return luminance;
}
