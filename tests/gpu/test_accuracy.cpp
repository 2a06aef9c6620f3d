// The area-light accuracy suite (rgraph accuracy, graph/cli/accuracy.h) at a small size: every
// light type × placement × material runs, every case lights enough pixels to measure, and today's
// errors stay where they were measured (64×48, 16 reference frames per half; printed). These are
// today's levels, not the targets (#15: sphere ≤ 1 %, disk ≤ 3 %, rect and tube ≤ 5 % in every
// case): the horizon and glossy-metal cases are far from them until the lights move to linearly
// transformed cosines.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "cli/accuracy.h"

using namespace rg;

namespace {

class Accuracy : public GpuFixture {};

TEST_F(Accuracy, EveryCaseRunsAndStaysWithinTodaysErrors) {
    AccuracyOptions o;
    o.width = 64;
    o.height = 48;
    o.frames = 16;
    auto cases = runAccuracy(*s_runtime, o);
    ASSERT_TRUE(cases) << cases.error().message;
    ASSERT_EQ(cases->size(), 36u);
    std::printf("%s", accuracyTable(*cases).c_str());
    // Measured mean error (%) of the real-time lights, rough / glossy / metal, worst placement,
    // with room for the reference's noise at this sample count.
    const std::map<std::string, std::array<double, 3>> bound = {
        {"sphere", {8, 11, 45}}, {"disk", {15, 19, 55}}, {"rect", {14, 12, 65}}, {"tube", {14, 16, 70}}};
    for (const auto& c : *cases) {
        SCOPED_TRACE(c.name());
        EXPECT_GT(c.pixels, 100u);  // lit pixel-channels: a glossy metal's highlight is small (~150 at 64×48)
        EXPECT_TRUE(std::isfinite(c.meanError) && std::isfinite(c.energyError));
        EXPECT_LT(c.referenceNoise, 0.16);
        const int m = c.material == "rough" ? 0 : c.material == "glossy" ? 1 : 2;
        EXPECT_LT(c.meanError * 100.0, bound.at(c.light)[size_t(m)]);
        if (c.placement == "facing" && c.material == "rough") {
            EXPECT_LT(c.meanError, c.light == "sphere" ? 0.02 : 0.08);
        }
    }
    const std::string dir = std::string(RG_TEST_TMP) + "/accuracy";
    ASSERT_TRUE(writeAccuracyReport(*cases, dir));
    EXPECT_TRUE(std::filesystem::exists(dir + "/index.html"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/rect_horizon_metal.png"));
}

}  // namespace
