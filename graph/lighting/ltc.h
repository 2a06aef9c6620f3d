// Linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light
// Shading with Linearly Transformed Cosines"; Heitz & Hill 2017 for disks and spheres): the GGX
// lobe of the standard BRDF (seed 000 lst:2, with F = 1) times ⟨n·l⟩ approximated, per roughness
// and view angle, by a clamped cosine Do(ω) = max(ω.z, 0)/π seen through a 3×3 matrix M:
//   D(ω) = Do(ω_o) · |det M⁻¹| / |M⁻¹ω|³,  ω_o = M⁻¹ω / |M⁻¹ω|.
// The integral of D over a light's solid angle is the integral of Do over the light transformed by
// M⁻¹ — a polygon's or an ellipse's cosine-weighted form factor, which has a closed form. Horizon
// clipping falls out: Do is 0 below its horizon. The diffuse lobe uses M = identity: the exact
// form factor (shaders/lib/lighting.glsl multiplies it by the Disney diffuse at its mean direction).
//
// This file holds the table (fitted by tools/ltc_fit.cpp, committed as ltc_ggx.inc), its lookup,
// the fitting itself, and the CPU twins of shaders/lib/ltc.glsl's integrals, for tests and tools.
//
// Table layout: kSize × kSize entries over x = linearRoughness (column, 0..1) and
// y = sqrt(1 − ⟨n·v⟩) (row, 0..1), entry [row · kSize + column]. M⁻¹ is expressed in the
// frame (T1, T2, N), T1 the view's tangent direction (V = (sin θv, 0, cos θv)); it has the form
//   M⁻¹ = [[a, 0, b], [0, 1, 0], [c, 0, d]]   (row-major; scaled so that its middle element is 1,
// which leaves D unchanged). magnitude = ∫ D_GGX/π · Vis · ⟨n·l⟩ dl (the lobe's albedo with F = 1),
// fresnel = the same weighted by (1 − ⟨v·h⟩)⁵, so that Schlick's F(f0, f90) integrates to
// f0 · (magnitude − fresnel) + f90 · fresnel.
#pragma once

#include <array>
#include <span>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace rg::ltc {

inline constexpr int kSize = 64;

struct Entry {
    std::array<float, 4> inverse{1, 0, 0, 1};  // M⁻¹'s (a, b, c, d)
    float magnitude = 0, fresnel = 0;
};

// The committed table (ltc_ggx.inc), kSize² entries.
std::span<const Entry> table();

// The table coordinates of (linearRoughness, ⟨n·v⟩), in texels (0..kSize−1), and the bilinear
// lookup of the GLSL twin (clamp to edge).
glm::vec2 tableCoordinates(float linearRoughness, float NdotV);
Entry lookup(float linearRoughness, float NdotV);
glm::mat3 inverseMatrix(const std::array<float, 4>& abcd);  // glm: column-major

// ---- The fit (tools/ltc_fit.cpp) -------------------------------------------------------------

// The lobe's moments for one cell: magnitude, fresnel (as above) and its average direction.
struct Moments {
    double magnitude = 0, fresnel = 0;
    glm::dvec3 direction{0, 0, 1};
};
Moments lobeMoments(float linearRoughness, float NdotV, int samples = 128);

struct Fit {
    Entry entry;
    double error = 0;  // the objective at the result: ∫ |D − f/magnitude| dω
    int evaluations = 0;
};
// Fits one cell by Nelder–Mead over (m00, m11, m02, δ) of M = [X Y Z] · [[m00, 0, m02], [0, m11, 0],
// [0, 0, 1]], Z the lobe's average direction turned by δ (radians, in the plane of n and v),
// starting from `start` (the previous cell's parameters; null: the isotropic α, α, 0, 0).
// `parameters` receives the fitted ones.
Fit fitCell(float linearRoughness, float NdotV, const glm::dvec4* start, glm::dvec4* parameters,
            int samples = 32);

// How far the LTC with inverse matrix `inverse` is from the lobe it stands for: ∫ |D − f/magnitude| dω,
// 0 for a perfect fit, 2 for disjoint ones (tests; rgraph-ltc-fit's report).
double fitDistance(float linearRoughness, float NdotV, const glm::mat3& inverse, int samples = 64);

// D(ω) of the LTC with inverse matrix `inverse` (ω unit length).
double distribution(const glm::dmat3& inverse, const glm::dvec3& w);

// ---- Integrals (CPU twins of lib/ltc.glsl) -----------------------------------------------------

// ∫ over the spherical polygon through `vertices` (any length; relative to the shaded point, in
// the cosine's space, not normalised) of max(ω.z, 0)/π dω — the polygon clipped to the upper
// hemisphere (Sutherland–Hodgman against z = 0), then the sum of its edges' form factors. Either
// winding. `direction` (optional) receives the unnormalised vector form factor of the clipped
// polygon (its mean direction).
float polygonIntegral(std::span<const glm::vec3> vertices, glm::vec3* direction = nullptr);

// The same for the ellipse centre + cos t · axis1 + sin t · axis2 (axes need not be orthogonal:
// any conjugate pair, as a linearly transformed disk gives): the ellipse's cone of directions as
// an elliptic cone, its form factor in closed form, and the horizon by the sphere of the same
// form factor around the cone's axis (seed 000 lst:10's exact sphere formula). `direction`
// receives the cone's axis (unit).
float ellipseIntegral(glm::vec3 centre, glm::vec3 axis1, glm::vec3 axis2,
                      glm::vec3* direction = nullptr);

// ∫ of the GGX lobe's D over the polygon `local` (in the shaded point's frame (T1, T2, N)): the
// polygon clipped to the shading horizon first, then through the table's M⁻¹ (`tableInverse`) and
// polygonIntegral. The fitted D leaks below the shading horizon, where the lobe is 0; a light
// crossing the surface's plane would get that leak as light (lib/ltc.glsl's rgLtcQuadHorizon).
float horizonPolygonIntegral(std::span<const glm::vec3> local, const glm::mat3& tableInverse,
                             glm::vec3* direction = nullptr);

// The factor on a closed-form integral that corrects the fitted cosine's shape to GGX's (lib/ltc.glsl's
// rgLtcRatio, after Heitz et al.'s 2018 ratio estimator): f(ω)⟨n·l⟩ / (magnitude · D(ω)) at the
// closed form's mean direction `mean` (cosine's space), faded to 1 as ⟨n·l⟩ or the elevation in the cosine's space there falls below 0.25. `inverse`: world → cosine's space (the
// table's M⁻¹ after the frame's rotation); N, V world; f the standard lobe with F = 1.
float lobeRatio(const glm::mat3& inverse, glm::vec3 N, glm::vec3 V, float alpha, float magnitude,
                glm::vec3 mean);

// The same correction for a sphere light, the cap of half-angle σ (sin²σ = `sinSigmaSqr`) around
// the unit direction L (lib/ltc.glsl's rgLtcSphereRatio): the lobe's integral over the cap over
// magnitude × D's, both by one quadrature of kSphereRatioTaps directions of equal solid angle on a
// golden-angle spiral; D counted above the shading horizon only. 1 where D is 0 at every tap.
inline constexpr int kSphereRatioTaps = 32;
float sphereRatio(const glm::mat3& inverse, glm::vec3 N, glm::vec3 V, float alpha, float magnitude,
                  glm::vec3 L, float sinSigmaSqr);

}  // namespace rg::ltc
