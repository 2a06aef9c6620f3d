// Pipeline scripts on the GPU: runtime reconfiguration, shader swaps, stencil and persistent
// resources, rg.frame, transactional reload, and every example of scripts/README.md rendered.
#include <gtest/gtest.h>

#include "../gpu/gpu_fixture.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "image/image.h"
#include "layout/layout.h"

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "core/compiler.h"
#include "lua/lua_host.h"
#include "lua_test_util.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::test;

namespace {

// ---- on the GPU: reconfiguration and reload ----

class LuaGpu : public GpuFixture {
protected:
    static SessionOptions small() {
        SessionOptions o;
        o.compile.outputWidth = 32;
        o.compile.outputHeight = 16;
        return o;
    }
    Image output(Session& s) {
        auto img = s_runtime->executor().readback(s.pipeline().output);
        EXPECT_TRUE(img.has_value()) << (img ? "" : img.error().message);
        return img ? *img : Image();
    }
};

TEST_F(LuaGpu, DisableOnFrame2EnableOnFrame3) {
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(script("reconfigure.lua")).has_value());
    std::vector<Image> frames;
    for (int f = 0; f < 3; ++f) {
        auto r = s.frame();
        ASSERT_TRUE(r.has_value()) << r.error().message;
        frames.push_back(output(s));
    }
    EXPECT_EQ(frames[0].pixels, frames[2].pixels);
    EXPECT_NE(frames[0].pixels, frames[1].pixels);
    EXPECT_FLOAT_EQ(frames[0].at(5, 3, 0) - frames[1].at(5, 3, 0),
                    0.25f);  // the tint's contribution
    EXPECT_EQ(s.rebuilds(), 2u);
    // Re-enabling brings back the passes and resources it had: nothing new was compiled.
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared,
              (std::vector<std::string>{"tint"}));
}

// A pass's only_when (every parameter of its list on) and a write's load = "pass": the second
// pass adds to what the first cleared while the first runs, to its own clear otherwise — also when
// a parameter switched at run time leaves the first out, and when it comes back.
TEST_F(LuaGpu, OnlyWhenPassesAndLoadAfterFollowTheParameters) {
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(script("first_phase.lua")).has_value());
    auto red = [&] {
        auto r = s.frame();
        EXPECT_TRUE(r.has_value()) << r.error().message;
        return output(s).at(5, 3, 0);
    };
    auto loads = [&] {
        const PassDesc* second = s_runtime->executor().graph().findPass("second");
        return second && second->accesses.at(0).load;
    };
    EXPECT_FLOAT_EQ(red(), 0.75f);
    EXPECT_TRUE(loads());
    ASSERT_TRUE(s.setOverride("occlusion", Value(false)).has_value());
    EXPECT_FLOAT_EQ(red(), 0.25f) << "the first pass left out, the second clears";
    EXPECT_FALSE(loads());
    ASSERT_TRUE(s.setOverride("occlusion", Value(true)).has_value());
    EXPECT_FLOAT_EQ(red(), 0.75f);
    ASSERT_TRUE(s.setOverride("culling", Value(false)).has_value());
    EXPECT_FLOAT_EQ(red(), 0.25f);
}

TEST_F(LuaGpu, ShaderSwapRebuildsOnlyThatPass) {
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(script("swap_shader.lua")).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_FLOAT_EQ(output(s).at(1, 1, 3), 1.0f);
    EXPECT_FLOAT_EQ(output(s).at(1, 1, 1), 1.0f / 64.0f);  // transform: g = pattern.r = x / 64
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_FLOAT_EQ(output(s).at(1, 1, 1), 0.75f);  // tint.frag: the constant tint
    EXPECT_EQ(s.rebuilds(), 1u);
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared,
              (std::vector<std::string>{"transform"}));
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesReused,
              (std::vector<std::string>{"generate"}));
    ASSERT_FALSE(s.log().empty());
    EXPECT_NE(s.log().back().find("'transform' uses test/tint.frag; recompiled in"),
              std::string::npos)
        << s.log().back();
}

TEST_F(LuaGpu, ShadersIncludeTheGeneratedPackCode) {
    Session s(*s_runtime, small());
    auto r = s.load(script("gbuffer.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    auto info = analyzeLayout(s.pipeline().layouts[0]);
    ASSERT_TRUE(info.has_value());
    std::vector<TexelValue> texels;
    for (const auto& t : info->desc.targets) {
        auto img = s_runtime->executor().readback(t.name);
        ASSERT_TRUE(img.has_value()) << img.error().message;
        texels.push_back(texelFromFloats(
            t.format, &img->pixels[(3 * img->width + 7) * img->channels], img->channels));
    }
    auto g = unpackTexel(*info, texels);
    auto channel = [&](const char* name) { return g[static_cast<size_t>(info->find(name))]; };
    EXPECT_EQ(channel("materialId").u[0], 2u);
    EXPECT_NEAR(channel("smoothness").v[0], 0.7f, 0.5f / 1023 + 1e-5f);
    EXPECT_NEAR(channel("metalMask").v[0], 1.0f, 1e-6f);
    EXPECT_NEAR(channel("reflectance").v[0], 0.5f,
                0.5f / 255 + 1e-5f);  // 127.5 rounds up: exactly half a step
    EXPECT_NEAR(channel("ao").v[0], 0.9f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(srgbEncode(channel("baseColor").v[0]), srgbEncode(0.8f), 1.0f / 255);
    const float len = std::sqrt(0.3f * 0.3f + 0.5f * 0.5f + 0.8f * 0.8f);
    const auto& n = channel("normal").v;
    EXPECT_GT((n[0] * 0.3f - n[1] * 0.5f + n[2] * 0.8f) / len,
              std::cos(4.2e-3f));  // the 10+10-bit octahedral bound
}

TEST_F(LuaGpu, StencilAndDepthTestedFullscreenPasses) {
    Session s(*s_runtime, small());
    auto r = s.load(script("stencil_depth.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    auto px = [&](const char* name) {
        auto img = s_runtime->executor().readback(name);
        EXPECT_TRUE(img.has_value());
        return img ? img->at(10, 7, 0) : -1.0f;
    };
    EXPECT_FLOAT_EQ(px("hit"), 1.0f);   // stencil 3 == 3
    EXPECT_FLOAT_EQ(px("miss"), 0.0f);  // stencil 3 != 2: only the clear
    EXPECT_FLOAT_EQ(px("near"), 1.0f);  // 0.25 < 0.5
    EXPECT_FLOAT_EQ(px("far"), 0.0f);   // 0.75 is behind 0.5
}

TEST_F(LuaGpu, PersistentResourcesCarryOverFrames) {
    Session s(*s_runtime, small());
    auto r = s.load(script("persistent.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    for (int f = 1; f <= 3; ++f) {
        ASSERT_TRUE(s.frame().has_value());
        EXPECT_FLOAT_EQ(output(s).at(4, 4, 0), 0.5f * static_cast<float>(f));
    }
    // A rebuild that keeps the resource keeps its contents.
    ASSERT_TRUE(s.load(script("persistent.lua")).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_FLOAT_EQ(output(s).at(4, 4, 0), 2.0f);
}

TEST_F(LuaGpu, SceneMaterialParametersAreCheckedByName) {
    // #14: a typo'd game-team parameter, or one of the wrong type, is an error at the scene's
    // declaration (file:line), with the model's parameters and a did-you-mean; a right one loads.
    const std::string file = std::string(RG_TEST_TMP) + "/params_scene.lua";
    auto sceneWith = [&](const std::string& params) {
        std::ofstream(file) << "local scene = require \"scene\"\n"
                               "scene.material \"coated\" { model = \"clear_coat\", params = { "
                            << params
                            << " } }\n"
                               "scene.sphere \"s\" { radius = 0.5, material = \"coated\" }\n";
        SessionOptions o = small();
        o.scene = file;
        Session s(*s_runtime, o);
        auto r = s.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
        return r.has_value() ? std::string() : r.error().describe();
    };
    EXPECT_EQ(sceneWith("coatSmoothness = 0.5, coatStrength = 1"), "");
    EXPECT_NE(
        sceneWith("coatSmoothnes = 0.5")
            .find("params_scene.lua:2: scene.material.coated.params.coatSmoothnes: model "
                  "'clear_coat' has no "
                  "parameter 'coatSmoothnes' (did you mean 'coatSmoothness'?); its parameters: "
                  "'coatNormalScale', 'coatSmoothness', 'coatStrength'"),
        std::string::npos)
        << sceneWith("coatSmoothnes = 0.5");
    EXPECT_NE(sceneWith("coatStrength = \"full\"")
                  .find("params_scene.lua:2: scene.material.coated.params.coatStrength: expected a "
                        "number (as model "
                        "'clear_coat' declares it), got string"),
              std::string::npos)
        << sceneWith("coatStrength = \"full\"");
}

TEST_F(LuaGpu, ParametersAndResourcesNameWhatTheSceneHas) {
    // rg.param's `scene = SETTING`: scripts/lighting.lua's area_lights drives the scene's
    // area_light_model; a setting the scene does not have is an error at the load naming the
    // parameter where it was declared and the settings there are.
    const std::string file = std::string(RG_TEST_TMP) + "/scene_setting.lua";
    std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
    const std::string deferred((std::istreambuf_iterator<char>(in)), {});
    const int line = static_cast<int>(std::count(deferred.begin(), deferred.end(), '\n')) + 1;
    std::ofstream(file)
        << deferred << "rg.param \"glow\" { type = \"number\", default = 1, scene = \"glow\" }\n";
    Session bad(*s_runtime, small());
    auto r = bad.load(file);
    ASSERT_FALSE(r);
    EXPECT_NE(
        r.error().describe().find("scene_setting.lua:" + std::to_string(line) +
                                  ": params.glow: scene = 'glow': the scene has no setting "
                                  "'glow' (it has: 'area_light_model', 'jitter', 'antialiasing')"),
        std::string::npos)
        << r.error().describe();

    // scene_layers names an extent the scene has: an unknown one is an error at the build,
    // where the scene is known, naming the resource and the extents there are.
    std::ofstream(file)
        << deferred
        << "rg.resource \"maps\" { format = \"d32f\", size = { 64, 64 }, layers = 4, "
           "scene_layers = \"lamps\" }\n";
    Session layers(*s_runtime, small());
    auto l = layers.load(file);
    ASSERT_FALSE(l);
    EXPECT_NE(l.error().describe().find(
                  "scene_setting.lua:" + std::to_string(line) +
                  ": resource 'maps': scene_layers = 'lamps': the scene has "
                  "no such extent (it has 'shadow_views', 'shadow_casters', 'shadow_batches', "
                  "'camera_batches', 'draws', 'camera_runs', 'lights')"),
              std::string::npos)
        << l.error().describe();
    // So does a buffer's scene_count.
    std::ofstream(file) << deferred
                        << "rg.buffer \"lists\" { size = 16, scene_count = \"lamps\", "
                           "count_bytes = 8 }\n";
    Session counts(*s_runtime, small());
    auto c = counts.load(file);
    ASSERT_FALSE(c);
    EXPECT_NE(c.error().describe().find("scene_setting.lua:" + std::to_string(line) +
                                        ": resource 'lists': scene_count = 'lamps': the scene "
                                        "has no such extent"),
              std::string::npos)
        << c.error().describe();

    // only_when.scene names a feature the scene has, likewise.
    std::ofstream(file) << deferred
                        << "rg.resource \"extra\" { format = \"rgba8\", only_when = { scene = "
                           "\"sky\" } }\n";
    Session features(*s_runtime, small());
    auto f = features.load(file);
    ASSERT_FALSE(f);
    EXPECT_NE(f.error().describe().find(
                  "scene_setting.lua:" + std::to_string(line) +
                  ": resource 'extra': only_when.scene = 'sky': the scene "
                  "has no such feature (it has 'lightmap', 'material:MODEL', 'motion', 'draws:N', "
                  "'local_shadows', 'gpu_draws')"),
              std::string::npos)
        << f.error().describe();
    // "material:NAME" names a material the pipeline declares: a misspelt one would drop the
    // resource in every scene.
    std::ofstream(file) << deferred
                        << "rg.resource \"extra\" { format = \"rgba8\", only_when = { scene = "
                           "\"material:transmision\" } }\n";
    Session misspelt(*s_runtime, small());
    auto m = misspelt.load(file);
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().describe().find(": resource 'extra': only_when.scene = "
                                        "'material:transmision': the pipeline declares no material "
                                        "'transmision' (it has 'standard', "),
              std::string::npos)
        << m.error().describe();

    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua"));
    const ParamDesc* model = s.pipeline().findParam("area_lights");
    ASSERT_NE(model, nullptr);
    EXPECT_EQ(model->sceneSetting, "area_light_model");
}

TEST_F(LuaGpu, SurfaceFilesResolveNextToTheDeclaringScript) {
    // #14: a game team's material in a folder of its own (outside the repository): its surface
    // function sits next to the script that declares it, and renders from there.
    const fs::path dir = fs::path(RG_TEST_TMP) / "team_material";
    fs::create_directories(dir);
    std::ofstream(dir / "red.glsl")
        << "GBuffer_disney rgSurface(RgSurface s) {\n"
           "    GBuffer_disney g;\n    g.normal = s.normal;\n    g.smoothness = 0.5;\n"
           "    g.materialId = RG_MATERIAL_ID;\n    g.baseColor = vec3(1.0, 0.0, 0.0);\n"
           "    g.materialData = 0u;\n    g.normalExtra = 0u;\n    g.reserved = 0.0;\n"
           "    g.metalMask = 0.0;\n    g.reflectance = 0.5;\n    g.ao = 1.0;\n    g.emissive = "
           "vec3(0.0);\n"
           "    return g;\n}\n";
    std::ofstream(dir / "pipeline.lua") << "local rg = require \"rg\"\nrequire \"disney\"\n"
                                           "rg.material \"red\" { id = 1, layout = \"disney\", "
                                           "path = \"standard\", surface = \"red.glsl\" }\n"
                                           "rg.resource \"GB0\" { format = \"rgb10a2\" "
                                           "}\nrg.resource \"GB1\" { format = \"rgba8_srgb\" }\n"
                                           "rg.resource \"GB2\" { format = \"rgba8\" "
                                           "}\nrg.resource \"GB3\" { format = \"rgba16f\" }\n"
                                           "rg.resource \"depth\" { format = \"d32f_s8\" }\n"
                                           "rg.pass \"gbuffer\" { kind = \"scene\", writes = { "
                                           "\"GB0\", \"GB1\", \"GB2\", \"GB3\", \"depth\" } }\n"
                                           "rg.output \"GB1\"\n";
    std::ofstream(dir / "scene.lua")
        << "local scene = require \"scene\"\n"
           "scene.material \"m\" { model = \"red\" }\n"
           "scene.plane \"p\" { size = { 10, 10 }, material = \"m\" }\n"
           "scene.camera \"c\" { position = { 0, 3, 0.001 }, target = { 0, 0, 0 }, fov = 60 }\n";
    SessionOptions o = small();
    o.scene = (dir / "scene.lua").string();
    Session s(*s_runtime, o);
    auto r = s.load((dir / "pipeline.lua").string());
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    auto gb1 = s_runtime->executor().readback("GB1");
    ASSERT_TRUE(gb1.has_value()) << gb1.error().describe();
    // GB1 holds the base colour (sRGB): the red the team's surface wrote, at the plane's centre.
    EXPECT_NEAR(gb1->at(gb1->width / 2, gb1->height / 2, 0), 1.0f, 1e-3f);
    EXPECT_NEAR(gb1->at(gb1->width / 2, gb1->height / 2, 1), 0.0f, 1e-3f);
}

TEST_F(LuaGpu, LayoutsOfTheSameNameInTwoPipelinesDoNotCollide) {
    // #14: generated G-buffer headers went to one folder per layout name, so two pipelines that
    // declare "shared" differently overwrote each other's. Now each set of layouts has a folder
    // named by its content, and a session switches the compiler to its own.
    const fs::path dir = fs::path(RG_TEST_TMP) / "layout_collision";
    fs::create_directories(dir);
    auto pipeline =
        [&](const std::string& name, const std::string& channel) {
            std::ofstream(dir / name)
                << "local rg = require \"rg\"\n"
                   "rg.layout \"shared\" { { \"T\", \"rgba8\", { \""
                << channel
                << ":unorm:8\", \"rest:unorm:8\" } } }\n"
                   "rg.resource \"output\" { format = \"rgba32f\" }\n"
                   "rg.pass \"fill\" { kind = \"compute\", shader = \"test/pattern.comp\", writes "
                   "= { \"output\" }, bind = { pattern = \"output\" } }\n"
                   "rg.output \"output\"\n";
            return (dir / name).string();
        };
    LuaHost host(luaHostOptionsWithoutDevice());
    auto a = host.load(pipeline("a.lua", "alpha"));
    ASSERT_TRUE(a.has_value()) << a.error().message;
    auto b = host.load(pipeline("b.lua", "beta"));
    ASSERT_TRUE(b.has_value()) << b.error().message;
    auto da = writeLayoutHeaders(*a), db = writeLayoutHeaders(*b);
    ASSERT_TRUE(da.has_value() && db.has_value());
    EXPECT_NE(*da, *db);
    auto text = [](const std::string& folder) {
        std::ifstream in(fs::path(folder) / "gbuffer_shared.glsl");
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    EXPECT_NE(text(*da).find("alpha"), std::string::npos);
    EXPECT_EQ(text(*da).find("beta"), std::string::npos);
    EXPECT_NE(text(*db).find("beta"), std::string::npos);
    // The same layouts again: the same folder.
    auto again = writeLayoutHeaders(*a);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(*again, *da);
    // A session's build compiles against its own pipeline's folder.
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(pipeline("a.lua", "alpha")).has_value());
    EXPECT_EQ(s_runtime->shaders().options().generatedDir, *da);
    ASSERT_TRUE(s.load(pipeline("b.lua", "beta")).has_value());
    EXPECT_EQ(s_runtime->shaders().options().generatedDir, *db);
}

TEST_F(LuaGpu, CadenceOnceRecordsAfterEachBuildAndEachReset) {
    Session s(*s_runtime, small());
    auto r = s.load(script("cadence_once.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    for (int f = 1; f <= 3; ++f) {
        ASSERT_TRUE(s.frame().has_value());
        EXPECT_FLOAT_EQ(output(s).at(4, 4, 0), 0.5f) << "frame " << f;  // once, not per frame
    }
    // Cleared history: the pass fills it again, once.
    ASSERT_TRUE(s_runtime->executor().resetPersistent().has_value());
    for (int f = 1; f <= 2; ++f) {
        ASSERT_TRUE(s.frame().has_value());
        EXPECT_FLOAT_EQ(output(s).at(4, 4, 0), 0.5f) << "after the reset, frame " << f;
    }
    // A bad cadence is named with the values it may take.
    const std::string bad = std::string(RG_TEST_TMP) + "/bad_cadence.lua";
    fs::create_directories(RG_TEST_TMP);
    std::ifstream in(script("cadence_once.lua"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("cadence = \"once\""), 16, "cadence = \"daily\"");
    std::ofstream(bad) << text;
    auto loaded =
        s.load(bad);  // kept as the transaction's new plan, or refused when it is prepared
    Result<void> e = loaded ? s.frame() : Result<void>(std::unexpected(loaded.error()));
    ASSERT_FALSE(e.has_value());
    EXPECT_NE(
        e.error().describe().find(
            "pass 'accumulate': params.cadence: unknown 'daily', expected one of: 'frame', 'once'"),
        std::string::npos)
        << e.error().describe();
    // A pass run once that writes a transient resource would leave garbage in the frames it skips.
    const std::string transient = std::string(RG_TEST_TMP) + "/once_transient.lua";
    std::ofstream(transient)
        << "local rg = require \"rg\"\n"
           "rg.resource \"output\" { format = \"rgba32f\" }\n"
           "rg.pass \"fill\" { kind = \"compute\", shader = \"test/pattern.comp\", writes = { "
           "\"output\" }, bind = { pattern = \"output\" }, cadence = \"once\" }\n"
           "rg.output \"output\"\n";
    auto t = s.load(transient);
    Result<void> te = t ? s.frame() : Result<void>(std::unexpected(t.error()));
    ASSERT_FALSE(te.has_value());
    EXPECT_NE(te.error().describe().find("params.cadence: 'once' writes only persistent resources; "
                                         "'output' is not (declare it with persistent = true)"),
              std::string::npos)
        << te.error().describe();
}

TEST_F(LuaGpu, AShadowPassNamesABadCull) {
    SessionOptions o = small();
    o.scene = std::string(RG_SOURCE_ROOT) + "/tests/gpu/scenes/shadow_box.lua";
    const std::string file = std::string(RG_TEST_TMP) + "/bad_cull.lua";
    fs::create_directories(RG_TEST_TMP);
    std::ofstream(file) << "local rg = require \"rg\"\n"
                           "require \"disney\"\n"
                           "rg.resource \"maps\" { format = \"d32f\", size = { 64, 64 } }\n"
                           "rg.resource \"out\" { format = \"rgba8\" }\n"
                           "rg.pass \"casters\" { kind = \"scene\", shadow = true, writes = { "
                           "\"maps\" }, cull = \"sideways\" }\n"
                           "rg.pass \"show\" { kind = \"fullscreen\", shader = \"test/tint.frag\", "
                           "reads = { \"maps\" }, writes = { \"out\" } }\n"
                           "rg.output \"out\"\n";
    Session s(*s_runtime, o);
    auto loaded = s.load(file);
    Result<void> e = loaded ? s.frame() : Result<void>(std::unexpected(loaded.error()));
    ASSERT_FALSE(e.has_value());
    EXPECT_NE(e.error().describe().find("pass 'casters': params.cull: unknown 'sideways', expected "
                                        "one of: 'none', 'clockwise', 'counter_clockwise'"),
              std::string::npos)
        << e.error().describe();
}

TEST_F(LuaGpu, PerMipDispatchWritesEveryMipOfTheChain) {
    Session s(*s_runtime, small());
    auto r = s.load(script("per_mip.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    Image out = output(s);
    ASSERT_EQ(out.width, 8u);
    // 16x8, full chain: 16x8, 8x4, 4x2, 2x1, 1x1.
    const float sizes[5][2] = {{16, 8}, {8, 4}, {4, 2}, {2, 1}, {1, 1}};
    for (uint32_t m = 0; m < 5; ++m) {
        EXPECT_EQ(out.at(m, 0, 0), static_cast<float>(m)) << "mip " << m;
        EXPECT_EQ(out.at(m, 0, 1), 5.0f) << "mip " << m;
        EXPECT_EQ(out.at(m, 0, 2), sizes[m][0]) << "mip " << m;
        EXPECT_EQ(out.at(m, 0, 3), sizes[m][1]) << "mip " << m;
    }
    EXPECT_EQ(out.at(5, 0, 1), 0.0f);
}

TEST_F(LuaGpu, ParameterChangeRebuildsNothing) {
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(script("params.lua")).has_value());
    ASSERT_TRUE(s.frame().has_value());
    Image a = output(s);
    ASSERT_TRUE(s.frame().has_value());
    Image b = output(s);
    EXPECT_EQ(s.rebuilds(), 0u);
    EXPECT_FLOAT_EQ(b.at(9, 4, 1), 2 * a.at(9, 4, 1));
    EXPECT_FLOAT_EQ(b.at(0, 0, 3), 2.0f);
}

// A pipeline of one compute pass writing `pattern`, with a `scale` parameter and rg.frame's body
// as given, written into the tests' temporary folder; returns its path.
std::string patternScript(const std::string& name, const std::string& frameBody) {
    fs::create_directories(RG_TEST_TMP);
    const std::string file = std::string(RG_TEST_TMP) + "/" + name;
    std::ofstream(file) << "local rg = require 'rg'\n"
                           "rg.param 'scale' { type = 'number', default = 1, min = 0, max = 16 }\n"
                           "rg.resource 'pattern' { format = 'rgba16f' }\n"
                           "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', "
                           "writes = { 'pattern' } }\n"
                           "rg.output 'pattern'\n"
                           "function rg.frame(ctx)\n" +
                               frameBody + "end\n";
    return file;
}

// The first frame's rg.frame runs at the load (its plan is built with what it changes): an error
// there fails the load, naming the line; a later frame's error fails that frame.
TEST_F(LuaGpu, FrameCallbackErrorsAreReported) {
    Session s(*s_runtime, small());
    auto r = s.load(script("bad_frame.lua"));
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(firstLine(r.error()),
              "rg.frame: " + kScripts +
                  "bad_frame.lua:9: ctx.params: unknown parameter 'scael' (did you mean 'scale'?)");
    EXPECT_FALSE(s.loaded());
    const std::string file = patternScript("bad_second_frame.lua",
                                           "    if ctx.frame == 1 then ctx.params.scael = 2 end\n");
    ASSERT_TRUE(s.load(file).has_value());
    ASSERT_TRUE(s.frame().has_value());
    auto second = s.frame();
    ASSERT_FALSE(second.has_value());
    const std::string message = firstLine(second.error());
    EXPECT_TRUE(message.starts_with("rg.frame: ") &&
                message.ends_with("bad_second_frame.lua:7: ctx.params: unknown parameter 'scael' "
                                  "(did you mean 'scale'?)"))
        << message;
}

// An override set between the load and the first frame holds from that frame on, though the
// first frame's rg.frame ran at the load.
TEST_F(LuaGpu, OverridesSetAfterTheLoadHoldFromTheFirstFrame) {
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(patternScript("override_first.lua", "")).has_value());
    ASSERT_TRUE(s.setOverride("scale", Value(3.0)).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_DOUBLE_EQ(s.pipeline().findParam("scale")->value.asNumber(0), 3.0);
    // A reload that fails keeps the running pipeline and its overrides, also those of parameters
    // the failed script does not declare.
    const std::string broken = std::string(RG_TEST_TMP) + "/override_broken.lua";
    std::ofstream(broken) << "local rg = require 'rg'\n"
                             "rg.resource 'pattern' { format = 'rgba16f' }\n"
                             "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', "
                             "writes = { 'pattern' } }\n"
                             "rg.output 'pattern'\n"
                             "function rg.frame(ctx) ctx.params.gain = 2 end\n";
    ASSERT_FALSE(s.load(broken).has_value());
    EXPECT_EQ(s.overrides().params.count("scale"), 1u);
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_DOUBLE_EQ(s.pipeline().findParam("scale")->value.asNumber(0), 3.0);
}

// One rule for pass switches: a script's explicit switch holds until switched again, against the
// default loop's automatic ones (auto_enabled: a class with draws gets its lighting pass), which
// still decide every pass nobody switched; the library's overrides win over both.
TEST_F(LuaGpu, ExplicitSwitchesHoldAgainstTheAutomaticOnes) {
    const std::string file = std::string(RG_TEST_TMP) + "/explicit_switch.lua";
    std::ofstream(file) << "require \"pipelines.deferred\"\n"
                           "local loop = rg.frame\n"
                           "function rg.frame(ctx)\n"
                           "    loop(ctx)\n"
                           "    if ctx.frame == 0 then ctx.pass(\"lighting_clearcoat\").enabled = "
                           "false end\n"
                           "end\n";
    SessionOptions o = small();
    o.scene = std::string(RG_SOURCE_ROOT) + "/tests/gpu/scenes/materials.lua";
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(file).has_value());
    auto enabled = [&](const std::string& pass) {
        return s.pipeline().graph.findPass(pass)->enabled;
    };
    for (int f = 0; f < 3; ++f) {
        ASSERT_TRUE(s.frame().has_value());
        // The scene draws clear coat, so the loop would switch it on every frame.
        EXPECT_FALSE(enabled("lighting_clearcoat")) << "frame " << f;
        // Automatic switches still decide what nobody switched: the scene has decals, a
        // blended pane and no local probes.
        EXPECT_TRUE(enabled("decals")) << "frame " << f;
        EXPECT_TRUE(enabled("forward")) << "frame " << f;
        EXPECT_FALSE(enabled("probe_capture")) << "frame " << f;
    }
    ASSERT_TRUE(s.setPassOverride("lighting_clearcoat", true).has_value());
    for (int f = 0; f < 2; ++f) {
        ASSERT_TRUE(s.frame().has_value());
        EXPECT_TRUE(enabled("lighting_clearcoat")) << "frame " << f;
    }
    // A reload starts the script's switches afresh: frame 0 switches it off again, and the
    // override, which the reload keeps, switches it on.
    ASSERT_TRUE(s.load(file).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_TRUE(enabled("lighting_clearcoat"));
}

// A pass's shader may be HLSL (NAME.comp.hlsl, NAME.frag.hlsl): bound by name like GLSL, its
// uniforms from the parameters; test/pattern.comp.hlsl and test/transform.frag.hlsl render exactly
// what their GLSL twins do, alone or together. An error in one names the file and line.
TEST_F(LuaGpu, AnHlslPassRendersAsItsGlslTwin) {
    auto render = [&](const std::string& compute, const std::string& shader) {
        const std::string file = std::string(RG_TEST_TMP) + "/hlsl_" +
                                 std::to_string(std::hash<std::string>{}(compute + shader)) +
                                 ".lua";
        std::ofstream(file) << "local rg = require 'rg'\n"
                               "rg.param 'scale' { type = 'number', default = 2 }\n"
                               "rg.resource 'pattern' { format = 'rgba16f' }\n"
                               "rg.resource 'output' { format = 'rgba16f' }\n"
                               "rg.pass 'generate' { kind = 'compute', shader = '"
                            << compute
                            << "', writes = { 'pattern' } }\n"
                               "rg.pass 'transform' { kind = 'fullscreen', shader = '"
                            << shader
                            << "', reads = { 'pattern' }, writes = { 'output' } }\n"
                               "rg.output 'output'\n";
        Session s(*s_runtime, small());
        auto r = s.load(file);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r || !s.frame()) return Image{};
        auto img = s_runtime->executor().readback("output");
        return img ? std::move(*img) : Image{};
    };
    const Image glsl = render("test/pattern.comp", "test/transform.frag");
    for (const auto& [compute, fragment] :
         {std::pair{"test/pattern.comp.hlsl", "test/transform.frag"},
          std::pair{"test/pattern.comp", "test/transform.frag.hlsl"},
          std::pair{"test/pattern.comp.hlsl", "test/transform.frag.hlsl"}}) {
        SCOPED_TRACE(std::string(compute) + " + " + fragment);
        const Image hlsl = render(compute, fragment);
        ASSERT_FALSE(hlsl.pixels.empty());
        ASSERT_EQ(glsl.pixels.size(), hlsl.pixels.size());
        EXPECT_EQ(glsl.pixels, hlsl.pixels);
        EXPECT_GT(*std::max_element(hlsl.pixels.begin(), hlsl.pixels.end()), 1.0f);  // scale 2
    }

    const std::string broken = std::string(RG_TEST_TMP) + "/broken.frag.hlsl";
    std::ofstream(broken) << "float4 main() : SV_Target {\n    return float4(1, 2);\n}\n";
    const std::string file = std::string(RG_TEST_TMP) + "/hlsl_broken.lua";
    std::ofstream(file) << "local rg = require 'rg'\nrg.resource 'output' { format = 'rgba16f' }\n"
                           "rg.pass 'fill' { kind = 'fullscreen', shader = '"
                        << broken << "', writes = { 'output' } }\nrg.output 'output'\n";
    Session s(*s_runtime, small());
    auto r = s.load(file);
    ASSERT_FALSE(r.has_value());
    EXPECT_NE(r.error().describe().find("pass 'fill': " + broken + ":2:"), std::string::npos)
        << r.error().describe();
}

// rg.frame runs once a frame, the first at the load: a script counting its calls sees one per frame.
TEST_F(LuaGpu, FrameCallbackRunsOncePerFrame) {
    const std::string file = patternScript("count_frames.lua",
                                           "    calls = (calls or 0) + 1\n"
                                           "    ctx.params.scale = calls\n"
                                           "    assert(calls == ctx.frame + 1, 'called ' .. calls "
                                           ".. ' times by frame ' .. ctx.frame)\n");
    Session s(*s_runtime, small());
    ASSERT_TRUE(s.load(file).has_value());
    for (int f = 0; f < 3; ++f) {
        auto r = s.frame();
        ASSERT_TRUE(r.has_value()) << r.error().message;
        EXPECT_DOUBLE_EQ(s.pipeline().findParam("scale")->value.asNumber(0), f + 1.0);
    }
}

TEST_F(LuaGpu, ReloadIsTransactional) {
    fs::create_directories(RG_TEST_TMP);
    const std::string file = std::string(RG_TEST_TMP) + "/reload.lua";
    auto write = [&](const std::string& text) { std::ofstream(file) << text; };
    const std::string valid =
        "local rg = require 'rg'\n"
        "rg.param 'scale' { type = 'number', default = SCALE, min = 0, max = 16 }\n"
        "rg.resource 'pattern' { format = 'rgba16f' }\n"
        "rg.resource 'output' { format = 'rgba16f' }\n"
        "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', writes = { 'pattern' "
        "} }\n"
        "rg.pass 'transform' { kind = 'fullscreen', shader = 'test/transform.frag', reads = { "
        "'pattern' }, writes = { 'output' } }\n"
        "rg.output 'output'\n";
    auto withScale = [&](const char* scale) {
        std::string t = valid;
        t.replace(t.find("SCALE"), 5, scale);
        return t;
    };
    Session s(*s_runtime, small());
    write(withScale("1"));
    ASSERT_TRUE(s.load(file).has_value());
    ASSERT_TRUE(s.frame().has_value());
    Image first = output(s);

    write(withScale("1") + "rg.pass 'oops' { kind = 'fullscreen', reads = { 'nothing' } }\n");
    auto broken = s.load(file);
    ASSERT_FALSE(broken.has_value());
    EXPECT_NE(broken.error().message.find(
                  "reload.lua:8: passes.oops.reads[1]: unknown resource 'nothing'"),
              std::string::npos)
        << broken.error().message;
    ASSERT_TRUE(s.frame().has_value());  // the previous pipeline keeps rendering
    EXPECT_EQ(output(s).pixels, first.pixels);

    write(withScale("1") +
          "rg.pass 'bad_shader' { kind = 'fullscreen', shader = 'tests/gpu/shaders/broken.frag', "
          "writes = { 'output' }, after = { 'transform' } }\n");
    auto badShader = s.load(file);
    ASSERT_FALSE(badShader.has_value());
    EXPECT_NE(badShader.error().message.find("broken.frag:7:"), std::string::npos)
        << badShader.error().message;
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(output(s).pixels, first.pixels);

    write(withScale("0.5"));
    ASSERT_TRUE(s.load(file).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_FLOAT_EQ(output(s).at(0, 0, 3), 0.5f);
}

TEST_F(LuaGpu, ModulePassesRender) {
    Session s(*s_runtime, small());
    auto r = s.load(script("with_modules.lua"));
    ASSERT_TRUE(r.has_value()) << r.error().message;
    ASSERT_TRUE(s.frame().has_value());
    auto img = s_runtime->executor().passResult("final");
    ASSERT_TRUE(img.has_value()) << img.error().message;
    // transform gives (g, r, 1 - b, 1); the module adds (0, 0, 0.125, 0) on top.
    EXPECT_FLOAT_EQ(img->at(0, 0, 2), 1.0f - 0.0f + 0.125f);
}

class ScriptsReadme : public LuaGpu {};

TEST_F(ScriptsReadme, EveryExampleLoadsCompilesAndRenders) {
    auto examples = readmeExamples();
    ASSERT_GE(examples.size(), 10u);
    fs::create_directories(RG_TEST_TMP);
    for (size_t i = 0; i < examples.size(); ++i) {
        const std::string file =
            std::string(RG_TEST_TMP) + "/readme_example_" + std::to_string(i + 1) + ".lua";
        std::ofstream(file) << examples[i];
        SCOPED_TRACE("example " + std::to_string(i + 1) + ":\n" + examples[i]);
        // An example that starts with "-- view: NAME" is rendered through that view.
        SessionOptions o = small();
        if (examples[i].starts_with("-- view: "))
            o.view = examples[i].substr(9, examples[i].find('\n') - 9);
        Session s(*s_runtime, o);
        auto r = s.load(file);
        ASSERT_TRUE(r.has_value()) << r.error().describe();
        for (int f = 0; f < 2; ++f) {
            auto fr = s.frame();
            ASSERT_TRUE(fr.has_value()) << fr.error().describe();
        }
        auto img = s_runtime->executor().readback(s.displayResource());
        ASSERT_TRUE(img.has_value()) << img.error().describe();
        if (!o.view.empty()) {  // the view drew something: the pattern is not black
            float sum = 0;
            for (float v : img->pixels) sum += v;
            EXPECT_GT(sum, 0.0f) << o.view;
        }
    }
}

}  // namespace
