// Pipeline scripts on the CPU: the sandbox, every kind of bad script with its exact message, the
// schema and modules. On the GPU: test_lua_gpu.cpp; layouts: test_lua_layouts.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "layout/layout.h"

#include "core/compiler.h"
#include "lua/lua_host.h"
#include "lua_test_util.h"
#include "runtime/session.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::test;

namespace {

Result<PipelineDesc> load(const std::string& name,
                          LuaHostOptions o = luaHostOptionsWithoutDevice()) {
    LuaHost host(o);
    return host.load(script(name));
}

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
    EXPECT_EQ(firstLine(p.error()),
              kScripts + "runtime_error.lua:3: attempt to index a nil value (local 'settings')");
    EXPECT_NE(p.error().message.find("stack traceback:"), std::string::npos);
}

TEST(LuaErrors, UnknownFieldSuggestsTheClosest) {
    EXPECT_EQ(loadError("unknown_field.lua"),
              kScripts +
                  "unknown_field.lua:3: passes.tonemap.shadr: unknown field (did you mean "
                  "'shader'?); expected one of: "
                  "'kind', 'reads', 'writes', 'after', 'enabled', 'side_effect', 'doc', 'insert', "
                  "'only_when', "
                  "'shader', 'defines', "
                  "'switches', 'bind', 'uniforms', 'constants', 'filter', 'clear', 'blend', "
                  "'stencil', 'depth', 'camera'");
}

// switches = { param = "DEFINE" } names a declared parameter and a define (a GLSL identifier).
TEST(LuaErrors, SwitchesNameParametersAndDefines) {
    EXPECT_EQ(loadError("switch_unknown.lua"),
              kScripts +
                  "switch_unknown.lua:4: passes.tonemap.switches.curv: unknown parameter 'curv' "
                  "(did you mean 'curve'?) "
                  "(declare it with rg.param)");
    EXPECT_EQ(loadError("switch_bad_define.lua"),
              kScripts +
                  "switch_bad_define.lua:4: passes.tonemap.switches.curve: expected the name of a "
                  "define (a GLSL "
                  "identifier), got '2CURVE'");
    auto p = load("switch_ok.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    GraphDesc g = graphWithParams(*p);
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["RG_CURVE"],
              Value(1.0));  // "neutral": the index of the choice
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["RG_DITHER"], Value(0.0));
    EXPECT_EQ(g.findPass("tonemap")->params["defines"]["KEEP"], Value(true));
    EXPECT_TRUE(isSwitch(*p, "curve"));
    EXPECT_FALSE(isSwitch(*p, "other"));
}

// A pass parameter that names a resource the pass writes (the scene pass's lightmap_specular).
TEST(LuaErrors, AWrittenParameterNamesOneOfThePasssWrites) {
    EXPECT_EQ(loadError("written_not.lua"),
              kScripts +
                  "written_not.lua:10: passes.gbuffer.lightmap_specular: 'spec' is not written by "
                  "the pass (it writes 'GB0', 'GB1', 'GB2', 'GB3', 'depth')");
}

TEST(LuaErrors, WrongType) {
    EXPECT_EQ(
        loadError("wrong_type.lua"),
        kScripts + "wrong_type.lua:2: resources.output.format: expected a string, got number");
}

TEST(LuaErrors, SceneLayersNamesWhatTheSceneCanSize) {
    EXPECT_EQ(loadError("scene_layers_unknown.lua"),
              kScripts +
                  "scene_layers_unknown.lua:2: resources.maps.scene_layers: expected the name "
                  "of a layer extent of the scene, e.g. \"shadow_views\" (the layers its "
                  "shadowed local lights need, at most `layers`)");
}

TEST(LuaErrors, OnlyWhenTakesABooleanParameter) {
    EXPECT_EQ(loadError("only_when_param.lua"),
              kScripts +
                  "only_when_param.lua:3: resources.extra.only_when.param: parameter 'spec' is a "
                  "number; only_when takes a boolean one");
}

// A pass's only_when too, each parameter of a list by its place; and `load = "pass"` names a pass.
TEST(LuaErrors, PassOnlyWhenAndLoadAfterNameWhatExists) {
    EXPECT_EQ(loadError("only_when_pass_params.lua"),
              kScripts +
                  "only_when_pass_params.lua:5: passes.first.only_when.param[2]: parameter 'size' "
                  "is a number; only_when takes a boolean one");
    EXPECT_EQ(loadError("load_unknown_pass.lua"),
              kScripts +
                  "load_unknown_pass.lua:4: passes.second.writes[1].load: unknown pass 'frist' "
                  "(did you mean 'first'?)");
    // The named pass runs first and draws what is loaded.
    EXPECT_EQ(loadError("load_later_pass.lua"),
              kScripts +
                  "load_later_pass.lua:4: passes.first.writes[1].load: pass 'second' runs after "
                  "this one: name the pass that drew 'output' first");
}

// A scene feature is a name or name:name ("material:transmission" on line 2 is one); "material:"
// is neither.
TEST(LuaErrors, OnlyWhenNamesASceneFeature) {
    EXPECT_EQ(loadError("only_when_scene_name.lua"),
              kScripts +
                  "only_when_scene_name.lua:3: resources.extra.only_when.scene: 'material:' is not "
                  "a name (or name:name, name:number)");
}

// A path without a stencil class is the forward pass's only: its materials say forward = true.
TEST(LuaErrors, AClasslessPathIsForwardOnly) {
    EXPECT_EQ(loadError("forward_path_needs_forward.lua"),
              kScripts +
                  "forward_path_needs_forward.lua:4: materials.veil.path: lighting path 'veil' has "
                  "no stencil class (it is the forward pass's only): give the material forward = "
                  "true, or the path a stencil class");
}

// rg.resource's `history` names a resource of its own, and its table takes name and mips only;
// rg.history's `of` names a texture.
TEST(LuaErrors, AHistoryNamesAResourceOfItsOwn) {
    EXPECT_EQ(loadError("history_clash.lua"),
              kScripts +
                  "history_clash.lua:3: resources.taa_history: 'taa_history' is declared "
                  "twice (first as the history of taa at " +
                  kScripts + "history_clash.lua:2)");
    EXPECT_EQ(loadError("history_of_buffer.lua"),
              kScripts +
                  "history_of_buffer.lua:4: resources.counts_history.of: 'counts' is a "
                  "buffer; a history is a texture's (rg.resource)");
    EXPECT_EQ(loadError("history_bad.lua"),
              kScripts +
                  "history_bad.lua:2: resources.ao.history.mip: unknown field (did you "
                  "mean 'mips'?); expected one of: 'name', 'mips'");
}

TEST(LuaErrors, OutOfRangeValue) {
    EXPECT_EQ(loadError("out_of_range.lua"),
              kScripts +
                  "out_of_range.lua:2: params.exposure.default: parameter 'exposure' expects a "
                  "number in [-6, 16], got 20");
}

TEST(LuaErrors, UnknownResource) {
    EXPECT_EQ(loadError("unknown_resource.lua"),
              kScripts +
                  "unknown_resource.lua:6: passes.lighting.reads[3]: unknown resource 'GB9' (did "
                  "you mean 'GB0'?)");
}

TEST(LuaPipeline, TiledBufferGrowsWithTheOutput) {
    auto p = load("tiled_buffer.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    CompileOptions o;
    o.outputWidth = 100;  // 13 x 5 tiles of 8 pixels
    o.outputHeight = 33;
    auto plan = compile(graphWithParams(*p), o);
    ASSERT_TRUE(plan.has_value()) << plan.error().message;
    auto lists = std::find_if(plan->resources.begin(), plan->resources.end(),
                              [](auto& r) { return r.name == "lists"; });
    ASSERT_NE(lists, plan->resources.end());
    EXPECT_EQ(lists->bufferSize, 16u + 13u * 5u * 64u);
    EXPECT_EQ(loadError("tiled_buffer_half.lua"),
              kScripts +
                  "tiled_buffer_half.lua:2: resources.lists.tile_bytes: missing (a tiled buffer "
                  "gives both tile, in pixels, and tile_bytes)");
    EXPECT_EQ(loadError("scene_buffer_half.lua"),
              kScripts +
                  "scene_buffer_half.lua:2: resources.lists.count_bytes: missing (a scene-sized "
                  "buffer gives both scene_count and count_bytes)");
}

TEST(LuaErrors, CycleIsReportedByTheCompiler) {
    auto p = load("cycle.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_FALSE(plan.has_value());
    EXPECT_EQ(plan.error().message,
              kScripts + "cycle.lua:4: cycle between passes: 'first' -> 'second' -> 'first'");
}

TEST(LuaErrors, MaterialsNamingOneStencilValueMustDecodeAlike) {
    // A pixel's stencil value is its material's identity: two materials that name the same class
    // share it, so their pixels must decode alike.
    EXPECT_EQ(loadError("id_collision.lua"),
              kScripts +
                  "id_collision.lua:5: materials.toon.stencil: its pixels would carry stencil "
                  "value 1 (stencil class 'lit_standard'), the identity of material 'glossy' (" +
                  kScripts +
                  "id_collision.lua:4), which decodes otherwise (layout 'disney'): materials "
                  "sharing a stencil value share their layout, channels and decals; give it a "
                  "class of its own (rg.stencil \"...\" { variant_of = \"lit_standard\" } keeps "
                  "the class's lighting) or leave out stencil to have a variant chosen");
    // A class's 16 values: the standard material's, then 15 variants; the sixteenth material
    // that decodes otherwise finds none.
    EXPECT_EQ(loadError("id_exhausted.lua"),
              kScripts +
                  "id_exhausted.lua:10: materials.m16: no material identity left for stencil "
                  "class "
                  "'lit_standard': its 16 stencil values are held by materials 'standard', 'm1', "
                  "'m2', 'm3', 'm4', 'm5', 'm6', 'm7', 'm8', 'm9', 'm10', 'm11', 'm12', 'm13', "
                  "'m14', 'm15' and declared variants; declare a stencil class of its own");
}

TEST(LuaPipeline, MaterialsTakeTheirClassValueOrAVariantOfIt) {
    auto identity = [](const PipelineDesc& p, const std::string& name) {
        for (const MaterialDesc& m : p.materials)
            if (m.name == name) return m.identity;
        return 0xFFFFu;
    };
    auto p = load("id_decals_differ.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    EXPECT_EQ(identity(*p, "standard"), 0x01u);
    EXPECT_EQ(identity(*p, "glossy"), 0x11u);  // other decals: the first free variant
    EXPECT_EQ(identity(*p, "matte"), 0x01u);   // decodes as the standard material: shares it
    // No class: low bits 0 (no lighting pass lights it); a materialId of its own width is fine.
    auto w = load("id_placement.lua");
    ASSERT_TRUE(w.has_value()) << w.error().message;
    EXPECT_EQ(identity(*w, "wide"), 0x10u);
    EXPECT_EQ(identity(*w, "standard"), 0x01u);
}

TEST(LuaErrors, PathDecodesOneLayout) {
    EXPECT_EQ(loadError("path_layout.lua"),
              kScripts +
                  "path_layout.lua:5: materials.toon.path: lighting path 'standard' lights layout "
                  "'disney' (material 'standard', "
                  "materials/disney.lua:23); this material's layout is 'toon': a path's lighting "
                  "pass and shading function decode one "
                  "layout, so declare a path of its own");
}

TEST(LuaErrors, StencilVariantsKeepTheirBase) {
    // A variant's value does not depend on which values other classes took.
    EXPECT_EQ(loadError("stencil_variant_unknown.lua"),
              kScripts +
                  "stencil_variant_unknown.lua:3: stencil.wet.variant_of: unknown stencil class "
                  "'lit_standrd' (did you mean 'lit_standard'?); "
                  "expected one of: 'lit_standard'");
}

TEST(LuaErrors, MaterialParameterNamesCannotClashWithTheGeneratedShader) {
    // #14: a parameter becomes a #define in the generated G-buffer shader; a layout channel's name
    // broke it with an error inside the generated file. Now refused where it is declared.
    EXPECT_EQ(
        loadError("param_clash.lua"),
        kScripts +
            "param_clash.lua:4: materials.toon.params.smoothness: clashes with channel "
            "'smoothness' of layout 'disney' "
            "(target GB0): the generated shader defines each parameter as a name; choose another");
    EXPECT_NE(loadError("param_reserved.lua")
                  .find("param_reserved.lua:4: materials.toon.params.uv0: clashes with 'uv0' of "
                        "the generated "
                        "G-buffer shader"),
              std::string::npos)
        << loadError("param_reserved.lua");
}

TEST(LuaErrors, MaterialTexturesAreFewAndNamedApart) {
    // A texture becomes NAME(s) in the generated shader, beside the parameters' names.
    EXPECT_EQ(loadError("material_textures_bad.lua"),
              kScripts +
                  "material_textures_bad.lua:4: materials.toon.textures[1]: 'ink' is already a "
                  "parameter or texture of this material; choose another");
    EXPECT_EQ(loadError("material_textures_many.lua"),
              kScripts +
                  "material_textures_many.lua:4: materials.toon.textures: at most 3 textures a "
                  "material, got 4");
}

TEST(LuaErrors, StencilExhaustion) {
    EXPECT_EQ(loadError("stencil_exhaustion.lua"),
              kScripts +
                  "stencil_exhaustion.lua:4: stencil.class16: no stencil value left: 4 stencil "
                  "bits hold 15 classes, all "
                  "taken by 'class1', 'class2', 'class3', 'class4', 'class5', 'class6', 'class7', "
                  "'class8', 'class9', "
                  "'class10', 'class11', 'class12', 'class13', 'class14', 'class15'");
}

TEST(LuaErrors, RunawayLoopIsStopped) {
    LuaHostOptions o = luaHostOptionsWithoutDevice();
    o.instructions = 5'000'000;
    EXPECT_EQ(loadError("runaway.lua", o), kScripts +
                                               "runaway.lua:3: script stopped after 5 million "
                                               "instructions: a runaway loop? (limit: 5 million)");
}

TEST(LuaErrors, MemoryLimit) {
    LuaHostOptions o = luaHostOptionsWithoutDevice();
    o.memoryBytes = 16u << 20;
    // Lua reports running out of memory without a position: the message names where the script
    // was last seen running (the count hook's sample).
    EXPECT_EQ(loadError("memory_hog.lua", o), kScripts +
                                                  "memory_hog.lua:2: script stopped: it used more "
                                                  "than 16 MiB of Lua memory (last running here)");
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
        EXPECT_NE(m.find("script stopped: it used more than 16 MiB of Lua memory"),
                  std::string::npos)
            << m;
    }
}

TEST(LuaErrors, ForbiddenOsExecute) {
    EXPECT_EQ(
        loadError("forbidden.lua"),
        kScripts + "forbidden.lua:2: os.execute is not available to rgraph scripts (sandbox)");
    EXPECT_FALSE(fs::exists("/tmp/rgraph-sandbox-escape"));
}

TEST(LuaErrors, ForbiddenIo) {
    EXPECT_EQ(
        loadError("forbidden_io.lua"),
        kScripts + "forbidden_io.lua:1: io.open is not available to rgraph scripts (sandbox)");
}

TEST(LuaErrors, RequireCannotLeaveTheSearchFolders) {
    EXPECT_EQ(loadError("require_escape.lua"),
              kScripts +
                  "require_escape.lua:1: require: '..etc.passwd' is not a module name (dotted "
                  "names of letters, digits, '_' "
                  "and '-')");
}

TEST(LuaErrors, MissingScript) {
    auto p = load("no_such_script.lua");
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(p.error().message,
              "cannot open pipeline script '" + script("no_such_script.lua") + "'");
}

TEST(LuaErrors, HostSurvivesAndLoadsAgainAfterErrors) {
    LuaHost host(luaHostOptionsWithoutDevice());
    for (const char* bad :
         {"syntax_error.lua", "runtime_error.lua", "forbidden.lua", "unknown_field.lua"})
        EXPECT_FALSE(host.load(script(bad)).has_value());
    auto ok = host.load(script("params.lua"));
    ASSERT_TRUE(ok.has_value()) << ok.error().message;
    EXPECT_EQ(ok->graph.passes.size(), 2u);
}

TEST(LuaPipeline, DefaultPipelineDeclaresTheMaterialSystem) {
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    ASSERT_EQ(p->layouts.size(), 5u);
    EXPECT_EQ(p->layouts[0].name, "disney");
    EXPECT_EQ(p->layouts[0].targets.size(), 4u);
    EXPECT_EQ(p->layouts[1].name, "clearcoat");  // two normals, the base's and the coat's
    EXPECT_EQ(p->layouts[1].targets.size(), 4u);
    EXPECT_EQ(p->layouts[2].name, "two_colour");  // tbl:3, over the same four targets
    EXPECT_EQ(p->layouts[2].targets.size(), 4u);
    EXPECT_EQ(p->layouts[3].name, "sheen");  // and the cloth material's
    EXPECT_EQ(p->layouts[3].targets.size(), 4u);
    EXPECT_EQ(p->layouts[4].name, "transmission");  // the unpacked form the forward pass shades
    // The standard material, two game-team materials, the two-colour base material and the sheen
    // material, each with its id and stencil class; the transmission, forward only, without one.
    ASSERT_EQ(p->materials.size(), 6u);
    EXPECT_EQ(p->materials[0].name, "standard");
    EXPECT_EQ(p->materials[0].id, 0u);
    EXPECT_EQ(p->materials[0].stencil, "lit_standard");
    EXPECT_EQ(p->materials[1].name, "clear_coat");
    EXPECT_EQ(p->materials[1].id, 0u);  // its own layout, without a materialId
    EXPECT_EQ(p->materials[1].stencil, "lit_clearcoat");
    EXPECT_EQ(p->materials[2].name, "foliage");
    EXPECT_EQ(p->materials[2].fills, (std::vector<std::string>{"GB0", "GB1"}));
    EXPECT_EQ(p->materials[2].fixup, "foliage_fixup");
    EXPECT_EQ(p->materials[3].name, "two_colour");
    EXPECT_EQ(p->materials[2].id, 0u);  // decodes as the standard material after its fix-up
    EXPECT_EQ(p->materials[2].stencil, "foliage");
    EXPECT_EQ(p->materials[3].id, 2u);  // id 3 is left free for a game team
    EXPECT_EQ(p->materials[3].stencil, "lit_two_colour");
    EXPECT_EQ(p->materials[4].name, "sheen");
    EXPECT_EQ(p->materials[4].stencil, "lit_sheen");
    EXPECT_EQ(p->materials[5].name, "transmission");
    EXPECT_TRUE(p->materials[5].forward);
    EXPECT_EQ(p->materials[5].stencil, "");
    EXPECT_EQ(p->materials[5].identity, 0x10u);  // no class: low bits 0, no lighting pass
    ASSERT_EQ(p->stencilClasses.size(), 5u);
    EXPECT_EQ(p->stencilClasses[0].value, 1u);  // lit_standard, allocated
    EXPECT_EQ(p->stencilClasses[1].value, 2u);  // lit_clearcoat, allocated
    EXPECT_EQ(p->stencilClasses[2].value,
              0x11u);  // foliage: a variant of lit_standard (high bits 1)
    EXPECT_EQ(p->stencilClasses[2].mask, 0xFFu);
    EXPECT_EQ(p->stencilClasses[2].base, "lit_standard");
    EXPECT_EQ(p->stencilClasses[0].mask, 0x0Fu);  // a class's pass lights its variants too
    EXPECT_EQ(p->stencilClasses[3].value, 3u);    // lit_two_colour, allocated
    EXPECT_EQ(p->stencilClasses[4].value, 4u);    // lit_sheen, allocated
    // Decals: the standard material takes all five parameters, the others the common three,
    // the two-colour material's base colour into its diffuse colour.
    EXPECT_EQ(p->materials[0].decals, (std::vector<std::string>{"normal", "baseColor", "smoothness",
                                                                "metalMask", "reflectance"}));
    EXPECT_EQ(p->materials[1].decals,
              (std::vector<std::string>{"normal", "baseColor", "smoothness"}));
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
    // culling, its maps' clears (without a sun), the local lights' caster culling and maps
    // (scripts/shadows.lua), the
    // camera's culling on the GPU in two phases (scripts/culling.lua: for scenes of many draws —
    // the first phase's culling and G-buffer, the pyramid of its depth, the second's culling), the
    // G-buffer half with the passes inserted after it (the light froxels' clear, screen-space AO's
    // half-resolution depths, each cascade's map drawn and filtered into the sun's mask at once, the
    // foliage fix-up, then the AO itself on the fixed-up normals: scripts/ao.lua), the Hi-Z
    // pyramid, SSR's mask and SSR (scripts/ssr.lua), the composition of SSR and the probes
    // (scripts/reflections.lua), the lighting, the sky, the points and lines, the copy of the opaque
    // frame the transmission sees through, and forward.
    ASSERT_GE(order.size(), 70u);
    EXPECT_EQ(std::vector<std::string>(order.begin(), order.begin() + 68),
              (std::vector<std::string>{"env_cube",
                                        "env_mips",
                                        "env_irradiance",
                                        "env_hot",
                                        "env_smooth_mips",
                                        "env_prefilter",
                                        "dfg_table",
                                        "probe_capture",
                                        "probe_mips",
                                        "probe_prefilter",
                                        "sun_cascades",
                                        "sun_cull_clear",
                                        "sun_cull",
                                        "shadow_clear0",
                                        "shadow_clear1",
                                        "shadow_clear2",
                                        "local_cull_clear",
                                        "local_cull",
                                        "shadow_local",
                                        "camera_early_clear",
                                        "camera_cull_early",
                                        "gbuffer_early",
                                        "camera_hiz",
                                        "camera_cull_clear",
                                        "camera_cull",
                                        "gbuffer",
                                        "light_froxels_clear",
                                        "ao_depth",
                                        "sun_visibility_clear",
                                        "sun_classify",
                                        "sun_visibility_half_clear",
                                        "sun_classify_half",
                                        "shadow_sun0",
                                        "sun_mask0",
                                        "sun_mask_half0",
                                        "shadow_sun1",
                                        "sun_mask1",
                                        "sun_mask_half1",
                                        "shadow_sun2",
                                        "sun_mask2",
                                        "sun_mask_half2",
                                        "foliage_fixup",
                                        "gtao",
                                        "ao_blur",
                                        "ao_temporal",
                                        "ao_upsample",
                                        "light_froxels",
                                        "light_froxels_large",
                                        "light_froxels_sort",
                                        "light_culling",
                                        "decals_copy0",
                                        "decals_copy1",
                                        "decals_copy2",
                                        "decals",
                                        "hiz",
                                        "ssr_mask",
                                        "ssr",
                                        "ssr_temporal",
                                        "reflection_compose",
                                        "lighting_standard",
                                        "lighting_clearcoat",
                                        "lighting_two_colour",
                                        "lighting_sheen",
                                        "sky",
                                        "lines",
                                        "opaque_copy",
                                        "opaque_mips",
                                        "forward"}));
    // The histories' keep passes come after every other (rg.resource's `history`, rg.history).
    EXPECT_EQ(std::vector<std::string>(order.end() - 6, order.end()),
              (std::vector<std::string>{"ssr_history_keep", "ssr_distance_history_keep",
                                        "ao_history_keep", "taa_history_keep", "hdr_history_keep",
                                        "hdr_history_mips"}));
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_TRUE(plan.has_value()) << plan.error().message;
    // Every script it pulled in is known, for hot reload.
    EXPECT_EQ(
        p->files.size(),
        20u);  // deferred, post, lighting, render_loop, motion, culling, ibl, shadows, probes, ao, ssr, reflections, lightmap, gbuffer_reader, disney, clearcoat, foliage, two_colour, sheen, transmission
}

TEST(LuaPipeline, ModulesAreNamespacedAndInsertedAfterTheirAnchor) {
    auto p = load("with_modules.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    std::vector<std::string> order;
    for (const auto& pass : p->graph.passes) order.push_back(pass.name);
    EXPECT_EQ(order, (std::vector<std::string>{"generate", "transform", "team_tint.make_overlay",
                                               "team_tint.apply", "final"}));
    EXPECT_NE(p->graph.findResource("team_tint.overlay"), nullptr);
    EXPECT_EQ(p->graph.findPass("team_tint.apply")->accesses[0].resource, "team_tint.overlay");
    EXPECT_EQ(p->modules, (std::vector<std::string>{"team_tint"}));
    ASSERT_TRUE(compile(graphWithParams(*p), {}).has_value());
}

// A second rg.output replaces the first one whole (its hdr goes too), and the load keeps a note
// naming both declarations, which --verbose prints.
TEST(LuaPipeline, ASecondOutputReplacesTheFirstAndSaysSo) {
    auto p = load("output_twice.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    EXPECT_EQ(p->output, "second");
    EXPECT_EQ(p->hdr, "");
    ASSERT_EQ(p->notes.size(), 1u);
    EXPECT_EQ(p->notes[0],
              kScripts + "output_twice.lua:8: rg.output (display 'second') replaces the one at " +
                  kScripts + "output_twice.lua:7 (display 'first', hdr 'linear')");
    auto once = load("with_modules.lua");  // one rg.output: no note
    ASSERT_TRUE(once.has_value());
    EXPECT_TRUE(once->notes.empty());
}

TEST(LuaPipeline, TwoWritersFromDifferentModulesAreAnError) {
    auto p = load("module_clash.lua");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    auto plan = compile(graphWithParams(*p), {});
    ASSERT_FALSE(plan.has_value());
    EXPECT_EQ(
        plan.error().message,
        kScripts +
            "modules/team_clash.lua:4: passes 'transform' and 'team_clash.overwrite' both write "
            "'output' with no order "
            "between them: make 'team_clash.overwrite' load it or list 'transform' in its after");
}

}  // namespace
