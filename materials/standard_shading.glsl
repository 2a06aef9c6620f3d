// Shading of the standard lighting path (seed 000 §3.1, §4): the Disney diffuse and GGX specular
// of every light (shaders/lib/lighting.glsl: punctual, sun and area lights; the diffuse lobe from
// the light's illuminance, the specular lobe from its representative point), the probes
// (lib/ibl.glsl, with RG_IBL / RG_PROBES / RG_REFLECTION) and emissive, as absolute luminance.
// One function for both halves of the render loop (fig:14): the deferred lighting pass
// (shaders/passes/deferred_lighting.frag) calls it on the unpacked G-buffer, the forward pass on the
// material's own surface function's output (rgraph generates that shader from the lighting path's
// `shading`). `pixel` finds the tile's lights (RG_LIGHT_TILES) and the screen-space terms.
vec3 rgShade(GBuffer_disney g, vec3 position, vec3 V, ivec2 pixel) {
    // §3.2.1: metals take their f0 from the base colour, dielectrics 0.16 · reflectance².
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;
    // GB2's reserved channel: 1 where GB3 holds radiosity alone — the baked lightmap's on a surface
    // without emission of its own (materials/standard.glsl), or the distant probe's diffuse a
    // fix-up wrote (seed 000 lst:3, materials/foliage): that pixel gets no second probe diffuse,
    // and its radiosity is occluded as the probe's would be, by min(material AO, SSAO) (seed 002
    // §4.10.3). GB3's radiosity already carries the material's AO (lib/lightmap.glsl; foliage's
    // is 1), so it is scaled by min(material AO, SSAO) / material AO.
    float ao = rgAmbientOcclusion(g.ao, position);
    bool radiosity = g.reserved > 0.5;
    vec3 luminance = radiosity ? g.emissive * (ao / max(g.ao, 1e-3)) : g.emissive;
    RgLightList list = rgLightList(pixel);  // the tile's lights (lib/light_tiles.glsl); every light without tiles
    float sun = rgSunVisibility(position, g.normal);  // the sun's shadow (RG_SHADOWS), once
#if defined(RG_LIGHT_TILES) && defined(RG_SCENE_GLOBAL_LIGHTS)
    // The lights that reach every pixel, known per scene with their types (passes/shader_program.cpp):
    // unrolled, each read at a constant index from the uniform window (lib/lighting.glsl's
    // rgGlobalLight: one load on a CPU rasteriser, not one per pixel) and evaluated with only its
    // type's branch; then the tile's lights with only the ranged types.
    const uint globalLights[] = uint[](RG_SCENE_GLOBAL_LIGHT_INDICES);
    const uint globalTypes[] = uint[](RG_SCENE_GLOBAL_LIGHT_TYPE_LIST);
    for (int k = 0; k < RG_SCENE_GLOBAL_LIGHTS; ++k) {
        RgLightSample s = rgEvaluateLightOf(rgGlobalLight(globalLights[k]), globalLights[k], 1u << globalTypes[k], position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, diffuseColor, f0, linearRoughness);
    }
#if RG_SCENE_TILE_LIGHT_TYPES != 0  // 0: every light is unrolled above, the tiles' lists hold nothing more
    for (uint k = list.global; k < list.count; ++k) {
        RgLightSample s = rgEvaluateLightOf(rgListLight(list, k), uint(RG_SCENE_TILE_LIGHT_TYPES), position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, diffuseColor, f0, linearRoughness);
    }
#endif
#else
    for (uint k = 0u; k < list.count; ++k) {
        uint i = rgListLight(list, k);
        RgLightSample s = rgEvaluateLight(i, position, g.normal, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, g.normal, V, diffuseColor, f0, linearRoughness);
    }
#endif
    luminance += rgStandardIbl(position, g.normal, V, radiosity ? vec3(0.0) : diffuseColor, f0, linearRoughness, ao);  // the probes (RG_IBL, RG_PROBES)
    return luminance;
}
