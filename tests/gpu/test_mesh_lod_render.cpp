// Levels of detail built by meshoptimizer (graph/scene/mesh_lod.h) as the passes use them: a row
// of 45-segment spheres (a grid that does not halve, so no exact levels of their own) running
// away from the camera takes coarser levels with distance, and the image stays what the full
// meshes give (RG_LOD=0).
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "passes/gpu_scene.h"
#include "runtime/session.h"
#include "scene/scene.h"

using namespace rg;

namespace {

const char* kRow = R"(local scene = require "scene"
scene.material "grey" { base_color = { 0.6, 0.6, 0.6 }, smoothness = 0.6 }
scene.plane "floor" { size = { 12, 60 }, position = { 0, 0, -24 }, material = "grey" }
for i = 0, 11 do
    scene.sphere("s" .. i) { radius = 0.5, segments = 45, position = { (i % 2) * 1.2 - 0.6, 0.5, -i * 3 }, material = "grey" }
end
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.4, -0.7, -0.5 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.2, 3 }, target = { 0, 0.5, -10 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }
)";

class MeshLodRender : public GpuFixture {};

TEST_F(MeshLodRender, FarSpheresTakeCoarserLevelsAndTheImageStays) {
    TempFolder tmp("lod_row");
    std::ofstream(tmp.dir / "row.lua") << kRow;
    auto scene = loadSceneScript((tmp.dir / "row.lua").string(), {});
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    auto gpu = passes::GpuScene::create(s_runtime->gpu(), *scene);
    ASSERT_TRUE(gpu.has_value()) << gpu.error().describe();
    passes::GpuScene& g = **gpu;
    g.updateFrame(0, 640, 360);
    std::vector<uint32_t> levels;  // per sphere, front to back
    for (size_t d = 0; d < g.draws().size(); ++d) {
        const passes::DrawItem& item = g.draws()[d];
        if (item.lodCount < 2) continue;  // the floor
        uint32_t level = 0;
        while (level < item.lodCount && item.lods[level].firstIndex != g.viewLod(d).firstIndex)
            ++level;
        levels.push_back(level);
    }
    ASSERT_EQ(levels.size(), 12u) << "every sphere has meshoptimizer's levels";
    EXPECT_EQ(levels.front(), 0u) << "the nearest sphere keeps its full mesh";
    EXPECT_GE(levels.back(), 2u) << "the farthest takes a coarse level";
    for (size_t i = 1; i < levels.size(); ++i)
        EXPECT_GE(levels[i] + (i % 2 ? 1u : 0u), levels[i - 1]) << "sphere " << i;

    const std::string row = (tmp.dir / "row.lua").string();
    const Image a = renderHdr(row, true, 640, 360), b = renderHdr(row, false, 640, 360);
    ASSERT_EQ(a.width, 640u);
    ASSERT_EQ(b.width, 640u);
    const RenderDifference d = greenDifference(a, b);
    std::printf(
        "meshoptimizer levels %u..%u: mean |difference| %.3f %% of the mean, %.2f %% of "
        "pixels off by more than 5 %%\n",
        levels.front(), levels.back(), 100.0 * d.mean, 100.0 * d.share);
    EXPECT_LT(d.mean, 0.01);
    EXPECT_LT(d.share, 0.01);
}

// Nodes a scene script declares alike share one mesh, and the G-buffer draws a run of them as
// one instanced draw (passes/scene_pass.cpp drawGroups, scene.vert), the sun's cascades each
// batch of casters per level of detail (cascade_cull.comp, shadow.vert): the image is the one
// drawing them one at a time gives (RG_INSTANCING=0), bit for bit.
TEST_F(MeshLodRender, InstancedRunsDrawWhatSingleDrawsDo) {
    const std::string city = std::string(RG_SOURCE_ROOT) + "/scripts/scenes/city.lua";
    auto render = [&](bool instancing, uint32_t* instances) {
        if (!instancing) setenv("RG_INSTANCING", "0", 1);
        SessionOptions o = sceneOptions(city, {}, 320, 180);
        o.sceneArgs["nodes"] = "400";
        o.sceneArgs["materials"] = "4";
        o.captures = {"hdr"};
        Session s(*s_runtime, o);
        Image hdr;
        auto r = s.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (r && s.frame()) {
            if (auto img = s_runtime->executor().readback("hdr")) hdr = std::move(*img);
            EXPECT_LT(s.gpuScene()->scene().meshes.size(), 16u) << "the nodes share meshes";
            *instances = s.gpuScene()->instancesUsed(0);
        }
        unsetenv("RG_INSTANCING");
        return hdr;
    };
    uint32_t instanced = 0, single = 0;
    const Image a = render(true, &instanced), b = render(false, &single);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    ASSERT_FALSE(a.pixels.empty());
    size_t differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
    std::printf("%u draws drawn as instances, %zu of %zu values differ\n", instanced, differ,
                a.pixels.size());
    EXPECT_GT(instanced, 50u) << "runs of shared meshes are drawn instanced";
    EXPECT_EQ(single, 0u);
    EXPECT_EQ(differ, 0u);
}

}  // namespace
