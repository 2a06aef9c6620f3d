// The physical camera and post chain on the GPU: auto-exposure settles on the metered EV and
// adapts at its speed, manual exposure follows the camera, pre-exposure keeps RGBA16F finite
// under a sun, the EXR's HDR is absolute luminance, and the GLSL sRGB functions match their
// definition at the breakpoints.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "core/photometry.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kScripts = std::string(RG_SOURCE_ROOT) + "/tests/lua/scripts/";

class PostGpu : public GpuFixture {
protected:
    std::unique_ptr<Session> session(const std::string& script) {
        SessionOptions o;
        o.compile.outputWidth = 64;
        o.compile.outputHeight = 48;
        auto s = std::make_unique<Session>(*s_runtime, o);
        auto r = s->load(kScripts + script);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        return s;
    }
    // ev100, exposure, preExposure, initialized
    std::array<float, 4> state() {
        auto bytes = s_runtime->executor().readbackBuffer("exposure");
        EXPECT_TRUE(bytes.has_value());
        std::array<float, 4> s{};
        if (bytes) std::memcpy(s.data(), bytes->data(), sizeof s);
        return s;
    }
    // Sets a parameter the way rg.frame would (a uniform, no rebuild).
    void setParam(Session& s, const std::string& name, Value v) {
        auto& p = const_cast<PipelineDesc&>(s.pipeline());
        p.findParam(name)->value = v;
        s_runtime->executor().updateUniforms(graphWithParams(p));
    }
};

TEST_F(PostGpu, AutoExposureSettlesOnTheMeteredEv) {
    for (double L : {0.5, 1000.0, 31831.0}) {
        auto s = session("post_uniform.lua");
        setParam(*s, "luminance", Value(L));
        for (int f = 0; f < 3; ++f) ASSERT_TRUE(s->frame().has_value());
        auto st = state();
        const double want = photometry::ev100FromLuminance(L);  // log2(L · 100 / 12.5)
        EXPECT_NEAR(st[0], want, 0.05) << L << " cd/m²";
        EXPECT_NEAR(st[1], photometry::exposureFromEv100(st[0]), st[1] * 1e-5);
        EXPECT_EQ(st[3], 1.0f);
    }
}

TEST_F(PostGpu, AutoExposureAdaptsAtItsSpeed) {
    auto s = session("post_uniform.lua");
    setParam(*s, "luminance", Value(1000.0));
    for (int f = 0; f < 2; ++f) ASSERT_TRUE(s->frame().has_value());
    const double start = state()[0];
    // Four stops brighter: each frame moves (target − ev)·(1 − e^(−dt·speed_up)), dt = 1/60, speed_up = 3.
    setParam(*s, "luminance", Value(16000.0));
    const double target = photometry::ev100FromLuminance(16000.0);
    double ev = start;
    for (int f = 0; f < 10; ++f) {
        ASSERT_TRUE(s->frame().has_value());
        ev += (target - ev) * (1.0 - std::exp(-3.0 / 60.0));
        EXPECT_NEAR(state()[0], ev, 0.02) << "frame " << f;
    }
    // And down at speed_down = 1.
    setParam(*s, "luminance", Value(1000.0));
    const double down = photometry::ev100FromLuminance(1000.0);
    ASSERT_TRUE(s->frame().has_value());
    ev += (down - ev) * (1.0 - std::exp(-1.0 / 60.0));
    EXPECT_NEAR(state()[0], ev, 0.02);
}

TEST_F(PostGpu, ManualExposureFollowsTheCamera) {
    auto s = session("post_uniform.lua");
    setParam(*s, "exposure_mode", Value("manual"));
    ASSERT_TRUE(s->frame().has_value());
    auto st = state();
    EXPECT_NEAR(st[0], 14.966, 0.001);       // f/16, 1/125 s, ISO 100
    EXPECT_NEAR(st[1], 2.604e-5, 0.001e-5);  // 1 / (1.2 · 2^EV100)
}

TEST_F(PostGpu, PreExposureKeepsHalfFloatsFiniteUnderTheSun) {
    // A white diffuse surface under a 100 000 lux sun is E·ρ/π ≈ 31 831 cd/m²; the sun's disk
    // is ≈ 1.6e9 cd/m², far beyond half precision (65 504) unless pre-exposed.
    auto s = session("post_uniform.lua");
    setParam(*s, "luminance", Value(31831.0));
    setParam(*s, "highlight", Value(1.6e9));
    setParam(*s, "initial_ev100", Value(15.0));
    for (int f = 0; f < 4; ++f) ASSERT_TRUE(s->frame().has_value());
    for (const char* target : {"hdr", "bloom_down1", "bloom_up1", "display"}) {
        auto img = s_runtime->executor().readback(target);
        if (!img) continue;  // transient intermediates cannot be read back
        for (float v : img->pixels) ASSERT_TRUE(std::isfinite(v)) << target;
    }
    auto hdr = s_runtime->executor().readback("hdr");
    ASSERT_TRUE(hdr.has_value());
    for (float v : hdr->pixels) ASSERT_TRUE(std::isfinite(v));
    const float pre = state()[2];
    EXPECT_NEAR(hdr->at(32, 24, 0) / pre, 1.6e9f, 1.6e9f * 1e-3f);  // the sun disk, recovered
    EXPECT_NEAR(hdr->at(2, 2, 0) / pre, 31831.0f, 31831.0f * 1e-3f);
    // The same frame without pre-exposure (exposure 1 ⇔ EV100 = log2(1/1.2)) overflows half
    // precision: the disk saturates (lavapipe rounds towards zero to 65504; others give inf).
    setParam(*s, "exposure_mode", Value("manual"));
    setParam(*s, "aperture", Value(1.0));
    setParam(*s, "shutter", Value(1.2));
    setParam(*s, "iso", Value(100.0));
    for (int f = 0; f < 2; ++f) ASSERT_TRUE(s->frame().has_value());
    auto overflow = s_runtime->executor().readback("hdr");
    ASSERT_TRUE(overflow.has_value());
    EXPECT_NEAR(state()[2], 1.0f, 1e-5f);
    const float v = overflow->at(32, 24, 0);
    EXPECT_TRUE(std::isinf(v) || v == 65504.0f) << v;
}

TEST_F(PostGpu, HdrOutputIsAbsoluteLuminance) {
    auto s = session("post_uniform.lua");
    setParam(*s, "luminance", Value(1000.0));
    for (int f = 0; f < 3; ++f) ASSERT_TRUE(s->frame().has_value());
    auto hdr = s_runtime->executor().readback("hdr");
    ASSERT_TRUE(hdr.has_value());
    const float pre = state()[2];
    EXPECT_NEAR(hdr->at(10, 10, 1) / pre, 1000.0f, 1000.0f * 1e-3f);  // half precision
    // The display image of a uniform field metered by auto-exposure: the metered middle grey.
    auto display = s_runtime->executor().readback("display");
    ASSERT_TRUE(display.has_value());
    const float grey = display->at(10, 10, 0);
    EXPECT_GT(grey, 0.2f);
    EXPECT_LT(grey, 0.6f);
    EXPECT_FLOAT_EQ(display->at(10, 10, 0), display->at(50, 40, 0));
}

TEST_F(PostGpu, BloomConservesEnergy) {
    SessionOptions o;
    o.compile.outputWidth = 256;
    o.compile.outputHeight = 128;
    o.captures = {"bloom_up1", "bloom_down1", "bloom_down3", "bloom_down5"};
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(kScripts + "post_uniform.lua").has_value());
    setParam(s, "luminance", Value(100.0));
    setParam(s, "highlight", Value(1e5));  // a small bright disc: most energy in a few pixels
    for (int f = 0; f < 2; ++f) ASSERT_TRUE(s.frame().has_value());
    auto mean = [&](const char* name) {
        auto img = s_runtime->executor().readback(name);
        EXPECT_TRUE(img.has_value());
        double sum = 0;
        for (uint32_t y = 0; y < img->height; ++y)
            for (uint32_t x = 0; x < img->width; ++x) sum += img->at(x, y, 1);
        return sum / (double(img->width) * img->height);
    };
    const double input = mean("hdr");
    std::printf("bloom energy: input %.5f, down1 %.5f, down3 %.5f, down5 %.5f, up1/5 %.5f\n", input,
                mean("bloom_down1"), mean("bloom_down3"), mean("bloom_down5"),
                mean("bloom_up1") / 5.0);
    // Every down level keeps the average, up to the clamp-to-edge border (which weighs border
    // texels more: it grows as levels get small); the up chain sums the 5 levels.
    EXPECT_NEAR(mean("bloom_down1"), input, input * 0.001);
    EXPECT_NEAR(mean("bloom_down3"), input, input * 0.002);
    EXPECT_NEAR(mean("bloom_down5"), input, input * 0.005);
    EXPECT_NEAR(mean("bloom_up1") / 5.0, input, input * 0.01);
}

TEST_F(PostGpu, FxaaSmoothsAnAliasedEdgeOnly) {
    SessionOptions o;
    o.compile.outputWidth = 64;
    o.compile.outputHeight = 48;
    o.captures = {"display_ldr"};
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(kScripts + "post_edge.lua").has_value());
    ASSERT_TRUE(s.frame().has_value());
    auto before = s_runtime->executor().readback("display_ldr");
    auto after = s_runtime->executor().readback("display");
    ASSERT_TRUE(before.has_value() && after.has_value());
    const float dark = before->at(0, 40, 0), bright = before->at(60, 2, 0);
    ASSERT_GT(bright - dark, 0.3f);
    int blended = 0, changedAway = 0;
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float b = before->at(x, y, 0), a = after->at(x, y, 0);
            const float edgeDistance = std::abs(static_cast<float>(x) + 0.5f -
                                                0.7f * (static_cast<float>(y) + 0.5f) - 10.0f);
            // Before FXAA every pixel is one of the two levels; after, edge pixels lie between.
            EXPECT_TRUE(b == dark || b == bright);
            if (a > dark + 0.02f && a < bright - 0.02f) ++blended;
            if (edgeDistance > 3.0f && a != b) ++changedAway;
        }
    EXPECT_GT(blended, 30);  // most of the ~48 edge pixels
    EXPECT_EQ(changedAway, 0);
}

// The tone curve is a switch of the tonemap pass (scripts/post.lua: compiled in): changing it at
// run time rebuilds that pass alone and gives the image a load with that curve gives; a
// highlight of 8× the metered grey separates the curves (ACES compresses it, linear clips).
TEST_F(PostGpu, SwitchingTheToneCurveRebuildsTheTonemapPassOnly) {
    auto displayAfterLoad = [&](const char* curve) {
        SessionOptions o;
        o.compile.outputWidth = 64;
        o.compile.outputHeight = 48;
        o.params["tonemap"] = Value(curve);
        o.params["exposure_mode"] = Value("manual");
        Session s(*s_runtime, o);
        EXPECT_TRUE(s.load(kScripts + "post_uniform.lua").has_value());
        EXPECT_TRUE(s.frame().has_value());
        return *s_runtime->executor().readback("display");
    };
    const Image aces = displayAfterLoad("aces"), linear = displayAfterLoad("linear");
    SessionOptions o;
    o.compile.outputWidth = 64;
    o.compile.outputHeight = 48;
    o.params["exposure_mode"] = Value("manual");
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(kScripts + "post_uniform.lua").has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(s_runtime->executor().readback("display")->pixels, aces.pixels);  // the default curve
    ASSERT_TRUE(s.setOverride("tonemap", Value("linear")).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(s.rebuilds(), 1u);
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared,
              (std::vector<std::string>{"tonemap"}));
    EXPECT_EQ(s_runtime->executor().readback("display")->pixels, linear.pixels);
    EXPECT_NE(aces.pixels, linear.pixels);
    // The same value again is no change.
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(s.rebuilds(), 1u);
}

TEST_F(PostGpu, GlslSrgbMatchesItsDefinition) {
    GraphDesc g;
    ResourceDesc out;
    out.name = "srgb_out";
    out.kind = ResourceKind::Buffer;
    out.buffer.size = 512;
    out.exported = true;
    g.resources = {out};
    Value::List x;
    std::vector<float> inputs = {0.0f,     0.001f, 0.0031308f, 0.0031309f, 0.04045f,
                                 0.04046f, 0.1f,   0.5f,       0.9f,       1.0f};
    while (inputs.size() < 64) inputs.push_back(static_cast<float>(inputs.size()) / 64.0f);
    for (float v : inputs) x.push_back(Value(static_cast<double>(v)));
    PassDesc p;
    p.name = "srgb";
    p.kind = "compute";
    p.accesses = {{"srgb_out", Usage::StorageWrite}};
    p.params = Value(Value::Table{{"shader", Value("test/srgb.comp")},
                                  {"groups", Value(Value::List{1, 1, 1})},
                                  {"uniforms", Value(Value::Table{{"x", Value(x)}})}});
    g.passes = {p};
    auto& ex = s_runtime->executor();
    ASSERT_TRUE(ex.build(g, {}).has_value());
    ASSERT_TRUE(ex.frame().has_value());
    auto bytes = ex.readbackBuffer("srgb_out");
    ASSERT_TRUE(bytes.has_value());
    std::vector<float> r(128);
    std::memcpy(r.data(), bytes->data(), 512);
    for (size_t i = 0; i < 64; ++i) {
        const double v = inputs[i];
        const double encode = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        const double decode = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(r[i], encode, 2e-6) << "encode " << v;
        EXPECT_NEAR(r[64 + i], decode, 2e-6) << "decode " << v;
        EXPECT_NEAR(r[i], srgbEncode(inputs[i]), 2e-6);
    }
    // Both pieces meet at the breakpoint: the function is continuous there.
    EXPECT_NEAR(r[2], 12.92 * 0.0031308, 1e-6);
    EXPECT_NEAR(r[3], r[2], 1e-5);
}

}  // namespace

// post.at: a team's pass at each insertion point of the chain (a pass scaling its `source`).
// Doubling the image at "linear" is doubling the scene's luminance; doubling it at "exposed" is
// one stop of exposure compensation; halving it at "display_linear" halves the display's linear
// value; 1 − x at "display" inverts the display image. The tone mapping is split only where a
// point is used, and a point that is not used adds no pass.
TEST_F(PostGpu, TeamPassesGoWhereTheInsertionPointsSay) {
    struct Frame {
        Image display;
        std::vector<std::string> passes;
    };
    auto render = [&](const std::string& point, double scale, double offset, double luminance,
                      double ec) {
        const std::string file =
            std::string(RG_TEST_TMP) + "/post_at_" + (point.empty() ? "none" : point) + ".lua";
        std::ofstream out(file);
        out << "local rg = require 'rg'\nlocal post = require 'post'\n"
            << "post.params { exposure_mode = 'manual', dither = false, ec = " << ec << " }\n"
            << "post.exposure_state()\n"
            << "rg.param 'luminance' { type = 'number', default = " << luminance
            << ", min = 0, max = 1e12 }\n"
            << "rg.resource 'hdr' { format = 'rgba16f' }\n"
            << "rg.pass 'emit' { kind = 'fullscreen', shader = 'test/emit_ramp.frag', "
               "reads = { { 'exposure', as = 'storage' } }, writes = { 'hdr' } }\n";
        if (!point.empty())
            out << "post.at('" << point << "', 'team', { kind = 'fullscreen', shader = "
                << "'test/post_scale.frag', uniforms = { post_scale = " << scale
                << ", post_offset = " << offset << " } })\n";
        out << "post.chain { input = 'hdr', output = 'display' }\n"
               "rg.output { display = 'display', hdr = 'hdr', exposure = 'exposure' }\n";
        out.close();
        SessionOptions o;
        o.compile.outputWidth = 64;
        o.compile.outputHeight = 48;
        Session s(*s_runtime, o);
        Frame f;
        auto r = s.load(file);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r || !s.frame()) return f;
        for (const auto& p : s_runtime->executor().plan().passes) f.passes.push_back(p.name);
        auto img = s_runtime->executor().readback("display");
        if (img) f.display = std::move(*img);
        return f;
    };
    auto maxDiff = [](const Image& a, const Image& b, auto&& expect) {
        EXPECT_EQ(a.pixels.size(), b.pixels.size());
        float worst = 0;
        for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
            if (i % 4 != 3) worst = std::max(worst, std::fabs(expect(a.pixels[i]) - b.pixels[i]));
        return worst;
    };
    auto has = [](const Frame& f, const char* pass) {
        return std::find(f.passes.begin(), f.passes.end(), pass) != f.passes.end();
    };
    const double L = 20000;  // the ramp: 0.025 … 1.04 of white at Sunny 16
    const Frame base = render("", 1, 0, L, 0);
    ASSERT_FALSE(base.display.pixels.empty());
    EXPECT_TRUE(has(base, "tonemap"));
    EXPECT_FALSE(has(base, "expose") || has(base, "encode") || has(base, "team"));
    auto same = [](float v) { return v; };

    const Frame linear = render("linear", 2, 0, L, 0), brighter = render("", 1, 0, 2 * L, 0);
    EXPECT_TRUE(has(linear, "team"));
    EXPECT_LE(maxDiff(brighter.display, linear.display, same), 1.0f / 255) << "linear";
    EXPECT_GT(maxDiff(base.display, linear.display, same), 0.1f);

    const Frame exposed = render("exposed", 2, 0, L, 0), stop = render("", 1, 0, L, 1);
    EXPECT_TRUE(has(exposed, "expose") && has(exposed, "tonemap") && !has(exposed, "encode"));
    EXPECT_LE(maxDiff(stop.display, exposed.display, same), 1.0f / 255) << "exposed";

    const Frame half = render("display_linear", 0.5, 0, L, 0);
    EXPECT_TRUE(has(half, "tonemap") && has(half, "encode") && !has(half, "expose"));
    auto halved = [](float v) { return srgbEncode(0.5f * srgbDecode(v)); };
    EXPECT_LE(maxDiff(base.display, half.display, halved), 2.0f / 255) << "display_linear";
    EXPECT_GT(maxDiff(base.display, half.display, same), 0.1f);

    const Frame inverted = render("display", -1, 1, L, 0);
    EXPECT_LE(maxDiff(base.display, inverted.display, [](float v) { return 1.0f - v; }), 1e-6f);
}

// shaders/post/vignette.frag at post.at "exposed" (the README's example): a uniform field comes
// out as cos⁴θ of the centre, θ the angle off the optical axis for a 90° vertical field of view.
TEST_F(PostGpu, TheVignetteFollowsTheCos4Law) {
    const std::string file = std::string(RG_TEST_TMP) + "/post_vignette.lua";
    std::ofstream(file)
        << "local rg = require 'rg'\nlocal post = require 'post'\n"
           "post.params { exposure_mode = 'manual', dither = false, tonemap = 'linear' }\n"
           "post.exposure_state()\n"
           "rg.param 'luminance' { type = 'number', default = 20000, min = 0, max = 1e9 }\n"
           "rg.param 'highlight' { type = 'number', default = 0, min = 0, max = 1e12 }\n"
           "rg.param 'vignette' { type = 'number', default = 1, min = 0, max = 1 }\n"
           "rg.param 'vignette_fov' { type = 'number', default = 90, min = 1, max = 170 }\n"
           "rg.resource 'hdr' { format = 'rgba16f' }\n"
           "rg.pass 'emit' { kind = 'fullscreen', shader = 'test/emit.frag', "
           "reads = { { 'exposure', as = 'storage' } }, writes = { 'hdr' } }\n"
           "post.at('exposed', 'vignette', { kind = 'fullscreen', shader = "
           "'post/vignette.frag' })\n"
           "post.chain { input = 'hdr', output = 'display', bloom_levels = 0, fxaa = false }\n"
           "rg.output { display = 'display', hdr = 'hdr', exposure = 'exposure' }\n";
    SessionOptions o;
    o.compile.outputWidth = 64;
    o.compile.outputHeight = 48;
    Session s(*s_runtime, o);
    auto r = s.load(file);
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    auto display = s_runtime->executor().readback("display");
    ASSERT_TRUE(display.has_value());
    auto linear = [&](int x, int y) { return srgbDecode(display->at(x, y, 1)); };
    const double centre = (linear(31, 23) + linear(32, 24)) / 2;
    ASSERT_GT(centre, 0.2);
    for (const auto& [x, y] :
         {std::pair{0, 0}, std::pair{63, 24}, std::pair{32, 47}, std::pair{10, 40}}) {
        const double px = ((x + 0.5) / 64 * 2 - 1) * 64.0 / 48, py = (y + 0.5) / 48 * 2 - 1;
        const double cos2 = 1 / (1 + px * px + py * py);  // tan(45°) = 1
        EXPECT_NEAR(linear(x, y) / centre, cos2 * cos2, 0.01) << x << "," << y;
    }
}

// Emission relative to the exposure (emissive_unit = "ev", seed 002 §5.1.3): its luminance is
// colour · 2^(EV100 + EC − 3) with the EV100 the frame is pre-exposed with, so at two camera
// settings four stops apart the luminance is 16 times apart and the exposed image the same —
// from the G-buffer pass and from the forward pass alike.
TEST_F(PostGpu, EmissionRelativeToTheExposureKeepsItsPlaceOnScreen) {
    for (const bool forward : {false, true}) {
        double exposedAt[2] = {0, 0};
        int k = 0;
        for (const char* aperture : {"16", "4"}) {
            SessionOptions o =
                sceneOptions(std::string(RG_SOURCE_ROOT) + "/tests/gpu/scenes/emissive_ev.lua",
                             {{"forward", forward ? "1" : "0"}, {"aperture", aperture}}, 64, 48);
            o.params["exposure_mode"] = Value("manual");
            Readback r =
                renderAndRead(o, std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua", 2,
                              {"hdr"}, {"exposure"});
            ASSERT_TRUE(r.images.count("hdr") && r.buffers.count("exposure"));
            float st[4];
            std::memcpy(st, r.buffers["exposure"].data(), sizeof st);
            const double ev = st[0];  // manual: the camera's, the same every frame
            const double want = (forward ? 1.0 : 0.5 * 2.0) * std::exp2(ev - 3.0);
            const double got = r["hdr"].at(32, 24, 0) / r.preExposure;
            std::printf("%s, f/%s: EV100 %.3f, red %.1f nits (want %.1f)\n",
                        forward ? "forward" : "G-buffer", aperture, ev, got, want);
            EXPECT_NEAR(got, want, want * 0.02);
            exposedAt[k++] = got * photometry::exposureFromEv100(ev);
        }
        EXPECT_NEAR(exposedAt[0], exposedAt[1], exposedAt[0] * 0.02);
    }
}

// rg.resource's `history` (tests/lua/scripts/history.lua): `count` reads its last frame through
// `count_history` and adds 1, so frame N holds N — until the history is emptied: by a camera
// cut, by a switch of the passes writing `count`, by a rebuild of one (a compiled-in switch).
// A uniform change rebuilds nothing and keeps it; its keep pass goes last.
TEST_F(PostGpu, AHistoryCarriesTheLastFrameUntilWhatWritesItChanges) {
    SessionOptions o;
    o.compile.outputWidth = 16;
    o.compile.outputHeight = 8;
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(kScripts + "history.lua").has_value());
    auto count = [&] {
        EXPECT_TRUE(s.frame().has_value());
        auto img = s_runtime->executor().readback("count");
        EXPECT_TRUE(img.has_value());
        return img ? img->at(3, 5, 0) : -1.0f;
    };
    const auto& passes = s_runtime->executor().plan().passes;
    ASSERT_FALSE(passes.empty());
    EXPECT_EQ(passes.back().name, "count_history_keep");
    EXPECT_EQ(count(), 1.0f);
    EXPECT_EQ(count(), 2.0f);
    EXPECT_EQ(count(), 3.0f);
    s.cut();  // a camera cut: every history empty
    EXPECT_EQ(count(), 1.0f);
    EXPECT_EQ(count(), 2.0f);
    // Another pass writes `count` now: its first frame starts from nothing (2, not 4).
    auto r = s.setPassOverride("count_twice", true);
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.setPassOverride("count", false).has_value());
    EXPECT_EQ(count(), 2.0f);
    EXPECT_EQ(count(), 4.0f);
    ASSERT_TRUE(s.setPassOverride("count", true).has_value());
    ASSERT_TRUE(s.setPassOverride("count_twice", false).has_value());
    EXPECT_EQ(count(), 1.0f);
    EXPECT_EQ(count(), 2.0f);
    // A uniform changes nothing that was built: the history carries on.
    ASSERT_TRUE(s.setOverride("step", Value(0.5)).has_value());
    EXPECT_EQ(count(), 2.5f);
    // A compiled-in switch prepares `count` anew: from nothing again.
    ASSERT_TRUE(s.setOverride("hundred", Value(true)).has_value());
    EXPECT_EQ(count(), 100.5f);
    EXPECT_EQ(count(), 201.0f);
    EXPECT_NE(std::find(s_runtime->executor().lastBuildReport().passesPrepared.begin(),
                        s_runtime->executor().lastBuildReport().passesPrepared.end(), "count"),
              s_runtime->executor().lastBuildReport().passesPrepared.end());
}

// A hot reload (what `rgraph watch` does when a file changes) keeps a history whose writers are
// unchanged and empties it when the shader of one changed: the counter of history.lua, copied
// with its shader beside it, goes on over a reload of the same files and starts again once the
// shader is edited.
TEST_F(PostGpu, AHotReloadEmptiesTheHistoryOfAnEditedShaderOnly) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(RG_TEST_TMP) / "history_reload";
    fs::create_directories(dir);
    fs::copy_file(kScripts + "history.lua", dir / "history.lua",
                  fs::copy_options::overwrite_existing);
    std::string pipeline;
    {
        std::ifstream in(dir / "history.lua");
        pipeline.assign(std::istreambuf_iterator<char>(in), {});
    }
    // The shader beside the pipeline (a pass's shader is found in the pipeline's folder too).
    for (size_t at; (at = pipeline.find("test/count.frag")) != std::string::npos;)
        pipeline.replace(at, std::string("test/count.frag").size(), "count_copy.frag");
    std::ofstream(dir / "history.lua") << pipeline;
    const fs::path shader = dir / "count_copy.frag";
    fs::copy_file(std::string(RG_SOURCE_ROOT) + "/shaders/test/count.frag", shader,
                  fs::copy_options::overwrite_existing);
    SessionOptions o;
    o.compile.outputWidth = 16;
    o.compile.outputHeight = 8;
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load((dir / "history.lua").string()).has_value());
    auto count = [&] {
        EXPECT_TRUE(s.frame().has_value());
        auto img = s_runtime->executor().readback("count");
        return img ? img->at(3, 5, 0) : -1.0f;
    };
    EXPECT_EQ(count(), 1.0f);
    EXPECT_EQ(count(), 2.0f);
    ASSERT_TRUE(s.load((dir / "history.lua").string()).has_value());  // nothing changed
    EXPECT_EQ(count(), 3.0f);
    std::ofstream(shader, std::ios::app) << "// edited\n";
    fs::last_write_time(shader, fs::last_write_time(shader) + std::chrono::seconds(2));
    ASSERT_TRUE(s.load((dir / "history.lua").string()).has_value());  // the shader changed
    EXPECT_EQ(count(), 1.0f);
    EXPECT_EQ(count(), 2.0f);
}
