// The BRDF on the CPU against the seeds: its components, normalisation and white furnace (seed 000
// §3.1, lst:1, lst:2, Figure 9), and why punctual highlights exceed the light (seed 004). No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/light_units.h"
#include "lighting/area_lights.h"
#include "lighting/brdf.h"
#include "lighting/punctual.h"
#include "lighting_test_util.h"

using namespace rg;
using namespace rg::test;

// =============================================================================================
// BRDF (seed 000 §3.1)
// =============================================================================================

TEST(Brdf, ComponentsFollowTheListings) {
    // D_GGX has no 1/π: its peak is 1/α².
    EXPECT_FLOAT_EQ(brdf::D_GGX(1.0f, 0.25f), 16.0f);
    // Schlick: f0 at normal incidence, f90 at grazing incidence.
    EXPECT_FLOAT_EQ(brdf::F_Schlick(0.04f, 1.0f, 1.0f), 0.04f);
    EXPECT_FLOAT_EQ(brdf::F_Schlick(0.04f, 1.0f, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(brdf::F_Schlick(glm::vec3(0.04f), 0.5f, 0.0f).y, 0.5f);
    // u beyond 1 (NdotV + 1e-5 in lst:2) gives f0, as brdf.glsl clamps the base of its pow (an
    // unclamped (1 − 1.5)^5 would give 0.01 here).
    EXPECT_EQ(brdf::F_Schlick(0.04f, 1.0f, 1.5f), 0.04f);
    EXPECT_EQ(brdf::F_Schlick(glm::vec3(0.04f), 1.0f, 1.5f), glm::vec3(0.04f));
    EXPECT_EQ(brdf::Fr_DisneyDiffuse(1.00001f, 1.0f, 1.0f, 0.5f),
              brdf::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 0.5f));
    // lst:1 at linearRoughness 0 and normal incidence is Lambert (1, before the 1/π); at roughness 1
    // the renormalisation factor 1/1.51 applies, fd90 = 0.5 + 2 LdotH².
    EXPECT_FLOAT_EQ(brdf::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(brdf::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 1.0f), 1.0f / 1.51f);
    const float fd90 = 0.5f + 2.0f * 0.6f * 0.6f;
    EXPECT_NEAR(brdf::Fr_DisneyDiffuse(0.0f, 0.0f, 0.6f, 1.0f), fd90 * fd90 / 1.51f, 1e-6);
    // §3.2.1: reflectance 0.5 is 4 % (the common dielectric), 1 is 16 %.
    EXPECT_FLOAT_EQ(brdf::rgDielectricF0(0.5f), 0.04f);
    EXPECT_FLOAT_EQ(brdf::rgDielectricF0(1.0f), 0.16f);
    // Specular micro-occlusion: f0 below 2 % darkens f90.
    EXPECT_FLOAT_EQ(brdf::standardF90(glm::vec3(0.04f)), 1.0f);
    EXPECT_NEAR(brdf::standardF90(glm::vec3(0.01f)), 50.0f * 0.0099f, 1e-6);

    // rgStandardBrdf is the sum of the parts, times NdotL, as in brdf.glsl.
    const glm::vec3 N(0, 0, 1), V = glm::normalize(glm::vec3(0.3f, 0.1f, 0.9f)),
                                L = glm::normalize(glm::vec3(-0.5f, 0.2f, 0.7f));
    const glm::vec3 H = glm::normalize(V + L);
    const float NdotV = glm::dot(N, V) + 1e-5f, NdotL = glm::dot(N, L), LdotH = glm::dot(L, H),
                NdotH = glm::dot(N, H);
    const float lr = 0.6f, alpha = lr * lr;
    const glm::vec3 f0(0.04f, 0.5f, 0.9f), diffuse(0.8f, 0.5f, 0.1f);
    const glm::vec3 expected =
        (diffuse * brdf::Fr_DisneyDiffuse(NdotV, NdotL, LdotH, lr) / brdf::kPi +
         brdf::D_GGX(NdotH, alpha) * brdf::F_Schlick(f0, brdf::standardF90(f0), LdotH) *
             brdf::V_SmithGGXCorrelated(NdotL, NdotV, alpha) / brdf::kPi) *
        NdotL;
    const glm::vec3 got = brdf::rgStandardBrdf(N, V, L, diffuse, f0, lr);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(got[c], expected[c]);
    // Below the horizon nothing arrives.
    EXPECT_EQ(brdf::rgStandardBrdf(N, V, glm::vec3(0, 0, -1), diffuse, f0, lr), glm::vec3(0.0f));
}

TEST(Brdf, GgxDistributionIsNormalised) {
    // ∫ D(h)/π ⟨n·h⟩ dω_h = 1: the projected microfacet area is the macro surface. Isotropic, so
    // the φ integral is 2π and the rest a 1D midpoint rule in cos θ (fine enough for α ≥ 0.05).
    for (float alpha : {0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        const int n = 400000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double mu = (i + 0.5) / n;
            sum += brdf::D_GGX(static_cast<float>(mu), alpha) / kPi * mu;
        }
        const double integral = sum * 2.0 * kPi / n;
        EXPECT_NEAR(integral, 1.0, 1e-3) << "alpha " << alpha;
        // Without the 1/π (as D_GGX returns it) the integral is π: the listing's convention.
        EXPECT_NEAR(integral * kPi, kPi, 4e-3);
    }
    // The same with the generic hemisphere integrator where the lobe is wide enough for it.
    for (float alpha : {0.3f, 0.6f, 1.0f}) {
        const double integral = brdf::integrateHemisphere(
            [&](const glm::dvec3& h) {
                return brdf::D_GGX(static_cast<float>(h.z), alpha) / kPi * h.z;
            },
            4000, 8);
        EXPECT_NEAR(integral, 1.0, 1e-3) << "alpha " << alpha;
    }
}

TEST(Brdf, HeightCorrelatedSmithIsSymmetricAndAtLeastTheSeparableForm) {
    // The seed's original form (the comment in lst:2): Λ(x) = (−1 + sqrt(1 + α² tan²x)) / 2,
    // G = 1 / (1 + Λv + Λl), V = G / (4 NdotL NdotV). The separable (uncorrelated) Smith form
    // G₁(l) G₁(v) = 1 / ((1 + Λl)(1 + Λv)) ≤ 1 / (1 + Λl + Λv): the height-correlated visibility is
    // never below the uncorrelated one (it removes the separable form's over-darkening; equal only
    // where a Λ is 0, i.e. at normal incidence).
    const auto lambda = [](double c, double a) {
        return (-1.0 + std::sqrt(1.0 + a * a * (1.0 - c * c) / (c * c))) * 0.5;
    };
    int strictlyAbove = 0, samples = 0;
    for (float alpha : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f}) {
        for (float nl = 0.05f; nl <= 1.0f; nl += 0.05f) {
            for (float nv = 0.05f; nv <= 1.0f; nv += 0.05f) {
                const float v = brdf::V_SmithGGXCorrelated(nl, nv, alpha);
                EXPECT_EQ(v, brdf::V_SmithGGXCorrelated(nv, nl, alpha))
                    << nl << " " << nv << " " << alpha;
                const double ll = lambda(nl, alpha), lv = lambda(nv, alpha);
                const double original = 1.0 / (1.0 + lv + ll) / (4.0 * nl * nv);
                EXPECT_NEAR(v, original, 2e-5 * original) << nl << " " << nv << " " << alpha;
                const double separable = 1.0 / ((1.0 + ll) * (1.0 + lv)) / (4.0 * nl * nv);
                EXPECT_GE(v, separable * (1.0 - 1e-5)) << nl << " " << nv << " " << alpha;
                strictlyAbove += v > separable * (1.0 + 1e-4);
                ++samples;
                // G ≤ 1.
                EXPECT_LE(v * 4.0 * nl * nv, 1.0 + 1e-5);
            }
        }
    }
    EXPECT_GT(strictlyAbove, samples / 2);  // the difference is real, not rounding
}

TEST(Brdf, AlbedoEstimatorsAgreeWithBruteForce) {
    // The importance-sampled albedo against a plain equal-area grid over the hemisphere evaluating
    // rgStandardBrdf itself (float, as the shader).
    struct Case {
        float NdotV, lr, f0;
    };
    for (const Case c : {Case{0.9f, 0.5f, 0.04f}, Case{0.5f, 0.8f, 0.04f}, Case{0.3f, 0.4f, 1.0f},
                         Case{0.7f, 1.0f, 0.5f}}) {
        const glm::vec3 V(std::sqrt(1.0f - c.NdotV * c.NdotV), 0.0f, c.NdotV);
        const float diffuse = c.f0 >= 1.0f ? 0.0f : 1.0f;
        const double brute = brdf::integrateHemisphere(
            [&](const glm::dvec3& l) {
                return static_cast<double>(brdf::rgStandardBrdf(glm::vec3(0, 0, 1), V, glm::vec3(l),
                                                                glm::vec3(diffuse), glm::vec3(c.f0),
                                                                c.lr)
                                               .x);
            },
            1500, 1500);
        const double estimate = brdf::standardAlbedo(c.NdotV, c.lr, diffuse, c.f0);
        EXPECT_NEAR(estimate, brute, 1e-3) << c.NdotV << " " << c.lr << " " << c.f0;
    }
}

TEST(Brdf, SpecularLobeWhiteFurnace) {
    // F = 1: the single-scattering GGX lobe with height-correlated Smith never reflects more than it
    // receives; smooth surfaces reflect (almost) everything; rough ones lose the multiple-bounce part.
    double lowest = 1.0;
    for (int i = 0; i <= 10; ++i) {
        const float lr = static_cast<float>(i) / 10.0f;
        for (float nv : {0.02f, 0.1f, 0.3f, 0.5f, 0.7f, 0.9f, 1.0f}) {
            const double a = brdf::specularAlbedo(nv, lr, 1.0f, 1.0f);
            EXPECT_LE(a, 1.0 + 1e-4) << "linearRoughness " << lr << " NdotV " << nv;
            if (lr <= 0.1f && nv >= 0.1f) {
                EXPECT_GT(a, 0.99) << "linearRoughness " << lr << " NdotV " << nv;
            }
            lowest = std::min(lowest, a);
        }
    }
    // The least is at alpha = 1 and normal view, where it has a closed form: D/π = 1/π and
    // V = 0.5 / (1 + NdotL), so ρ = 2π ∫ μ / (2π (1 + μ)) dμ = 1 − ln 2. The rest is the energy that
    // multiple scattering between microfacets would return.
    EXPECT_NEAR(brdf::specularAlbedo(1.0f, 1.0f, 1.0f, 1.0f), 1.0 - std::log(2.0), 1e-4);
    EXPECT_NEAR(lowest, 1.0 - std::log(2.0), 1e-4);
    std::printf("specular white furnace (F = 1): min albedo %.4f\n", lowest);
}

TEST(Brdf, RenormalisedDisneyPlusSpecularStaysCloseToOne) {
    // Figure 9 (c): the directional albedo of f_r + f_d with the renormalised Disney diffuse is "not
    // exactly 1 but close enough". White diffuse, f0 = 4 %, over NdotV and linearRoughness.
    double maxAlbedo = 0.0, minAlbedo = 2.0, maxAboveGrazing = 0.0, maxFromHalf = 0.0;
    float maxAt[2] = {}, minAt[2] = {};
    for (int i = 0; i <= 20; ++i) {
        const float lr = static_cast<float>(i) / 20.0f;
        for (int j = 0; j <= 20; ++j) {
            const float nv = j == 0 ? 0.01f : static_cast<float>(j) / 20.0f;
            const double a = brdf::standardAlbedo(nv, lr, 1.0f, 0.04f, 64);
            if (a > maxAlbedo) maxAlbedo = a, maxAt[0] = nv, maxAt[1] = lr;
            if (a < minAlbedo) minAlbedo = a, minAt[0] = nv, minAt[1] = lr;
            if (nv >= 0.25f) maxAboveGrazing = std::max(maxAboveGrazing, a);
            if (nv >= 0.5f) maxFromHalf = std::max(maxFromHalf, a);
        }
    }
    std::printf(
        "Figure 9 (c), f0 = 0.04, white diffuse: max %.4f (NdotV %.2f, linearRoughness %.2f), "
        "min %.4f (NdotV %.2f, linearRoughness %.2f), max for NdotV >= 0.25: %.4f, for NdotV >= "
        "0.5: %.4f\n",
        maxAlbedo, maxAt[0], maxAt[1], minAlbedo, minAt[0], minAt[1], maxAboveGrazing, maxFromHalf);
    // Measured: max 1.098 at grazing view (NdotV 0.01) on the roughest surface, min 0.698 at normal
    // view on it. It exceeds 1 only at grazing views: at most 1.015 for NdotV ≥ 0.25 and 0.993 (the
    // smooth surface) for NdotV ≥ 0.5.
    EXPECT_LT(maxAlbedo, 1.11);
    EXPECT_GT(maxAlbedo, 1.05);
    EXPECT_LT(maxAboveGrazing, 1.02);
    EXPECT_LE(maxFromHalf, 1.0);
    EXPECT_GT(minAlbedo, 0.68);
    EXPECT_LT(minAlbedo, 0.72);

    // Without the renormalisation (Disney's original: bias 0.5, factor 1), Figure 9 (a): far above 1.
    const auto originalDisney = [](float NdotV, float NdotL, float LdotH, float lr) {
        const float fd90 = 0.5f + 2.0f * LdotH * LdotH * lr;
        return brdf::F_Schlick(1.0f, fd90, NdotL) * brdf::F_Schlick(1.0f, fd90, NdotV);
    };
    double originalMax = 0.0;
    for (float nv : {0.01f, 0.1f, 0.5f, 1.0f}) {
        const glm::dvec3 v(std::sqrt(1.0 - nv * nv), 0.0, nv);
        originalMax =
            std::max(originalMax, brdf::integrateHemisphere(
                                      [&](const glm::dvec3& l) {
                                          const double LdotH = glm::dot(l, glm::normalize(l + v));
                                          return originalDisney(nv, static_cast<float>(l.z),
                                                                static_cast<float>(LdotH), 1.0f) /
                                                 kPi * l.z;
                                      },
                                      400, 400));
    }
    std::printf("original Disney diffuse, linearRoughness 1: max albedo %.4f\n", originalMax);
    EXPECT_GT(originalMax, 1.4);

    // White base colour through the metal mask (diffuse = 1 − metal, f0 = lerp(0.04, 1, metal)):
    // f0 from 0.04 to 1; the albedo never exceeds the dielectric's maximum and metals stay ≤ 1.
    for (float f0 : {0.04f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        const float metal = (f0 - 0.04f) / 0.96f;
        double m = 0.0;
        for (int i = 0; i <= 10; ++i)
            for (float nv : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f})
                m = std::max(m, brdf::standardAlbedo(nv, static_cast<float>(i) / 10.0f,
                                                     1.0f - metal, f0, 48));
        std::printf("white furnace, f0 = %.2f (metal %.2f): max albedo %.4f\n", f0, metal, m);
        EXPECT_LE(m, maxAlbedo + 1e-3) << "f0 " << f0;
        if (f0 >= 1.0f) {
            EXPECT_LE(m, 1.0 + 1e-4);
        }
    }
}

TEST(Brdf, PunctualHighlightsExceedTheLightsIlluminance) {
    // Seed 004: a BRDF is not bounded by 1, so a punctual light's highlight can be far brighter than
    // its "intensity": GGX α = 0.1 lit by a 1 lux directional light peaks above 10 cd/m² (at the mirror
    // direction for a 60° view: D/π = 1/(π α²) = 31.8, V ≈ 0.985, ⟨n·l⟩ = 0.5 → 15.7).
    const float lr = std::sqrt(0.1f);  // alpha = 0.1
    const float s60 = std::sqrt(3.0f) / 2.0f;
    const glm::vec3 N(0, 0, 1), V(s60, 0.0f, 0.5f), L(-s60, 0.0f, 0.5f);
    const float luminance =
        brdf::rgStandardBrdf(N, V, L, glm::vec3(0.0f), glm::vec3(1.0f), lr).x * /* lux= */ 1.0f;
    EXPECT_GT(luminance, 10.0f);
    EXPECT_NEAR(luminance, 15.7f, 0.1f);
    // No energy is created: the same lobe integrates to at most 1 (SpecularLobeWhiteFurnace). The
    // resolution is that a punctual light's luminance is infinite — a sphere of fixed power has a
    // luminance growing as 1 / r² while the illuminance it delivers stays Φ / (4π d²) (eq:38).
    EXPECT_LE(brdf::specularAlbedo(V.z, lr, 1.0f, 1.0f), 1.0 + 1e-4);
    EXPECT_NEAR(lighting::sphereLuminanceFromLumens(100, 0.001) /
                    lighting::sphereLuminanceFromLumens(100, 0.01),
                100.0, 1e-9);
}
