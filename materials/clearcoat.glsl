// Clear-coat surface (materials/clearcoat.lua): the standard base, and the coat — its strength
// (coatStrength × coatStrengthMap's R), smoothness (1 − (1 − coatSmoothness) × coatRoughnessMap's G)
// and normal: the vertex normal, or coatNormalMap in the surface's tangent frame, its xy times
// coatNormalScale (glTF's clearcoatNormalTexture; the base's normal map does not reach the coat).
GBuffer_clearcoat rgSurface(RgSurface s) {
    GBuffer_clearcoat g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.spare = 0u;
    g.baseColor = s.baseColor;
    g.coatWeight = clamp(coatStrength * coatStrengthMap(s).r, 0.0, 1.0);
    g.coatNormal = s.tangentFrame[2];
    if (coatNormalMap_present) {
        vec3 m = coatNormalMap(s).xyz * 2.0 - 1.0;
        m.xy *= coatNormalScale;
        g.coatNormal = normalize(s.tangentFrame * m);
    }
    g.coatGloss = clamp(1.0 - (1.0 - coatSmoothness) * coatRoughnessMap(s).g, 0.0, 1.0);
    g.metalMask = s.metalMask;
    g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
