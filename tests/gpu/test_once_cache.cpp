// The disk cache of once-per-build outputs (gpu::Executor::setOnceCache, SessionOptions::onceCache):
// on tests/gpu/scenes/probes.lua with a local probe (environment filtering, the DFG table, the
// probe's capture and filtering all run once), a render that finds its entry restores those
// outputs instead of recording the passes, and renders exactly what recording them renders.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <filesystem>
#include <fstream>

using namespace rg;
namespace fs = std::filesystem;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
const std::string kScene = kRoot + "/tests/gpu/scenes/probes.lua";
const std::string kPipeline = kRoot + "/scripts/pipelines/deferred.lua";
constexpr uint32_t W = 96, H = 64;

class OnceCache : public GpuFixture {
protected:
    void SetUp() override {
        GpuFixture::SetUp();
        m_dir = fs::temp_directory_path() / ("rgraph_once_cache_" + std::to_string(::getpid()));
        fs::remove_all(m_dir);
    }
    void TearDown() override {
        fs::remove_all(m_dir);
        GpuFixture::TearDown();
    }
    struct Render {
        Image hdr, reflection;
        gpu::Executor::OnceCacheStats stats;
    };
    Render render(const std::string& probes, bool cached) {
        SessionOptions o = sceneOptions(kScene, {{"probes", probes}}, W, H);
        if (cached) o.onceCache = m_dir.string();
        Readback r = renderAndRead(o, kPipeline, 2, {"hdr", "reflection"});
        Render out;
        if (r.images.size() == 2) {
            out.hdr = r["hdr"];
            out.reflection = r["reflection"];
        }
        out.stats = rt().executor().onceCacheStats();
        return out;
    }
    std::vector<fs::path> entries() const {
        std::vector<fs::path> out;
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(m_dir / "once", ec)) out.push_back(e.path());
        return out;
    }
    fs::path m_dir;
};

void expectIdentical(const Image& a, const Image& b, const char* what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    size_t differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
    EXPECT_EQ(differ, 0u) << what << ": values that differ";
}

TEST_F(OnceCache, TheSecondRenderRestoresWhatTheFirstSaved) {
    const Render recorded = render("one", false);
    const Render first = render("one", true);
    // env_cube, env_mips, env_irradiance, env_hot, env_smooth_mips, env_prefilter, dfg_table,
    // probe_capture, probe_mips, probe_prefilter.
    EXPECT_EQ(first.stats.savedPasses, 10u);
    EXPECT_EQ(first.stats.restoredPasses, 0u);
    ASSERT_EQ(entries().size(), 1u);
    const Render second = render("one", true);
    EXPECT_EQ(second.stats.restoredPasses, 10u);
    EXPECT_EQ(second.stats.savedPasses, 0u);
    EXPECT_EQ(second.stats.file, first.stats.file);
    expectIdentical(first.hdr, recorded.hdr, "hdr, saved vs recorded");
    expectIdentical(second.hdr, recorded.hdr, "hdr, restored vs recorded");
    expectIdentical(second.reflection, recorded.reflection, "reflection, restored vs recorded");
    // The probe's mirror image is in the restored reflection (not zeros from an empty capture).
    float peak = 0.0f;
    for (float v : second.reflection.pixels) peak = std::max(peak, v);
    EXPECT_GT(peak, 1.0f);
}

TEST_F(OnceCache, AnotherSceneIsAnotherEntry) {
    const Render one = render("one", true);
    const Render two = render("priority", true);
    EXPECT_EQ(two.stats.savedPasses, 10u);
    EXPECT_NE(two.stats.file, one.stats.file);
    EXPECT_EQ(entries().size(), 2u);
    const Render again = render("one", true);
    EXPECT_EQ(again.stats.restoredPasses, 10u);
    EXPECT_EQ(again.stats.file, one.stats.file);
    expectIdentical(again.hdr, one.hdr, "hdr, restored vs saved");
}

TEST_F(OnceCache, ADamagedEntryIsRecordedAgain) {
    const Render first = render("one", true);
    ASSERT_EQ(entries().size(), 1u);
    fs::resize_file(entries()[0], fs::file_size(entries()[0]) / 2);
    const Render second = render("one", true);
    EXPECT_EQ(second.stats.restoredPasses, 0u);
    EXPECT_EQ(second.stats.savedPasses, 10u);
    expectIdentical(second.hdr, first.hdr, "hdr after a damaged entry");
    const Render third = render("one", true);
    EXPECT_EQ(third.stats.restoredPasses, 10u);
}

}  // namespace
