// Pipeline scripts: the sandbox, every kind of bad script with its exact message, the schema,
// modules, and (on the GPU) runtime reconfiguration and transactional reload.
#include <gtest/gtest.h>

#include "../gpu/gpu_fixture.h"

#include <filesystem>
#include <fstream>
#include <random>

#include "image/image.h"
#include "layout/layout.h"

#include "cli/runtime.h"
#include "cli/session.h"
#include "core/compiler.h"
#include "lua/lua_host.h"

namespace fs = std::filesystem;
using namespace rg;

namespace {

const std::string kScripts = "tests/lua/scripts/";

std::string script(const std::string& name) { return std::string(RG_SOURCE_ROOT) + "/" + kScripts + name; }

Result<PipelineDesc> load(const std::string& name, LuaHostOptions o = luaHostOptionsWithoutDevice()) {
    LuaHost host(o);
    return host.load(script(name));
}

// The first line of an error (the rest is the traceback).
std::string firstLine(const Error& e) { return e.message.substr(0, e.message.find('\n')); }

std::string loadError(const std::string& name, LuaHostOptions o = luaHostOptionsWithoutDevice()) {
    auto p = load(name, o);
    EXPECT_FALSE(p.has_value()) << name << " loaded but should not";
    return p ? "" : firstLine(p.error());
}

TEST(LuaErrors, SyntaxError) {
    EXPECT_EQ(loadError("syntax_error.lua"),
              kScripts + "syntax_error.lua:3: unexpected symbol near <eof>");
}

TEST(LuaErrors, RuntimeErrorHasTraceback) {
    auto p = load("runtime_error.lua");
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(firstLine(p.error()), kScripts + "runtime_error.lua:3: attempt to index a nil value (local 'settings')");
    EXPECT_NE(p.error().message.find("stack traceback:"), std::string::npos);
}

TEST(LuaErrors, UnknownFieldSuggestsTheClosest) {
    EXPECT_EQ(loadError("unknown_field.lua"),
              kScripts + "unknown_field.lua:3: passes.tonemap.shadr: unknown field (did you mean 'shader'?); expected one of: "
                         "'kind', 'reads', 'writes', 'after', 'enabled', 'side_effect', 'doc', 'insert', 'shader', 'defines', "
                         "'switches', 'bind', 'uniforms', 'constants', 'filter', 'clear', 'blend', 'stencil', 'depth'");
}

// switches = { param = "DEFINE" } names a declared parameter and a define (a GLSL identifier).
TEST(LuaErrors, SwitchesNameParametersAndDefines) {
    EXPECT_EQ(loadError("switch_unknown.lua"),
              kScripts + "switch_unknown.lua:4: passes.tonemap.switches.curv: unknown parameter 'curv' (did you mean 'curve'?) "
                         "(declare it with rg.param)");
    EXPECT_EQ(loadError("switch_bad_define.lua"),
              kScripts + "switch_bad_define.lua:4: passes.tonemap.switches.curve: expected the name of a define (a GLSL "
                         "identifier), got '2CURVE'");
    auto p = load("switch_ok.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    GraphDesc g = graphWithParams(*p);
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["RG_CURVE"], Value(1.0));  // "neutral": the index of the choice
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["RG_DITHER"], Value(0.0));
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["KEEP"], Value(true));
    EXPECT_TRUE(isSwitch(*p, "curve"));
    EXPECT_FALSE(isSwitch(*p, "other"));
}

TEST(LuaErrors, WrongType) {
    EXPECT_EQ(loadError("wrong_type.lua"), kScripts + "wrong_type.lua:2: resources.output.format: expected a string, got number");
}

TEST(LuaErrors, SceneLayersNamesWhatTheSceneCanSize) {
    EXPECT_EQ(loadError("scene_layers_unknown.lua"),
              kScripts + "scene_layers_unknown.lua:2: resources.maps.scene_layers: expected \"shadow_views\" (the layers the scene's "
                         "shadowed local lights need, at most `layers`)");
}

TEST(LuaErrors, OutOfRangeValue) {
    EXPECT_EQ(loadError("out_of_range.lua"), kScripts + "out_of_range.lua:2: params.exposure.default: parameter 'exposure' expects a "
                                                        "number in [-6, 16], got 20");
}

TEST(LuaErrors, UnknownResource) {
    EXPECT_EQ(loadError("unknown_resource.lua"),
              kScripts + "unknown_resource.lua:6: passes.lighting.reads[3]: unknown resource 'GB9' (did you mean 'GB0'?)");
}

TEST(LuaPipeline, TiledBufferGrowsWithTheOutput) {
    auto p = load("tiled_buffer.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    CompileOptions o;
    o.outputWidth = 100;  // 13 x 5 tiles of 8 pixels
    o.outputHeight = 33;
    auto plan = compile(graphWithParams(*p), o);
    ASSERT_TRUE(plan.has_value()) << plan.error().message;
    auto lists = std::find_if(plan->resources.begin(), plan->resources.end(), [](auto& r) { return r.name == "lists"; });
    ASSERT_NE(lists, plan->resources.end());
    EXPECT_EQ(lists->bufferSize, 16u + 13u * 5u * 64u);
    EXPECT_EQ(loadError("tiled_buffer_half.lua"),
              kScripts + "tiled_buffer_half.lua:2: resources.lists.tile_bytes: missing (a tiled buffer gives both tile, in pixels, and tile_bytes)");
}

TEST(LuaErrors, CycleIsReportedByTheCompiler) {
    auto p = load("cycle.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_FALSE(plan.has_value());
    EXPECT_EQ(plan.error().message, kScripts + "cycle.lua:4: cycle between passes: 'first' -> 'second' -> 'first'");
}

TEST(LuaErrors, MaterialIdCollisionNamesBothDeclarations) {
    // Materials share an id only when their pixels decode alike: the same layout...
    EXPECT_EQ(loadError("id_collision.lua"),
              kScripts + "id_collision.lua:5: materials.toon.id: 1 is the id of material 'clearcoat' (" + kScripts +
                  "id_collision.lua:4) of layout 'disney': materials share an id only when their pixels decode alike (the same layout); choose a free id");
    // ...and the same decal parameters.
    EXPECT_EQ(loadError("id_decals_differ.lua"),
              kScripts + "id_decals_differ.lua:4: materials.glossy.decals: 0 is the id of material 'standard' (materials/disney.lua:23) with other channels "
                         "or decals: materials sharing an id decode alike; match them or choose a free id");
}

TEST(LuaErrors, MaterialIdKeptInDifferentBitsIsRefused) {
    EXPECT_EQ(loadError("id_placement.lua"),
              kScripts + "id_placement.lua:8: materials.wide.layout: layout 'wide' keeps materialId in target GB0.A bits 0..2 (uint), but layout "
                         "'disney' (material 'standard', materials/disney.lua:23) keeps it in target GB0.A bits 0..1 (uint): every layout of a "
                         "pipeline keeps materialId in the same place");
}

TEST(LuaErrors, PathDecodesOneLayout) {
    EXPECT_EQ(loadError("path_layout.lua"),
              kScripts + "path_layout.lua:5: materials.toon.path: lighting path 'standard' lights layout 'disney' (material 'standard', "
                         "materials/disney.lua:23); this material's layout is 'toon': a path's lighting pass and shading function decode one "
                         "layout, so declare a path of its own");
}

TEST(LuaErrors, StencilVariantsKeepTheirBase) {
    // A variant's value does not depend on which values other classes took.
    EXPECT_EQ(loadError("stencil_variant_unknown.lua"),
              kScripts + "stencil_variant_unknown.lua:3: stencil.wet.variant_of: unknown stencil class 'lit_standrd' (did you mean 'lit_standard'?); "
                         "expected one of: 'lit_standard'");
}

TEST(LuaErrors, MaterialParameterNamesCannotClashWithTheGeneratedShader) {
    // #14: a parameter becomes a #define in the generated G-buffer shader; a layout channel's name
    // broke it with an error inside the generated file. Now refused where it is declared.
    EXPECT_EQ(loadError("param_clash.lua"),
              kScripts + "param_clash.lua:4: materials.toon.params.smoothness: clashes with channel 'smoothness' of layout 'disney' "
                         "(target GB0): the generated shader defines each parameter as a name; choose another");
    EXPECT_NE(loadError("param_reserved.lua").find("param_reserved.lua:4: materials.toon.params.uv0: clashes with 'uv0' of the generated "
                                                   "G-buffer shader"),
              std::string::npos)
        << loadError("param_reserved.lua");
}

TEST(LuaErrors, StencilExhaustion) {
    EXPECT_EQ(loadError("stencil_exhaustion.lua"),
              kScripts + "stencil_exhaustion.lua:4: stencil.class16: no stencil value left: 4 stencil bits hold 15 classes, all "
                         "taken by 'class1', 'class2', 'class3', 'class4', 'class5', 'class6', 'class7', 'class8', 'class9', "
                         "'class10', 'class11', 'class12', 'class13', 'class14', 'class15'");
}

TEST(LuaErrors, RunawayLoopIsStopped) {
    LuaHostOptions o = luaHostOptionsWithoutDevice();
    o.instructions = 5'000'000;
    EXPECT_EQ(loadError("runaway.lua", o),
              kScripts + "runaway.lua:3: script stopped after 5 million instructions: a runaway loop? (limit: 5 million)");
}

TEST(LuaErrors, MemoryLimit) {
    LuaHostOptions o = luaHostOptionsWithoutDevice();
    o.memoryBytes = 16u << 20;
    // Lua reports running out of memory without a position: the message names where the script
    // was last seen running (the count hook's sample).
    EXPECT_EQ(loadError("memory_hog.lua", o), kScripts + "memory_hog.lua:2: script stopped: it used more than 16 MiB of Lua memory (last running here)");
}

TEST(LuaErrors, MemoryLimitInTheFrameCallback) {
    LuaHostOptions o = luaHostOptionsWithoutDevice();
    o.memoryBytes = 16u << 20;
    LuaHost host(o);
    auto p = host.load(script("frame_memory_hog.lua"));
    ASSERT_TRUE(p.has_value()) << p.error().message;
    for (uint64_t frame = 0; frame < 3; ++frame) {
        auto r = host.frame(FrameContext{frame, 0.0, std::nullopt}, *p);
        ASSERT_FALSE(r.has_value());
        // Named by its line, or — when the limit is hit before the count hook samples a line —
        // by the script's file.
        const std::string& m = r.error().message;
        EXPECT_EQ(m.rfind("rg.frame: ", 0), 0u) << m;
        EXPECT_NE(m.find("frame_memory_hog.lua"), std::string::npos) << m;
        EXPECT_NE(m.find("script stopped: it used more than 16 MiB of Lua memory"), std::string::npos) << m;
    }
}

TEST(LuaErrors, ForbiddenOsExecute) {
    EXPECT_EQ(loadError("forbidden.lua"), kScripts + "forbidden.lua:2: os.execute is not available to rgraph scripts (sandbox)");
    EXPECT_FALSE(fs::exists("/tmp/rgraph-sandbox-escape"));
}

TEST(LuaErrors, ForbiddenIo) {
    EXPECT_EQ(loadError("forbidden_io.lua"), kScripts + "forbidden_io.lua:1: io.open is not available to rgraph scripts (sandbox)");
}

TEST(LuaErrors, RequireCannotLeaveTheSearchFolders) {
    EXPECT_EQ(loadError("require_escape.lua"),
              kScripts + "require_escape.lua:1: require: '..etc.passwd' is not a module name (dotted names of letters, digits, '_' "
                         "and '-')");
}

TEST(LuaErrors, MissingScript) {
    auto p = load("no_such_script.lua");
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(p.error().message, "cannot open pipeline script '" + script("no_such_script.lua") + "'");
}

TEST(LuaErrors, HostSurvivesAndLoadsAgainAfterErrors) {
    LuaHost host(luaHostOptionsWithoutDevice());
    for (const char* bad : {"syntax_error.lua", "runtime_error.lua", "forbidden.lua", "unknown_field.lua"})
        EXPECT_FALSE(host.load(script(bad)).has_value());
    auto ok = host.load(script("params.lua"));
    ASSERT_TRUE(ok.has_value()) << ok.error().message;
    EXPECT_EQ(ok->graph.passes.size(), 2u);
}

TEST(LuaPipeline, DefaultPipelineDeclaresTheMaterialSystem) {
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    ASSERT_EQ(p->layouts.size(), 2u);
    EXPECT_EQ(p->layouts[0].name, "disney");
    EXPECT_EQ(p->layouts[0].targets.size(), 4u);
    EXPECT_EQ(p->layouts[1].name, "two_colour");  // tbl:3, over the same four targets
    EXPECT_EQ(p->layouts[1].targets.size(), 4u);
    // The standard material, two game-team materials and the two-colour base material, each
    // with its id and stencil class.
    ASSERT_EQ(p->materials.size(), 4u);
    EXPECT_EQ(p->materials[0].name, "standard");
    EXPECT_EQ(p->materials[0].id, 0u);
    EXPECT_EQ(p->materials[0].stencil, "lit_standard");
    EXPECT_EQ(p->materials[1].name, "clear_coat");
    EXPECT_EQ(p->materials[1].id, 1u);
    EXPECT_EQ(p->materials[1].stencil, "lit_clearcoat");
    EXPECT_EQ(p->materials[2].name, "foliage");
    EXPECT_EQ(p->materials[2].fills, (std::vector<std::string>{"GB0", "GB1"}));
    EXPECT_EQ(p->materials[2].fixup, "foliage_fixup");
    EXPECT_EQ(p->materials[3].name, "two_colour");
    EXPECT_EQ(p->materials[2].id, 0u);  // decodes as the standard material after its fix-up
    EXPECT_EQ(p->materials[2].stencil, "foliage");
    EXPECT_EQ(p->materials[3].id, 2u);  // id 3 is left free for a game team
    EXPECT_EQ(p->materials[3].stencil, "lit_two_colour");
    ASSERT_EQ(p->stencilClasses.size(), 4u);
    EXPECT_EQ(p->stencilClasses[0].value, 1u);  // lit_standard, allocated
    EXPECT_EQ(p->stencilClasses[1].value, 2u);  // lit_clearcoat, allocated
    EXPECT_EQ(p->stencilClasses[2].value, 0x11u);  // foliage: a variant of lit_standard (high bits 1)
    EXPECT_EQ(p->stencilClasses[2].mask, 0xFFu);
    EXPECT_EQ(p->stencilClasses[2].base, "lit_standard");
    EXPECT_EQ(p->stencilClasses[0].mask, 0x0Fu);   // a class's pass lights its variants too
    EXPECT_EQ(p->stencilClasses[3].value, 3u);  // lit_two_colour, allocated
    // Decals: the standard material takes all five parameters, the others the common three,
    // the two-colour material's base colour into its diffuse colour.
    EXPECT_EQ(p->materials[0].decals, (std::vector<std::string>{"normal", "baseColor", "smoothness", "metalMask", "reflectance"}));
    EXPECT_EQ(p->materials[1].decals, (std::vector<std::string>{"normal", "baseColor", "smoothness"}));
    EXPECT_EQ(p->materials[2].decals, p->materials[0].decals);  // shares id 0: decodes alike
    EXPECT_EQ(p->materials[3].channels.at("baseColor"), "diffuseColor");
    EXPECT_EQ(p->materials[3].channels.at("f0"), "f0");
    EXPECT_EQ(p->output, "display");
    EXPECT_EQ(p->hdr, "hdr");
    EXPECT_EQ(p->exposure, "exposure");
    // Modules' passes land at their insertion points.
    std::vector<std::string> order;
    for (const auto& pass : p->graph.passes) order.push_back(pass.name);
    // The environment filtering (scripts/ibl.lua, required by render_loop) comes first, then the
    // local probes' capture and filtering (scripts/probes.lua). Then the sun's cascades, its caster
    // culling, its maps' clears (without a sun) and the local lights' maps (scripts/shadows.lua), the
    // G-buffer half with the passes inserted after it (light culling, screen-space AO's
    // half-resolution depths, each cascade's map drawn and filtered into the sun's mask at once, the
    // foliage fix-up, then the AO itself on the fixed-up normals: scripts/ao.lua), the Hi-Z
    // pyramid, SSR's mask and SSR (scripts/ssr.lua), the composition of SSR and the probes
    // (scripts/reflections.lua), the lighting, the sky and forward.
    EXPECT_EQ(std::vector<std::string>(order.begin(), order.begin() + 52),
              (std::vector<std::string>{"env_cube", "env_mips", "env_irradiance", "env_hot", "env_smooth_mips", "env_prefilter", "dfg_table", "probe_capture",
                                        "probe_mips", "probe_prefilter", "sun_cascades", "sun_cull",
                                        "shadow_clear0", "shadow_clear1", "shadow_clear2", "shadow_local", "gbuffer", "light_culling_coarse", "ao_depth",
                                        "sun_visibility_clear", "sun_classify", "sun_visibility_half_clear", "sun_classify_half",
                                        "shadow_sun0", "sun_mask0", "sun_mask_half0", "shadow_sun1", "sun_mask1", "sun_mask_half1",
                                        "shadow_sun2", "sun_mask2", "sun_mask_half2",
                                        "foliage_fixup", "gtao", "ao_blur", "ao_upsample", "light_culling", "decals_copy0", "decals_copy1", "decals_copy2",
                                        "decals", "hiz", "ssr_mask", "ssr", "reflection_compose", "lighting_standard", "lighting_clearcoat", "lighting_two_colour",
                                        "sky", "forward", "ssr_history_copy", "ssr_history_mips"}));
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_TRUE(plan.has_value()) << plan.error().message;
    // Every script it pulled in is known, for hot reload.
    EXPECT_EQ(p->files.size(), 15u);  // deferred, post, lighting, render_loop, ibl, shadows, probes, ao, ssr, reflections, lightmap, disney, clearcoat, foliage, two_colour
}

TEST(LuaPipeline, ModulesAreNamespacedAndInsertedAfterTheirAnchor) {
    auto p = load("with_modules.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    std::vector<std::string> order;
    for (const auto& pass : p->graph.passes) order.push_back(pass.name);
    EXPECT_EQ(order, (std::vector<std::string>{"generate", "transform", "team_tint.make_overlay", "team_tint.apply", "final"}));
    EXPECT_NE(p->graph.findResource("team_tint.overlay"), nullptr);
    EXPECT_EQ(p->graph.findPass("team_tint.apply")->accesses[0].resource, "team_tint.overlay");
    EXPECT_EQ(p->modules, (std::vector<std::string>{"team_tint"}));
    ASSERT_TRUE(compile(graphWithParams(*p), {}).has_value());
}

TEST(LuaPipeline, TwoWritersFromDifferentModulesAreAnError) {
    auto p = load("module_clash.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_FALSE(plan.has_value());
    EXPECT_EQ(plan.error().message,
              kScripts + "modules/team_clash.lua:4: passes 'transform' and 'team_clash.overwrite' both write 'output' with no order "
                         "between them: make 'team_clash.overwrite' load it or list 'transform' in its after");
}

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
    EXPECT_FLOAT_EQ(frames[0].at(5, 3, 0) - frames[1].at(5, 3, 0), 0.25f);  // the tint's contribution
    EXPECT_EQ(s.rebuilds(), 2u);
    // Re-enabling brings back the passes and resources it had: nothing new was compiled.
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared, (std::vector<std::string>{"tint"}));
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
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared, (std::vector<std::string>{"transform"}));
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesReused, (std::vector<std::string>{"generate"}));
    ASSERT_FALSE(s.log().empty());
    EXPECT_NE(s.log().back().find("'transform' uses test/tint.frag; recompiled in"), std::string::npos) << s.log().back();
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
        texels.push_back(texelFromFloats(t.format, &img->pixels[(3 * img->width + 7) * img->channels], img->channels));
    }
    auto g = unpackTexel(*info, texels);
    auto channel = [&](const char* name) { return g[static_cast<size_t>(info->find(name))]; };
    EXPECT_EQ(channel("materialId").u[0], 2u);
    EXPECT_NEAR(channel("smoothness").v[0], 0.7f, 0.5f / 1023 + 1e-5f);
    EXPECT_NEAR(channel("metalMask").v[0], 1.0f, 1e-6f);
    EXPECT_NEAR(channel("reflectance").v[0], 0.5f, 0.5f / 255 + 1e-5f);  // 127.5 rounds up: exactly half a step
    EXPECT_NEAR(channel("ao").v[0], 0.9f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(srgbEncode(channel("baseColor").v[0]), srgbEncode(0.8f), 1.0f / 255);
    const float len = std::sqrt(0.3f * 0.3f + 0.5f * 0.5f + 0.8f * 0.8f);
    const auto& n = channel("normal").v;
    EXPECT_GT((n[0] * 0.3f - n[1] * 0.5f + n[2] * 0.8f) / len, std::cos(4.2e-3f));  // the 10+10-bit octahedral bound
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
                               "scene.material \"coated\" { model = \"clear_coat\", params = { " << params << " } }\n"
                               "scene.sphere \"s\" { radius = 0.5, material = \"coated\" }\n";
        SessionOptions o = small();
        o.scene = file;
        Session s(*s_runtime, o);
        auto r = s.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
        return r.has_value() ? std::string() : r.error().describe();
    };
    EXPECT_EQ(sceneWith("coatSmoothness = 0.5, coatStrength = 1"), "");
    EXPECT_NE(sceneWith("coatSmoothnes = 0.5").find("params_scene.lua:2: scene.material.coated.params.coatSmoothnes: model 'clear_coat' has no "
                                                    "parameter 'coatSmoothnes' (did you mean 'coatSmoothness'?); its parameters: "
                                                    "'coatSmoothness', 'coatStrength'"),
              std::string::npos)
        << sceneWith("coatSmoothnes = 0.5");
    EXPECT_NE(sceneWith("coatStrength = \"full\"").find("params_scene.lua:2: scene.material.coated.params.coatStrength: expected a number (as model "
                                                         "'clear_coat' declares it), got string"),
              std::string::npos)
        << sceneWith("coatStrength = \"full\"");
}

TEST_F(LuaGpu, SurfaceFilesResolveNextToTheDeclaringScript) {
    // #14: a game team's material in a folder of its own (outside the repository): its surface
    // function sits next to the script that declares it, and renders from there.
    const fs::path dir = fs::path(RG_TEST_TMP) / "team_material";
    fs::create_directories(dir);
    std::ofstream(dir / "red.glsl") << "GBuffer_disney rgSurface(RgSurface s) {\n"
                                       "    GBuffer_disney g;\n    g.normal = s.normal;\n    g.smoothness = 0.5;\n"
                                       "    g.materialId = RG_MATERIAL_ID;\n    g.baseColor = vec3(1.0, 0.0, 0.0);\n"
                                       "    g.materialData = 0u;\n    g.normalExtra = 0u;\n    g.reserved = 0.0;\n"
                                       "    g.metalMask = 0.0;\n    g.reflectance = 0.5;\n    g.ao = 1.0;\n    g.emissive = vec3(0.0);\n"
                                       "    return g;\n}\n";
    std::ofstream(dir / "pipeline.lua") << "local rg = require \"rg\"\nrequire \"disney\"\n"
                                          "rg.material \"red\" { id = 1, layout = \"disney\", path = \"standard\", surface = \"red.glsl\" }\n"
                                          "rg.resource \"GB0\" { format = \"rgb10a2\" }\nrg.resource \"GB1\" { format = \"rgba8_srgb\" }\n"
                                          "rg.resource \"GB2\" { format = \"rgba8\" }\nrg.resource \"GB3\" { format = \"rgba16f\" }\n"
                                          "rg.resource \"depth\" { format = \"d32f_s8\" }\n"
                                          "rg.pass \"gbuffer\" { kind = \"scene\", writes = { \"GB0\", \"GB1\", \"GB2\", \"GB3\", \"depth\" } }\n"
                                          "rg.output \"GB1\"\n";
    std::ofstream(dir / "scene.lua") << "local scene = require \"scene\"\n"
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
    auto pipeline = [&](const std::string& name, const std::string& channel) {
        std::ofstream(dir / name) << "local rg = require \"rg\"\n"
                                     "rg.layout \"shared\" { { \"T\", \"rgba8\", { \"" << channel << ":unorm:8\", \"rest:unorm:8\" } } }\n"
                                     "rg.resource \"output\" { format = \"rgba32f\" }\n"
                                     "rg.pass \"fill\" { kind = \"compute\", shader = \"test/pattern.comp\", writes = { \"output\" }, bind = { pattern = \"output\" } }\n"
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
    auto loaded = s.load(bad);  // kept as the transaction's new plan, or refused when it is prepared
    Result<void> e = loaded ? s.frame() : Result<void>(std::unexpected(loaded.error()));
    ASSERT_FALSE(e.has_value());
    EXPECT_NE(e.error().describe().find("pass 'accumulate': params.cadence: unknown 'daily', expected one of: 'frame', 'once'"), std::string::npos)
        << e.error().describe();
    // A pass run once that writes a transient resource would leave garbage in the frames it skips.
    const std::string transient = std::string(RG_TEST_TMP) + "/once_transient.lua";
    std::ofstream(transient) << "local rg = require \"rg\"\n"
                                "rg.resource \"output\" { format = \"rgba32f\" }\n"
                                "rg.pass \"fill\" { kind = \"compute\", shader = \"test/pattern.comp\", writes = { \"output\" }, bind = { pattern = \"output\" }, cadence = \"once\" }\n"
                                "rg.output \"output\"\n";
    auto t = s.load(transient);
    Result<void> te = t ? s.frame() : Result<void>(std::unexpected(t.error()));
    ASSERT_FALSE(te.has_value());
    EXPECT_NE(te.error().describe().find("params.cadence: 'once' writes only persistent resources; 'output' is not (declare it with persistent = true)"),
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
                           "rg.pass \"casters\" { kind = \"scene\", shadow = true, writes = { \"maps\" }, cull = \"sideways\" }\n"
                           "rg.pass \"show\" { kind = \"fullscreen\", shader = \"test/tint.frag\", reads = { \"maps\" }, writes = { \"out\" } }\n"
                           "rg.output \"out\"\n";
    Session s(*s_runtime, o);
    auto loaded = s.load(file);
    Result<void> e = loaded ? s.frame() : Result<void>(std::unexpected(loaded.error()));
    ASSERT_FALSE(e.has_value());
    EXPECT_NE(e.error().describe().find("pass 'casters': params.cull: unknown 'sideways', expected one of: 'none', 'clockwise', 'counter_clockwise'"),
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
                           "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', writes = { 'pattern' } }\n"
                           "rg.output 'pattern'\n"
                           "function rg.frame(ctx)\n" + frameBody + "end\n";
    return file;
}

// The first frame's rg.frame runs at the load (its plan is built with what it changes): an error
// there fails the load, naming the line; a later frame's error fails that frame.
TEST_F(LuaGpu, FrameCallbackErrorsAreReported) {
    Session s(*s_runtime, small());
    auto r = s.load(script("bad_frame.lua"));
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(firstLine(r.error()),
              "rg.frame: " + kScripts + "bad_frame.lua:9: ctx.params: unknown parameter 'scael' (did you mean 'scale'?)");
    EXPECT_FALSE(s.loaded());
    const std::string file = patternScript("bad_second_frame.lua", "    if ctx.frame == 1 then ctx.params.scael = 2 end\n");
    ASSERT_TRUE(s.load(file).has_value());
    ASSERT_TRUE(s.frame().has_value());
    auto second = s.frame();
    ASSERT_FALSE(second.has_value());
    const std::string message = firstLine(second.error());
    EXPECT_TRUE(message.starts_with("rg.frame: ") &&
                message.ends_with("bad_second_frame.lua:7: ctx.params: unknown parameter 'scael' (did you mean 'scale'?)"))
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
                             "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', writes = { 'pattern' } }\n"
                             "rg.output 'pattern'\n"
                             "function rg.frame(ctx) ctx.params.gain = 2 end\n";
    ASSERT_FALSE(s.load(broken).has_value());
    EXPECT_EQ(s.overrides().params.count("scale"), 1u);
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_DOUBLE_EQ(s.pipeline().findParam("scale")->value.asNumber(0), 3.0);
}

// rg.frame runs once a frame, the first at the load: a script counting its calls sees one per frame.
TEST_F(LuaGpu, FrameCallbackRunsOncePerFrame) {
    const std::string file = patternScript("count_frames.lua",
                                           "    calls = (calls or 0) + 1\n"
                                           "    ctx.params.scale = calls\n"
                                           "    assert(calls == ctx.frame + 1, 'called ' .. calls .. ' times by frame ' .. ctx.frame)\n");
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
        "rg.pass 'generate' { kind = 'compute', shader = 'test/pattern.comp', writes = { 'pattern' } }\n"
        "rg.pass 'transform' { kind = 'fullscreen', shader = 'test/transform.frag', reads = { 'pattern' }, writes = { 'output' } }\n"
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
    EXPECT_NE(broken.error().message.find("reload.lua:8: passes.oops.reads[1]: unknown resource 'nothing'"), std::string::npos)
        << broken.error().message;
    ASSERT_TRUE(s.frame().has_value());  // the previous pipeline keeps rendering
    EXPECT_EQ(output(s).pixels, first.pixels);

    write(withScale("1") + "rg.pass 'bad_shader' { kind = 'fullscreen', shader = 'tests/gpu/shaders/broken.frag', writes = { 'output' }, after = { 'transform' } }\n");
    auto badShader = s.load(file);
    ASSERT_FALSE(badShader.has_value());
    EXPECT_NE(badShader.error().message.find("broken.frag:7:"), std::string::npos) << badShader.error().message;
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

}  // namespace

namespace {

// Every ```lua block of scripts/README.md, in order.
std::vector<std::string> readmeExamples() {
    std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/README.md");
    std::vector<std::string> blocks;
    std::string line, block;
    bool inside = false;
    while (std::getline(in, line)) {
        if (!inside && line == "```lua") {
            inside = true;
            block.clear();
        } else if (inside && line == "```") {
            inside = false;
            blocks.push_back(block);
        } else if (inside)
            block += line + "\n";
    }
    return blocks;
}

class ScriptsReadme : public LuaGpu {};

TEST_F(ScriptsReadme, EveryExampleLoadsCompilesAndRenders) {
    auto examples = readmeExamples();
    ASSERT_GE(examples.size(), 10u);
    fs::create_directories(RG_TEST_TMP);
    for (size_t i = 0; i < examples.size(); ++i) {
        const std::string file = std::string(RG_TEST_TMP) + "/readme_example_" + std::to_string(i + 1) + ".lua";
        std::ofstream(file) << examples[i];
        SCOPED_TRACE("example " + std::to_string(i + 1) + ":\n" + examples[i]);
        Session s(*s_runtime, small());
        auto r = s.load(file);
        ASSERT_TRUE(r.has_value()) << r.error().describe();
        for (int f = 0; f < 2; ++f) {
            auto fr = s.frame();
            ASSERT_TRUE(fr.has_value()) << fr.error().describe();
        }
        auto img = s_runtime->executor().readback(s.pipeline().output);
        ASSERT_TRUE(img.has_value()) << img.error().describe();
    }
}

}  // namespace

namespace {

// Every layout any shipped pipeline or README example declares survives pack -> unpack within its
// encoding's bound (uint exact; unorm/snorm half a step; sRGB half a step in the encoded domain;
// octahedral normals within 2·asin(3√2 / 2N); floats at the format's precision).
void roundTrip(const LayoutDesc& layout, std::mt19937& rng) {
    auto info = analyzeLayout(layout);
    ASSERT_TRUE(info.has_value()) << info.error().message;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), signedUnit(-1.0f, 1.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<ChannelValue> in(info->channels.size());
        for (size_t c = 0; c < in.size(); ++c) {
            const ChannelDesc& ch = info->channelDesc(c);
            for (int k = 0; k < 4; ++k) {
                in[c].v[static_cast<size_t>(k)] = ch.encoding == Encoding::Snorm || ch.encoding == Encoding::Oct ? signedUnit(rng)
                                                                                                                 : unit(rng);
                in[c].u[static_cast<size_t>(k)] = static_cast<uint32_t>(rng());
            }
            if (ch.encoding == Encoding::Oct) {
                float len = std::sqrt(in[c].v[0] * in[c].v[0] + in[c].v[1] * in[c].v[1] + in[c].v[2] * in[c].v[2]);
                if (len < 1e-3f) in[c].v = {0, 0, 1, 0};
            }
        }
        auto out = unpackTexel(*info, packTexel(*info, in));
        ASSERT_EQ(out.size(), in.size());
        for (size_t c = 0; c < in.size(); ++c) {
            const ChannelDesc& ch = info->channelDesc(c);
            const ChannelPlacement& pl = info->channels[c];
            const double n = std::pow(2.0, pl.bitsPerComponent) - 1.0;
            SCOPED_TRACE(layout.name + "." + ch.name);
            for (uint32_t k = 0; k < pl.components; ++k) {
                switch (ch.encoding) {
                case Encoding::Uint: {
                    uint32_t mask = pl.bitsPerComponent >= 32 ? ~0u : (1u << pl.bitsPerComponent) - 1u;
                    EXPECT_EQ(out[c].u[k], std::min(in[c].u[k], mask));
                    break;
                }
                case Encoding::Unorm: EXPECT_NEAR(out[c].v[k], in[c].v[k], 0.5 / n + 1e-6); break;
                case Encoding::Snorm: EXPECT_NEAR(out[c].v[k], in[c].v[k], 1.0 / (n - 1.0) + 1e-6); break;
                case Encoding::Srgb: EXPECT_NEAR(srgbEncode(out[c].v[k]), srgbEncode(in[c].v[k]), 0.5 / n + 1e-5); break;
                case Encoding::Float: EXPECT_NEAR(out[c].v[k], in[c].v[k], std::abs(in[c].v[k]) * 1e-3 + 1e-6); break;
                case Encoding::Oct: break;
                }
            }
            if (ch.encoding == Encoding::Oct) {
                const auto& a = in[c].v;
                const auto& b = out[c].v;
                double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
                double cosAngle = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / la;
                double bound = 2.0 * std::asin(3.0 * std::sqrt(2.0) / (2.0 * n));
                EXPECT_LE(std::acos(std::min(1.0, cosAngle)), bound + 1e-5);
            }
        }
    }
}

TEST(LuaLayouts, EveryDeclaredLayoutRoundTrips) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines"))
        if (e.path().extension() == ".lua") files.push_back(e.path().string());
    fs::create_directories(RG_TEST_TMP);
    auto examples = readmeExamples();
    for (size_t i = 0; i < examples.size(); ++i) {
        files.push_back(std::string(RG_TEST_TMP) + "/layout_example_" + std::to_string(i + 1) + ".lua");
        std::ofstream(files.back()) << examples[i];
    }
    std::mt19937 rng(7);
    size_t layouts = 0;
    for (const auto& f : files) {
        LuaHost host(luaHostOptionsWithoutDevice());
        auto p = host.load(f);
        ASSERT_TRUE(p.has_value()) << f << ": " << p.error().message;
        for (const auto& l : p->layouts) {
            roundTrip(l, rng);
            ++layouts;
        }
    }
    EXPECT_GE(layouts, 3u);  // disney (deferred.lua, the README) and the README's compact layout
}

}  // namespace
