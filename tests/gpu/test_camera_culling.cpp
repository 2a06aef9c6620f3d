// Draws chosen on the GPU. The G-buffer's (scripts/culling.lua, shaders/passes/camera_cull.comp):
// in a scene of at least culling.min_draws draws the culling pass lists each draw in its batch's
// indirect command and the G-buffer draws each camera run's commands (the materials of one
// pipeline, cull mode and texture set, their parameters read by index) with
// vkCmdDrawIndexedIndirectCount. The frustum test is conservative (the image without it is the
// same) and makes the CPU's choices (the image with gpu_culling off is the same), and it drops
// what lies outside the view. The local lights' shadow casters per view (scripts/shadows.lua,
// shaders/shadows/local_cull.comp): the maps the CPU's walk over every view and caster drew.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "image/image.h"
#include "layout/layout.h"
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
    uint32_t coarse = 0;        // instances drawn at a coarser level of detail than the full mesh
    uint32_t cpuInstances = 0;  // entries of the CPU's instance list the frame used
    size_t runs = 0;            // camera runs: one indirect count draw each
    uint32_t window = 1;        // materials a run's window holds
};

class GpuCulling : public GpuFixture {
protected:
    static CityFrame renderCity(const std::string& nodes,
                                const std::map<std::string, Value>& params, int minDraws,
                                bool fullMeshes = false);
};

// The project's city of `nodes` nodes at 320×180, one frame, with `params` set, through the default
// pipeline with the GPU culling from `minDraws` draws (culling.min_draws set before it loads).
CityFrame GpuCulling::renderCity(const std::string& nodes,
                                 const std::map<std::string, Value>& params, int minDraws,
                                 bool fullMeshes) {
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
    // A pass that traces the scene's triangles makes the camera draw the full meshes.
    if (r && fullMeshes) s.gpuScene()->drawFullMeshes();
    if (!r || !s.frame()) return out;
    out.cpuInstances = s.gpuScene()->instancesUsed(0);
    if (auto img = rt().executor().readback("hdr")) out.hdr = std::move(*img);
    const passes::GpuScene& scene = *s.gpuScene();
    out.runs = scene.cameraRuns().size();
    out.window = scene.materialWindow();
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
        if ((k / 20) % 4 != 0) out.coarse += instances;  // batch · 4 + level
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

TEST_F(GpuCulling, TheGpuDrawsWhatTheCpuDrawsAndCullsConservatively) {
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
    // 258 untextured standard materials: one count draw per window of materials (157 on
    // lavapipe's 64 KiB uniform blocks).
    EXPECT_EQ(gpu.runs, (258u + gpu.window - 1) / gpu.window);
    EXPECT_EQ(all.instances, all.gbufferDraws) << "without the test every draw is drawn";
    EXPECT_EQ(gpu.instances, gpu.inView) << "the draws the CPU's frustum test keeps";
    EXPECT_LT(gpu.instances, gpu.gbufferDraws) << "what lies behind the camera is dropped";
    EXPECT_GT(gpu.instances, 0u);
    EXPECT_GT(gpu.counted, 0u);
    EXPECT_EQ(gpu.cpuInstances, 0u) << "the G-buffer drew the GPU's commands, not the CPU's runs";
    EXPECT_GT(cpu.cpuInstances, 0u);
    EXPECT_GT(gpu.coarse, 0u) << "the far buildings at coarser levels";
    EXPECT_EQ(valuesThatDiffer(gpu.hdr, all.hdr), 0u) << "culling is conservative";
    EXPECT_EQ(valuesThatDiffer(gpu.hdr, cpu.hdr), 0u) << "the GPU makes the CPU's choices";
}

// Where a pass traces the full meshes (the reference mode: GpuScene::drawFullMeshes), the GPU's
// levels are the full ones too.
TEST_F(GpuCulling, FullMeshesWhereAPassTracesThem) {
    const CityFrame full = renderCity("2000", {}, 1024, true);
    ASSERT_TRUE(full.culledOnGpu);
    EXPECT_GT(full.instances, 0u);
    EXPECT_EQ(full.coarse, 0u);
}

// Two-phase occlusion culling over frames of the city as the camera walks down its street and
// turns (blocks come into view every frame): each frame's image is the one without the occlusion
// test, bit for bit — a draw the first phase (last frame's visible set) lacks is drawn by the
// second where it shows — while frames after the first draw most of the G-buffer in the first
// phase and leave the hidden draws out. At 320×180 and at 203×117, whose depth pyramid has blocks
// of 8 and 9 pixels and mips of odd sizes; with TAA's sub-pixel jitter on (the test's pixel
// margin); and with occlusion_culling switched off and on again mid-walk.
TEST_F(GpuCulling, OcclusionCullingChangesNoPixelAsTheCameraMoves) {
    const std::string city = std::string(RG_SOURCE_ROOT) + "/scripts/scenes/city.lua";
    fs::create_directories(RG_TEST_TMP);
    const std::string pipeline = std::string(RG_TEST_TMP) + "/occlusion_from_1024.lua";
    {
        std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
        std::stringstream deferred;
        deferred << in.rdbuf();
        std::ofstream(pipeline) << "require(\"culling\").min_draws = 1024\n" << deferred.str();
    }
    auto instances = [&](const char* name) {
        uint32_t total = 0;
        if (auto commands = rt().executor().readbackBuffer(name))
            for (size_t k = 0; k + 20 <= commands->size(); k += 20) {
                uint32_t n = 0;
                std::memcpy(&n, commands->data() + k + 4, 4);
                total += n;
            }
        return total;
    };
    constexpr int kFrames = 6;
    struct Frames {
        std::vector<Image> hdr;
        std::vector<uint32_t> first, second;
    };
    // switchAt: the frame from which occlusion_culling is off for one frame, then on again.
    auto render = [&](bool occlusion, uint32_t width, uint32_t height, int switchAt = -1) {
        SessionOptions o = sceneOptions(city, {}, width, height);
        o.sceneArgs["nodes"] = "2000";
        o.sceneArgs["walk"] = "60";
        o.captures = {"hdr", "camera_draws", "camera_early_draws"};
        o.params["occlusion_culling"] = Value(occlusion);
        o.paramsIfDeclared["taa_jitter"] = Value(true);
        Session s(rt(), o);
        Frames out;
        auto r = s.load(pipeline);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        for (int f = 0; r && f < kFrames; ++f) {
            if (switchAt >= 0 && (f == switchAt || f == switchAt + 1)) {
                auto set = s.setOverride("occlusion_culling", Value(f != switchAt));
                EXPECT_TRUE(set.has_value()) << set.error().describe();
            }
            if (!s.frame()) break;
            if (auto img = rt().executor().readback("hdr")) out.hdr.push_back(std::move(*img));
            out.first.push_back(instances("camera_early_draws"));
            out.second.push_back(instances("camera_draws"));
        }
        return out;
    };
    for (auto [width, height] : {std::pair{320u, 180u}, std::pair{203u, 117u}}) {
        const Frames on = render(true, width, height), off = render(false, width, height);
        ASSERT_EQ(on.hdr.size(), size_t(kFrames));
        ASSERT_EQ(off.hdr.size(), size_t(kFrames));
        uint32_t newlyShown = 0;
        for (size_t f = 0; f < kFrames; ++f) {
            std::printf(
                "%ux%u frame %zu: %u drawn first, %u second, %u in the frustum; %zu of %zu "
                "values differ\n",
                width, height, f, on.first[f], on.second[f], off.second[f],
                valuesThatDiffer(on.hdr[f], off.hdr[f]), on.hdr[f].pixels.size());
            EXPECT_EQ(valuesThatDiffer(on.hdr[f], off.hdr[f]), 0u) << width << " frame " << f;
            EXPECT_EQ(off.first[f], 0u) << "occlusion_culling = false: one phase";
            if (f == 0) continue;
            EXPECT_GT(on.first[f], 0u) << "last frame's visible set, first";
            newlyShown += on.second[f];
            // Frame 0 tested everything against an empty depth (its first phase drew nothing),
            // so frame 1 draws it all first; from frame 2 the sets are the ones that showed.
            if (f >= 2) {
                EXPECT_LT(on.first[f] + on.second[f], off.second[f] / 2) << "most hidden";
            }
        }
        EXPECT_EQ(on.first[0], 0u) << "no last frame: everything tested against an empty depth";
        EXPECT_EQ(on.second[0], off.second[0]);
        EXPECT_GT(newlyShown, 0u) << "blocks coming into view drawn in the second phase";
        if (width != 320) continue;
        // Switched off at frame 2 and on again at frame 3: the graph is rebuilt each time.
        const Frames switched = render(true, width, height, 2);
        ASSERT_EQ(switched.hdr.size(), size_t(kFrames));
        EXPECT_EQ(switched.first[2], 0u) << "one phase while off";
        EXPECT_GT(switched.first[5], 0u) << "two phases again";
        for (size_t f = 0; f < kFrames; ++f)
            EXPECT_EQ(valuesThatDiffer(switched.hdr[f], off.hdr[f]), 0u) << "switched, frame " << f;
    }
}

// Below culling.min_draws the CPU keeps choosing, and where the device cannot draw the GPU's lists.
TEST_F(GpuCulling, ASmallSceneKeepsTheCpuPath) {
    const CityFrame small = renderCity("2000", {}, 4096);
    ASSERT_FALSE(small.hdr.pixels.empty());
    EXPECT_FALSE(small.culledOnGpu) << "1522 draws, fewer than 4096";
    // Nor where the passes cannot draw from GPU-written instance lists (scene feature gpu_draws:
    // here instancing off), so that no culling runs for a G-buffer that would not use it.
    setenv("RG_INSTANCING", "0", 1);
    const CityFrame single = renderCity("2000", {}, 1024);
    unsetenv("RG_INSTANCING");
    ASSERT_FALSE(single.hdr.pixels.empty());
    EXPECT_FALSE(single.culledOnGpu) << "RG_INSTANCING=0: the CPU's path";
    EXPECT_EQ(
        valuesThatDiffer(single.hdr, renderCity("2000", {{"gpu_culling", Value(false)}}, 1024).hdr),
        0u);
}

// A point light's six cube faces over a ring of boxes sharing one mesh (one caster batch of eight,
// the ground another) and spheres with levels of detail: the casters culled per view on the GPU
// draw the maps the CPU's walk over every view and caster drew (gpu_shadow_culling = false), and
// the CPU no longer walks them.
const char* kRing = R"(local scene = require "scene"
scene.material "grey" { base_color = { 0.6, 0.6, 0.6 }, smoothness = 0.3 }
scene.plane "ground" { size = { 30, 30 }, material = "grey" }
for i = 0, 7 do
    local a = i * math.pi / 4
    scene.box("box" .. i) { size = { 0.6, 0.6, 0.6 }, position = { 3 * math.cos(a), 0.3, 3 * math.sin(a) }, material = "grey" }
    scene.sphere("ball" .. i) { radius = 0.3, segments = 45, position = { 5 * math.cos(a + 0.3), 0.3, 5 * math.sin(a + 0.3) }, material = "grey" }
end
scene.light "lamp" { type = "point", intensity = 4000, unit = "lm", position = { 0, 1.5, 0 }, range = 30, shadow = true }
scene.camera "main" { position = { 0, 9, 9 }, target = { 0, 0, 0 }, fov = 45, aperture = 4, shutter = 1 / 60, iso = 100 }
)";

TEST_F(GpuCulling, LocalLightsCastersCulledPerViewAsTheCpuDid) {
    TempFolder tmp("local_cull");
    std::ofstream(tmp.dir / "ring.lua") << kRing;
    auto render = [&](bool gpu, uint64_t* walks, uint32_t* instances, std::vector<Image>* maps) {
        SessionOptions o = sceneOptions((tmp.dir / "ring.lua").string(), {}, 320, 180);
        o.captures = {"hdr", "local_shadow", "local_shadow_draws"};
        o.params["gpu_shadow_culling"] = Value(gpu);
        Session s(rt(), o);
        Image hdr;
        auto r = s.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r || !s.frame()) return hdr;
        if (auto img = rt().executor().readback("hdr")) hdr = std::move(*img);
        for (uint32_t layer = 0; layer < 6; ++layer)
            if (auto map = rt().executor().readback("local_shadow", layer))
                maps->push_back(std::move(*map));
        *walks = s.gpuScene()->shadowViewWalks();
        *instances = 0;
        if (auto commands = rt().executor().readbackBuffer("local_shadow_draws"))
            for (size_t k = 0; k + 20 <= commands->size(); k += 20) {
                uint32_t n = 0;
                std::memcpy(&n, commands->data() + k + 4, 4);
                *instances += n;
            }
        return hdr;
    };
    uint64_t gpuWalks = 0, cpuWalks = 0;
    uint32_t gpuInstances = 0, cpuInstances = 0;
    std::vector<Image> gpuMaps, cpuMaps;
    const Image gpu = render(true, &gpuWalks, &gpuInstances, &gpuMaps);
    const Image cpu = render(false, &cpuWalks, &cpuInstances, &cpuMaps);
    ASSERT_FALSE(gpu.pixels.empty());
    ASSERT_EQ(gpuMaps.size(), 6u);
    ASSERT_EQ(cpuMaps.size(), 6u);
    size_t mapsDiffer = 0;
    for (size_t f = 0; f < 6; ++f) mapsDiffer += valuesThatDiffer(gpuMaps[f], cpuMaps[f]);
    std::printf(
        "six views, 17 casters: %u instances listed on the GPU; CPU walks %llu and %llu; "
        "%zu map texels and %zu image values differ\n",
        gpuInstances, static_cast<unsigned long long>(gpuWalks),
        static_cast<unsigned long long>(cpuWalks), mapsDiffer, valuesThatDiffer(gpu, cpu));
    EXPECT_GT(gpuInstances, 17u) << "casters in more than one face";
    EXPECT_LT(gpuInstances, 6u * 17u) << "not every caster in every face";
    EXPECT_EQ(gpuWalks, 0u) << "the shadow pass drew the GPU's commands";
    EXPECT_GT(cpuWalks, 0u);
    EXPECT_EQ(cpuInstances, 0u) << "gpu_shadow_culling = false: the buffers leave the graph";
    EXPECT_EQ(mapsDiffer, 0u);
    EXPECT_EQ(valuesThatDiffer(gpu, cpu), 0u);
}

// Many materials, few draw calls (GpuScene::CameraRun): 24 boxes, each its own material (its own
// colour and smoothness), every third double-sided; boxes 16-23 have base-colour maps: a.png and
// b.png (4×4, one texture array: layers 0 and 1) and c.png (8×8, an array of its own), the ground a
// checker (16×16). Their draws go in one indirect count draw per camera run — pipeline material,
// alpha mode, cull mode, texture set (an array and sampler per slot) and window of materials: four
// sets and six runs here, not 25 — and each
// box's G-buffer holds its own material's parameters (read by index from its run's window of
// them) and its own image's texels (the layer its material names), on the GPU's path and on the
// CPU's, whose G-buffers and images are the same.
const char* kPalette = R"(local scene = require "scene"
-- 150 materials no draw uses: the boxes' fall on both sides of the end of the first window of
-- materials (157 of them in a 64 KiB uniform block).
for k = 1, 150 do scene.material("spare" .. k) { base_color = { 1, 0, 1 } } end
scene.material "ground" { base_color = { 0.4, 0.4, 0.4 }, base_color_map = "ground.png" }
scene.plane "ground" { size = { 20, 20 }, material = "ground" }
for i = 0, 23 do
  local m = { base_color = { (i + 1) / 24, 0.5, 1 - (i + 1) / 24 }, smoothness = 0.2 + i / 40, double_sided = i % 3 == 0 }
  if i >= 16 then m.base_color_map = i < 20 and "a.png" or i < 22 and "b.png" or "c.png" end
  scene.material("m" .. i)(m)
  scene.box("box" .. i) { size = { 0.6, 0.6, 0.6 }, position = { (i % 12 - 5.5) * 1.2, 0.3, (i // 12 - 0.5) * 1.5 }, material = "m" .. i }
end
-- Upside down: seen from above, only its back face, which only a double-sided draw shows.
scene.material "back" { base_color = { 0.9, 0.1, 0.1 }, double_sided = true }
scene.plane "lid" { size = { 1.5, 1.5 }, position = { 0, 0.05, 2.5 }, rotation = { 180, 0, 0 }, material = "back" }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.3, -0.8, -0.5 } }
scene.camera "main" { position = { 0, 10, 4 }, target = { 0, 0, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }
)";

TEST_F(GpuCulling, ManyMaterialsDrawInOneCallPerPipelineCullModeAndTextures) {
    TempFolder tmp("palette");
    std::ofstream(tmp.dir / "palette.lua") << kPalette;
    const std::tuple<const char*, uint32_t, float> maps[] = {
        {"a.png", 4, 0.9f}, {"b.png", 4, 0.6f}, {"c.png", 8, 0.75f}};
    for (auto [name, size, grey] : maps) {
        Image map(size, size, 3);
        std::fill(map.pixels.begin(), map.pixels.end(), grey);
        ASSERT_TRUE(writePng((tmp.dir / name).string(), map).has_value());
    }
    // The ground's checker, minified far off: its mip level comes from the uv's derivatives over
    // 2 × 2 pixels, helper invocations' included.
    Image checker(16, 16, 3);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x)
            for (uint32_t c = 0; c < 3; ++c)
                checker.pixels[(y * 16 + x) * 3 + c] = (x + y) % 2 ? 0.9f : 0.1f;
    ASSERT_TRUE(writePng((tmp.dir / "ground.png").string(), checker).has_value());
    std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
    std::stringstream deferred;
    deferred << in.rdbuf();
    std::ofstream(tmp.dir / "culled.lua") << "require(\"culling\").min_draws = 1\n"
                                          << deferred.str();
    constexpr uint32_t kW = 320, kH = 180;
    const char* targets[] = {"GB0", "GB1", "GB2", "GB3"};
    struct Frame {
        std::vector<Image> gbuffer;
        Image hdr;
        std::vector<uint8_t> counts;
        std::vector<std::array<float, 4>> colourSmoothness;  // per box, its top's centre; the lid
        size_t sets = 0, runs = 0;
        uint32_t window = 0;
    };
    auto render = [&](bool gpu) {
        Frame f;
        SessionOptions o = sceneOptions((tmp.dir / "palette.lua").string(), {}, kW, kH);
        o.captures = {"hdr", "GB0", "GB1", "GB2", "GB3", "camera_draw_counts"};
        o.params["gpu_culling"] = Value(gpu);
        Session s(rt(), o);
        auto r = s.load((tmp.dir / "culled.lua").string());
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r || !s.frame()) return f;
        const passes::GpuScene& scene = *s.gpuScene();
        EXPECT_EQ(scene.scene().materials.size(), 176u);
        f.sets = scene.textureSetCount();
        f.runs = scene.cameraRuns().size();
        f.window = scene.materialWindow();
        for (const char* t : targets) {
            auto img = rt().executor().readback(t);
            EXPECT_TRUE(img.has_value()) << t;
            if (img) f.gbuffer.push_back(std::move(*img));
        }
        if (auto img = rt().executor().readback("hdr")) f.hdr = std::move(*img);
        if (auto counts = rt().executor().readbackBuffer("camera_draw_counts"))
            f.counts = std::move(*counts);
        // The standard layout's channels at each box's top.
        auto info = analyzeLayout(s.pipeline().layouts.front());
        EXPECT_TRUE(info.has_value());
        if (!info || f.gbuffer.size() != 4) return f;
        const Camera& c = scene.scene().cameras.front();
        const glm::mat4 viewProj = cameraViewProj(c.position, c.target, 45.0f, kW, kH);
        for (int i = 0; i < 25; ++i) {
            const glm::vec3 top = i < 24 ? glm::vec3((float(i % 12) - 5.5f) * 1.2f, 0.6f,
                                                     (float(i / 12) - 0.5f) * 1.5f)
                                         : glm::vec3(0.0f, 0.05f, 2.5f);
            const glm::ivec2 px = pixelOf(viewProj, kW, kH, top);
            std::vector<TexelValue> texels;
            for (size_t t = 0; t < 4; ++t)
                texels.push_back(texelFromFloats(
                    info->desc.targets[t].format,
                    &f.gbuffer[t]
                         .pixels[(size_t(px.y) * kW + size_t(px.x)) * f.gbuffer[t].channels],
                    f.gbuffer[t].channels));
            const auto channels = unpackTexel(*info, texels);
            const auto& base = channels[static_cast<size_t>(info->find("baseColor"))].v;
            f.colourSmoothness.push_back(
                {base[0], base[1], base[2],
                 channels[static_cast<size_t>(info->find("smoothness"))].v[0]});
        }
        return f;
    };
    const Frame gpu = render(true);
    const Frame cpu = render(false);
    // Every image an array of its own (arrays closed at 80 bytes, below one 4×4 image's 84).
    setenv("RG_TEXTURE_ARRAY_BYTES", "80", 1);
    const Frame split = render(true);
    unsetenv("RG_TEXTURE_ARRAY_BYTES");
    ASSERT_EQ(gpu.gbuffer.size(), 4u);
    ASSERT_EQ(cpu.gbuffer.size(), 4u);
    ASSERT_EQ(split.gbuffer.size(), 4u);
    EXPECT_EQ(gpu.sets, 4u) << "none; a.png and b.png's array; c.png's; the ground's";
    EXPECT_EQ(split.sets, 5u) << "a.png and b.png apart";
    // Window 0 (materials 0-156): the ground; boxes 0-5, untextured, both cull modes. Window 1:
    // boxes 6-23 and the lid — untextured and 4×4 both cull modes, 8×8 single-sided; split, a.png
    // and b.png both cull modes each.
    if (gpu.window == 157) {
        EXPECT_EQ(gpu.runs, 8u);
        EXPECT_EQ(split.runs, 10u);
    }
    // The GPU's path: a count per camera run (each has draws in view), the rest of the buffer 0.
    size_t counted = 0;
    for (size_t k = 0; k + 4 <= gpu.counts.size(); k += 4) {
        uint32_t n = 0;
        std::memcpy(&n, gpu.counts.data() + k, 4);
        counted += n != 0;
    }
    EXPECT_EQ(counted, gpu.runs) << "every run drawn";
    EXPECT_TRUE(cpu.counts.empty()) << "gpu_culling = false: the CPU's path";
    for (const Frame* f : {&gpu, &cpu}) {
        ASSERT_EQ(f->colourSmoothness.size(), 25u);
        const auto& lid = f->colourSmoothness[24];
        EXPECT_NEAR(srgbEncode(lid[0]), srgbEncode(0.9f), 0.6f / 255) << "the lid's back face";
        EXPECT_NEAR(srgbEncode(lid[1]), srgbEncode(0.1f), 0.6f / 255) << "the lid's back face";
        for (int i = 0; i < 24; ++i) {
            const auto& v = f->colourSmoothness[static_cast<size_t>(i)];
            // The factor times the map's texel (sRGB-decoded from its 8 bits); white without.
            const float grey = i < 16 ? 1.0f
                                      : srgbDecode(std::round(std::get<2>(maps[i < 20   ? 0
                                                                               : i < 22 ? 1
                                                                                        : 2]) *
                                                              255) /
                                                   255);
            const float red = float(i + 1) / 24.0f, blue = 1.0f - red;
            EXPECT_NEAR(srgbEncode(v[0]), srgbEncode(red * grey), 0.6f / 255) << "box " << i;
            EXPECT_NEAR(srgbEncode(v[1]), srgbEncode(0.5f * grey), 0.6f / 255) << "box " << i;
            EXPECT_NEAR(srgbEncode(v[2]), srgbEncode(blue * grey), 0.6f / 255) << "box " << i;
            EXPECT_NEAR(v[3], 0.2f + float(i) / 40.0f, 0.5f / 1023 + 1e-5f) << "box " << i;
        }
    }
    for (size_t t = 0; t < 4; ++t) {
        EXPECT_EQ(valuesThatDiffer(gpu.gbuffer[t], cpu.gbuffer[t]), 0u) << targets[t];
        EXPECT_EQ(valuesThatDiffer(split.gbuffer[t], gpu.gbuffer[t]), 0u) << targets[t];
    }
    EXPECT_EQ(valuesThatDiffer(gpu.hdr, cpu.hdr), 0u);
    EXPECT_EQ(valuesThatDiffer(split.hdr, gpu.hdr), 0u);
}

}  // namespace
