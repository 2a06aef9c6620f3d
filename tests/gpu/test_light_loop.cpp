// The standard light loop's two forms (materials/standard_shading.glsl): with up to four lights
// that reach every pixel, they are unrolled with their indices and types known per scene
// (RG_SCENE_GLOBAL_LIGHTS, passes/shader_program.cpp), and the tile's ranged lights follow with
// only their types; with more, one loop over the whole list. Both must light the scene alike.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;

class LightLoop : public GpuFixture {
protected:
    static Image hdr(const std::map<std::string, std::string>& args) {
        SessionOptions o =
            sceneOptions(kRoot + "/tests/gpu/scenes/global_lights.lua", args, 160, 120);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
        return r.images.empty() ? Image{} : r["hdr"];
    }
};

TEST_F(LightLoop, UnrolledGlobalLightsLightTheSceneAsTheGenericLoop) {
    const Image unrolled = hdr({});  // sun, point, spot without a range: unrolled
    const Image generic =
        hdr({{"more", "1"}});  // five without a range (two of them dark): one loop
    ASSERT_EQ(unrolled.width, 160u);
    ASSERT_EQ(generic.pixels.size(), unrolled.pixels.size());
    double worst = 0.0, peak = 0.0;
    for (size_t i = 0; i < unrolled.pixels.size(); ++i) {
        peak = std::max(peak, double(generic.pixels[i]));
        worst = std::max(worst, std::abs(double(unrolled.pixels[i]) - double(generic.pixels[i])) /
                                    std::max(1e-3, double(generic.pixels[i])));
    }
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(worst, 1e-4) << "largest relative difference between the two loops";
}

TEST_F(LightLoop, LargeRangedLightsUnrolledLightTheSceneAsTheTilesLists) {
    // At most four lights, every ranged one reaching a quarter of the scene's diagonal: all are
    // unrolled and no tile loop is compiled (passes/shader_program.cpp). The window ends each light
    // at its range exactly, so pixels beyond it get what the tiles' lists gave them: nothing.
    // Against the same lights through the generic loop (two dark lights more make five).
    const Image unrolled = hdr({{"few", "1"}});
    const Image generic = hdr({{"few", "1"}, {"more", "1"}});
    ASSERT_EQ(unrolled.width, 160u);
    ASSERT_EQ(generic.pixels.size(), unrolled.pixels.size());
    double worst = 0.0, peak = 0.0;
    size_t reached = 0;
    for (size_t i = 0; i < unrolled.pixels.size(); ++i) {
        peak = std::max(peak, double(generic.pixels[i]));
        worst = std::max(worst, std::abs(double(unrolled.pixels[i]) - double(generic.pixels[i])) /
                                    std::max(1e-3, double(generic.pixels[i])));
    }
    // The ranged lights do light the scene (against the sun alone, brighter somewhere).
    const Image sunAlone = hdr({{"few", "1"}, {"dark", "1"}});
    ASSERT_EQ(sunAlone.pixels.size(), unrolled.pixels.size());
    for (size_t i = 0; i < unrolled.pixels.size(); ++i)
        reached += unrolled.pixels[i] > 1.05f * sunAlone.pixels[i] + 1e-3f;
    EXPECT_GT(peak, 0.0);
    EXPECT_GT(reached, 100u) << "pixels the ranged lights brighten";
    EXPECT_LT(worst, 1e-4)
        << "largest relative difference between the unrolled and the generic loop";
}

}  // namespace
