// Shading of the transmission path (materials/transmission.lua), forward only: per light and from
// the probes, the standard BRDF with the diffuse colour scaled by 1 − transmission; then the light
// from behind, transmission × (1 − the specular lobe's split-sum albedo, f0 DFG.x + f90 DFG.y) ×
// base colour × the volume's transmittance × the opaque frame's radiance where the refracted view
// ray leaves the volume. As the glTF sample viewer does it (KHR_materials_volume's "thickness" is
// the distance the ray travels inside): the exit point is P + refract(−V, N, 1/η) · thickness,
// projected with this frame's camera, read at mip log2(the frame's larger side) · linear roughness ·
// clamp(2η − 2, 0, 1) (a rough surface blurs what lies behind it, less so as η nears 1). The IOR η
// is the reflectance's: f0 = 0.16 · reflectance² = ((η − 1)/(η + 1))² (so at most 2.33, and
// KHR_materials_specular's factor, which scales f0, changes it too).
//
// The opaque frame holds luminance × this frame's pre-exposure (the HDR it copies): divided back
// here. Without it (RG_OPAQUE: the scene draws no transmission material, or a pass that does not
// read `opaque`) nothing is seen through the surface.
#ifdef RG_OPAQUE
#ifndef RG_OPAQUE_BINDING
#define RG_OPAQUE_BINDING 40
#endif
layout(set = 0, binding = RG_OPAQUE_BINDING) uniform sampler2D opaque;
#endif

// η of a dielectric of Frostbite reflectance r (seed 000 §3.2.1: f0 = 0.16 r²).
float rgIorOfReflectance(float reflectance) {
    float s = sqrt(clamp(rgDielectricF0(reflectance), 0.0, 0.99));
    return (1.0 + s) / (1.0 - s);
}

// The radiance (cd/m²) arriving from behind along the refracted view ray.
vec3 rgTransmittedRadiance(GBuffer_transmission g, vec3 position, vec3 N, vec3 V, float linearRoughness) {
#ifdef RG_OPAQUE
    float ior = rgIorOfReflectance(g.reflectance);
    vec3 exitPoint = position + refract(-V, N, 1.0 / ior) * g.thickness;
    vec4 clip = camera.viewProj * vec4(exitPoint, 1.0);
    // An exit point behind the eye (a thick volume at the near plane) has no place on screen: the
    // pixel's own.
    vec2 uv = clip.w > 1e-6 ? clip.xy / clip.w * 0.5 + 0.5 : gl_FragCoord.xy * camera.viewport.zw;
    float lod = log2(float(max(textureSize(opaque, 0).x, textureSize(opaque, 0).y))) * linearRoughness *
                clamp(2.0 * ior - 2.0, 0.0, 1.0);
    return textureLod(opaque, uv, lod).rgb / rgPreExposure(ex.state, params.initial_ev100);
#else
    return vec3(0.0);
#endif
}

vec3 rgShade(GBuffer_transmission g, vec3 position, vec3 V, ivec2 pixel) {
    vec3 N = g.normal;
    float linearRoughness = 1.0 - g.smoothness;
    float transmission = g.transmission * (1.0 - g.metalMask);  // a metal transmits nothing
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask) * (1.0 - g.transmission);
    vec3 luminance = g.emissive;
    RgLightList list = rgLightList(pixel);  // the froxel's lights (lib/light_tiles.glsl)
    float sun = rgSunVisibility(position, N);  // the sun's shadow (RG_SHADOWS), once
    for (uint k = 0u; k < list.count; ++k) {
        RgLightSample s = rgEvaluateLight(rgListLight(list, k), position, N, V, linearRoughness, sun);
        luminance += rgStandardLighting(s, N, V, diffuseColor, f0, linearRoughness);
    }
    luminance += rgStandardIbl(position, N, V, diffuseColor, f0, linearRoughness, 1.0);  // the probes (RG_IBL)
    if (transmission > 0.0) {
        float NdotV = clamp(dot(N, V), 1e-4, 1.0);
        vec3 dfgTerms = rgDfg(NdotV, linearRoughness);  // 0 without the table (RG_IBL)
        float f90 = rgF90(f0);  // as rgStandardIbl
        vec3 reflected = f0 * dfgTerms.x + f90 * dfgTerms.y;
        luminance += transmission * (1.0 - reflected) * g.baseColor * g.volumeColor *
                     rgTransmittedRadiance(g, position, N, V, linearRoughness);
    }
    return luminance;
}
