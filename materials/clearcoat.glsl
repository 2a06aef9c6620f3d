// Clear-coat surface: the standard base plus the coat's parameters in the spare channels of the
// disney layout (coatSmoothness and coatStrength come from the material's params, generated as
// material.custom slots).
GBuffer_disney rgSurface(RgSurface s) {
    GBuffer_disney g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.materialId = RG_MATERIAL_ID;
    g.baseColor = s.baseColor;
    g.materialData = uint(clamp(coatStrength, 0.0, 1.0) * 31.0 + 0.5);  // 5 bits
    g.normalExtra = 0u;
    g.reserved = clamp(coatSmoothness, 0.0, 1.0);
    g.metalMask = s.metalMask;
    g.reflectance = s.reflectance;
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
