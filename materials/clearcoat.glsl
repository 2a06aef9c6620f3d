// Clear-coat surface: the standard base plus the coat's parameters in the spare channels of the
// disney layout (coatSmoothness and coatStrength come from the material's params, generated as
// material.custom slots), each times its texture where the scene material has one (glTF's
// clearcoatTexture R and clearcoatRoughnessTexture G).
GBuffer_disney rgSurface(RgSurface s) {
    float strength = coatStrength * coatStrengthMap(s).r;
    float smoothness = 1.0 - (1.0 - coatSmoothness) * coatRoughnessMap(s).g;
    GBuffer_disney g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.materialId = RG_MATERIAL_ID;
    g.baseColor = s.baseColor;
    g.materialData = uint(clamp(strength, 0.0, 1.0) * 31.0 + 0.5);  // 5 bits
    g.normalExtra = 0u;
    g.reserved = clamp(smoothness, 0.0, 1.0);
    g.metalMask = s.metalMask;
    g.reflectance = s.reflectance;
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
