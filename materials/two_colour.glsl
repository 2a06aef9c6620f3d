// Surface function of the two-colour base material (seed 000 tbl:3): the sampled surface's diffuse
// and f0 colours into the `two_colour` layout (materials/two_colour.lua). Its own texture
// specularGlossinessMap (glTF's specularGlossinessTexture: RGB the specular colour, sRGB; A the
// glossiness) multiplies f0 and the smoothness (white, nothing, without one).
GBuffer_two_colour rgSurface(RgSurface s) {
    vec4 specularGlossiness = specularGlossinessMap(s);
    GBuffer_two_colour g;
    g.normal = s.normal;
    g.smoothness = s.smoothness * specularGlossiness.a;
    g.materialId = RG_MATERIAL_ID;
    g.diffuseColor = s.diffuseColor;
    g.materialData = 0u;
    g.normalExtra = 0u;
    g.f0 = s.f0 * specularGlossiness.rgb;
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
