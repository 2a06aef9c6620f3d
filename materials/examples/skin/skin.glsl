// Surface function of the skin material: the sampled surface's base colour, smoothness and AO,
// and the material's scatter colour (scatterR/G/B: material.custom slots) into the layout.
GBuffer_skin rgSurface(RgSurface s) {
    GBuffer_skin g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.spare = 0u;
    g.baseColor = s.baseColor;
    g.unused = 0u;
    g.scatter = clamp(vec3(scatterR, scatterG, scatterB), 0.0, 1.0);
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
