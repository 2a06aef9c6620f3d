// The G-buffer's draws chosen on the GPU (scripts/culling.lua, shaders/passes/camera_cull.comp):
// in a scene of at least culling.min_draws draws the culling pass lists each draw in its batch's
// indirect command and the G-buffer draws each material's commands with
// vkCmdDrawIndexedIndirectCount. The frustum test is conservative (the image without it is the
// same) and makes the CPU's choices (the image with gpu_culling off is the same), and it drops
// what lies outside the view.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "passes/gpu_scene.h"
#include "runtime/session.h"

using namespace rg;
namespace fs = std::filesystem;

namespace {

struct CityFrame {
    Image hdr;
    bool culledOnGpu = false;   // the culling pass ran
    uint32_t instances = 0;     // the instances its commands draw
    uint32_t gbufferDraws = 0;  // the draws the G-buffer draws at all (not blended)
    uint32_t inView = 0;        // of those, the ones the CPU's frustum test keeps
    uint32_t counted = 0;       // the commands the counts let the G-buffer draw
};

class CameraCulling : public GpuFixture {
protected:
    static CityFrame renderCity(const std::string& nodes,
                                const std::map<std::string, Value>& params, int minDraws);
};

// The project's city of `nodes` nodes at 320×180, one frame, with `params` set, through the default
// pipeline with the GPU culling from `minDraws` draws (culling.min_draws set before it loads).
CityFrame CameraCulling::renderCity(const std::string& nodes,
                                    const std::map<std::string, Value>& params, int minDraws) {
    const std::string city = std::string(RG_SOURCE_ROOT) + "/scripts/scenes/city.lua";
    std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
    std::stringstream deferred;
    deferred << in.rdbuf();
    fs::create_directories(RG_TEST_TMP);
    const std::string pipeline =
        std::string(RG_TEST_TMP) + "/culled_from_" + std::to_string(minDraws) + ".lua";
    std::ofstream(pipeline) << "require(\"culling\").min_draws = " << minDraws << "\n"
                            << deferred.str();
    SessionOptions o = sceneOptions(city, {}, 320, 180);
    o.sceneArgs["nodes"] = nodes;
    o.captures = {"hdr", "camera_draws", "camera_draw_counts"};
    o.params = params;
    Session s(rt(), o);
    CityFrame out;
    auto r = s.load(pipeline);
    EXPECT_TRUE(r.has_value()) << r.error().describe();
    if (!r || !s.frame()) return out;
    if (auto img = rt().executor().readback("hdr")) out.hdr = std::move(*img);
    const passes::GpuScene& scene = *s.gpuScene();
    for (size_t d = 0; d < scene.draws().size(); ++d)
        if (scene.scene().materials[scene.draws()[d].material].alphaMode != AlphaMode::Blend) {
            ++out.gbufferDraws;
            out.inView += scene.drawInView(d);
        }
    auto commands = rt().executor().readbackBuffer("camera_draws");
    auto counts = rt().executor().readbackBuffer("camera_draw_counts");
    out.culledOnGpu = commands.has_value() && counts.has_value();
    if (!out.culledOnGpu) return out;
    // VkDrawIndexedIndirectCommand: indexCount, instanceCount, firstIndex, vertexOffset,
    // firstInstance.
    for (size_t k = 0; k + 20 <= commands->size(); k += 20) {
        uint32_t instances = 0;
        std::memcpy(&instances, commands->data() + k + 4, 4);
        out.instances += instances;
    }
    for (size_t m = 0; m + 4 <= counts->size(); m += 4) {
        uint32_t n = 0;
        std::memcpy(&n, counts->data() + m, 4);
        out.counted += n;
    }
    return out;
}

size_t valuesThatDiffer(const Image& a, const Image& b) {
    size_t differ = a.pixels.size() == b.pixels.size() ? 0 : SIZE_MAX;
    for (size_t i = 0; differ != SIZE_MAX && i < a.pixels.size(); ++i)
        differ += a.pixels[i] != b.pixels[i];
    return differ;
}

TEST_F(CameraCulling, TheGpuDrawsWhatTheCpuDrawsAndCullsConservatively) {
    const CityFrame gpu = renderCity("2000", {}, 1024);
    const CityFrame all = renderCity("2000", {{"frustum_culling", Value(false)}}, 1024);
    const CityFrame cpu = renderCity("2000", {{"gpu_culling", Value(false)}}, 1024);
    ASSERT_FALSE(gpu.hdr.pixels.empty());
    ASSERT_TRUE(gpu.culledOnGpu) << "a city of 2000 nodes has more than 1024 draws";
    ASSERT_TRUE(all.culledOnGpu);
    EXPECT_FALSE(cpu.culledOnGpu) << "gpu_culling = false: the buffers leave the graph";
    std::printf(
        "%u G-buffer draws, %u in view on the CPU: %u instances drawn with the frustum test (%u "
        "commands counted), %u without; %zu and %zu of %zu values differ from the CPU's choice\n",
        gpu.gbufferDraws, gpu.inView, gpu.instances, gpu.counted, all.instances,
        valuesThatDiffer(gpu.hdr, cpu.hdr), valuesThatDiffer(all.hdr, cpu.hdr),
        gpu.hdr.pixels.size());
    EXPECT_EQ(all.instances, all.gbufferDraws) << "without the test every draw is drawn";
    EXPECT_EQ(gpu.instances, gpu.inView) << "the draws the CPU's frustum test keeps";
    EXPECT_LT(gpu.instances, gpu.gbufferDraws) << "what lies behind the camera is dropped";
    EXPECT_GT(gpu.instances, 0u);
    EXPECT_GT(gpu.counted, 0u);
    EXPECT_EQ(valuesThatDiffer(gpu.hdr, all.hdr), 0u) << "culling is conservative";
    EXPECT_EQ(valuesThatDiffer(gpu.hdr, cpu.hdr), 0u) << "the GPU makes the CPU's choices";
}

// Below culling.min_draws the CPU keeps choosing.
TEST_F(CameraCulling, ASmallSceneKeepsTheCpuPath) {
    const CityFrame small = renderCity("2000", {}, 4096);
    ASSERT_FALSE(small.hdr.pixels.empty());
    EXPECT_FALSE(small.culledOnGpu) << "1522 draws, fewer than 4096";
}

}  // namespace
