// Reference mode (scripts/pipelines/reference.lua, seed 000 §2.3): the same G-buffer lit by Monte
// Carlo integration of every light. First the integrator itself — a delta light, where both
// pipelines evaluate the same formula, and a 0.5 mm sphere, which must converge to that point
// light — then each area light's real-time approximation (shaders/lib/lighting.glsl) against it
// on tests/gpu/scenes/reference_*.lua: a white diffuse floor (reflectance 0: only the diffuse
// approximation shows there) and four spheres (rough, glossy, gold, chrome) under one light.
// Each bound below is the error measured at 160x90 with 64 frames x 4 samples, plus a margin for
// the reference's remaining noise (about 1/sqrt(256) of a pixel's value, averaged over the region).
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 160, H = 90;

struct Render {
    Image hdr;  // cd/m²
    Image gb2;  // metal mask (g), reflectance (b): the floor is the only surface of reflectance 0
    Image depth;
};

class Reference : public GpuFixture {
protected:
    static Render render(const std::string& pipeline, const std::string& scene, uint32_t frames,
                         const std::map<std::string, std::string>& sceneArgs = {}) {
        SessionOptions o;
        o.sceneArgs = sceneArgs;
        o.compile.outputWidth = W;
        o.compile.outputHeight = H;
        o.scene = kRoot + "/tests/gpu/scenes/" + scene;
        o.params["exposure_mode"] = Value("manual");
        o.params["light_shapes"] = Value(false);  // the lights' lighting alone, not their look
        o.paramsIfDeclared["taa_jitter"] = Value(false);   // pixels compared one by one
        o.paramsIfDeclared["specular_aa"] = Value(false);  // roughness as the scene gives it
        // The same meshes in both (the reference mode draws the full ones): the lights' terms are
        // compared, not the spheres' levels of detail.
        o.levelsOfDetail = false;
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/" + pipeline, frames,
                                   {"hdr", "GB2", "depth"});
        Render out;
        if (r.images.size() != 3) return out;
        out.hdr = r["hdr"];
        for (float& v : out.hdr.pixels)
            v /= r.preExposure;  // the pre-exposure this frame was rendered with
        out.gb2 = r["GB2"];
        out.depth = r["depth"];
        return out;
    }

    struct Error {
        double floorMean = 0;    // mean relative error over the floor (diffuse only)
        double surfaceMean = 0;  // mean relative error over every surface the reference lights
        double bias = 0;         // Σ real-time / Σ reference − 1 over the same pixels
    };
    // Relative errors and energy over RGB where the reference is above 1 % of its brightest
    // surface (the rest — back faces, the far floor, points inside a light — is nearly nothing).
    static Error compare(const Render& rt, const Render& ref) {
        Error e;
        double peak = 0;
        for (size_t i = 0; i < size_t(W) * H; ++i)
            if (ref.depth.pixels[i] < 1.0f)
                for (int c = 0; c < 3; ++c)
                    peak = std::max(peak, double(ref.hdr.pixels[i * 4 + c]));
        double floorSum = 0, surfaceSum = 0, rtSum = 0, refSum = 0;
        size_t floorN = 0, surfaceN = 0;
        for (size_t i = 0; i < size_t(W) * H; ++i) {
            if (ref.depth.pixels[i] >= 1.0f) continue;
            const bool floor = ref.gb2.pixels[i * 4 + 2] == 0.0f;
            for (int c = 0; c < 3; ++c) {
                const double a = rt.hdr.pixels[i * 4 + c], b = ref.hdr.pixels[i * 4 + c];
                if (b < 0.01 * peak) continue;
                rtSum += a;
                refSum += b;
                const double rel = std::abs(a - b) / b;
                surfaceSum += rel;
                ++surfaceN;
                if (floor) {
                    floorSum += rel;
                    ++floorN;
                }
            }
        }
        e.floorMean = floorN ? floorSum / double(floorN) : 0;
        e.surfaceMean = surfaceN ? surfaceSum / double(surfaceN) : 0;
        e.bias = refSum > 0 ? rtSum / refSum - 1.0 : 0;
        return e;
    }

    static Error measure(const char* scene,
                         const std::map<std::string, std::string>& sceneArgs = {}) {
        Render rt = render("deferred.lua", scene, 1, sceneArgs);
        Render ref = render("reference.lua", scene, 64, sceneArgs);
        Error e = compare(rt, ref);
        std::string args;
        for (const auto& [k, v] : sceneArgs) args += " " + k + "=" + v;
        std::printf("%-22s%s floor %.4f, surfaces %.4f, energy %+.4f\n", scene, args.c_str(),
                    e.floorMean, e.surfaceMean, e.bias);
        return e;
    }
};

TEST_F(Reference, PointLightIsExactInBoth) {
    Error e = measure("reference_point.lua");
    EXPECT_LT(e.surfaceMean, 1e-3);
    EXPECT_LT(std::abs(e.bias), 1e-3);
}

TEST_F(Reference, TinySphereConvergesToThePointLight) {
    // A 0.5 mm sphere: the reference samples its cone, the real-time path takes lst:10 — both
    // must reach the point light's exact answer (checks the sampling and its pdf).
    Error e = measure("reference_sphere_tiny.lua");
    EXPECT_LT(e.surfaceMean, 0.01);
    EXPECT_LT(std::abs(e.bias), 0.005);
}

// Measured (160x90, 256 samples): floor 0.0023, surfaces 0.0062, energy -0.0075. lst:10 is exact
// for a sphere's illuminance; what is left is the Disney diffuse taken towards the light's centre
// and, on the glossy spheres, the representative point's energy factor.
TEST_F(Reference, SphereLight) {
    Error e = measure("reference_sphere.lua");
    EXPECT_LT(e.floorMean, 0.01);
    EXPECT_LT(e.surfaceMean, 0.02);
    EXPECT_LT(std::abs(e.bias), 0.025);
}

// Measured: floor 0.0245, surfaces 0.028, energy -0.037: lst:10's disk form with the disk's own
// facing factor, a little dark (the seed calls it a small discrepancy); highlights lose energy.
TEST_F(Reference, DiskLight) {
    Error e = measure("reference_disk.lua");
    EXPECT_LT(e.floorMean, 0.035);
    EXPECT_LT(e.surfaceMean, 0.04);
    EXPECT_LT(std::abs(e.bias), 0.055);
}

// Measured: floor 0.040, surfaces 0.048, energy -0.043: structured sampling (4 corners + centre ×
// the solid angle, seed 002 §4.7.2.5) of a 1.6 m x 0.5 m light 1.8 m up.
TEST_F(Reference, RectangleLight) {
    Error e = measure("reference_rect.lua");
    EXPECT_LT(e.floorMean, 0.055);
    EXPECT_LT(e.surfaceMean, 0.065);
    EXPECT_LT(std::abs(e.bias), 0.06);
}

// Measured: floor 0.036, surfaces 0.047, energy -0.074: the capsule as a rectangle facing the
// point plus one sphere (seed 002 §4.7.2.6); near-mirror highlights lose most (sphere × line
// energy factors).
TEST_F(Reference, TubeLight) {
    Error e = measure("reference_tube.lua");
    EXPECT_LT(e.floorMean, 0.05);
    EXPECT_LT(e.surfaceMean, 0.065);
    EXPECT_LT(std::abs(e.bias), 0.10);
}

TEST_F(Reference, LightsAcrossTheHorizon) {
    // reference_horizon.lua: a floor around a light that dips below it, the case lst:10's horizon
    // handling exists for. Floor only (the scene has nothing else); pixels inside the sphere or
    // tube get nothing in the reference (emitters emit outwards) and near-nothing pixels are left
    // out by compare(). Measured: see each bound.
    const struct {
        const char* light;
        double floor, energy;
    } cases[] = {
        {"sphere", 0.20, 0.15},  // measured 0.13, +0.10: lst:10 is exact for the illuminance; the
                                 // Disney diffuse taken towards the centre is not, this close
        {"disk", 0.20, 0.30},    // measured 0.13, -0.21: the disk's facing factor at the horizon
        {"rect", 0.50, 0.50},    // measured 0.34, +0.38: clamped corner cosines over-light
        {"tube", 0.30, 0.15},    // measured 0.21, +0.06
    };
    for (const auto& c : cases) {
        Error e = measure("reference_horizon.lua", {{"light", c.light}});
        EXPECT_LT(e.floorMean, c.floor) << c.light;
        EXPECT_LT(std::abs(e.bias), c.energy) << c.light;
    }
}

TEST_F(Reference, PointsInsideASphereOrTubeGetNothing) {
    // reference_horizon.lua: the floor under the sphere's centre (0.2 m up, 0.5 m radius) and the
    // tube's axis (0.05 m up, 0.1 m radius) lies inside the light. Its surface emits outwards, so
    // the reference gives those points 0; the real-time evaluation gives 0 too (before: lst:10's and
    // the capsule's formulas blew up there).
    for (const char* light : {"sphere", "tube"}) {
        Render rt = render("deferred.lua", "reference_horizon.lua", 1, {{"light", light}});
        Render ref = render("reference.lua", "reference_horizon.lua", 16, {{"light", light}});
        ASSERT_FALSE(rt.hdr.pixels.empty());
        ASSERT_FALSE(ref.hdr.pixels.empty());
        // The camera looks at the origin: the image's centre is the floor right under the light.
        const size_t i = (size_t(H / 2) * W + W / 2) * 4;
        std::printf("%s: the floor inside the light: real-time %.4g, reference %.4g nits\n", light,
                    rt.hdr.pixels[i + 1], ref.hdr.pixels[i + 1]);
        EXPECT_EQ(rt.hdr.pixels[i + 1], 0.0f) << light;
        EXPECT_LT(ref.hdr.pixels[i + 1], 1e-3f) << light;
    }
}

TEST_F(Reference, AccumulationKeepsItsFramesUntilTheSceneChanges) {
    // The accumulator's alpha counts its frames. A reload of the same pipeline and scene (watch)
    // keeps them; a scene whose file changed starts again (the old frames show another scene).
    const std::string scene = std::string(RG_TEST_TMP) + "/reference_reload.lua";
    auto writeScene = [&](const char* intensity) {
        std::ofstream(scene)
            << "local scene = require 'scene'\n"
            << "scene.material 'm' { base_color = { 0.5, 0.5, 0.5 } }\n"
            << "scene.plane 'floor' { size = { 4, 4 }, material = 'm' }\n"
            << "scene.light 'key' { type = 'sphere', intensity = " << intensity
            << ", unit = 'lm', radius = 0.2, position = { 0, 1, 0 } }\n"
            << "scene.camera 'c' { position = { 0, 2, 2 }, target = { 0, 0, 0 } }\n";
    };
    writeScene("1000");
    SessionOptions o;
    o.compile.outputWidth = 32;
    o.compile.outputHeight = 16;
    o.scene = scene;
    o.captures = {"reference_accum"};
    Session s(*s_runtime, o);
    auto framesHeld = [&]() {
        auto img = s_runtime->executor().readback("reference_accum");
        EXPECT_TRUE(img.has_value());
        return img ? img->at(16, 8, 3) : -1.0f;
    };
    const std::string pipeline = kRoot + "/scripts/pipelines/reference.lua";
    ASSERT_TRUE(s.load(pipeline).has_value());
    for (int f = 0; f < 3; ++f) ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(framesHeld(), 3.0f);
    ASSERT_TRUE(s.load(pipeline).has_value());  // same pipeline, same scene: the frames stay
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(framesHeld(), 4.0f);
    writeScene("2000");
    ASSERT_TRUE(s.load(pipeline).has_value());  // the scene changed: start again
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(framesHeld(), 1.0f);
}

}  // namespace

// The environment as a light of its own (reference.comp's samples from SceneEnvironmentCdf): a
// rough sphere under a dim sky (1 nit) with a small bright patch (20 000 nits, 8 x 5 texels of a
// 256 x 128 image, up and to the front right). Sampling the environment's luminance finds the
// patch with every sample; sampling the BRDF finds it by chance — the same mean, far more noise.
TEST_F(Reference, EnvironmentLuminanceSamplingAgreesWithBrdfSamplingWithLessNoise) {
    namespace fs = std::filesystem;
    const std::string dir = std::string(RG_TEST_TMP) + "/reference_environment";
    fs::create_directories(dir);
    Image env(256, 128, 4);
    for (uint32_t y = 0; y < 128; ++y)
        for (uint32_t x = 0; x < 256; ++x)
            for (uint32_t c = 0; c < 4; ++c)
                env.pixels[env.index(x, y, c)] = c == 3 ? 1.0f
                                                 : (x >= 220 && x < 228 && y >= 42 && y < 47)
                                                     ? 2e4f
                                                     : 1.0f;
    ASSERT_TRUE(
        writeExr(dir + "/patch.exr", {ImageLayer{"", {"R", "G", "B", "A"}, env}}).has_value());
    std::ofstream(dir + "/scene.lua")
        << "local scene = require \"scene\"\n"
           "scene.material \"rough\" { base_color = { 0.8, 0.8, 0.8 }, smoothness = 0.3 }\n"
           "scene.sphere \"ball\" { radius = 1, material = \"rough\", segments = 64 }\n"
           "scene.environment \"patch\" { kind = \"hdr\", file = \"patch.exr\" }\n"
           "scene.camera \"c\" { position = { 0, 0, 4 }, target = { 0, 0, 0 }, fov = 35 }\n";
    constexpr uint32_t w = 96, h = 64;
    auto render = [&](const std::string& strategy, uint32_t frames, double seed) {
        SessionOptions o = sceneOptions(dir + "/scene.lua", {}, w, h);
        o.params["reference_strategy"] = Value(strategy);
        o.params["reference_seed"] = Value(seed);
        Readback r =
            renderAndRead(o, kRoot + "/scripts/pipelines/reference.lua", frames, {"hdr", "depth"});
        std::pair<Image, Image> out;
        if (r.images.size() != 2) return out;
        out.first = r["hdr"];
        for (float& v : out.first.pixels) v /= r.preExposure;
        out.second = r["depth"];
        return out;
    };
    // Mean luminance over the sphere, and the noise of one frame: the RMS difference between two
    // seeds over the sphere, relative to its mean.
    auto sphereMean = [&](const std::pair<Image, Image>& a) {
        double sum = 0;
        size_t n = 0;
        for (size_t i = 0; i < size_t(w) * h; ++i)
            if (a.second.pixels[i] < 1.0f) sum += a.first.pixels[i * 4 + 1], ++n;
        return n ? sum / double(n) : 0.0;
    };
    auto noise = [&](const std::string& strategy) {
        auto a = render(strategy, 1, 0), b = render(strategy, 1, 1);
        double sum = 0;
        size_t n = 0;
        for (size_t i = 0; i < size_t(w) * h; ++i)
            if (a.second.pixels[i] < 1.0f) {
                const double d = a.first.pixels[i * 4 + 1] - b.first.pixels[i * 4 + 1];
                sum += d * d, ++n;
            }
        return n ? std::sqrt(sum / double(n)) /
                       std::max(0.5 * (sphereMean(a) + sphereMean(b)), 1e-6)
                 : 0.0;
    };
    const double noiseMis = noise("mis"), noiseLight = noise("light"), noiseBrdf = noise("brdf");
    const double light = sphereMean(render("light", 32, 0)), mis = sphereMean(render("mis", 32, 0)),
                 brdf = sphereMean(render("brdf", 256, 0));
    std::printf(
        "one frame's noise (RMS of two seeds' difference / mean): %.3f MIS, %.3f environment "
        "samples, %.3f BRDF samples; sphere mean "
        "%.2f (environment, 32 frames), %.2f (MIS, 32), %.2f (BRDF, 256) nits\n",
        noiseMis, noiseLight, noiseBrdf, light, mis, brdf);
    ASSERT_GT(brdf, 0.0);
    EXPECT_LT(noiseMis, 0.25 * noiseBrdf);
    EXPECT_NEAR(light / brdf, 1.0, 0.03);
    EXPECT_NEAR(mis / brdf, 1.0, 0.03);
}
