// Surface function of the standard (Disney) base material, seed 000 §3.2.1: the sampled surface
// into the `disney` G-buffer layout (tbl:2). rgraph includes this in the generated G-buffer
// shader of every material declared with surface = "materials/standard.glsl".
GBuffer_disney rgSurface(RgSurface s) {
    GBuffer_disney g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.materialId = RG_MATERIAL_ID;
    g.baseColor = s.baseColor;
    g.materialData = 0u;
    g.normalExtra = 0u;
    g.reserved = s.radiosity;  // 1: GB3 holds the lightmap's radiosity alone (AO-occluded)
    g.metalMask = s.metalMask;
    g.reflectance = s.reflectance;
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
