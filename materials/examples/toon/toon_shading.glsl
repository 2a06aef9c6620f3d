// Shading of the toon path, deferred (toon_lighting.frag) and forward (rgraph generates that
// shader from this function): per light, the illuminance E⊥ it delivers facing it, times the
// wrapped cosine w(c) = clamp((c + wrap) / (1 + wrap), 0, 1) cut into `steps` bands
// (ceil(w · steps) / steps), through a Lambert tint; a rim (1 − N·V)⁴ · rim of the same light;
// the distant probe's diffuse as ambient; emissive. Absolute luminance (nits). The wrapped band
// past the terminator takes the other lights, not the sun: rgSunVisibility is 0 where the
// surface faces away from it (the surface occludes it).
vec3 rgShade(GBuffer_toon g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    vec3 luminance = g.emissive;
    float steps = float(max(g.steps, 1u));
    float rim = g.rim * pow(1.0 - clamp(dot(N, V), 0.0, 1.0), 4.0);
    RgLightList list = rgLightList(pixel);
    float sun = rgSunVisibility(position, N);
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        // The light's direction and its illuminance on a surface facing it (the light evaluated
        // for the normal that faces it), shadowed as the standard path's.
        RgLightSample s = rgEvaluateLight(i, position, N, V, 1.0, sun);
        RgLightSample f = rgEvaluateLight(i, position, s.Ld, V, 1.0, sun);
        float w = clamp((dot(N, s.Ld) + g.wrap) / (1.0 + g.wrap), 0.0, 1.0);
        float band = ceil(w * steps) / steps;
        luminance += g.tint / RG_PI * f.diffuseIlluminance * (band + rim * step(0.0, w - 1e-4));
    }
    luminance += rgStandardIbl(position, N, V, g.tint, vec3(0.0), 1.0, rgAmbientOcclusion(g.ao, position));  // ambient: no specular
    return luminance;
}
