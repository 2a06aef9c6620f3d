// The surface function of m_decal_fourth_target.lua's material.
GBuffer_glow rgSurface(RgSurface s) {
    GBuffer_glow g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.materialId = RG_MATERIAL_ID;
    g.albedo = s.baseColor;
    return g;
}
