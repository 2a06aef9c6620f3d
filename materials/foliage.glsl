// Foliage surface: only what GB0 and GB1 hold is meaningful (normal, smoothness, materialId,
// base colour); the material fills those two targets and the fix-up pass writes the rest.
GBuffer_disney rgSurface(RgSurface s) {
    GBuffer_disney g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.materialId = RG_MATERIAL_ID;
    g.baseColor = s.baseColor;
    g.materialData = 0u;
    g.normalExtra = 0u;
    g.reserved = 0.0;
    g.metalMask = 0.0;
    g.reflectance = 0.0;
    g.ao = 1.0;
    g.emissive = vec3(0.0);
    return g;
}
