// The area-light accuracy suite (rgraph accuracy, graph/cli/accuracy.h) at a small size: every
// light type × placement × material runs under both area-light models against one reference, every
// case lights enough pixels to measure, and each model's errors stay where they were measured
// (64×48, 2 × 8 × 128 reference samples per pixel; printed). The bounds (sphere ≤ 1 %, disk
// ≤ 3 %, rect and tube ≤ 5 %) hold for LTC in most cases; the README's table (96×72, 2 × 4096
// samples) says which not, and by how much.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "cli/accuracy.h"
#include "runtime/session.h"

using namespace rg;

namespace {

class Accuracy : public GpuFixture {};

// The suite at ctest's size (64×48) with a reference of 2 × frames × samples per pixel.
AccuracyOptions smallSuite(uint32_t frames, uint32_t samples) {
    AccuracyOptions o;
    o.width = 64;
    o.height = 48;
    o.frames = frames;
    o.samples = samples;
    return o;
}

TEST_F(Accuracy, EveryCaseRunsAndStaysWithinTodaysErrors) {
    AccuracyOptions o = smallSuite(8, 128);
    auto cases = runAccuracy(*s_runtime, o);
    ASSERT_TRUE(cases) << cases.error().message;
    ASSERT_EQ(cases->size(), 72u);
    std::printf("%s", accuracyTable(*cases).c_str());
    // Measured mean error (%), rough / glossy / metal, worst placement, with room for the
    // reference's noise at this sample count (~0.5–2 %).
    const std::map<std::string, std::array<double, 3>> frostbite = {{"sphere", {5, 8, 50}},
                                                                    {"disk", {12, 17, 50}},
                                                                    {"rect", {13, 8, 60}},
                                                                    {"tube", {8, 10, 65}}};
    const std::map<std::string, std::array<double, 3>> ltc = {{"sphere", {2.5, 2.5, 3.5}},
                                                              {"disk", {3, 3.5, 4.5}},
                                                              {"rect", {3, 4, 5}},
                                                              {"tube", {4, 4, 7}}};
    std::map<std::string, double> metalFrostbite;
    for (const auto& c : *cases) {
        SCOPED_TRACE(c.name());
        EXPECT_GT(c.pixels,
                  100u);  // lit pixel-channels: a glossy metal's highlight is small (~150 at 64×48)
        EXPECT_TRUE(std::isfinite(c.meanError) && std::isfinite(c.energyError));
        EXPECT_LT(c.referenceNoise, 0.04);
        const int m = c.material == "rough" ? 0 : c.material == "glossy" ? 1 : 2;
        const auto& bound = c.model == "ltc" ? ltc : frostbite;
        EXPECT_LT(c.meanError * 100.0, bound.at(c.light)[size_t(m)]);
        if (c.model == "ltc") {
            EXPECT_LT(std::abs(c.energyError), 0.03);  // the bound
        }
        const std::string key = c.light + c.placement;
        if (c.material == "metal" && c.model == "frostbite") metalFrostbite[key] = c.meanError;
        // LTC's point: the glossy metal's highlight, several times closer than the representative point.
        if (c.material == "metal" && c.model == "ltc") {
            EXPECT_LT(c.meanError * 3.0, metalFrostbite.at(key));
        }
    }
    const std::string dir = std::string(RG_TEST_TMP) + "/accuracy";
    ASSERT_TRUE(writeAccuracyReport(*cases, dir));
    EXPECT_TRUE(std::filesystem::exists(dir + "/index.html"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/rect_horizon_metal_ltc.png"));
}

TEST_F(Accuracy, TheSphereMeetsItsBoundOnTheGlossyMetal) {
    // The sphere's hardest cases, the glossy metal facing, grazing and crossing the horizon, under
    // LTC (rgLtcSphereRatio's 32-tap ratio) against a reference converged far enough that the
    // issue's 1 % bound means something: 64×48, 2 × 32768 samples per pixel, its own noise
    // 0.3–0.4 %, which the measured error includes. Measured: 0.30 / 0.50 / 0.70 %; the ratio at
    // the closed form's mean direction alone (rgLtcRatio, as the other lights use) gave 0.72 / 1.99
    // / 2.93 % here, and fails.
    AccuracyOptions o = smallSuite(64, 512);
    o.lights = {"sphere"};
    o.materials = {"metal"};
    o.models = {"ltc"};
    auto cases = runAccuracy(*s_runtime, o);
    ASSERT_TRUE(cases) << cases.error().message;
    ASSERT_EQ(cases->size(), 3u);
    std::printf("%s", accuracyTable(*cases).c_str());
    for (const auto& c : *cases) {
        SCOPED_TRACE(c.name());
        EXPECT_GT(c.pixels, 100u);
        EXPECT_LT(c.referenceNoise, 0.005);
        EXPECT_LT(c.meanError, 0.01);
        EXPECT_LT(std::abs(c.energyError), 0.03);
    }
}

}  // namespace

namespace {

class AreaLightModel : public GpuFixture {};

// The pipeline's area_lights parameter is a field of the scene's light block: switching it between
// frames changes the glossy metal's highlight and rebuilds nothing; the two models agree on the
// rough floor's diffuse light within a few per cent.
TEST_F(AreaLightModel, SwitchesBetweenFramesWithoutARebuild) {
    auto meanHdr = [](const Image& im) {
        double sum = 0.0;
        for (size_t i = 0; i < im.pixels.size(); i += 4)
            sum += im.pixels[i] + im.pixels[i + 1] + im.pixels[i + 2];
        return sum / double(im.pixels.size() / 4);
    };
    for (const char* material : {"metal", "rough"}) {
        SCOPED_TRACE(material);
        SessionOptions so;
        so.compile.outputWidth = 64;
        so.compile.outputHeight = 48;
        so.scene = projectRoot() + "/scripts/scenes/accuracy.lua";
        so.sceneArgs = {{"light", "rect"}, {"placement", "facing"}, {"material", material}};
        so.params["exposure_mode"] = Value("manual");
        Session s(*s_runtime, so);
        ASSERT_TRUE(s.load(projectRoot() + "/scripts/pipelines/deferred.lua"));
        ASSERT_EQ(s.pipeline().findParam("area_lights")->value.asString(), "ltc");  // the default
        ASSERT_TRUE(s.frame());
        auto ltc = readAbsoluteHdr(s_runtime->executor(), s.pipeline());
        ASSERT_TRUE(ltc);
        const uint32_t rebuilds =
            s.rebuilds();  // the first frame's toggles (no decals, no sun, no probes)
        ASSERT_TRUE(s.setOverride("area_lights", Value("frostbite")));
        ASSERT_TRUE(s.frame());
        auto frostbite = readAbsoluteHdr(s_runtime->executor(), s.pipeline());
        ASSERT_TRUE(frostbite);
        EXPECT_EQ(s.rebuilds(), rebuilds);
        const double a = meanHdr(ltc->image), b = meanHdr(frostbite->image);
        std::printf("%s: mean luminance ltc %.4f, frostbite %.4f cd/m2\n", material, a, b);
        if (std::string(material) == "metal") {
            double maxDiff = 0.0;
            for (size_t i = 0; i < ltc->image.pixels.size(); ++i)
                maxDiff = std::max(
                    maxDiff, double(std::abs(ltc->image.pixels[i] - frostbite->image.pixels[i])));
            EXPECT_GT(
                maxDiff,
                0.1 * a);  // the highlights differ (README: 3 % against 38 % from the reference)
        } else {
            EXPECT_NEAR(a, b, 0.05 * b);
        }
    }
}

}  // namespace
