// The Frostbite BRDF (seed 000 §3.1): renormalised Disney diffuse (lst:1), GGX distribution,
// height-correlated Smith visibility and Schlick's Fresnel with f90 (lst:2). The same functions
// are in C++ (graph/lighting/brdf.h) for tests. Roughness conventions (§3.2.1):
// linearRoughness = 1 − smoothness (perceptually linear), alpha = linearRoughness².
#ifndef RG_BRDF_GLSL
#define RG_BRDF_GLSL

#define RG_PI 3.14159265358979

// lst:2. u may exceed 1 by the 1e-5 lst:2 adds to NdotV, so the base is clamped at 0. The fifth
// power is multiplied out: pow() is exp2(5 · log2 x), two polynomial approximations on a CPU
// rasteriser, and the light loop takes three per light (−4.5 ms on the default frame's lighting).
float rgPow5(float x) {
    float x2 = x * x;
    return x2 * x2 * x;
}
vec3 F_Schlick(vec3 f0, float f90, float u) { return f0 + (f90 - f0) * rgPow5(max(1.0 - u, 0.0)); }
float F_Schlick(float f0, float f90, float u) { return f0 + (f90 - f0) * rgPow5(max(1.0 - u, 0.0)); }

// lst:1 — Disney diffuse with the energy renormalisation; divide by π for the BRDF.
float Fr_DisneyDiffuse(float NdotV, float NdotL, float LdotH, float linearRoughness) {
    float energyBias = mix(0.0, 0.5, linearRoughness);
    float energyFactor = mix(1.0, 1.0 / 1.51, linearRoughness);
    float fd90 = energyBias + 2.0 * LdotH * LdotH * linearRoughness;
    float lightScatter = F_Schlick(1.0, fd90, NdotL);
    float viewScatter = F_Schlick(1.0, fd90, NdotV);
    return lightScatter * viewScatter * energyFactor;
}

// lst:2 — height-correlated Smith G divided by 4·NdotL·NdotV.
float V_SmithGGXCorrelated(float NdotL, float NdotV, float alphaG) {
    float alphaG2 = alphaG * alphaG;
    float lambdaV = NdotL * sqrt((-NdotV * alphaG2 + NdotV) * NdotV + alphaG2);
    float lambdaL = NdotV * sqrt((-NdotL * alphaG2 + NdotL) * NdotL + alphaG2);
    return 0.5 / (lambdaV + lambdaL);
}

// lst:2 — GGX normal distribution without its 1/π.
float D_GGX(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float f = (NdotH * a2 - NdotH) * NdotH + 1.0;
    return a2 / (f * f);
}

// The sheen lobe (glTF KHR_materials_sheen; the seeds have no cloth model): Estevez and Kulla's
// "Charlie" distribution, D(h) = (2 + 1/α) sin(θh)^(1/α) / 2π with α = sheenRoughness², and
// Neubelt and Pettineo's visibility 1 / (4 (NdotL + NdotV − NdotL·NdotV)); the lobe's BRDF is
// their product (no Fresnel: the sheen colour is its reflectance). sin² is floored so the power of
// a near-zero base stays finite.
float rgSheenAlpha(float sheenRoughness) { return max(sheenRoughness * sheenRoughness, 1e-3); }
float D_Charlie(float NdotH, float alpha) {
    float sin2h = max(1.0 - NdotH * NdotH, 1.0 / 128.0);
    return (2.0 + 1.0 / alpha) * pow(sin2h, 0.5 / alpha) / (2.0 * RG_PI);
}
float V_Neubelt(float NdotL, float NdotV) { return 1.0 / (4.0 * max(NdotL + NdotV - NdotL * NdotV, 1e-4)); }
// The sheen lobe for one direction (its BRDF, before ⟨n·l⟩), and what it leaves the base beneath:
// 1 − max(sheen colour) · E, E its directional albedo at the view (clamped: E exceeds 1 at grazing
// views of the smoothest sheens). Shared by materials/sheen_shading.glsl and passes/reference.comp.
vec3 rgSheenBrdf(vec3 sheenColor, float NdotH, float NdotL, float NdotV, float alpha) {
    return sheenColor * D_Charlie(NdotH, alpha) * V_Neubelt(NdotL, NdotV);
}
float rgSheenScaling(vec3 sheenColor, float albedo) {
    return clamp(1.0 - max(sheenColor.r, max(sheenColor.g, sheenColor.b)) * albedo, 0.0, 1.0);
}

// f0 of a dielectric from Frostbite's reflectance parameter: 0.16 · reflectance² (§3.2.1).
float rgDielectricF0(float reflectance) { return 0.16 * reflectance * reflectance; }

// The standard material's BRDF times NdotL for one light direction: diffuse + specular.
// Returns the factor that multiplies the light's illuminance (lux) to give luminance.
// Specular micro-occlusion (seed 002 §4.10.2, Schüler): f0 below 2 % darkens f90.
float rgF90(vec3 f0) { return clamp(50.0 * dot(f0, vec3(0.33)), 0.0, 1.0); }

vec3 rgStandardBrdf(vec3 N, vec3 V, vec3 L, vec3 diffuseColor, vec3 f0, float linearRoughness) {
    float NdotV = abs(dot(N, V)) + 1e-5;  // lst:2: avoids artefacts at grazing view angles
    vec3 H = normalize(V + L);
    float LdotH = clamp(dot(L, H), 0.0, 1.0);
    float NdotH = clamp(dot(N, H), 0.0, 1.0);
    float NdotL = clamp(dot(N, L), 0.0, 1.0);
    float alpha = max(linearRoughness * linearRoughness, 1e-3);  // a perfect mirror has no highlight of finite size
    float f90 = rgF90(f0);
    vec3 F = F_Schlick(f0, f90, LdotH);
    float Vis = V_SmithGGXCorrelated(NdotL, NdotV, alpha);
    float D = D_GGX(NdotH, alpha);
    vec3 Fr = D * F * Vis / RG_PI;
    float Fd = Fr_DisneyDiffuse(NdotV, NdotL, LdotH, linearRoughness) / RG_PI;
    return (diffuseColor * Fd + Fr) * NdotL;
}

#endif
