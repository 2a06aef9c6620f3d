// Seed 002's IBL terms as the shaders compile them, against the seed's own listings computed here:
// §4.10.2 computeSpecOcclusion (lib/ibl.glsl rgSpecularOcclusion), §4.9.3
// computeDistanceBaseRoughness (lib/probes.glsl rgDistanceBasedRoughness) and the local roughness
// appendix F's sphere parallax feeds it (rgProbeParallax), evaluated by shaders/test/ibl_terms.comp
// over a 16 × 16 grid of inputs.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "runtime/runtime.h"

using namespace rg;

namespace {

// The seed's listings, as printed (002 §4.10.2 and §4.9.3); "roughness" is α there.
double computeSpecOcclusion(double NdotV, double AO, double roughness) {
    return std::clamp(std::pow(NdotV + AO, std::exp2(-16.0 * roughness - 1.0)) - 1.0 + AO, 0.0,
                      1.0);
}
double computeDistanceBaseRoughness(double distInteresectionToShadedPoint,
                                    double distInteresectionToProbeCenter, double linearRoughness) {
    const double newLinearRoughness = std::clamp(
        distInteresectionToShadedPoint / distInteresectionToProbeCenter * linearRoughness, 0.0,
        linearRoughness);
    return newLinearRoughness + (linearRoughness - newLinearRoughness) * linearRoughness;
}

class IblTerms : public GpuFixture {};

TEST_F(IblTerms, SpecularOcclusionAndDistanceBasedRoughnessAreTheSeedsListings) {
    GraphDesc g;
    ResourceDesc terms;
    terms.name = "terms";
    terms.texture.format = Format::RGBA32F;
    g.resources = {terms};
    PassDesc run;
    run.name = "terms";
    run.kind = "compute";
    run.accesses = {{"terms", Usage::StorageWrite}};
    run.params = Value(Value::Table{{"shader", Value("test/ibl_terms.comp")}});
    PassDesc fetch;
    fetch.name = "fetch";
    fetch.kind = "readback";
    fetch.accesses = {{"terms", Usage::CopySrc}};
    fetch.sideEffect = true;
    g.passes = {run, fetch};
    CompileOptions o;
    o.outputWidth = 16;
    o.outputHeight = 16;
    auto& ex = rt().executor();
    ASSERT_TRUE(ex.build(g, o).has_value());
    ASSERT_TRUE(ex.frame().has_value());
    auto img = ex.passResult("fetch");
    ASSERT_TRUE(img.has_value()) << img.error().describe();
    ASSERT_EQ(img->width, 16u);
    double worst[4] = {};
    int parallax = 0;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            const double u = (x + 0.5) / 16, v = (y + 0.5) / 16;
            const double want[3] = {computeSpecOcclusion(u, v, 0.1),
                                    computeSpecOcclusion(u, v, 0.6),
                                    computeDistanceBaseRoughness(4 * u, 0.25 + 3 * v, 0.3)};
            for (int c = 0; c < 3; ++c)
                worst[c] = std::max(worst[c], std::abs(img->at(x, y, uint32_t(c)) - want[c]));
            // Appendix F, a sphere of radius 2 at the origin: the ray from P along R leaves it at
            // the far root of |P + t R|² = 4; the exit point lies on the sphere, 2 m from the
            // centre (the capture point), so α' = clamp(t / 2 · 0.4, 0, 0.4), blended back.
            const glm::dvec3 P(3 * u - 1.5, 3 * v - 1.5, 0.4),
                R = glm::normalize(glm::dvec3(1.0, 0.3, -0.2));
            const double b = glm::dot(P, R), c = glm::dot(P, P) - 4.0;
            if (b * b - c < 0.0) continue;
            const double t = -b + std::sqrt(b * b - c);
            if (t <= 0.0) continue;
            const double local = computeDistanceBaseRoughness(t, 2.0, 0.4);
            worst[3] = std::max(worst[3], std::abs(img->at(x, y, 3) - local));
            ++parallax;
        }
    std::printf(
        "largest |shader - listing|: spec. occlusion %.2g (alpha 0.1), %.2g (alpha 0.6); distance "
        "roughness %.2g; the sphere parallax's roughness %.2g over %d points\n",
        worst[0], worst[1], worst[2], worst[3], parallax);
    EXPECT_LT(worst[0], 1e-5);
    EXPECT_LT(worst[1], 1e-5);
    EXPECT_LT(worst[2], 1e-5);
    EXPECT_LT(worst[3], 1e-4);
    EXPECT_GT(parallax, 200);
}

}  // namespace
