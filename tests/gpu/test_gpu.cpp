// GPU tests on the real Vulkan device (lavapipe in CI) with the validation layer on: every test
// ends by checking that the layer said nothing.
#include <gtest/gtest.h>

#include <chrono>

#include "gpu_fixture.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "runtime/runtime.h"
#include "image/image.h"

namespace fs = std::filesystem;
using namespace rg;

namespace {

class GpuTest : public GpuFixture {
protected:
};

ResourceDesc texture(const std::string& name, Format f, bool exported = false) {
    ResourceDesc r;
    r.name = name;
    r.texture.format = f;
    r.exported = exported;
    return r;
}

PassDesc pass(const std::string& name, const std::string& kind, std::vector<Access> accesses,
              Value::Table params = {}) {
    PassDesc p;
    p.name = name;
    p.kind = kind;
    p.accesses = std::move(accesses);
    p.params = Value(std::move(params));
    return p;
}

// The CPU version of shaders/test/pattern.comp.
std::array<float, 4> patternAt(uint32_t x, uint32_t y) {
    float checker = static_cast<float>(((x >> 3) + (y >> 3)) & 1u);
    return {static_cast<float>(x & 63u) / 64.0f, static_cast<float>(y & 63u) / 64.0f, checker,
            1.0f};
}
// The CPU version of shaders/test/transform.frag.
std::array<float, 4> transform(std::array<float, 4> c, float scale) {
    return {c[1] * scale, c[0] * scale, (1.0f - c[2]) * scale, scale};
}

// compute pattern -> fullscreen transform (scale 0.5) -> readback pass.
GraphDesc threePassGraph() {
    GraphDesc g;
    g.resources = {texture("pattern", Format::RGBA16F), texture("shaded", Format::RGBA16F)};
    g.passes = {
        pass("generate", "compute", {{"pattern", Usage::StorageWrite}},
             {{"shader", "test/pattern.comp"}}),
        pass(
            "transform", "fullscreen",
            {{"pattern", Usage::Sampled}, {"shaded", Usage::ColorAttachment}},
            {{"shader", "test/transform.frag"}, {"uniforms", Value(Value::Table{{"scale", 0.5}})}}),
        pass("fetch", "readback", {{"shaded", Usage::CopySrc}}),
    };
    g.passes.back().sideEffect = true;
    return g;
}

TEST_F(GpuTest, ThreePassGraphIsExactPixelForPixel) {
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 96;
    o.outputHeight = 40;
    ASSERT_TRUE(ex.build(threePassGraph(), o).has_value());
    ASSERT_EQ(ex.plan().passes.size(), 3u);
    ASSERT_TRUE(ex.frame().has_value());
    auto img = ex.passResult("fetch");
    ASSERT_TRUE(img.has_value()) << img.error().describe();
    ASSERT_EQ(img->width, 96u);
    ASSERT_EQ(img->height, 40u);
    ASSERT_EQ(img->channels, 4u);
    int mismatches = 0;
    for (uint32_t y = 0; y < 40; ++y)
        for (uint32_t x = 0; x < 96; ++x) {
            auto want = transform(patternAt(x, y), 0.5f);
            for (uint32_t c = 0; c < 4; ++c)
                if (img->at(x, y, c) != want[c] && mismatches++ < 5)
                    ADD_FAILURE() << "pixel (" << x << "," << y << ") channel " << c << ": "
                                  << img->at(x, y, c) << " != " << want[c];
        }
    EXPECT_EQ(mismatches, 0);
    ASSERT_EQ(ex.lastTimings().size(), 3u);
    EXPECT_EQ(ex.lastTimings()[1].name, "transform");
}

TEST_F(GpuTest, ParameterChangeNeedsNoRebuild) {
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 16;
    o.outputHeight = 16;
    GraphDesc g = threePassGraph();
    ASSERT_TRUE(ex.build(g, o).has_value());
    ASSERT_TRUE(ex.frame().has_value());
    auto a = ex.passResult("fetch");
    ASSERT_TRUE(a.has_value());
    EXPECT_FLOAT_EQ(a->at(3, 5, 3), 0.5f);
    // Uniforms are written every frame from the pass's params.
    const_cast<PassDesc&>(ex.graph().passes[1]).params.table()["uniforms"] =
        Value(Value::Table{{"scale", 2.0}});
    ASSERT_TRUE(ex.frame().has_value());
    auto b = ex.passResult("fetch");
    ASSERT_TRUE(b.has_value());
    EXPECT_FLOAT_EQ(b->at(3, 5, 3), 2.0f);
    EXPECT_FLOAT_EQ(b->at(3, 5, 0), transform(patternAt(3, 5), 2.0f)[0]);
}

TEST_F(GpuTest, AliasedTransientsShareMemoryAndStayExact) {
    // a -> b -> c -> output: a and c have disjoint lifetimes and the same size, so they alias.
    GraphDesc g;
    g.resources = {texture("a", Format::RGBA16F), texture("b", Format::RGBA16F),
                   texture("c", Format::RGBA16F),
                   texture("output", Format::RGBA16F, /*exported=*/true)};
    auto step = [](const std::string& name, const std::string& from, const std::string& to) {
        return pass(name, "fullscreen", {{from, Usage::Sampled}, {to, Usage::ColorAttachment}},
                    {{"shader", "test/transform.frag"},
                     {"bind", Value(Value::Table{{"pattern", Value(from)}})},
                     {"uniforms", Value(Value::Table{{"scale", 1.0}})}});
    };
    g.passes = {pass("generate", "compute", {{"a", Usage::StorageWrite}},
                     {{"shader", "test/pattern.comp"},
                      {"bind", Value(Value::Table{{"pattern", Value("a")}})}}),
                step("t1", "a", "b"), step("t2", "b", "c"), step("t3", "c", "output")};
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 64;
    o.outputHeight = 48;
    auto built = ex.build(g, o);
    ASSERT_TRUE(built.has_value()) << built.error().describe();
    const Plan& plan = ex.plan();
    const auto& ra = plan.resources[static_cast<size_t>(plan.findResource("a"))];
    const auto& rc = plan.resources[static_cast<size_t>(plan.findResource("c"))];
    ASSERT_GE(ra.heap, 0);
    EXPECT_EQ(ra.heap, rc.heap);
    EXPECT_EQ(ra.offset, rc.offset) << "a and c should share memory";
    EXPECT_LT(plan.transientBytesAliased, plan.transientBytesUnaliased);
    ASSERT_TRUE(ex.frame().has_value());
    auto img = ex.readback("output");
    ASSERT_TRUE(img.has_value()) << img.error().describe();
    int mismatches = 0;
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            auto want = transform(transform(transform(patternAt(x, y), 1), 1), 1);
            for (uint32_t ch = 0; ch < 4; ++ch) mismatches += img->at(x, y, ch) != want[ch];
        }
    EXPECT_EQ(mismatches, 0);
}

TEST_F(GpuTest, FramesInFlightAndReadbackOfTransientIsRefused) {
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 32;
    o.outputHeight = 32;
    auto g = builtinGraph("test");
    ASSERT_TRUE(g.has_value());
    ASSERT_TRUE(ex.build(*g, o).has_value());
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(ex.frame().has_value());
    auto out = ex.readback("output");
    ASSERT_TRUE(out.has_value()) << out.error().describe();
    EXPECT_FLOAT_EQ(out->at(9, 2, 0), transform(patternAt(9, 2), 1)[0]);
    auto bad = ex.readback("pattern");
    ASSERT_FALSE(bad.has_value());
    EXPECT_EQ(bad.error().message,
              "resource 'pattern' is transient: capture (export) it to read it back");
}

TEST_F(GpuTest, ExrOfARenderReadsBackEqual) {
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 40;
    o.outputHeight = 24;
    auto g = builtinGraph("test");
    ASSERT_TRUE(g.has_value());
    ASSERT_TRUE(ex.build(*g, o).has_value());
    ASSERT_TRUE(ex.frame().has_value());
    auto out = ex.readback("output");
    ASSERT_TRUE(out.has_value());
    fs::create_directories(RG_TEST_TMP);
    const std::string path = std::string(RG_TEST_TMP) + "/gpu_render.exr";
    ASSERT_TRUE(writeExr(path, {{"hdr", {"R", "G", "B", "A"}, *out}}, {}).has_value());
    auto back = readExr(path);
    ASSERT_TRUE(back.has_value()) << back.error().describe();
    ASSERT_EQ(back->layers.size(), 1u);
    EXPECT_EQ(back->layers[0].name, "hdr");
    EXPECT_EQ(back->layers[0].image.pixels, out->pixels);  // RGBA16F data is exact in half EXR
}

TEST_F(GpuTest, ClearCopyAndMipsKinds) {
    GraphDesc g;
    ResourceDesc src = texture("src", Format::RGBA16F);
    src.texture.sizeMode = SizeMode::Absolute;
    src.texture.width = 16;
    src.texture.height = 8;
    ResourceDesc dst = src;
    dst.name = "dst";
    dst.texture.mips = 0;  // full chain: 5 mips
    dst.exported = true;
    g.resources = {src, dst};
    g.passes = {
        pass("clear", "clear", {{"src", Usage::CopyDst}},
             {{"value", Value(Value::List{Value(0.25), Value(0.5), Value(0.75), Value(1.0)})}}),
        pass("copy", "copy", {{"src", Usage::CopySrc}, {"dst", Usage::CopyDst}}),
        pass("mips", "mips", {{"dst", Usage::CopyDst, /*load=*/true}})};
    auto& ex = rt().executor();
    auto built = ex.build(g, {});
    ASSERT_TRUE(built.has_value()) << built.error().describe();
    EXPECT_EQ(ex.plan().resources[1].mips, 5u);
    ASSERT_TRUE(ex.frame().has_value());
    auto img = ex.readback("dst");
    ASSERT_TRUE(img.has_value());
    EXPECT_FLOAT_EQ(img->at(15, 7, 0), 0.25f);
    EXPECT_FLOAT_EQ(img->at(0, 0, 2), 0.75f);
}

// A fullscreen pass clears the targets it does not load, unless nothing of them could show: with
// a shader that discards, the pixels it leaves keep the clear colour, frame after frame; without,
// every pixel is the shader's (and the targets are not cleared first).
TEST_F(GpuTest, FullscreenPassKeepsItsClearWhereItsShaderDiscards) {
    for (const char* shader : {"test/checker_cutout.frag", "test/tint.frag"}) {
        SCOPED_TRACE(shader);
        const bool cutout = std::string(shader) == "test/checker_cutout.frag";
        GraphDesc g;
        ResourceDesc out = texture("out", Format::RGBA16F, /*exported=*/true);
        out.texture.sizeMode = SizeMode::Absolute;
        out.texture.width = 8;
        out.texture.height = 4;
        g.resources = {out};
        g.passes = {
            pass("draw", "fullscreen", {{"out", Usage::ColorAttachment}},
                 {{"shader", Value(shader)},
                  {"clear", Value(Value::List{Value(0.25), Value(0.5), Value(0.75), Value(1.0)})},
                  {"uniforms",
                   Value(Value::Table{{"tint", Value(Value::List{Value(1.0), Value(0.0), Value(0.0),
                                                                 Value(1.0)})}})}})};
        auto& ex = rt().executor();
        ASSERT_TRUE(ex.build(g, {}).has_value());
        for (int frame = 0; frame < 2; ++frame) {
            ASSERT_TRUE(ex.frame().has_value());
            auto img = ex.readback("out");
            ASSERT_TRUE(img.has_value());
            for (uint32_t y = 0; y < 4; ++y)
                for (uint32_t x = 0; x < 8; ++x) {
                    const bool kept = cutout && ((x + y) & 1u) == 1u;
                    EXPECT_FLOAT_EQ(img->at(x, y, 0), kept ? 0.25f : 1.0f) << x << "," << y;
                    EXPECT_FLOAT_EQ(img->at(x, y, 1), kept ? 0.5f : 0.0f) << x << "," << y;
                }
        }
    }
}

// Every depth format clears and reads back as depth in [0, 1] (d16: to 1/65535).
TEST_F(GpuTest, DepthFormatsClearAndReadBack) {
    for (Format f : {Format::D16, Format::D32F, Format::D24S8, Format::D32FS8}) {
        SCOPED_TRACE(formatName(f));
        GraphDesc g;
        ResourceDesc d = texture("depth", f, /*exported=*/true);
        d.texture.sizeMode = SizeMode::Absolute;
        d.texture.width = 8;
        d.texture.height = 4;
        g.resources = {d};
        g.passes = {pass("clear", "clear", {{"depth", Usage::CopyDst}}, {{"depth", Value(0.25)}})};
        auto& ex = rt().executor();
        auto built = ex.build(g, {});
        ASSERT_TRUE(built.has_value()) << built.error().describe();
        ASSERT_TRUE(ex.frame().has_value());
        auto img = ex.readback("depth");
        ASSERT_TRUE(img.has_value()) << img.error().describe();
        EXPECT_NEAR(img->at(7, 3, 0), 0.25f, 1.0f / 65535.0f);
    }
}

TEST_F(GpuTest, ShaderErrorNamesFileLineAndPass) {
    GraphDesc g;
    g.resources = {texture("out", Format::RGBA8Unorm, true)};
    g.passes = {pass("broken", "fullscreen", {{"out", Usage::ColorAttachment}},
                     {{"shader", "tests/gpu/shaders/broken.frag"}})};
    auto r = rt().executor().build(g, {});
    ASSERT_FALSE(r.has_value());
    EXPECT_NE(r.error().message.find("pass 'broken'"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("broken.frag:7:"), std::string::npos) << r.error().message;
}

TEST_F(GpuTest, TexelBufferOutsideTheSceneIsNamed) {
    GraphDesc g;
    g.resources = {texture("out", Format::RGBA16F, true)};
    g.passes = {pass("texel", "fullscreen", {{"out", Usage::ColorAttachment}},
                     {{"shader", "tests/gpu/shaders/texel_buffer.frag"}})};
    auto r = rt().executor().build(g, {});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message,
              "pass 'texel': texel buffer 'lut' is not supported (use a storage buffer; a "
              "samplerBuffer is read only from the scene's lights, SceneLightTexels)");
}

TEST_F(GpuTest, UnboundShaderResourceIsReported) {
    GraphDesc g;
    g.resources = {texture("out", Format::RGBA16F, true)};
    g.passes = {pass("lonely", "fullscreen", {{"out", Usage::ColorAttachment}},
                     {{"shader", "test/transform.frag"}})};
    auto r = rt().executor().build(g, {});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message,
              "pass 'lonely': shader binding 'pattern' (set 0, binding 0, combined_image_sampler) "
              "matches no resource "
              "the pass reads or writes; list it in reads/writes or map it with bind = { pattern = "
              "\"resource\" }");
}

TEST_F(GpuTest, UnknownPassKindSuggestsTheClosest) {
    GraphDesc g;
    g.resources = {texture("out", Format::RGBA16F, true)};
    g.passes = {pass("p", "fulscreen", {{"out", Usage::ColorAttachment}})};
    auto r = rt().executor().build(g, {});
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message.substr(0, 63),
              "pass 'p': unknown kind 'fulscreen' (did you mean 'fullscreen'?)");
}

// A compute pass's timestamps hold its work. On lavapipe a timestamp is binned into the scene of
// the framebuffer last bound and taken when that scene is rasterised, while a dispatch runs at once:
// after a raster pass, a compute pass's begin time could be taken after its work (the busy pass below
// read 44 of 143 ms) until the executor resolved it before the pass (executor_record.cpp). A pass that
// is nearly all of the frame must read nearly all of its time. Last of the suite: its larger
// transients stay in the executor's heaps for the tests that follow in the same process.
TEST_F(GpuTest, AComputePassAfterARasterPassIsTimedWithItsWork) {
    auto& ex = rt().executor();
    CompileOptions o;
    o.outputWidth = 128;
    o.outputHeight = 128;
    GraphDesc g = threePassGraph();  // generate, transform (a raster pass), fetch
    g.resources.push_back(texture("busy", Format::RGBA16F));
    g.resources.push_back(texture("shown", Format::RGBA16F));
    g.passes.insert(
        g.passes.end() - 1,
        {pass("work", "compute", {{"busy", Usage::StorageWrite}},
              {{"shader", "test/busy.comp"},
               {"uniforms", Value(Value::Table{{"iterations", 4000.0}})}}),
         pass("show", "fullscreen", {{"busy", Usage::Sampled}, {"shown", Usage::ColorAttachment}},
              {{"shader", "test/transform.frag"},
               {"bind", Value(Value::Table{{"pattern", Value(std::string("busy"))}})},
               {"uniforms", Value(Value::Table{{"scale", 0.5}})}}),
         pass("see", "readback", {{"shown", Usage::CopySrc}})});
    g.passes[g.passes.size() - 2].sideEffect = true;
    auto built = ex.build(g, o);
    ASSERT_TRUE(built.has_value()) << built.error().describe();
    std::vector<std::string> order;
    for (const auto& p : ex.plan().passes) order.push_back(p.name);
    ASSERT_EQ(order,
              (std::vector<std::string>{"generate", "transform", "work", "show", "see", "fetch"}));
    ASSERT_TRUE(ex.frame().has_value());  // the JIT's frame
    ASSERT_TRUE(ex.finish().has_value());
    double work = 0.0, wall = 0.0;
    for (int f = 0; f < 3; ++f) {
        const auto start = std::chrono::steady_clock::now();
        ASSERT_TRUE(ex.frame().has_value());
        ASSERT_TRUE(ex.finish().has_value());
        wall += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
        for (const auto& t : ex.lastTimings())
            if (t.name == "work") work += t.gpuMs;
    }
    std::printf("busy compute pass after a raster pass: %.2f ms of %.2f ms wall over 3 frames\n",
                work, wall);
    EXPECT_GT(work, 0.5 * wall);
}

}  // namespace

// The persistent VkPipelineCache (ContextOptions::pipelineCachePath): a file that is not this
// device's cache (garbage here) is ignored, and the context writes its own when it ends — a
// VkPipelineCacheHeaderVersionOne of this device and driver, which the next context takes.
TEST(PipelineCache, ForeignDataIsIgnoredAndTheCacheIsWrittenOnExit) {
    namespace fs = std::filesystem;
    const std::string dir = std::string(RG_TEST_TMP) + "/pipeline_cache";
    fs::create_directories(dir);
    const std::string path = dir + "/pipelines.bin";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << "not a pipeline cache, but long enough to look like a header at first";
    }
    gpu::ContextOptions o;
    o.pipelineCachePath = path;
    uint32_t vendor = 0, device = 0;
    {
        auto ctx = gpu::Context::create(o);
        ASSERT_TRUE(ctx.has_value()) << ctx.error().describe();
        ASSERT_NE((*ctx)->pipelineCache(), VK_NULL_HANDLE);
        vendor = (*ctx)->properties().vendorID;
        device = (*ctx)->properties().deviceID;
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    VkPipelineCacheHeaderVersionOne header{};
    ASSERT_GE(data.size(), sizeof header);
    std::memcpy(&header, data.data(), sizeof header);
    EXPECT_EQ(header.headerVersion, VK_PIPELINE_CACHE_HEADER_VERSION_ONE);
    EXPECT_EQ(header.vendorID, vendor);
    EXPECT_EQ(header.deviceID, device);
    auto again = gpu::Context::create(o);  // starts from it
    ASSERT_TRUE(again.has_value()) << again.error().describe();
}
