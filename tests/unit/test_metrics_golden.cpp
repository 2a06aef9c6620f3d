// Golden-test machinery without a GPU: golden storage round trips, golden test scripts and their
// errors (exact texts), the frame callback's ctx, and the report / JUnit writers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "golden/golden_test.h"
#include "golden/metrics.h"
#include "golden/report.h"
#include "golden/storage.h"
#include "metrics_test_util.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::golden;
using namespace rg::test;

namespace {

std::string tmpDir(const std::string& name) {
    const std::string dir = std::string(RG_TEST_TMP) + "/metrics/" + name;
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    return dir;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// ---- golden storage ----

// What comparisons assume: quantizeForStorage is exactly what a write and a read give back.
TEST(Storage, QuantisingMatchesTheFileRoundTrip) {
    const std::string dir = tmpDir("storage");
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.2f, 1.3f);
    struct Case {
        std::string format;
        uint32_t channels;
        float scale;
    };
    for (const Case& c : {Case{"rgba8", 4, 1.0f}, Case{"rgba8_srgb", 4, 1.0f}, Case{"r8", 1, 1.0f},
                          Case{"rgba16f", 4, 500.0f}, Case{"rg16f", 2, 1e-3f},
                          Case{"rgba32f", 4, 1e5f}, Case{"r32ui", 1, 1e4f}}) {
        Image img(13, 7, c.channels);
        for (float& v : img.pixels) v = u(rng) * c.scale;
        if (c.format == "r32ui")
            for (float& v : img.pixels) v = std::round(std::fabs(v));
        const Storage s = storageForFormat(c.format);
        const bool srgb = isSrgbFormat(c.format);
        const std::string path = dir + "/" + c.format + storageExtension(s);
        ASSERT_TRUE(writeStored(path, img, s, srgb).has_value()) << c.format;
        auto back = readStored(path, s, srgb);
        ASSERT_TRUE(back.has_value()) << back.error().message;
        const Image q = quantizeForStorage(img, s, srgb);
        ASSERT_EQ(back->channels, q.channels) << c.format;
        for (size_t i = 0; i < q.pixels.size(); ++i)
            ASSERT_EQ(back->pixels[i], q.pixels[i]) << c.format << " sample " << i;
        // Quantising twice changes nothing.
        EXPECT_EQ(quantizeForStorage(q, s, srgb).pixels, q.pixels) << c.format;
    }
    EXPECT_EQ(storageForFormat("rgba16f"), Storage::ExrHalf);
    EXPECT_EQ(storageForFormat("rgba8"), Storage::Png);
    EXPECT_EQ(storageForFormat("rgb10a2"), Storage::ExrFloat);
    EXPECT_EQ(storageForFormat("buffer:float32"), Storage::ExrFloat);
}

// ---- golden test scripts ----

std::string writeScript(const std::string& name, const std::string& text) {
    const std::string dir = std::string(RG_TEST_TMP) + "/metrics/scripts";
    fs::create_directories(dir);
    const std::string path = dir + "/" + name + ".lua";
    std::ofstream(path) << text;
    return path;
}

Result<std::unique_ptr<GoldenScript>> loadScript(const std::string& name, const std::string& text) {
    return GoldenScript::load(writeScript(name, text), name + ".lua");
}

std::string loadError(const std::string& name, const std::string& text) {
    auto s = loadScript(name, text);
    EXPECT_FALSE(s.has_value()) << name << " loaded but should not";
    if (s) return "";
    const std::string& m = s.error().message;
    return m.substr(0, m.find('\n'));  // without the traceback
}

const std::string kGood = R"(return {
    doc = "a test",
    pipeline = "scripts/pipelines/test.lua",
    size = { 64, 32 },
    frames = 3,
    params = { scale = 0.5 },
    captures = {
        output = { metric = "psnr", tolerance = 40 },
        pattern = { { metric = "max_abs", tolerance = 0 }, { metric = "flip", tolerance = 0.01, display = "srgb", channels = "rgb" } },
        ids = { metric = "exact" },
        n = { metric = "angular", encoding = "oct_unorm", channels = "rg", tolerance = 0.1 },
        o = { metric = "over_threshold", threshold = 1 / 255, tolerance = 0.001 },
    },
})";

TEST(GoldenScripts, AValidTestIsParsed) {
    auto s = loadScript("good", kGood);
    ASSERT_TRUE(s.has_value()) << s.error().message;
    const GoldenTest& t = (*s)->test();
    EXPECT_EQ(t.name, "good");
    EXPECT_EQ(t.golden, "good");
    EXPECT_EQ(t.pipeline, "scripts/pipelines/test.lua");
    EXPECT_EQ(t.width, 64u);
    EXPECT_EQ(t.height, 32u);
    EXPECT_EQ(t.frames, 3u);
    EXPECT_FALSE(t.hasFrameCallback);
    EXPECT_DOUBLE_EQ(t.params.at("scale").asNumber(), 0.5);
    ASSERT_EQ(t.captures.size(), 5u);
    std::map<std::string, CaptureSpec> byName;
    for (const auto& c : t.captures) byName[c.resource] = c;
    EXPECT_EQ(byName["output"].comparisons[0].metric, Metric::Psnr);
    EXPECT_DOUBLE_EQ(byName["output"].comparisons[0].tolerance, 40.0);
    ASSERT_EQ(byName["pattern"].comparisons.size(), 2u);
    EXPECT_EQ(byName["pattern"].comparisons[1].display, DisplayEncoding::Srgb);
    EXPECT_EQ(byName["pattern"].comparisons[1].channels, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(byName["ids"].comparisons[0].metric, Metric::Exact);
    EXPECT_DOUBLE_EQ(byName["ids"].comparisons[0].tolerance, 0.0);
    EXPECT_EQ(byName["n"].comparisons[0].normals, NormalEncoding::OctUnorm);
    EXPECT_NEAR(byName["o"].comparisons[0].threshold, 1.0 / 255.0, 1e-12);
}

TEST(GoldenScripts, EachKindOfMistakeHasItsMessage) {
    auto replace = [](std::string text, const std::string& from, const std::string& to) {
        auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    };
    EXPECT_EQ(loadError("syntax", "return { size = { 1, 2 }"),
              "syntax.lua:1: '}' expected near <eof>");
    EXPECT_EQ(loadError("not_a_table", "return 42"),
              "not_a_table.lua: a golden test script returns a table { pipeline = ..., size = ..., "
              "captures = ... }, got 42");
    EXPECT_EQ(
        loadError("unknown", replace(kGood, "frames = 3", "frmes = 3")),
        "unknown.lua: frmes: unknown field (did you mean 'frames'?); expected one of: 'doc', "
        "'pipeline', 'scene', "
        "'camera', 'size', 'frames', 'params', 'frame', 'golden', 'captures', 'cross_device'");
    EXPECT_EQ(loadError("too_big", replace(kGood, "{ 64, 32 }", "{ 512, 32 }")),
              "too_big.lua: size[1]: expected a whole number in [1, 256], got 512");
    EXPECT_EQ(loadError("size_shape", replace(kGood, "{ 64, 32 }", "\"64x32\"")),
              "size_shape.lua: size: expected { width, height }, got '64x32'");
    EXPECT_EQ(loadError("frames", replace(kGood, "frames = 3", "frames = 0")),
              "frames.lua: frames: expected a whole number in [1, 1000], got 0");
    EXPECT_EQ(
        loadError("no_pipeline", replace(kGood, "pipeline = \"scripts/pipelines/test.lua\",", "")),
        "no_pipeline.lua: pipeline: missing: the pipeline script to render (e.g. "
        "'scripts/pipelines/test.lua')");
    EXPECT_EQ(
        loadError("metric", replace(kGood, "\"psnr\"", "\"psnrr\"")),
        "metric.lua: captures.output.metric: unknown metric 'psnrr' (did you mean 'psnr'?); "
        "expected one of: 'max_abs', "
        "'rmse', 'psnr', 'over_threshold', 'rel_mean', 'rel_max', 'angular', 'exact', 'flip'");
    EXPECT_EQ(loadError("tolerance",
                        replace(kGood, "metric = \"psnr\", tolerance = 40", "metric = \"psnr\"")),
              "tolerance.lua: captures.output.tolerance: missing: metric 'psnr' needs one (peak "
              "signal-to-noise ratio in dB; the "
              "tolerance is the least PSNR allowed)");
    EXPECT_EQ(loadError("negative", replace(kGood, "tolerance = 0 }", "tolerance = -1 }")),
              "negative.lua: captures.pattern[1].tolerance: must not be negative, got -1");
    EXPECT_EQ(loadError("threshold", replace(kGood, "threshold = 1 / 255, ", "")),
              "threshold.lua: captures.o.threshold: missing: over_threshold counts pixels whose "
              "difference exceeds it");
    EXPECT_EQ(loadError("misplaced",
                        replace(kGood, "metric = \"exact\"", "metric = \"exact\", threshold = 1")),
              "misplaced.lua: captures.ids.threshold: metric 'exact' does not use 'threshold'; its "
              "fields: 'metric', 'tolerance', "
              "'channels'");
    EXPECT_EQ(loadError("channels", replace(kGood, "channels = \"rgb\"", "channels = \"rgx\"")),
              "channels.lua: captures.pattern[2].channels: expected letters of 'rgba' such as "
              "'rgb', got 'rgx'");
    EXPECT_EQ(loadError("oct", replace(kGood, "channels = \"rg\"", "channels = \"rgb\"")),
              "oct.lua: captures.n.channels: an octahedral normal needs 2 channels, got 'rgb'");
    EXPECT_EQ(loadError("encoding", replace(kGood, "\"oct_unorm\"", "\"octa\"")),
              "encoding.lua: captures.n.encoding: expected one of: 'signed', 'unorm', 'oct', "
              "'oct_unorm', got 'octa'");
    EXPECT_EQ(loadError("empty", "return { pipeline = 'p.lua', size = { 8, 8 }, captures = {} }"),
              "empty.lua: captures: expected a table { resource = { metric = ..., tolerance = ... "
              "} } with at least one entry, got "
              "table");
    EXPECT_EQ(loadError("cross", replace(kGood, "frames = 3,",
                                         "frames = 3, cross_device = { display = { metric = "
                                         "\"flip\", tolerance = 0.05 } },")),
              "cross.lua: cross_device.display: not one of the test's captures (a cross-device "
              "bound compares a captured image with the primary device family's golden)");
    EXPECT_EQ(
        loadError("cross_shape", replace(kGood, "frames = 3,", "frames = 3, cross_device = 1,")),
        "cross_shape.lua: cross_device: expected a table { capture = { metric = ..., tolerance "
        "= ... } } naming captures, got 1");
    EXPECT_EQ(loadError("cross_metric", replace(kGood, "frames = 3,",
                                                "frames = 3, cross_device = { output = { metric = "
                                                "\"flp\", tolerance = 0.05 } },")),
              "cross_metric.lua: cross_device.output.metric: unknown metric 'flp' (did you mean "
              "'flip'?); expected one of: 'max_abs', 'rmse', 'psnr', 'over_threshold', 'rel_mean', "
              "'rel_max', 'angular', 'exact', 'flip'");
    EXPECT_EQ(loadError("camera", replace(kGood, "frames = 3,", "frames = 3, camera = \"main\",")),
              "camera.lua: camera: names a camera of the scene: set 'scene' too");
    EXPECT_EQ(loadError("golden", replace(kGood, "frames = 3,", "frames = 3, golden = \"../x\",")),
              "golden.lua: golden: expected the name of another golden test, got '../x'");
    EXPECT_EQ(loadError("function", replace(kGood, "doc = \"a test\"", "doc = function() end")),
              "function.lua: doc: a function is not allowed here (only the top-level 'frame' is a "
              "function)");
    EXPECT_EQ(loadError("frame_type", replace(kGood, "frames = 3,", "frames = 3, frame = 5,")),
              "frame_type.lua: frame: expected a function(ctx), got number");
    EXPECT_EQ(loadError("mixed", replace(kGood, "{ 64, 32 }", "{ 64, 32, w = 1 }")),
              "mixed.lua: size: mixes list entries and named fields");
}

TEST(GoldenScripts, TheSandboxHoldsAndLimitsStopRunaways) {
    EXPECT_EQ(loadError("io", "local f = io.open('/etc/passwd') return {}"),
              "io.lua:1: attempt to index a nil value (global 'io')");
    EXPECT_EQ(loadError("load", "load('return 1') return {}"),
              "load.lua:1: load is not available to golden test scripts (sandbox)");
    EXPECT_EQ(loadError("require", "require 'rg' return {}"),
              "require.lua:1: require is not available to golden test scripts (sandbox)");
    EXPECT_EQ(loadError("os", "os.execute('touch /tmp/x') return {}"),
              "os.lua:1: attempt to index a nil value (global 'os')");
    GoldenScript::Limits small;
    small.instructions = 2'000'000;
    auto s = GoldenScript::load(writeScript("runaway", "while true do end"), "runaway.lua", small);
    ASSERT_FALSE(s.has_value());
    EXPECT_EQ(s.error().message.substr(0, s.error().message.find('\n')),
              "runaway.lua:1: golden test script stopped after 2 million instructions: a runaway "
              "loop? (limit: 2 million)");
    small.memoryBytes = 8u << 20;
    auto m = GoldenScript::load(
        writeScript("hog", "local t = {} for i = 1, 1e8 do t[i] = i end return {}"), "hog.lua",
        small);
    ASSERT_FALSE(m.has_value());
    EXPECT_NE(m.error().message.find(
                  "hog.lua:1: golden test script stopped: it used more than 8 MiB of Lua memory"),
              std::string::npos)
        << m.error().message;
    auto missing = GoldenScript::load("/nonexistent/x.lua", "x.lua");
    ASSERT_FALSE(missing.has_value());
    EXPECT_EQ(missing.error().message, "cannot open golden test script '/nonexistent/x.lua'");
}

// A pipeline as the frame callback sees it: two parameters and two passes.
PipelineDesc fakePipeline() {
    PipelineDesc p;
    ParamDesc scale;
    scale.name = "scale";
    scale.type = ParamType::Number;
    scale.value = Value(1.0);
    scale.min = 0;
    scale.max = 16;
    ParamDesc mode;
    mode.name = "mode";
    mode.type = ParamType::Choice;
    mode.value = Value("a");
    mode.choices = {"a", "b"};
    p.params = {scale, mode};
    PassDesc gen;
    gen.name = "generate";
    gen.kind = "compute";
    gen.params = Value(Value::Table{{"shader", Value("test/pattern.comp")}});
    PassDesc tint;
    tint.name = "tint";
    tint.kind = "fullscreen";
    tint.params = Value(Value::Table{{"shader", Value("test/tint.frag")}});
    p.graph.passes = {gen, tint};
    return p;
}

TEST(GoldenScripts, TheFrameCallbackChangesParametersAndPasses) {
    auto s = loadScript("frames", R"(return {
    pipeline = "p.lua", size = { 8, 8 }, frames = 4, captures = { output = { metric = "exact" } },
    frame = function(ctx)
        if ctx.frame == 1 then ctx.params.scale = ctx.params.scale * 0.5 end
        if ctx.frame == 2 then ctx.pass("tint").enabled = false; ctx.params.mode = "b" end
        if ctx.frame == 3 then ctx.pass("generate").shader = "other.comp" end
    end,
})");
    ASSERT_TRUE(s.has_value()) << s.error().message;
    EXPECT_TRUE((*s)->test().hasFrameCallback);
    const PipelineDesc p = fakePipeline();
    auto f0 = (*s)->frame({0, 0.0}, p);
    ASSERT_TRUE(f0.has_value()) << f0.error().message;
    EXPECT_TRUE(f0->empty());
    auto f1 = (*s)->frame({1, 1.0 / 60}, p);
    ASSERT_TRUE(f1.has_value()) << f1.error().message;
    EXPECT_DOUBLE_EQ(f1->params.at("scale").asNumber(), 0.5);
    EXPECT_FALSE(f1->structural());
    auto f2 = (*s)->frame({2, 2.0 / 60}, p);
    ASSERT_TRUE(f2.has_value()) << f2.error().message;
    EXPECT_EQ(f2->enabled.at("tint"), false);
    EXPECT_EQ(f2->params.at("mode").asString(), "b");
    auto f3 = (*s)->frame({3, 3.0 / 60}, p);
    ASSERT_TRUE(f3.has_value()) << f3.error().message;
    EXPECT_EQ(f3->shaders.at("generate"), "other.comp");
}

TEST(GoldenScripts, FrameCallbackErrorsNameTheLine) {
    auto frameError = [](const std::string& name, const std::string& body) {
        auto s = loadScript(name,
                            "return { pipeline = 'p.lua', size = { 8, 8 }, captures = { o = { "
                            "metric = 'exact' } },\n"
                            "frame = function(ctx)\n" +
                                body + "\nend }");
        EXPECT_TRUE(s.has_value()) << (s ? "" : s.error().message);
        if (!s) return std::string();
        auto r = (*s)->frame({0, 0.0}, fakePipeline());
        EXPECT_FALSE(r.has_value());
        return r ? std::string() : r.error().message.substr(0, r.error().message.find('\n'));
    };
    EXPECT_EQ(frameError("unknown_param", "ctx.params.scal = 1"),
              "unknown_param.lua:3: ctx.params: unknown parameter 'scal' (did you mean 'scale'?)");
    EXPECT_EQ(frameError("range", "ctx.params.scale = 20"),
              "range.lua:3: ctx.params: parameter 'scale' expects a number in [0, 16], got 20");
    EXPECT_EQ(frameError("choice", "ctx.params.mode = 'c'"),
              "choice.lua:3: ctx.params: parameter 'mode' expects one of 'a', 'b', got 'c'");
    EXPECT_EQ(frameError("unknown_pass", "ctx.pass('tnt').enabled = false"),
              "unknown_pass.lua:3: ctx.pass: unknown pass 'tnt' (did you mean 'tint'?)");
    EXPECT_EQ(frameError("enabled_type", "ctx.pass('tint').enabled = 1"),
              "enabled_type.lua:3: ctx.pass('tint').enabled: expected a boolean, got number");
    EXPECT_EQ(frameError("runtime", "local x = nil; x.y = 1"),
              "runtime.lua:3: attempt to index a nil value (local 'x')");
}

TEST(GoldenScripts, FindingTestsByPattern) {
    EXPECT_TRUE(matchesPattern("shading", ""));
    EXPECT_TRUE(matchesPattern("shading", "shading"));
    EXPECT_FALSE(matchesPattern("shading_sun", "shading"));
    EXPECT_TRUE(matchesPattern("shading_sun", "shading*"));
    EXPECT_TRUE(matchesPattern("deferred_pipeline", "*pipe*"));
    EXPECT_FALSE(matchesPattern("test_pipeline", "deferred_*"));
    const std::string dir = tmpDir("find");
    for (const char* n : {"b.lua", "a.lua", "a_two.lua", "notes.txt"})
        std::ofstream(dir + "/" + n) << "return {}";
    fs::create_directories(dir + "/sub");
    std::ofstream(dir + "/sub/c.lua") << "return {}";
    auto all = findGoldenTests(dir, "");
    ASSERT_TRUE(all.has_value());
    ASSERT_EQ(all->size(), 3u);
    EXPECT_EQ(fs::path((*all)[0]).filename(), "a.lua");
    EXPECT_EQ(fs::path((*all)[2]).filename(), "b.lua");
    auto some = findGoldenTests(dir, "a*");
    ASSERT_TRUE(some.has_value());
    EXPECT_EQ(some->size(), 2u);
    auto none = findGoldenTests(dir + "/missing", "");
    ASSERT_FALSE(none.has_value());
    EXPECT_EQ(none.error().message, "no golden test folder '" + dir + "/missing'");
}

// ---- report and JUnit ----

RunReport sampleReport() {
    RunReport run;
    run.environment.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
    run.environment.driver = "llvmpipe Mesa 22.3.6";
    run.profile = "LP_NUM_THREADS=2";
    run.seconds = 1.5;
    TestOutcome pass;
    pass.name = "good";
    pass.status = TestStatus::Passed;
    pass.width = pass.height = 4;
    pass.frames = 1;
    CaptureOutcome c;
    c.resource = "output";
    c.format = "rgba16f";
    c.actual = filled(4, 4, 4, 0.5f);
    c.expected = c.actual;
    ComparisonOutcome cmp;
    cmp.spec = with(Metric::MaxAbs, 0);
    cmp.result = *compare(c.actual, c.expected, cmp.spec);
    c.comparisons = {cmp};
    c.passed = true;
    pass.captures = {c};
    TestOutcome bad = pass;
    bad.name = "bad <one> & \"two\"";
    bad.status = TestStatus::Failed;
    bad.captures[0].actual.at(1, 1, 0) = 1.0f;
    bad.captures[0].comparisons[0].result =
        *compare(bad.captures[0].actual, bad.captures[0].expected, cmp.spec);
    bad.captures[0].passed = false;
    bad.firstDivergent = "output";
    bad.message = "first divergent resource in pipeline order: 'output'";
    TestOutcome err;
    err.name = "broken";
    err.status = TestStatus::Error;
    err.message = "broken.lua:1: unexpected symbol";
    run.tests = {pass, bad, err};
    return run;
}

TEST(Report, HtmlHasEveryTestItsMetricsAndTheViews) {
    const std::string dir = tmpDir("report");
    ASSERT_TRUE(writeHtmlReport(dir, sampleReport()).has_value());
    const std::string html = readFile(dir + "/index.html");
    EXPECT_NE(html.find("rgraph golden tests: 1 passed, 1 failed, 1 errors"), std::string::npos);
    EXPECT_NE(html.find("bad &lt;one&gt; &amp; &quot;two&quot;"), std::string::npos);  // escaped
    EXPECT_EQ(html.find("bad <one>"), std::string::npos);
    EXPECT_NE(html.find("first divergent resource in pipeline order"), std::string::npos);
    EXPECT_NE(html.find("class=\"swipebox\""), std::string::npos);
    EXPECT_NE(html.find("class=\"exposure\""), std::string::npos);
    EXPECT_NE(html.find("diff: max_abs"), std::string::npos);
    EXPECT_NE(html.find("broken.lua:1: unexpected symbol"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos);  // nothing to fetch: works offline
}

TEST(Report, JunitCountsFailuresAndErrors) {
    const std::string dir = tmpDir("junit");
    ASSERT_TRUE(writeJunit(dir + "/golden.xml", sampleReport()).has_value());
    const std::string xml = readFile(dir + "/golden.xml");
    EXPECT_NE(xml.find("<testsuite name=\"golden\" tests=\"3\" failures=\"1\" errors=\"1\""),
              std::string::npos)
        << xml;
    EXPECT_NE(
        xml.find("<testcase classname=\"golden\" name=\"bad &lt;one&gt; &amp; &quot;two&quot;\""),
        std::string::npos);
    EXPECT_NE(
        xml.find(
            "<failure message=\"first divergent resource in pipeline order: &apos;output&apos;\">"),
        std::string::npos);
    EXPECT_NE(xml.find("<error message=\"broken.lua:1: unexpected symbol\">"), std::string::npos);
    EXPECT_NE(xml.find("output: max_abs 0.5 &gt; 0 FAIL"), std::string::npos);
}

TEST(Report, Base64) {
    const uint8_t man[] = {'M', 'a', 'n'};
    EXPECT_EQ(base64Encode(man, 3), "TWFu");
    EXPECT_EQ(base64Encode(man, 2), "TWE=");
    EXPECT_EQ(base64Encode(man, 1), "TQ==");
    EXPECT_EQ(base64Encode(man, 0), "");
}

}  // namespace
