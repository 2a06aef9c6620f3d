// Surface function of the toon material: the sampled surface's base colour as the tint, and the
// material's parameters (toonBands, toonWrap, toonRim: material.custom slots) into the layout.
GBuffer_toon rgSurface(RgSurface s) {
    GBuffer_toon g;
    g.normal = s.normal;
    g.rim = clamp(toonRim, 0.0, 1.0);
    g.materialId = RG_MATERIAL_ID;
    g.tint = s.baseColor;
    g.steps = uint(clamp(toonBands, 1.0, 31.0) + 0.5);
    g.spare = 0u;
    g.wrap = clamp(toonWrap, 0.0, 1.0);
    g.reserved = vec2(0.0);
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
