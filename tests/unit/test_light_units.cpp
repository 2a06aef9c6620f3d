// Light units on the CPU against the seeds: lumens to candela (seed 000 tbl:9), bulbs at a
// distance (tbl:10), attenuation (lst:4) and area lights in lumens (tbl:12, eq:12). No GPU.
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
#include "lighting/light_table.h"
#include "lighting/punctual.h"
#include "lighting_test_util.h"

using namespace rg;
using namespace rg::test;

// =============================================================================================
// Light units
// =============================================================================================

TEST(LightUnits, Table9PointSpotAndFrustumLumensToCandela) {
    const double phi = 800.0;
    // Point: Φ / 4π.
    EXPECT_NEAR(lights::pointIntensityFromLumens(phi), phi / (4 * kPi), 1e-12);
    // Spot: Φ / (2π (1 − cos(θ_outer / 2))) with θ_outer the full opening angle, or Frostbite's Φ / π.
    // light_units takes the half-angle.
    for (double opening : {deg(10), deg(60), deg(90), deg(170)}) {
        const double printed = phi / (2 * kPi * (1 - std::cos(opening / 2)));
        EXPECT_NEAR(lights::spotIntensityFromLumens(phi, opening / 2, /* exactCone= */ true),
                    printed, printed * 1e-12);
        EXPECT_NEAR(phi / lighting::coneSolidAngle(opening), printed, printed * 1e-12);
        EXPECT_NEAR(lights::spotIntensityFromLumens(phi, opening / 2), phi / kPi, 1e-12);  // eq:17
    }
    // Frustum: Φ / (4 arcsin(sin(θa/2) sin(θb/2))).
    for (auto [a, b] :
         {std::pair{deg(30), deg(60)}, std::pair{deg(90), deg(90)}, std::pair{deg(120), deg(20)}}) {
        const double printed = phi / (4 * std::asin(std::sin(a / 2) * std::sin(b / 2)));
        EXPECT_NEAR(lighting::frustumIntensityFromLumens(phi, a, b), printed, printed * 1e-12);
        // The denominator is the pyramid's solid angle: seed 002's rightPyramidSolidAngle agrees.
        EXPECT_NEAR(lighting::frustumSolidAngle(a, b),
                    lighting::rightPyramidSolidAngle(1.0, std::tan(a / 2), std::tan(b / 2)), 1e-12);
    }
    // A 180° × 180° frustum is the hemisphere (2π sr); a narrow one tends to θa·θb.
    EXPECT_NEAR(lighting::frustumSolidAngle(kPi, kPi), 2 * kPi, 1e-12);
    EXPECT_NEAR(lighting::frustumSolidAngle(1e-3, 2e-3), 2e-6, 1e-12);
    // And by brute force: the fraction of the hemisphere inside a 60° × 40° pyramid.
    const double ta = std::tan(deg(30)), tb = std::tan(deg(20));
    const double numeric = brdf::integrateHemisphere(
        [&](const glm::dvec3& l) {
            return std::abs(l.x) <= ta * l.z && std::abs(l.y) <= tb * l.z ? 1.0 : 0.0;
        },
        2000, 2000);
    EXPECT_NEAR(numeric, lighting::frustumSolidAngle(deg(60), deg(40)), 2e-3 * numeric);
}

TEST(LightUnits, Table10BulbsAtDistance) {
    // seed 000 tbl:10, the Frostbite rows: a 625 lm and a 1200 lm point light facing a white diffuse
    // plane, E = Φ / (4π d²) (eq:19). The table prints integers, mostly rounded (49.7 → 50) but
    // 4973.6 and 16441.6 cut to 4973 and 16441: within 1 lx.
    const double distances[] = {1.0, 0.5, 0.25, 0.1, 0.055};
    const double printed625[] = {50, 199, 796, 4973, 16441};
    const double printed1200[] = {95, 382, 1528, 9549, 31568};
    for (int i = 0; i < 5; ++i) {
        const double d = distances[i];
        const double e625 = lights::illuminance(lights::pointIntensityFromLumens(625), d);
        const double e1200 = lights::illuminance(lights::pointIntensityFromLumens(1200), d);
        EXPECT_NEAR(e625, printed625[i], 1.0) << "625 lm at " << d << " m";
        EXPECT_NEAR(e1200, printed1200[i], 1.0) << "1200 lm at " << d << " m";
        // The same through lst:4 in float: I · getDistanceAtt(d), without and with a far radius.
        const float cd625 = static_cast<float>(lights::pointIntensityFromLumens(625));
        const glm::vec3 toLight(0.0f, 0.0f, static_cast<float>(d));
        EXPECT_NEAR(cd625 * lighting::getDistanceAtt(toLight, 0.0f), e625, e625 * 1e-6);
        EXPECT_NEAR(cd625 * lighting::getDistanceAtt(toLight, 1.0f / (100.0f * 100.0f)), e625,
                    e625 * 1e-6);
        // "Doubling the lumens doubles the illuminance": 1200 / 625 exactly.
        EXPECT_NEAR(e1200 / e625, 1200.0 / 625.0, 1e-12);
        std::printf("tbl:10  d = %5.3f m: 625 lm -> %8.1f lx, 1200 lm -> %8.1f lx\n", d, e625,
                    e1200);
    }
    // The unrounded values the issue quotes.
    EXPECT_NEAR(lights::illuminance(lights::pointIntensityFromLumens(625), 1.0), 49.7, 0.05);
    EXPECT_NEAR(lights::illuminance(lights::pointIntensityFromLumens(625), 0.5), 198.9, 0.05);
    EXPECT_NEAR(lights::illuminance(lights::pointIntensityFromLumens(625), 0.25), 795.8, 0.05);
    EXPECT_NEAR(lights::illuminance(lights::pointIntensityFromLumens(625), 0.1), 4973.6, 0.05);
}

TEST(LightUnits, Listing4AttenuationClampsAtOneCentimetreAndWindowsToZero) {
    // eq:14: below 1 cm the light is as bright as at 1 cm.
    EXPECT_FLOAT_EQ(lighting::getDistanceAtt(glm::vec3(0.0f, 0.005f, 0.0f), 0.0f),
                    1.0f / (0.01f * 0.01f));
    EXPECT_FLOAT_EQ(lighting::getDistanceAtt(glm::vec3(0.0f, 0.0f, 0.0f), 0.0f),
                    1.0f / (0.01f * 0.01f));
    // eq:26 (n = 4): reaches exactly 0 at the radius and stays there, decreasing all the way.
    const float invSqrRadius = 1.0f / (5.0f * 5.0f);
    EXPECT_EQ(lighting::getDistanceAtt(glm::vec3(5.0f, 0.0f, 0.0f), invSqrRadius), 0.0f);
    EXPECT_EQ(lighting::getDistanceAtt(glm::vec3(7.0f, 0.0f, 0.0f), invSqrRadius), 0.0f);
    float previous = lighting::getDistanceAtt(glm::vec3(0.01f, 0.0f, 0.0f), invSqrRadius);
    for (float d = 0.02f; d < 5.0f; d += 0.01f) {
        const float a = lighting::getDistanceAtt(glm::vec3(d, 0.0f, 0.0f), invSqrRadius);
        EXPECT_LT(a, previous) << d;
        previous = a;
    }
    // Half-way the window is (1 − (1/4)²)² = 0.8789.
    EXPECT_NEAR(lighting::smoothDistanceAtt(2.5f * 2.5f, invSqrRadius),
                std::pow(1.0f - 0.0625f, 2.0f), 1e-6);

    // Cone: 1 inside the inner angle, 0 outside the outer, the squared ramp between.
    const auto so =
        lighting::spotAngleScaleOffset(static_cast<float>(deg(20)), static_cast<float>(deg(30)));
    const glm::vec3 spot(0.0f, 0.0f, -1.0f);
    const auto dirAt = [](double angle) {
        return glm::vec3(static_cast<float>(std::sin(angle)), 0.0f,
                         -static_cast<float>(std::cos(angle)));
    };
    EXPECT_FLOAT_EQ(lighting::getAngleAtt(dirAt(deg(10)), spot, so.scale, so.offset), 1.0f);
    EXPECT_FLOAT_EQ(lighting::getAngleAtt(dirAt(deg(35)), spot, so.scale, so.offset), 0.0f);
    const double ramp =
        (std::cos(deg(25)) - std::cos(deg(30))) / (std::cos(deg(20)) - std::cos(deg(30)));
    EXPECT_NEAR(lighting::getAngleAtt(dirAt(deg(25)), spot, so.scale, so.offset), ramp * ramp,
                1e-5);
}

TEST(LightUnits, Table12AreaLightsLumensToLuminance) {
    const double phi = 1000.0, r = 0.05, l = 0.6, w = 0.4, h = 0.25;
    // The table's expressions, as printed.
    EXPECT_NEAR(lighting::sphereLuminanceFromLumens(phi, r), phi / (4 * r * r * kPi * kPi), 1e-9);
    EXPECT_NEAR(lighting::diskLuminanceFromLumens(phi, r), phi / (r * r * kPi * kPi), 1e-9);
    EXPECT_NEAR(lighting::tubeLuminanceFromLumens(phi, r, l),
                phi / ((2 * kPi * r * l + 4 * kPi * r * r) * kPi), 1e-9);
    EXPECT_NEAR(lighting::rectangleLuminanceFromLumens(phi, w, h), phi / (kPi * w * h), 1e-9);
    // All are eq:33, Φ / (A π), with the emitting area: sphere 4πr², one-sided disk πr², capsule
    // 2πrl + 4πr², one-sided rectangle wh.
    EXPECT_NEAR(lighting::sphereLuminanceFromLumens(phi, r),
                lighting::lambertianLuminance(phi, 4 * kPi * r * r), 1e-9);
    EXPECT_NEAR(lighting::diskLuminanceFromLumens(phi, r),
                lighting::lambertianLuminance(phi, kPi * r * r), 1e-9);
    EXPECT_NEAR(lighting::tubeLuminanceFromLumens(phi, r, l),
                lighting::lambertianLuminance(phi, 2 * kPi * r * l + 4 * kPi * r * r), 1e-9);
    EXPECT_NEAR(lighting::rectangleLuminanceFromLumens(phi, w, h),
                lighting::lambertianLuminance(phi, w * h), 1e-9);
    // A tube of length 0 is a sphere.
    EXPECT_NEAR(lighting::tubeLuminanceFromLumens(phi, r, 0.0),
                lighting::sphereLuminanceFromLumens(phi, r), 1e-9);

    // The dispatcher: lm through tbl:12, EV100 through eq:12 (2^(EV − 3)), nits unchanged.
    const lighting::AreaLightShape rect{lighting::AreaShape::Rectangle, 0.0, 0.0, w, h};
    EXPECT_NEAR(lighting::areaLightLuminance(rect, phi, lighting::AreaUnit::Lumens),
                phi / (kPi * w * h), 1e-9);
    EXPECT_DOUBLE_EQ(lighting::areaLightLuminance(rect, 10.0, lighting::AreaUnit::Ev100), 128.0);
    EXPECT_DOUBLE_EQ(lighting::areaLightLuminance(rect, 500.0, lighting::AreaUnit::Nits), 500.0);
    // Emissive surfaces: EV100 16 is 8192 nits, EV100 −3 is 1/64 (tbl:7's values through eq:12).
    EXPECT_DOUBLE_EQ(lighting::emissiveLuminance(16.0, lighting::AreaUnit::Ev100), 8192.0);
    EXPECT_DOUBLE_EQ(lighting::emissiveLuminance(-3.0, lighting::AreaUnit::Ev100), 1.0 / 64.0);
    EXPECT_DOUBLE_EQ(lighting::emissiveLuminance(42.0, lighting::AreaUnit::Nits), 42.0);
}

TEST(LightUnits, AreaLightsInLumensLightLikeTheirPunctualCounterparts) {
    // eq:38: a sphere of tbl:12 luminance lights a facing point like a point light of the same lumens,
    // whatever its radius; checked against the brute-force integral over the cap it subtends.
    const double phi = 1200.0, d = 2.0;
    for (double r : {0.01, 0.1, 0.5, 1.5}) {
        const double L = lighting::sphereLuminanceFromLumens(phi, r);
        const double sinSigma = r / d;
        EXPECT_NEAR(L * capIlluminanceReference(1.0, sinSigma, 400), phi / (4 * kPi * d * d),
                    1e-4 * phi / (4 * kPi * d * d))
            << "r = " << r;
        EXPECT_NEAR(L * lighting::sphereIlluminance(r, d * d, 1.0), phi / (4 * kPi * d * d),
                    1.001e-3 * phi / (4 * kPi * d * d))
            << "lst:10 clamps cos θ to 0.999";
        // Seed 004 writes the sphere's radiance as Φ / (8π² r²): half of tbl:12's, and half the
        // point light's illuminance — tbl:12 (a Lambertian emitter, eq:33) is the consistent one.
        EXPECT_NEAR(phi / (8 * kPi * kPi * r * r) / L, 0.5, 1e-12);
    }
    // eq:39: a disk of tbl:12 luminance gives Φ / (π (d² + r²)), tending to the spot light's Φ / (π d²).
    for (double r : {0.01, 0.1, 0.5}) {
        const double L = lighting::diskLuminanceFromLumens(phi, r);
        const double E = L * lighting::diskIlluminanceAboveHorizon(r, d * d, 1.0, 1.0);
        EXPECT_NEAR(E, phi / (kPi * (d * d + r * r)), 1e-9 * E);
        EXPECT_NEAR(L * capIlluminanceReference(1.0, r / std::sqrt(r * r + d * d), 400), E,
                    1e-4 * E);
    }
    EXPECT_NEAR(lighting::diskLuminanceFromLumens(phi, 1e-4) *
                    lighting::diskIlluminanceAboveHorizon(1e-4, d * d, 1.0, 1.0),
                lights::illuminance(lights::spotIntensityFromLumens(phi, 0.5), d), 1e-6);
}

TEST(LightUnits, AnyRangeKeepsItsWindowOnTheGpu) {
    // 1/range² in GpuLight::directionRange.w: 0 means no range (the light reaches every pixel and
    // is in the global list), so a range so long that 1/range² underflows keeps the smallest
    // normal float rather than turning into "no range" behind the shaders' back.
    std::vector<Light> lights(3);
    lights[0].range = 5.0f;
    lights[1].range = 1e20f;
    lights[2].range = 0.0f;
    auto table = lighting::convertLights(lights);
    ASSERT_TRUE(table.has_value()) << table.error().describe();
    EXPECT_FLOAT_EQ(table->lights[0].directionRange.w, 1.0f / 25.0f);
    EXPECT_GT(table->lights[1].directionRange.w, 0.0f);
    EXPECT_EQ(table->lights[2].directionRange.w, 0.0f);
}
