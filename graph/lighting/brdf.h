// The Frostbite standard BRDF on the CPU (seed 000 §3.1): the C++ twin of shaders/lib/brdf.glsl —
// same names, same float arithmetic, same clamps — so tests and tools can evaluate exactly what the
// shaders evaluate. Plus numerical integration of it: directional (hemispherical-directional)
// albedo ρ(v) = ∫ f(v, l) ⟨n·l⟩ dl (seed 000 eq:6), the white-furnace quantity of Figure 9.
//
// Conventions (seed 000 §3.2.1): linearRoughness = 1 − smoothness (perceptually linear),
// alpha = linearRoughness². Angles are given as cosines; vectors are unit length. The BRDF is in
// 1/sr; times illuminance (lux) it gives luminance (cd/m²). Pure functions, thread-safe.
#pragma once

#include <functional>

#include <glm/vec3.hpp>

namespace rg::brdf {

// RG_PI of brdf.glsl (the GLSL literal, rounded to float).
inline constexpr float kPi = 3.14159265358979f;

// lst:2 — Schlick's Fresnel with an explicit f90: f0 + (f90 − f0) max(1 − u, 0)^5, u = cos of the
// angle between the light (or view) and the half vector (may exceed 1 by lst:2's 1e-5).
glm::vec3 F_Schlick(glm::vec3 f0, float f90, float u);
float F_Schlick(float f0, float f90, float u);

// lst:1 — Disney diffuse with Frostbite's energy renormalisation (bias 0 → 0.5, factor 1 → 1/1.51
// with linearRoughness). Without the 1/π: the diffuse BRDF is Fr_DisneyDiffuse(...) / π.
float Fr_DisneyDiffuse(float NdotV, float NdotL, float LdotH, float linearRoughness);

// lst:2 — height-correlated Smith masking-shadowing G₂ divided by 4·NdotL·NdotV ("visibility").
float V_SmithGGXCorrelated(float NdotL, float NdotV, float alphaG);

// lst:2 — GGX / Trowbridge-Reitz distribution WITHOUT its 1/π (the caller divides by π).
float D_GGX(float NdotH, float alpha);

// §3.2.1 — f0 of a dielectric from the reflectance parameter: 0.16 · reflectance² (0.5 → 4 %).
float rgDielectricF0(float reflectance);

// The two values rgStandardBrdf derives inline, named so the integrators below use the same ones:
// alpha = max(linearRoughness², 1e-3) (a perfect mirror has no highlight of finite size) and the
// specular micro-occlusion f90 = clamp(50 · dot(f0, 0.33), 0, 1) (seed 002 §4.10.2).
float standardAlpha(float linearRoughness);
float standardF90(glm::vec3 f0);

// The standard material's BRDF times NdotL for one light direction, diffuse + specular: the factor
// that multiplies the light's illuminance (lux, perpendicular to the light) to give luminance.
// Mirrors rgStandardBrdf of brdf.glsl line for line (NdotV = |n·v| + 1e-5, lst:2).
glm::vec3 rgStandardBrdf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                         glm::vec3 f0, float linearRoughness);

// ---- Numerical integration (tests, tools, documentation; not for per-pixel use) ----------------

// Sampling GGX's distribution of visible normals (Heitz 2018) for a unit view v (tangent frame,
// n = +z) and alpha: halfVector(u1, u2) maps a point of the unit square to a half vector h (the
// hemisphere configuration: the view stretched by alpha, a disk sample warped onto the projected
// half of the visible hemisphere); the light l = reflect(−v, h) then has the density
// pdf(l) = G₁(v) D(h)/π / (4 NdotV), and f·⟨n·l⟩/pdf = F · G₂/G₁(v) — bounded, which keeps grazing
// views and rough lobes low-variance. g1 = G₁(v) = 1 / (1 + Λ(v)).
struct VisibleNormals {
    double a;
    glm::dvec3 v, vh, t1, t2;
    double g1;
    VisibleNormals(const glm::dvec3& view, double alpha);
    glm::dvec3 halfVector(double u1, double u2) const;
    double pdf(const glm::dvec3& l) const;
};

// Directional albedo of the specular lobe, ∫ D/π · F · V ⟨n·l⟩ dl, for a view at NdotV (0..1],
// alpha = standardAlpha(linearRoughness) and Schlick's F(f0, f90). Estimated by importance
// sampling the GGX distribution of half vectors on a deterministic samples × samples stratified
// grid (cell midpoints), so the result is reproducible. Single scattering only: at high roughness
// it loses energy (the multiple-bounce part is missing), as the seed's Figure 9 shows.
double specularAlbedo(float NdotV, float linearRoughness, float f0, float f90, int samples = 128);

// Directional albedo of the renormalised Disney diffuse, ∫ Fr_DisneyDiffuse/π ⟨n·l⟩ dl, for a white
// diffuse colour. Cosine-weighted stratified grid of samples × samples directions.
double diffuseAlbedo(float NdotV, float linearRoughness, int samples = 128);

// The sheen lobe (shaders/lib/brdf.glsl, glTF KHR_materials_sheen): Estevez and Kulla's "Charlie"
// distribution with α = max(sheenRoughness², 1e-3) and Neubelt and Pettineo's visibility; their
// product is the lobe's BRDF for a white sheen colour.
double sheenBrdf(double NdotH, double NdotL, double NdotV, double sheenRoughness);

// Directional albedo of the sheen lobe, ∫ sheenBrdf ⟨n·l⟩ dl, for a view at NdotV: the DFG
// table's w (shaders/ibl/dfg.comp). Brute force over an equal-area grid of cells × 4·cells
// directions (integrateHemisphere): independent of the table's cosine-distributed samples.
double sheenAlbedo(float NdotV, float sheenRoughness, int cells = 256);

// Directional albedo of the standard BRDF for a grey material — what rgStandardBrdf integrates to:
// diffuseColor · diffuseAlbedo + specularAlbedo with f90 = standardF90(f0) (eq:6, Figure 9 (c)).
double standardAlbedo(float NdotV, float linearRoughness, float diffuseColor, float f0,
                      int samples = 128);

// ∫ f(l) dω over the upper hemisphere (z > 0, the normal is +z) by the midpoint rule on an
// equal-area grid of cosThetaCells × phiCells cells (cos θ and φ uniform). Brute force, no
// importance: good for smooth integrands, and as an independent check of the estimators above.
double integrateHemisphere(const std::function<double(const glm::dvec3& l)>& f, int cosThetaCells,
                           int phiCells);

}  // namespace rg::brdf
