// Surface function of the transmission material (materials/transmission.lua): the standard
// surface, the transmission factor (transmissionFactor × transmissionMap's R) and the volume's
// thickness (thicknessFactor × thicknessMap's G) with its transmittance across that thickness by
// Beer–Lambert, T = attenuationColor^(thickness / attenuationDistance) (glTF KHR_materials_volume:
// the colour white light turns after travelling attenuationDistance; 0 here is its +∞).
GBuffer_transmission rgSurface(RgSurface s) {
    GBuffer_transmission g;
    g.normal = s.normal;
    g.smoothness = s.smoothness;
    g.metalMask = s.metalMask;
    g.baseColor = s.baseColor;
    g.transmission = clamp(transmissionFactor * transmissionMap(s).r, 0.0, 1.0);
    g.volumeColor = vec3(1.0);
    g.thickness = max(thicknessFactor * thicknessMap(s).g, 0.0);
    vec3 attenuation = clamp(vec3(attenuationColorR, attenuationColorG, attenuationColorB), 1e-4, 1.0);
    if (attenuationDistance > 0.0 && g.thickness > 0.0)
        g.volumeColor = pow(attenuation, vec3(g.thickness / attenuationDistance));
    g.reflectance = s.reflectance;
    g.emissive = s.emissive;
    return g;
}
