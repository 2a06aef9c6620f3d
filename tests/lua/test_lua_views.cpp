// Debug views declared in Lua (rg.view, scripts/views.lua) on the CPU: what a view adds to the
// pipeline, how it is found (name, pattern), what it may ask of the pipeline and the scene, and
// every way a view or a request for one goes wrong, with its exact message. Rendered views are
// checked by the GPU tests that read them (test_scene_render, test_shadows, test_probes,
// test_lightmap_render, test_material_package) and by tests/cli.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "lua/lua_host.h"
#include "lua_test_util.h"
#include "runtime/session.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::test;

namespace {

const std::string kDeferred = std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua";
const std::string kTestPipeline = std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/test.lua";

// A pipeline script in the test folder: the smallest pipeline with `extra` after it.
std::string pipelineWith(const std::string& name, const std::string& extra) {
    fs::create_directories(RG_TEST_TMP);
    const std::string file = std::string(RG_TEST_TMP) + "/" + name + ".lua";
    std::ofstream(file)
        << "local rg = require \"rg\"\n"
           "local views = require \"views\"\n"
           "rg.resource \"pattern\" { format = \"rgba16f\" }\n"
           "rg.resource \"output\" { format = \"rgba16f\" }\n"
           "rg.pass \"generate\" { kind = \"compute\", shader = \"test/pattern.comp\", "
           "writes = { \"pattern\" } }\n"
           "rg.pass \"transform\" { kind = \"fullscreen\", shader = "
           "\"test/transform.frag\", reads = { \"pattern\" }, writes = { \"output\" } }\n"
           "rg.output \"output\"\n"
        << extra;
    return file;
}

struct Loaded {
    LuaHost host{luaHostOptionsWithoutDevice()};
    PipelineDesc pipeline;
    explicit Loaded(const std::string& file) {
        auto p = host.load(file);
        EXPECT_TRUE(p.has_value()) << p.error().describe();
        if (p) pipeline = std::move(*p);
    }
    Result<PipelineDesc> view(const std::string& name, const ViewFacts* scene = nullptr) {
        return host.addView(name, pipeline, scene);
    }
    std::string error(const std::string& name, const ViewFacts* scene = nullptr) {
        auto p = view(name, scene);
        EXPECT_FALSE(p.has_value()) << "view '" << name << "' was added but should not be";
        return p ? "" : firstLine(p.error());
    }
};

const PassDesc* findPass(const PipelineDesc& p, const std::string& name) {
    for (const auto& pass : p.graph.passes)
        if (pass.name == name) return &pass;
    return nullptr;
}

TEST(LuaViews, AStandardViewIsAPassAfterThePipelines) {
    Loaded d(kDeferred);
    auto p = d.view("normals");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    ASSERT_EQ(p->graph.passes.size(), d.pipeline.graph.passes.size() + 1);
    // After the pipeline's passes; only the histories' keep passes (the frame's end) follow it.
    const auto at = std::find_if(p->graph.passes.begin(), p->graph.passes.end(),
                                 [](const PassDesc& q) { return q.name == "debug_view"; });
    ASSERT_NE(at, p->graph.passes.end());
    for (auto q = at + 1; q != p->graph.passes.end(); ++q)
        EXPECT_TRUE(q->name.ends_with("_history_keep") || q->name.ends_with("_history_mips"))
            << q->name;
    const PassDesc& last = *at;
    EXPECT_EQ(last.params["shader"].asString(), "passes/debug_view.frag");
    EXPECT_EQ(last.params["uniforms"]["view"].asNumber(), 0.0);
    std::vector<std::string> reads;
    for (const auto& a : last.accesses) reads.push_back(a.resource);
    EXPECT_EQ(reads, (std::vector<std::string>{"GB0", "GB1", "GB2", "GB3", "depth", "depth",
                                               "debug_view"}));
    EXPECT_TRUE(last.accesses[5].stencil);  // the pixel's material identity
    EXPECT_TRUE(p->graph.findResource("debug_view"));
    // The standard views' file is one of the pipeline's (a change to it reloads under watch).
    EXPECT_TRUE(std::any_of(p->files.begin(), p->files.end(),
                            [](const std::string& f) { return f.ends_with("scripts/views.lua"); }));
    // The pipeline load() returned is left as it was.
    EXPECT_FALSE(d.pipeline.graph.findResource("debug_view"));
}

// One pass per stencil class of the pipeline, each testing its class's whole value.
TEST(LuaViews, TheStencilViewDrawsEveryClass) {
    Loaded d(kDeferred);
    auto p = d.view("stencil");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    ASSERT_FALSE(d.pipeline.stencilClasses.empty());
    ASSERT_TRUE(findPass(*p, "debug_view_clear"));
    for (const auto& c : d.pipeline.stencilClasses) {
        const PassDesc* pass = findPass(*p, "debug_view_" + c.name);
        ASSERT_TRUE(pass) << c.name;
        EXPECT_EQ(pass->params["stencil"]["ref"].asNumber(), double(c.value)) << c.name;
        EXPECT_EQ(pass->params["stencil"]["mask"].asNumber(), 255.0);
    }
}

// What the scene holds: the lights that cast shadows (shadow:LIGHT) and the lightmap's lobes
// (lightmap, sgN, which compile RG_LIGHTMAP_VIEW into the G-buffer pass).
TEST(LuaViews, SceneViewsAskTheScene) {
    Loaded d(kDeferred);
    ViewFacts scene;
    scene.lights = {{"sun", false}, {"lamp", true}, {"spot", true}};
    auto shadow = d.view("shadow:spot", &scene);
    ASSERT_TRUE(shadow.has_value()) << shadow.error().describe();
    ASSERT_TRUE(findPass(*shadow, "debug_view"));
    EXPECT_EQ(findPass(*shadow, "debug_view")->params["uniforms"]["light"].asNumber(), 2.0);
    EXPECT_EQ(d.error("shadow:sun", &scene),
              "--view shadow:sun: the scene has no light 'sun' that casts shadows (those that do: "
              "'lamp', 'spot')");
    EXPECT_EQ(d.error("shadow:lamp"),
              "--view shadow:lamp: the scene has no light 'lamp' that casts shadows (none does: "
              "give a local light shadow = true)");
    EXPECT_EQ(d.error("lightmap", &scene),
              "--view lightmap: the scene has no baked lightmap (declare scene.lightmap; the "
              "pipeline's lightmap parameter must be on)");
    scene.lightmapLobes = 9;
    auto lobe = d.view("sg3", &scene);
    ASSERT_TRUE(lobe.has_value()) << lobe.error().describe();
    EXPECT_EQ(findPass(*lobe, "gbuffer")->params["defines"]["RG_LIGHTMAP_VIEW"].asNumber(), 5.0);
    EXPECT_FALSE(findPass(d.pipeline, "gbuffer")->params["defines"].has("RG_LIGHTMAP_VIEW"));
    EXPECT_EQ(d.error("sg9", &scene), "--view sg9: the lightmap has lobes sg0 .. sg8");
    EXPECT_EQ(
        d.error("sg"),
        "--view: unknown view 'sg'; expected one of: 'normals', 'basecolor', 'smoothness', "
        "'metalmask', 'materialid', 'reflectance', 'ao', 'emissive', 'stencil', 'lights', "
        "'ssr', 'ssr_confidence', 'reflection', 'probes', 'motion', 'ssao', 'cascades', 'shadow', "
        "'shadow:LIGHT', 'lightmap', 'sgN'");
}

TEST(LuaViews, AViewNamesWhatThePipelineLacks) {
    Loaded t(kTestPipeline);
    EXPECT_EQ(t.error("normals"),
              "--view normals: the pipeline has no 'GB0' (views read the G-buffer GB0..GB3 and "
              "depth)");
    EXPECT_EQ(t.error("lights"),
              "--view lights: the pipeline has no 'light_tiles' (require \"lighting\" and light "
              "its passes with lighting.tiled)");
    EXPECT_EQ(t.error("lightmap", nullptr),
              "--view lightmap: the scene has no baked lightmap (declare scene.lightmap; the "
              "pipeline's lightmap parameter must be on)");
    ViewFacts scene;
    scene.lightmapLobes = 4;
    EXPECT_EQ(t.error("sg1", &scene), "--view sg1: the pipeline has no pass 'gbuffer'");
}

// A pipeline's own views come first, found by name or by pattern (its captures are the
// function's arguments), and may compile defines into the pipeline's passes.
TEST(LuaViews, APipelineDeclaresItsOwnViews) {
    Loaded own(pipelineWith("own_views", R"lua(
rg.view "pattern" { doc = "the pattern's red channel", build = function(v)
    views.need(v, "pattern", "the compute pass writes it")
    views.fullscreen { shader = "passes/ssao_view.frag", reads = { "pattern" }, bind = { ssao = "pattern" } }
end }
rg.view "tint:CHANNEL" { pattern = "^tint:(%a+)$", build = function(v, channel)
    local index = ({ red = 0, green = 1 })[channel] or v.fail("no channel '" .. channel .. "' (red, green)")
    v.define("transform", "TINT_CHANNEL", index)
    views.fullscreen { shader = "passes/ssao_view.frag", reads = { "output" }, bind = { ssao = "output" } }
end }
)lua"));
    auto p = own.view("pattern");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    EXPECT_EQ(p->graph.passes.back().params["bind"]["ssao"].asString(), "pattern");
    auto tint = own.view("tint:green");
    ASSERT_TRUE(tint.has_value()) << tint.error().describe();
    EXPECT_EQ(findPass(*tint, "transform")->params["defines"]["TINT_CHANNEL"].asNumber(), 1.0);
    EXPECT_EQ(own.error("tint:blue"), "--view tint:blue: no channel 'blue' (red, green)");
    const std::string unknown = own.error("nope");
    EXPECT_TRUE(unknown.starts_with(
        "--view: unknown view 'nope'; expected one of: 'normals', 'basecolor', "))
        << unknown;
    EXPECT_TRUE(unknown.ends_with("'sgN', 'pattern', 'tint:CHANNEL'")) << unknown;
    // After every failure the host adds a view as before.
    auto again = own.view("pattern");
    ASSERT_TRUE(again.has_value()) << again.error().describe();
    EXPECT_EQ(again->graph.passes.size(), p->graph.passes.size());
}

TEST(LuaViews, BadViewDeclarationsAreErrorsAtTheirLine) {
    const std::string tmp = fs::relative(RG_TEST_TMP, RG_SOURCE_ROOT).string() + "/";
    auto loadError = [&](const std::string& name, const std::string& extra) {
        LuaHost host(luaHostOptionsWithoutDevice());
        auto p = host.load(pipelineWith(name, extra));
        EXPECT_FALSE(p.has_value());
        return p ? "" : firstLine(p.error());
    };
    EXPECT_EQ(loadError("view_field", "\nrg.view \"x\" { buld = function(v) end }\n"),
              tmp +
                  "view_field.lua:9: rg.view \"x\": unknown field 'buld' (did you mean "
                  "'build'?); expected: 'doc', 'pattern', 'build'");
    EXPECT_EQ(loadError("view_build", "\nrg.view \"x\" { doc = \"no function\" }\n"),
              tmp +
                  "view_build.lua:9: rg.view \"x\".build: expected the function that declares "
                  "the view's passes, got nil");
    EXPECT_EQ(loadError("view_twice", "\nrg.view \"normals\" { build = function(v) end }\n"),
              tmp +
                  "view_twice.lua:9: rg.view \"normals\": already declared at "
                  "scripts/views.lua:60");
    EXPECT_EQ(loadError("view_name", "\nrg.view \"a b\" { build = function(v) end }\n"),
              tmp +
                  "view_name.lua:9: rg.view: expected a name (letters, digits, '_', '-' and "
                  "':'), e.g. rg.view \"name\" { build = function(v) ... end }");
}

TEST(LuaViews, BadViewsAreErrorsWhenAskedFor) {
    const std::string tmp = fs::relative(RG_TEST_TMP, RG_SOURCE_ROOT).string() + "/";
    Loaded bad(pipelineWith("bad_views", R"lua(
rg.view "param" { build = function(v) rg.param "gain" { type = "number", default = 1 } end }
rg.view "nothing" { build = function(v) end }
rg.view "broken" { build = function(v) return v.resources.pattern.x end }
)lua"));
    EXPECT_EQ(bad.error("param"),
              tmp +
                  "bad_views.lua:9: param \"gain\": a view declares passes and resources only "
                  "(rg.pass, rg.resource, rg.buffer)");
    EXPECT_EQ(bad.error("nothing"),
              "--view nothing: the view declared no 'debug_view' image (a view writes it; "
              "scripts/views.lua's views.target() declares it)");
    EXPECT_EQ(bad.error("broken"),
              tmp + "bad_views.lua:11: attempt to index a boolean value (field 'pattern')");
}

}  // namespace
