// IES profiles on the GPU (seed 000 §4.5, eq:27, lst:5): type C and type B profiles shaping a spot,
// as a mask or the intensity, and what convertLights makes of spots and what it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lights_fixture.h"

using namespace rg;
using namespace rg::test;

namespace {

// ---- IES: seed 000 §4.5, eq:27, lst:5 -----------------------------------------------------------

TEST_F(Lights, IesProfileShapesTheSpot) {
    Frame f = render(kScenes + "lights_ies.lua");
    ASSERT_TRUE(f.finite);
    const Light& l = f.scene.lights.front();
    auto profile = loadIes(l.ies);
    ASSERT_TRUE(profile.has_value()) << profile.error().describe();
    const IesTexture tex = bakeIes(*profile, passes::kIesWidth, passes::kIesHeight);
    // The light space convertLights builds: z the spot's direction (straight down), x its up made
    // perpendicular — parallel here, so direction × (1, 0, 0) = +z.
    const glm::vec3 z = glm::normalize(l.direction),
                    x = glm::normalize(glm::cross(z, glm::vec3(1, 0, 0))), y = glm::cross(z, x);
    ASSERT_NEAR(glm::distance(x, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    const glm::mat3 worldToLight = glm::transpose(glm::mat3(x, y, z));
    const double I = lights::spotIntensityFromLumens(1000.0, l.outerAngle);  // eq:17 (mask): Φ / π
    const auto cone = lighting::spotAngleScaleOffset(l.innerAngle, l.outerAngle);
    const glm::dvec3 pos(l.position);
    const double h = pos.y;
    auto expected = [&](glm::dvec3 P, double& profileValue) {
        const glm::dvec3 toLight = pos - P;
        const glm::dvec3 L = glm::normalize(toLight);
        profileValue = getIESProfileAttenuation(fv(L), worldToLight, tex);
        const double att = lighting::getDistanceAtt(fv(toLight), 0.0f) *
                           lighting::getAngleAtt(fv(-L), z, cone.scale, cone.offset) * profileValue;
        const glm::dvec3 V = glm::normalize(f.view.eye - P);
        return diffuseBrdf(f.floor.normal, V, L, 1.0f) * I * att * glm::dot(f.floor.normal, L);
    };
    // Points at 30° from the nadir towards horizontal 0° (+z) and 180° (−z), at 15°, and at 30°
    // towards 90° (+y of light space = z × x = −x... see y above).
    const double t30 = h * std::tan(30.0 * kPi / 180.0), t15 = h * std::tan(15.0 * kPi / 180.0);
    struct Probe {
        const char* name;
        glm::dvec3 at;
        double profile = 0, lum = 0;
    };
    std::vector<Probe> probes = {{"nadir", {0, 0, 0}},
                                 {"30° to 0°", {0, 0, t30}},
                                 {"30° to 180°", {0, 0, -t30}},
                                 {"15° to 0°", {0, 0, t15}},
                                 {"30° to 90°", glm::dvec3(y) * t30}};
    for (Probe& p : probes) {
        const glm::ivec2 px = pixelOf(f.view, p.at);
        const glm::dvec3 P = floorAt(f.view, px);
        const double want = expected(P, p.profile);
        p.lum = luminanceAt(f, px);
        std::printf(
            "ies    %-12s (%6.3f, %6.3f): profile %.4f, CPU %.4f cd/m², GPU %.4f cd/m² (%+.3f "
            "%%)\n",
            p.name, P.x, P.z, p.profile, want, p.lum, 100.0 * (p.lum - want) / want);
        EXPECT_NEAR(p.lum, want, 0.01 * want) << p.name;
    }
    // The pattern follows the profile: at the same 30° from the nadir, the forward throw (0°) is
    // the table's 409.7 / 149.9 = 2.73 times brighter than the back (180°).
    const double ratio = probes[1].lum / probes[2].lum;
    std::printf("ies    30° forward / back: GPU %.4f, table %.4f\n", ratio, 409.7 / 149.9);
    EXPECT_NEAR(ratio, probes[1].profile / probes[2].profile, 0.01 * ratio);
    EXPECT_NEAR(ratio, 409.7 / 149.9,
                0.03 * ratio);  // the 256 × 256 (θ, cos φ) texture vs the table
}

TEST_F(Lights, IesTypeBFloodlightThrowsTowardsPositiveH) {
    // A type B profile (a floodlight, graph/lighting/ies.h): 1000 cd at H = +30°, 250 cd at −30°,
    // 500 cd on the aim, 0 at ±90°, mirrored nowhere. The spot points straight down; its light space's +x
    // (horizontal 0° of type C, positive H of type B) is +z here, as in lights_ies.lua. At 30° from
    // the aim the floor towards +z must be 4x brighter than towards −z (the table's ratio), and
    // the same 30° towards ±x (positive and negative V) gets the aim's row, 500 vs 500.
    const std::string dir = std::string(RG_TEST_TMP) + "/ies_type_b";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/flood.ies") << "IESNA:LM-63-2002\n[TEST] type B\nTILT=NONE\n"
                                         "1 -1 1 5 5 2 2 0 0 0\n1 1 10\n"
                                         "-90 -30 0 30 90\n"     // vertical angles
                                         "-90 -30 0 30 90\n"     // horizontal angles
                                         "0 0 0 0 0\n"           // H = −90
                                         "0 250 250 250 0\n"     // H = −30
                                         "0 500 500 500 0\n"     // H = 0
                                         "0 1000 1000 1000 0\n"  // H = +30
                                         "0 0 0 0 0\n";          // H = +90
    std::ofstream(dir + "/flood.lua")
        << "local scene = require 'scene'\n"
           "scene.material 'white' { base_color = { 1, 1, 1 }, metal_mask = 0, smoothness = 0, "
           "reflectance = 0 }\n"
           "scene.plane 'floor' { size = { 12, 12 }, material = 'white' }\n"
           "scene.camera 'top' { position = { 0, 5, 0 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, "
           "fov = 60, near = 0.5, far = 100,"
           " aperture = 2.8, shutter = 1 / 60, iso = 100 }\n"
           "scene.light 'flood' { type = 'spot', intensity = 1, unit = 'cd', position = { 0, 1.5, "
           "0 }, direction = { 0, -1, 0 },"
           " inner_angle = 80, outer_angle = 85, ies = 'flood.ies', ies_mode = 'intensity' }\n";
    Frame f = render(dir + "/flood.lua");
    ASSERT_TRUE(f.finite);
    const double t = 1.5 * std::tan(25.0 * kPi / 180.0);  // inside the table's ±30°
    auto at = [&](glm::dvec3 p) { return luminanceAt(f, pixelOf(f.view, p)); };
    const double plusH = at({0, 0, t}), minusH = at({0, 0, -t}), plusV = at({t, 0, 0}),
                 minusV = at({-t, 0, 0});
    // At 25° of H the table gives 500 + (25/30)·500 and 500 − (25/30)·250.
    const double want = (500.0 + 25.0 / 30.0 * 500.0) / (500.0 - 25.0 / 30.0 * 250.0);
    std::printf("ies type B: +H %.4f, -H %.4f (ratio %.3f, table %.3f), +V %.4f, -V %.4f\n", plusH,
                minusH, plusH / minusH, want, plusV, minusV);
    EXPECT_NEAR(plusH / minusH, want, 0.03 * want);
    EXPECT_NEAR(plusV / minusV, 1.0, 0.03);
    // Beyond 30° the table falls to 0 at 90°: at 60° towards +H, (90 − 60) / 60 of 1000 cd.
    const double far = at({0, 0, 1.5 * std::tan(60.0 * kPi / 180.0)}),
                 near = at({0, 0, 1.5 * std::tan(30.0 * kPi / 180.0)});
    const double cos60 = 0.5, cos30 = std::sqrt(3.0) / 2.0;  // E ∝ I cos³θ / h² on the floor
    EXPECT_NEAR(far / near,
                (0.5 * 1000.0 * cos60 * cos60 * cos60) / (1000.0 * cos30 * cos30 * cos30),
                0.05 * far / near);
}

TEST_F(Lights, IesModeMaskOrIntensity) {
    // eq:27: the same profile as a mask (the declared 1000 lm → Φ / π cd) or as the intensity (its
    // own 470 cd maximum). No GPU: the conversion alone.
    Light l;
    l.name = "washer";
    l.type = LightType::Spot;
    l.intensity = 1000;
    l.unit = "lm";
    l.outerAngle = 1.0f;
    l.ies = kRoot + "/tests/unit/ies/bilateral_1991.ies";
    auto mask = passes::convertLights({l}, passes::IesMode::Mask);
    auto intensity = passes::convertLights({l}, passes::IesMode::Intensity);
    ASSERT_TRUE(mask.has_value() && intensity.has_value());
    EXPECT_NEAR(mask->lights[0].intensity.r, 1000.0 / kPi, 1e-3);
    EXPECT_NEAR(intensity->lights[0].intensity.r, 470.0, 1e-3);
    EXPECT_EQ(mask->lights[0].intensity.a, 0.0f);
    ASSERT_EQ(mask->profiles.size(), 1u);
    // Per light (Light::iesMode, the scene's `ies_mode`), over the scene's default.
    Light own = l;
    own.iesMode = "intensity";
    auto mixed = passes::convertLights({l, own}, passes::IesMode::Mask);
    ASSERT_TRUE(mixed.has_value());
    EXPECT_NEAR(mixed->lights[0].intensity.r, 1000.0 / kPi, 1e-3);
    EXPECT_NEAR(mixed->lights[1].intensity.r, 470.0, 1e-3);
    own.iesMode = "mask";
    auto overridden = passes::convertLights({own}, passes::IesMode::Intensity);
    ASSERT_TRUE(overridden.has_value());
    EXPECT_NEAR(overridden->lights[0].intensity.r, 1000.0 / kPi, 1e-3);
    // Two lights with one file share one baked profile.
    auto twice = passes::convertLights({l, l});
    ASSERT_TRUE(twice.has_value());
    EXPECT_EQ(twice->profiles.size(), 1u);
    EXPECT_EQ(twice->lights[1].intensity.a, 0.0f);
    // A missing file names the light and the file.
    l.ies = "/nonexistent/lamp.ies";
    auto missing = passes::convertLights({l});
    ASSERT_FALSE(missing.has_value());
    EXPECT_EQ(missing.error().message,
              "light 'washer' (spot): '/nonexistent/lamp.ies': no such IES file");
}

TEST_F(Lights, SpotLumensByEq17OrTheExactConeOfEq16) {
    // seed 000 eq:17 (the default): I = Φ / π whatever the cone; eq:16 (exact_cone): the flux
    // spread over the cone, I = Φ / (2π (1 − cos θ)), θ the outer half-angle. 1000 lm, θ = 30°.
    Light l;
    l.name = "torch";
    l.type = LightType::Spot;
    l.intensity = 1000;
    l.unit = "lm";
    l.outerAngle = static_cast<float>(kPi / 6);
    Light exact = l;
    exact.exactCone = true;
    auto r = passes::convertLights({l, exact});
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->lights[0].intensity.r, 1000.0 / kPi, 1e-3);
    EXPECT_NEAR(r->lights[1].intensity.r, 1000.0 / (2.0 * kPi * (1.0 - std::cos(kPi / 6))),
                1e-2);  // 1187.9 cd
    // The flux that leaves the exact cone is the declared one: ∫ I dω over the cone = Φ.
    EXPECT_NEAR(r->lights[1].intensity.r * 2.0 * kPi * (1.0 - std::cos(kPi / 6)), 1000.0, 0.1);
}

TEST_F(Lights, ConversionRefusesWhatTheShadersCannotTake) {
    Light sphere;
    sphere.name = "ball";
    sphere.type = LightType::Sphere;
    sphere.unit = "cd";
    sphere.radius = 0.1f;
    auto r = passes::convertLights({sphere});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(
        r.error().message,
        "light 'ball' (sphere): unit 'cd' is not one of 'lm', 'nits', 'ev100' (seed 000 tbl:8)");
    sphere.unit = "lm";
    sphere.radius = 0.0f;
    r = passes::convertLights({sphere});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message,
              "light 'ball' (sphere): radius must be positive metres, got 0.000000");
    std::vector<Light> many(passes::kMaxLights + 1);
    r = passes::convertLights(many);
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message,
              "the scene has 65537 lights; at most 65536 (the light lists' 16-bit indices)");
}

}  // namespace
