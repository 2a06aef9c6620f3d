#include "brdf.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/check.h"

namespace rg::brdf {

namespace {

// GLSL's mix(x, y, a) is defined as x·(1 − a) + y·a; keep that form so float results match.
float mix(float x, float y, float a) { return x * (1.0f - a) + y * a; }
float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

constexpr double kPiD = 3.14159265358979323846;

// The view direction for a given NdotV, in the tangent frame where n = +z.
glm::dvec3 viewVector(float NdotV) {
    const double c = std::clamp(static_cast<double>(NdotV), 0.0, 1.0);
    return {std::sqrt(1.0 - c * c), 0.0, c};
}

}  // namespace

// lst:2. As in brdf.glsl, the base is clamped at 0: u exceeds 1 by the 1e-5 lst:2 adds to NdotV,
// and GLSL's pow of a negative base is undefined.
glm::vec3 F_Schlick(glm::vec3 f0, float f90, float u) {
    return f0 + (glm::vec3(f90) - f0) * std::pow(std::max(1.0f - u, 0.0f), 5.0f);
}

float F_Schlick(float f0, float f90, float u) {
    return f0 + (f90 - f0) * std::pow(std::max(1.0f - u, 0.0f), 5.0f);
}

float Fr_DisneyDiffuse(float NdotV, float NdotL, float LdotH, float linearRoughness) {
    // seed 000 lst:1: the bias keeps Disney's retro-reflection, the factor removes its energy gain.
    const float energyBias = mix(0.0f, 0.5f, linearRoughness);
    const float energyFactor = mix(1.0f, 1.0f / 1.51f, linearRoughness);
    const float fd90 = energyBias + 2.0f * LdotH * LdotH * linearRoughness;
    const float lightScatter = F_Schlick(1.0f, fd90, NdotL);
    const float viewScatter = F_Schlick(1.0f, fd90, NdotV);
    return lightScatter * viewScatter * energyFactor;
}

float V_SmithGGXCorrelated(float NdotL, float NdotV, float alphaG) {
    // seed 000 lst:2, optimised form: Λ terms premultiplied by 2·NdotL·NdotV so that
    // G₂ / (4 NdotL NdotV) = 0.5 / (λV + λL). The NdotL/NdotV crossing is intended.
    const float alphaG2 = alphaG * alphaG;
    const float lambdaV = NdotL * std::sqrt((-NdotV * alphaG2 + NdotV) * NdotV + alphaG2);
    const float lambdaL = NdotV * std::sqrt((-NdotL * alphaG2 + NdotL) * NdotL + alphaG2);
    return 0.5f / (lambdaV + lambdaL);
}

float D_GGX(float NdotH, float alpha) {
    // seed 000 lst:2, without the 1/π (applied by the caller, as in the listing).
    const float a2 = alpha * alpha;
    const float f = (NdotH * a2 - NdotH) * NdotH + 1.0f;
    return a2 / (f * f);
}

float rgDielectricF0(float reflectance) { return 0.16f * reflectance * reflectance; }  // §3.2.1

float standardAlpha(float linearRoughness) {
    return std::max(linearRoughness * linearRoughness, 1e-3f);
}

float standardF90(glm::vec3 f0) { return saturate(50.0f * glm::dot(f0, glm::vec3(0.33f))); }

glm::vec3 rgStandardBrdf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                         glm::vec3 f0, float linearRoughness) {
    const float NdotV =
        std::abs(glm::dot(N, V)) + 1e-5f;  // lst:2: avoids artefacts at grazing view angles
    const glm::vec3 H = glm::normalize(V + L);
    const float LdotH = saturate(glm::dot(L, H));
    const float NdotH = saturate(glm::dot(N, H));
    const float NdotL = saturate(glm::dot(N, L));
    const float alpha = standardAlpha(linearRoughness);
    const float f90 = standardF90(f0);
    const glm::vec3 F = F_Schlick(f0, f90, LdotH);
    const float Vis = V_SmithGGXCorrelated(NdotL, NdotV, alpha);
    const float D = D_GGX(NdotH, alpha);
    const glm::vec3 Fr = D * F * Vis / kPi;
    const float Fd = Fr_DisneyDiffuse(NdotV, NdotL, LdotH, linearRoughness) / kPi;
    return (diffuseColor * Fd + Fr) * NdotL;
}

VisibleNormals::VisibleNormals(const glm::dvec3& view, double alpha) : a(alpha), v(view) {
    vh = glm::normalize(glm::dvec3(a * v.x, a * v.y, v.z));
    const double lenSq = vh.x * vh.x + vh.y * vh.y;
    t1 = lenSq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lenSq) : glm::dvec3(1.0, 0.0, 0.0);
    t2 = glm::cross(vh, t1);
    const double nv = std::max(v.z, 1e-7);
    g1 = 2.0 * nv / (nv + std::sqrt(a * a + (1.0 - a * a) * nv * nv));
}

glm::dvec3 VisibleNormals::halfVector(double u1, double u2) const {
    const double r = std::sqrt(u1), phi = 2.0 * kPiD * u2;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    const glm::dvec3 nh =
        p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::dvec3(a * nh.x, a * nh.y, std::max(0.0, nh.z)));
}

double VisibleNormals::pdf(const glm::dvec3& l) const {
    const glm::dvec3 h = glm::normalize(v + l);
    if (h.z <= 0.0) return 0.0;
    const double c = h.z * h.z, a2 = a * a, f = c * (a2 - 1.0) + 1.0;
    const double D = a2 / (kPiD * f * f);
    return g1 * D / (4.0 * std::max(v.z, 1e-7));
}

double specularAlbedo(float NdotV, float linearRoughness, float f0, float f90, int samples) {
    RG_CHECK(samples > 0) << "specularAlbedo needs at least one sample, got " << samples;
    const float alpha = standardAlpha(linearRoughness);
    const glm::dvec3 v = viewVector(NdotV);
    const VisibleNormals vn(v, alpha);  // f·⟨n·l⟩/pdf = F · G₂/G₁(v)
    const double nv = std::max(static_cast<double>(NdotV), 1e-7);
    double sum = 0.0;
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            const glm::dvec3 h = vn.halfVector((i + 0.5) / samples, (j + 0.5) / samples);
            const double VdotH = glm::dot(v, h);
            if (VdotH <= 0.0) continue;
            const glm::dvec3 l = 2.0 * VdotH * h - v;
            if (l.z <= 0.0) continue;
            const float F = F_Schlick(f0, f90, static_cast<float>(VdotH));
            const float Vis = V_SmithGGXCorrelated(static_cast<float>(l.z), NdotV, alpha);
            const double g2 =
                4.0 * static_cast<double>(Vis) * l.z * nv;  // Vis = G₂ / (4 NdotL NdotV)
            sum += static_cast<double>(F) * g2 / vn.g1;
        }
    return sum / (static_cast<double>(samples) * samples);
}

double sheenBrdf(double NdotH, double NdotL, double NdotV, double sheenRoughness) {
    const double alpha = std::max(sheenRoughness * sheenRoughness, 1e-3);
    const double sin2h = std::max(1.0 - NdotH * NdotH, 1.0 / 128.0);
    const double d = (2.0 + 1.0 / alpha) * std::pow(sin2h, 0.5 / alpha) / (2.0 * kPiD);
    return d / (4.0 * std::max(NdotL + NdotV - NdotL * NdotV, 1e-4));
}

double sheenAlbedo(float NdotV, float sheenRoughness, int cells) {
    RG_CHECK(cells > 0) << "sheenAlbedo needs at least one cell, got " << cells;
    const glm::dvec3 v = viewVector(NdotV);
    return integrateHemisphere(
        [&](const glm::dvec3& l) {
            const glm::dvec3 h = glm::normalize(v + l);
            return sheenBrdf(h.z, l.z, v.z, sheenRoughness) * l.z;
        },
        cells, 4 * cells);
}

double diffuseAlbedo(float NdotV, float linearRoughness, int samples) {
    RG_CHECK(samples > 0) << "diffuseAlbedo needs at least one sample, got " << samples;
    const glm::dvec3 v = viewVector(NdotV);
    double sum = 0.0;
    for (int i = 0; i < samples; ++i) {
        const double u1 = (i + 0.5) / samples;
        const double sinL = std::sqrt(u1), cosL = std::sqrt(1.0 - u1);  // cosine-weighted
        for (int j = 0; j < samples; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / samples;
            const glm::dvec3 l{sinL * std::cos(phi), sinL * std::sin(phi), cosL};
            const double LdotH = glm::dot(l, glm::normalize(l + v));
            // (Fd/π)·⟨n·l⟩ / (⟨n·l⟩/π) = Fd.
            sum += Fr_DisneyDiffuse(NdotV, static_cast<float>(cosL), static_cast<float>(LdotH),
                                    linearRoughness);
        }
    }
    return sum / (static_cast<double>(samples) * samples);
}

double standardAlbedo(float NdotV, float linearRoughness, float diffuseColor, float f0,
                      int samples) {
    const float f90 = standardF90(glm::vec3(f0));
    return diffuseColor * diffuseAlbedo(NdotV, linearRoughness, samples) +
           specularAlbedo(NdotV, linearRoughness, f0, f90, samples);
}

double integrateHemisphere(const std::function<double(const glm::dvec3& l)>& f, int cosThetaCells,
                           int phiCells) {
    RG_CHECK(cosThetaCells > 0 && phiCells > 0) << "integrateHemisphere needs a non-empty grid";
    // Equal-area cells: dω = d(cos θ) dφ, each cell 2π / (n·m) sr.
    const double cellSolidAngle = 2.0 * kPiD / (static_cast<double>(cosThetaCells) * phiCells);
    double sum = 0.0;
    for (int i = 0; i < cosThetaCells; ++i) {
        const double c = (i + 0.5) / cosThetaCells;
        const double s = std::sqrt(1.0 - c * c);
        for (int j = 0; j < phiCells; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / phiCells;
            sum += f({s * std::cos(phi), s * std::sin(phi), c});
        }
    }
    return sum * cellSolidAngle;
}

}  // namespace rg::brdf
