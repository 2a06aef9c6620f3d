// Surface function of the sheen material (materials/sheen.lua): the sampled surface's base colour,
// smoothness, metal mask and AO, and the sheen's colour and roughness — the params sheenColorR/G/B
// and sheenRoughnessFactor times the material's own textures sheenColorMap (RGB) and sheenRoughnessMap
// (A), white without them.
GBuffer_sheen rgSurface(RgSurface s) {
    GBuffer_sheen g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.spare = 0u;
    g.baseColor = s.baseColor;
    g.sheenRoughness = clamp(sheenRoughnessFactor * sheenRoughnessMap(s).a, 0.0, 1.0);
    g.sheenColor = clamp(vec3(sheenColorR, sheenColorG, sheenColorB) * sheenColorMap(s).rgb, 0.0, 1.0);
    g.ao = s.ao;
    g.emissive = s.emissive;
    g.metalMask = s.metalMask;
    return g;
}
