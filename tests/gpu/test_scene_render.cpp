// The default pipeline on a scene of known materials (tests/gpu/scenes/materials.lua): G-buffer
// channels read back within their encodings' bounds, materialId and stencil classes exact, the
// foliage fix-up filling what the foliage material leaves out, the clear coat's second lobe.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <glm/gtc/matrix_transform.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "layout/layout.h"
#include "passes/gpu_scene.h"
#include "scene/scene.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 256, H = 128;

class SceneRender : public GpuFixture {
protected:
    std::unique_ptr<Session> render(const std::string& pipeline, std::vector<std::string> captures,
                                    const std::string& view = "",
                                    const std::string& scene = "materials.lua",
                                    const std::map<std::string, std::string>& args = {}) {
        SessionOptions o;
        o.compile.outputWidth = W;
        o.compile.outputHeight = H;
        o.scene = kRoot + "/tests/gpu/scenes/" + scene;
        o.sceneArgs = args;
        // The G-buffer holds the scene's smoothness, not one widened by specular anti-aliasing.
        o.paramsIfDeclared["specular_aa"] = Value(false);
        if (scene !=
            "materials.lua") {  // the probe alone: a fixed exposure, no screen-space occlusion
            o.params["exposure_mode"] = Value("manual");
            o.params["ao_radius"] = Value(0.05);
        }
        o.captures = std::move(captures);
        o.view = view;
        auto s = std::make_unique<Session>(*s_runtime, o);
        auto r = s->load(kRoot + "/" + pipeline);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        for (int f = 0; f < 2; ++f) {
            auto fr = s->frame();
            EXPECT_TRUE(fr.has_value()) << fr.error().describe();
        }
        return s;
    }
    // The pixel a world point lands on with the scene's camera (as GpuScene::updateFrame sets it).
    static glm::ivec2 pixelOf(const Session& s, glm::vec3 p) {
        const Camera& c = s.scene()->cameras.front();
        glm::mat4 proj =
            glm::perspectiveRH_ZO(c.verticalFov, float(W) / float(H), c.nearPlane, c.farPlane);
        proj[1][1] *= -1.0f;
        glm::vec4 clip = proj * glm::lookAt(c.position, c.target, c.up) * glm::vec4(p, 1.0f);
        glm::vec2 ndc = glm::vec2(clip) / clip.w;
        return glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(W, H));
    }
    // The G-buffer at a pixel decoded as layout `layout` (default: the first, disney) with the
    // layout's C++ unpack.
    static std::vector<ChannelValue> gbufferAt(const Session& s, glm::ivec2 px, LayoutInfo& info,
                                               const std::string& layout = "") {
        const auto& layouts = s.pipeline().layouts;
        auto l = std::find_if(layouts.begin(), layouts.end(),
                              [&](auto& x) { return layout.empty() || x.name == layout; });
        EXPECT_NE(l, layouts.end()) << layout;
        auto li = analyzeLayout(*l);
        EXPECT_TRUE(li.has_value());
        info = *li;
        std::vector<TexelValue> texels;
        for (const auto& t : info.desc.targets) {
            auto img = s_runtime->executor().readback(t.name);
            EXPECT_TRUE(img.has_value()) << t.name;
            texels.push_back(texelFromFloats(
                t.format, &img->pixels[(size_t(px.y) * W + px.x) * img->channels], img->channels));
        }
        return unpackTexel(info, texels);
    }
    // Irradiance (lux) at normal n from the environment's SH (env_sh, captured or persistent), as
    // lib/environment.glsl's rgShIrradiance evaluates it.
    static glm::vec3 shIrradiance(glm::vec3 n) {
        auto bytes = s_runtime->executor().readbackBuffer("env_sh");
        EXPECT_TRUE(bytes.has_value());
        if (!bytes || bytes->size() < 9 * 16) return glm::vec3(0.0f);
        glm::vec4 sh[9];
        std::memcpy(sh, bytes->data(), sizeof sh);
        const float y[9] = {0.282095f,
                            0.488603f * n.y,
                            0.488603f * n.z,
                            0.488603f * n.x,
                            1.092548f * n.x * n.y,
                            1.092548f * n.y * n.z,
                            0.315392f * (3.0f * n.z * n.z - 1.0f),
                            1.092548f * n.x * n.z,
                            0.546274f * (n.x * n.x - n.y * n.y)};
        const float pi = 3.14159265f, a[9] = {pi,     2 * pi / 3, 2 * pi / 3, 2 * pi / 3, pi / 4,
                                              pi / 4, pi / 4,     pi / 4,     pi / 4};
        glm::vec3 e(0.0f);
        for (int i = 0; i < 9; ++i) e += a[i] * y[i] * glm::vec3(sh[i]);
        return glm::max(e, glm::vec3(0.0f));
    }
    // The same exposure for every render compared: manual, from the camera's default settings.
    static void setManualExposure(Session& s) {
        auto& p = const_cast<PipelineDesc&>(s.pipeline());
        p.findParam("exposure_mode")->value = Value("manual");
        s_runtime->executor().updateUniforms(graphWithParams(p));
    }
};

// The sphere centres of materials.lua, pulled towards the camera to the visible surface.
const glm::vec3 kStandard{-1.2f, 0.5f, 0.0f}, kCoated{0.0f, 0.5f, 0.0f}, kBush{1.2f, 0.4f, 0.4f};

TEST_F(SceneRender, GBufferHoldsTheMaterialParameters) {
    auto s = render("scripts/pipelines/deferred.lua", {"GB0", "GB1", "GB2", "GB3"});
    LayoutInfo info;
    auto g = gbufferAt(*s, pixelOf(*s, kStandard), info);
    auto ch = [&](const char* n) { return g[static_cast<size_t>(info.find(n))]; };
    EXPECT_EQ(ch("materialId").u[0], 0u);
    EXPECT_NEAR(srgbEncode(ch("baseColor").v[0]), srgbEncode(0.8f), 0.5f / 255 + 1e-4f);
    EXPECT_NEAR(srgbEncode(ch("baseColor").v[1]), srgbEncode(0.05f), 0.5f / 255 + 1e-4f);
    EXPECT_NEAR(ch("smoothness").v[0], 0.6f, 0.5f / 1023 + 1e-5f);
    EXPECT_EQ(ch("metalMask").v[0], 0.0f);
    EXPECT_NEAR(ch("reflectance").v[0], 0.5f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(ch("ao").v[0], 1.0f, 1e-6f);
    // The normal at the centre faces the camera, within the 10+10-bit octahedral bound.
    const glm::vec3 toCamera = glm::normalize(s->scene()->cameras.front().position - kStandard);
    const auto& n = ch("normal").v;
    EXPECT_GT(glm::dot(glm::vec3(n[0], n[1], n[2]), toCamera), 0.97f);

    // The clear coat in its own layout (materials/clearcoat.lua): the coat's smoothness, strength
    // and normal (the vertex normal: the sphere has no normal maps), the base's normal in GB0.
    LayoutInfo coatInfo;
    auto c = gbufferAt(*s, pixelOf(*s, kCoated), coatInfo, "clearcoat");
    auto cc = [&](const char* n) { return c[static_cast<size_t>(coatInfo.find(n))]; };
    EXPECT_NEAR(cc("coatGloss").v[0], 0.95f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(cc("coatWeight").v[0], 1.0f, 1e-6f);
    const auto& cn = cc("coatNormal").v;
    const auto& bn = cc("normal").v;
    const glm::vec3 coatToCamera = glm::normalize(s->scene()->cameras.front().position - kCoated);
    EXPECT_GT(glm::dot(glm::vec3(cn[0], cn[1], cn[2]), coatToCamera), 0.97f);
    EXPECT_GT(glm::dot(glm::vec3(cn[0], cn[1], cn[2]), glm::vec3(bn[0], bn[1], bn[2])), 0.999f);
}

TEST_F(SceneRender, FoliageIsFixedUpAfterFillingOnlyTwoTargets) {
    {
        // Without the fix-up, GB2 and GB3 under the bush keep what was drawn there before it — the
        // floor behind (reflectance 0.5, AO 1, no emissive) — not the foliage surface's own values
        // (reflectance 0): the foliage material wrote only GB0 and GB1.
        auto s = render("tests/lua/scripts/deferred_nofixup.lua", {"GB0", "GB1", "GB2", "GB3"});
        LayoutInfo info;
        auto g = gbufferAt(*s, pixelOf(*s, kBush), info);
        auto ch = [&](const char* n) { return g[static_cast<size_t>(info.find(n))]; };
        EXPECT_EQ(ch("materialId").u[0], 0u);  // foliage decodes as the standard material
        EXPECT_NEAR(ch("reflectance").v[0], 0.5f, 0.5f / 255 + 1e-5f);
        EXPECT_EQ(ch("ao").v[0], 1.0f);
        EXPECT_EQ(ch("emissive").v[1], 0.0f);
    }
    {
        auto s = render("scripts/pipelines/deferred.lua", {"GB0", "GB1", "GB2", "GB3", "env_sh"});
        LayoutInfo info;
        auto g = gbufferAt(*s, pixelOf(*s, kBush), info);
        auto ch = [&](const char* n) { return g[static_cast<size_t>(info.find(n))]; };
        EXPECT_EQ(ch("materialId").u[0], 0u);  // foliage decodes as the standard material
        EXPECT_NEAR(ch("reflectance").v[0], 0.35f, 0.5f / 255 + 1e-5f);  // foliage_reflectance
        EXPECT_EQ(ch("metalMask").v[0], 0.0f);
        EXPECT_NEAR(ch("ao").v[0], 1.0f, 1e-6f);
        EXPECT_EQ(ch("reserved").v[0], 1.0f);  // GB3 holds radiosity
        // lst:3: the distant probe's irradiance at the normal on the leaf colour as GB1 stores it,
        // E(n)·ρ/π (half precision), E from the environment's SH as the shaders evaluate it.
        const glm::vec3 n(ch("normal").v[0], ch("normal").v[1], ch("normal").v[2]);
        const float radiosity = ch("baseColor").v[1] * shIrradiance(n).y / 3.14159265f;
        EXPECT_GT(radiosity, 0.0f);
        EXPECT_NEAR(ch("emissive").v[1], radiosity, radiosity * 3e-3f);
    }
}

// Seed 000 lst:3 and 002 §4.10.3: foliage's indirect diffuse is the fix-up's radiosity alone (the
// probe at the normal), not that plus the lighting's probe diffuse. Under the sky alone the
// foliage box's face is what a box of no diffuse colour with its specular shows, plus E(n)·ρ/π.
TEST_F(SceneRender, FoliageTakesTheProbesDiffuseOnce) {
    auto leaf = render("scripts/pipelines/deferred.lua", {"GB0", "GB1", "GB2", "GB3"}, "",
                       "foliage_ibl.lua");
    const glm::ivec2 px(W / 2, H / 2);
    LayoutInfo info;
    auto g = gbufferAt(*leaf, px, info);
    auto ch = [&](const char* n) { return g[static_cast<size_t>(info.find(n))]; };
    const glm::vec3 n(ch("normal").v[0], ch("normal").v[1], ch("normal").v[2]);
    ASSERT_GT(n.z, 0.99f);
    const glm::vec3 rho(ch("baseColor").v[0], ch("baseColor").v[1], ch("baseColor").v[2]);
    const glm::vec3 E = shIrradiance(n);
    auto foliage = readAbsoluteHdr(s_runtime->executor(), leaf->pipeline());
    ASSERT_TRUE(foliage.has_value());
    leaf.reset();
    auto black =
        render("scripts/pipelines/deferred.lua", {}, "", "foliage_ibl.lua", {{"model", "black"}});
    auto specular = readAbsoluteHdr(s_runtime->executor(), black->pipeline());
    ASSERT_TRUE(specular.has_value());
    for (int c = 0; c < 3; ++c) {
        const float got = foliage->image.at(px.x, px.y, static_cast<uint32_t>(c));
        const float expected =
            specular->image.at(px.x, px.y, static_cast<uint32_t>(c)) + rho[c] * E[c] / 3.14159265f;
        std::printf("channel %d: foliage %.2f nits, specular alone %.2f + E·ρ/π %.2f = %.2f\n", c,
                    got, specular->image.at(px.x, px.y, static_cast<uint32_t>(c)),
                    rho[c] * E[c] / 3.14159265f, expected);
        EXPECT_NEAR(got / expected, 1.0f, 0.02f) << "channel " << c;
    }
}

TEST_F(SceneRender, StencilClassesRouteEveryMaterial) {
    auto s = render("scripts/pipelines/deferred.lua", {}, "stencil");
    auto view = s_runtime->executor().readback("debug_view");
    ASSERT_TRUE(view.has_value());
    auto rgbAt = [&](glm::vec3 p) {
        glm::ivec2 px = pixelOf(*s, p);
        return glm::vec3(view->at(uint32_t(px.x), uint32_t(px.y), 0),
                         view->at(uint32_t(px.x), uint32_t(px.y), 1),
                         view->at(uint32_t(px.x), uint32_t(px.y), 2));
    };
    // The view paints class i with palette entry i: lit_standard red, lit_clearcoat green, foliage
    // blue, lit_two_colour yellow.
    EXPECT_NEAR(glm::distance(rgbAt(kStandard), glm::vec3(0.9f, 0.2f, 0.2f)), 0.0f, 0.01f);
    EXPECT_NEAR(glm::distance(rgbAt(kCoated), glm::vec3(0.2f, 0.8f, 0.2f)), 0.0f, 0.01f);
    EXPECT_NEAR(glm::distance(rgbAt(kBush), glm::vec3(0.2f, 0.4f, 0.9f)), 0.0f, 0.01f);
    EXPECT_NEAR(glm::distance(rgbAt({-2.3f, 0.5f, 0.2f}), glm::vec3(0.9f, 0.8f, 0.2f)), 0.0f,
                0.01f);  // lit_two_colour
    // The sky (nothing drawn) keeps stencil 0: black.
    EXPECT_EQ(view->at(W / 2, 2, 0), 0.0f);
}

TEST_F(SceneRender, ClearCoatAddsItsSecondLobe) {
    // One red sphere lit by a lamp beside the camera, as a standard material, as a clear coat of
    // strength 0 (must light exactly like the standard) and of strength 1 (a second, sharp lobe).
    auto hdrOf = [&](const std::string& material) {
        const std::string file = std::string(RG_TEST_TMP) + "/coat_scene.lua";
        std::ofstream(file)
            << "local scene = require 'scene'\n"
            << "scene.material 'm' { " << material << " }\n"
            << "scene.sphere 'ball' { radius = 0.5, position = { 0, 0, 0 }, material = 'm', "
               "segments = 64 }\n"
            << "scene.light 'lamp' { type = 'point', intensity = 2000, unit = 'lm', position = { "
               "0.6, 0.6, 2.0 } }\n"
            << "scene.camera 'main' { position = { 0, 0, 2.5 }, target = { 0, 0, 0 }, fov = 30 }\n";
        SessionOptions o;
        // 256 x 256 puts a pixel exactly where N·V = 1 (with lst:2's +1e-5, NdotV > 1: a NaN
        // once came from pow of a negative base there).
        o.compile.outputWidth = 256;
        o.compile.outputHeight = 256;
        o.scene = file;
        Session s(*s_runtime, o);
        auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        setManualExposure(s);
        EXPECT_TRUE(s.frame().has_value());
        EXPECT_TRUE(s.frame().has_value());
        auto hdr = s_runtime->executor().readback("hdr");
        EXPECT_TRUE(hdr.has_value());
        return *hdr;
    };
    const std::string base = "base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.5";
    Image standard = hdrOf(base);
    Image noCoat = hdrOf("model = 'clear_coat', " + base +
                         ", params = { coatStrength = 0, coatSmoothness = 0.8 }");
    Image coat = hdrOf("model = 'clear_coat', " + base +
                       ", params = { coatStrength = 1, coatSmoothness = 0.8 }");
    double maxDiff = 0, peakStandard = 0, peakCoat = 0;
    for (size_t i = 0; i < standard.pixels.size(); ++i) {
        maxDiff = std::max(maxDiff, double(std::abs(standard.pixels[i] - noCoat.pixels[i])) /
                                        (1e-3 + std::abs(standard.pixels[i])));
        const double x = double((i / 4) % 256) - 128.0, y = double((i / 4) / 256) - 128.0;
        if (i % 4 == 1 &&
            x * x + y * y < 80.0 * 80.0) {  // green, on the ball: specular only (the ball is red)
            peakStandard = std::max(peakStandard, double(standard.pixels[i]));
            peakCoat = std::max(peakCoat, double(coat.pixels[i]));
        }
    }
    EXPECT_LT(maxDiff,
              2e-3);  // strength 0: the clear-coat path lights exactly like the standard one
    EXPECT_GT(peakCoat, 5.0 * peakStandard);  // the coat's smooth lobe
    for (const Image* img : {&standard, &noCoat, &coat})
        for (float v : img->pixels) ASSERT_TRUE(std::isfinite(v));
}

TEST_F(SceneRender, TogglingPassesPreparesNoOtherPass) {
    // The default pipeline on the default scene: its first frame switches the decal passes, the
    // forward pass and the maps' clears off (rg.frame: the scene has no decals, no blended draws,
    // and a sun). That callback runs at the load, whose plan leaves them out: they are never
    // prepared and the first frame rebuilds nothing. A later switch keeps the memory placement
    // (CompileOptions::previous), so no resource is created anew and no other pass is prepared;
    // switching a pass off and on again prepares that pass alone.
    SessionOptions o;
    o.compile.outputWidth = 96;
    o.compile.outputHeight = 64;
    o.scene = kRoot + "/scripts/scenes/default.lua";
    Session s(*s_runtime, o);
    auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    const std::vector<std::string> loaded = s_runtime->executor().lastBuildReport().passesPrepared;
    // The scene's materials are all standard: the clear-coat and two-colour lighting passes and the
    // foliage fix-up, which work on their stencil classes' pixels only, are off too.
    for (const char* off : {"decals", "decals_copy0", "forward", "shadow_clear0",
                            "lighting_clearcoat", "lighting_two_colour", "foliage_fixup"})
        EXPECT_EQ(std::count(loaded.begin(), loaded.end(), off), 0) << off << " was prepared";
    EXPECT_EQ(std::count(loaded.begin(), loaded.end(), "gbuffer"), 1);
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(s.rebuilds(), 0u);
    ASSERT_TRUE(s.setPassOverride("sky", false).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_TRUE(s_runtime->executor().lastBuildReport().passesPrepared.empty())
        << s_runtime->executor().lastBuildReport().summary();
    ASSERT_TRUE(s.setPassOverride("sky", true).has_value());
    ASSERT_TRUE(s.frame().has_value());
    EXPECT_EQ(s_runtime->executor().lastBuildReport().passesPrepared,
              (std::vector<std::string>{"sky"}));
    EXPECT_EQ(s_runtime->executor().lastBuildReport().resourcesCreated, 0u);
}

// A scene that draws the clear-coat, two-colour and foliage materials (materials.lua) keeps the
// passes of their stencil classes (lighting.per_class), and its rg.frame sees the draws per class.
TEST_F(SceneRender, PassesOfTheSceneStencilClassesRun) {
    Session s(*s_runtime, sceneOptions(kRoot + "/tests/gpu/scenes/materials.lua", {}, 96, 64));
    ASSERT_TRUE(s.load(kRoot + "/scripts/pipelines/deferred.lua").has_value());
    const std::vector<std::string> loaded = s_runtime->executor().lastBuildReport().passesPrepared;
    for (const char* on : {"lighting_clearcoat", "lighting_two_colour", "foliage_fixup"})
        EXPECT_EQ(std::count(loaded.begin(), loaded.end(), on), 1) << on << " was not prepared";
}

TEST_F(SceneRender, DecalsBlendTheCommonParametersOnly) {
    // materials.lua's "stain" decal (red, smoothness 0.9, metal 1, opacity 0.8) covers part of the
    // floor (materialId 0) and of the clear-coat sphere (its own layout).
    auto s = render("scripts/pipelines/deferred.lua", {"GB0", "GB1", "GB2", "GB3"});
    LayoutInfo info;
    auto floor = gbufferAt(*s, pixelOf(*s, {0.5f, 0.0f, 0.8f}), info);
    auto f = [&](const char* n) { return floor[static_cast<size_t>(info.find(n))]; };
    EXPECT_EQ(f("materialId").u[0], 0u);
    EXPECT_NEAR(srgbEncode(f("baseColor").v[0]), srgbEncode(0.2f * 0.2f + 0.9f * 0.8f), 1.0f / 255);
    EXPECT_NEAR(f("smoothness").v[0], 0.3f * 0.2f + 0.9f * 0.8f, 1.0f / 1023);
    EXPECT_NEAR(f("metalMask").v[0], 0.8f, 1.0f / 255);  // base material: metal mask blends
    LayoutInfo coatInfo;
    auto coat = gbufferAt(*s, pixelOf(*s, {0.3f, 0.5f, 0.4f}), coatInfo, "clearcoat");
    auto c = [&](const char* n) { return coat[static_cast<size_t>(coatInfo.find(n))]; };
    EXPECT_NEAR(c("coatWeight").v[0], 1.0f, 1e-6f);  // the coat's strength survives
    EXPECT_EQ(c("metalMask").v[0], 0.0f);            // not on the clear coat
    EXPECT_NEAR(srgbEncode(c("baseColor").v[0]), srgbEncode(0.8f * 0.2f + 0.9f * 0.8f), 1.0f / 255);
}

// The oxide sphere of materials.lua (two-colour, tbl:3) and the "patch" decal over its front.
const glm::vec3 kOxide{-2.3f, 0.5f, 0.2f}, kOxideEdge{-2.3f, 0.95f, -0.1f};

TEST_F(SceneRender, TwoColourMaterialFillsItsLayout) {
    auto s = render("scripts/pipelines/deferred.lua", {"GB0", "GB1", "GB2", "GB3"});
    LayoutInfo layoutInfo;
    const LayoutInfo* info = &layoutInfo;
    auto at = [&](glm::vec3 point) {
        return gbufferAt(*s, pixelOf(*s, point), layoutInfo, "two_colour");
    };
    // Above the decal: the material as declared, each channel within its encoding.
    auto g = at(kOxideEdge);
    auto ch = [&](const char* n) { return g[static_cast<size_t>(info->find(n))]; };
    EXPECT_EQ(ch("materialId").u[0], 2u);
    EXPECT_NEAR(srgbEncode(ch("diffuseColor").v[0]), srgbEncode(0.30f), 0.5f / 255 + 1e-4f);
    EXPECT_NEAR(srgbEncode(ch("diffuseColor").v[1]), srgbEncode(0.12f), 0.5f / 255 + 1e-4f);
    EXPECT_NEAR(srgbEncode(ch("diffuseColor").v[2]), srgbEncode(0.05f), 0.5f / 255 + 1e-4f);
    EXPECT_NEAR(ch("f0").v[0], 0.35f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(ch("f0").v[1], 0.25f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(ch("f0").v[2], 0.20f, 0.5f / 255 + 1e-5f);
    EXPECT_NEAR(ch("smoothness").v[0], 0.5f, 0.5f / 1023 + 1e-5f);
    EXPECT_NEAR(ch("ao").v[0], 1.0f, 1e-6f);
    // Under the decal (blue, opacity 0.5, smoothness 0.9, metal 1, reflectance 1): base colour
    // blends into the diffuse colour and smoothness blends; f0 — the two-colour material's
    // specular, like MetalMask/Reflectance on the base material — is left exactly as it was.
    auto d = at(kOxide);
    auto dc = [&](const char* n) { return d[static_cast<size_t>(info->find(n))]; };
    EXPECT_EQ(dc("materialId").u[0], 2u);
    EXPECT_NEAR(srgbEncode(dc("diffuseColor").v[2]), srgbEncode(0.05f * 0.5f + 0.8f * 0.5f),
                1.0f / 255);
    EXPECT_NEAR(dc("smoothness").v[0], 0.5f * 0.5f + 0.9f * 0.5f, 1.0f / 1023);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(dc("f0").v[c], ch("f0").v[c]) << "f0[" << c << "]";
    EXPECT_EQ(dc("ao").v[0], ch("ao").v[0]);
}

// A material model's own textures (rg.material's `textures`, a scene material's `textures`): the
// clear coat's coatStrengthMap (R × strength) and coatRoughnessMap (G × roughness), the two-colour
// material's specularGlossinessMap (RGB × f0, A × smoothness), each read at the surface's uv into
// the G-buffer — left half of each plane the texture's left texel, right half its right one. A
// texture name the model does not declare is refused naming the scene's material.
TEST_F(SceneRender, MaterialModelsReadTheirOwnTextures) {
    const std::string dir = RG_TEST_TMP;
    std::filesystem::create_directories(dir);
    // 8×1: four texels of `left`, four of `right` (bilinear filtering at a half's middle reads
    // that half's value alone).
    auto png = [&](const char* name, std::vector<float> both) {
        Image img(8, 1, 4);
        for (uint32_t x = 0; x < 8; ++x)
            for (uint32_t c = 0; c < 4; ++c) img.pixels[4 * x + c] = both[(x < 4 ? 0 : 4) + c];
        EXPECT_TRUE(writePng(dir + "/" + name, img).has_value());
    };
    png("coat.png", {1, 1, 1, 1, 0, 0, 0, 1});
    png("rough.png", {0, 0.5f, 0, 1, 0, 1, 0, 1});
    png("specgloss.png", {1, 0.5f, 0.25f, 1, 0.2f, 0.2f, 0.2f, 0.5f});
    auto write = [&](const std::string& coatTextures) {
        const std::string file = dir + "/own_textures.lua";
        std::ofstream(file)
            << "local scene = require 'scene'\n"
            << "scene.material 'coat' { model = 'clear_coat', base_color = { 0.5, 0.1, 0.1 }, "
               "params = { coatStrength = 1, coatSmoothness = 0.8 }, textures = { "
            << coatTextures << " } }\n"
            << "scene.material 'oxide' { model = 'two_colour', diffuse_color = { 0.2, 0.2, 0.2 }, "
               "f0 = { 0.5, 0.5, 0.5 }, smoothness = 0.8, textures = { specularGlossinessMap = "
               "'specgloss.png' } }\n"
            << "scene.plane 'top' { size = { 2, 1 }, position = { 0, 0.6, 0 }, rotation = { 90, "
               "0, 0 }, material = 'coat' }\n"
            << "scene.plane 'bottom' { size = { 2, 1 }, position = { 0, -0.6, 0 }, rotation = { "
               "90, 0, 0 }, material = 'oxide' }\n"
            << "scene.camera 'main' { position = { 0, 0, 4 }, target = { 0, 0, 0 }, fov = 40 }\n";
        return file;
    };
    SessionOptions o;
    o.compile.outputWidth = W;
    o.compile.outputHeight = H;
    o.paramsIfDeclared["specular_aa"] = Value(false);
    o.scene = write("coatStrengthMap = 'coat.png', coatRoughnessMap = 'rough.png'");
    o.captures = {"GB0", "GB1", "GB2", "GB3"};
    Session s(*s_runtime, o);
    auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    ASSERT_TRUE(s.frame().has_value());
    auto decode = [&](const char* layout, glm::vec3 point) {
        LayoutInfo info;
        auto values = gbufferAt(s, pixelOf(s, point), info, layout);
        std::map<std::string, ChannelValue> out;
        for (const auto& t : info.desc.targets)
            for (const auto& c : t.channels) out[c.name] = values[size_t(info.find(c.name))];
        return out;
    };
    // Clear coat: strength 1 × R (1 | 0); smoothness 1 − 0.2 × G (0.5 | 1).
    auto coatLeft = decode("clearcoat", {-0.5f, 0.6f, 0}),
         coatRight = decode("clearcoat", {0.5f, 0.6f, 0});
    EXPECT_NEAR(coatLeft["coatWeight"].v[0], 1.0f, 1e-6f);
    EXPECT_NEAR(coatRight["coatWeight"].v[0], 0.0f, 1e-6f);
    EXPECT_NEAR(coatLeft["coatGloss"].v[0], 1.0f - 0.2f * 128.0f / 255.0f, 0.5f / 255 + 1e-3f);
    EXPECT_NEAR(coatRight["coatGloss"].v[0], 0.8f, 0.5f / 255 + 1e-3f);
    // Two-colour: f0 0.5 × RGB, smoothness 0.8 × A.
    auto oxideLeft = decode("two_colour", {-0.5f, -0.6f, 0}),
         oxideRight = decode("two_colour", {0.5f, -0.6f, 0});
    const float f0Left[3] = {0.5f, 0.5f * 128.0f / 255.0f, 0.5f * 64.0f / 255.0f};  // 8-bit texels
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(oxideLeft["f0"].v[c], f0Left[c], 1.0f / 255 + 1e-3f) << c;
        EXPECT_NEAR(oxideRight["f0"].v[c], 0.5f * 51.0f / 255.0f, 1.0f / 255 + 1e-3f) << c;
    }
    EXPECT_NEAR(oxideLeft["smoothness"].v[0], 0.8f, 1.0f / 1023 + 1e-3f);
    EXPECT_NEAR(oxideRight["smoothness"].v[0], 0.8f * 128.0f / 255.0f, 1.0f / 1023 + 1e-3f);

    // exportGlb keeps them (extras.rgraph.textures): loaded back, each material has its model's
    // textures by name, on the same image, with the same encoding.
    ASSERT_TRUE(exportGlb(*s.scene(), dir + "/own_textures.glb"));
    auto back = loadGltf(dir + "/own_textures.glb");
    ASSERT_TRUE(back.has_value()) << back.error().message;
    for (const Material& m : s.scene()->materials) {
        auto it = std::find_if(back->materials.begin(), back->materials.end(),
                               [&](const Material& x) { return x.name == m.name; });
        ASSERT_NE(it, back->materials.end()) << m.name;
        for (const auto& [name, ref] : m.textures) {
            if (!ref.valid()) continue;
            ASSERT_TRUE(it->textures.count(name) && it->textures.at(name).valid()) << name;
            const SceneImage& a = s.scene()->images[size_t(ref.image)];
            const SceneImage& b = back->images[size_t(it->textures.at(name).image)];
            EXPECT_EQ(a.srgb, b.srgb) << name;
            EXPECT_EQ(a.pixels.pixels, b.pixels.pixels) << name;
        }
    }

    // A texture the clear coat does not have.
    SessionOptions bad = o;
    bad.scene = write("coatTintMap = 'coat.png'");
    Session b(*s_runtime, bad);
    auto e = b.load(kRoot + "/scripts/pipelines/deferred.lua");
    ASSERT_FALSE(e.has_value());
    EXPECT_NE(e.error().message.find("own_textures.lua:2: scene.material.coat.textures."
                                     "coatTintMap: model 'clear_coat' has no texture "
                                     "'coatTintMap'"),
              std::string::npos)
        << e.error().message;
}

TEST_F(SceneRender, TwoColourLightsAsTheStandardMaterialItConvertsFrom) {
    // tbl:3 / fig:14: Disney -> two-colour is diffuse = base·(1 − metal), f0 = lerp(0.16·refl², base,
    // metal). A ball of each kind, lit by a lamp, must give the same image up to the encodings
    // (sRGB 8-bit base colour vs linear 8-bit f0), and only the two-colour path lights it.
    auto hdrOf = [&](const std::string& material, bool twoColourPass = true) {
        const std::string file = std::string(RG_TEST_TMP) + "/two_colour_scene.lua";
        std::ofstream(file)
            << "local scene = require 'scene'\n"
            << "scene.material 'm' { " << material << " }\n"
            << "scene.sphere 'ball' { radius = 0.5, position = { 0, 0, 0 }, material = 'm', "
               "segments = 64 }\n"
            << "scene.light 'lamp' { type = 'point', intensity = 2000, unit = 'lm', position = { "
               "0.6, 0.6, 2.0 } }\n"
            << "scene.camera 'main' { position = { 0, 0, 2.5 }, target = { 0, 0, 0 }, fov = 30 }\n";
        SessionOptions o;
        o.compile.outputWidth = 128;
        o.compile.outputHeight = 128;
        o.scene = file;
        o.params["exposure_mode"] = Value("manual");
        if (!twoColourPass)
            o.frameHook = [](const FrameContext&, const PipelineDesc&) -> Result<FrameChanges> {
                FrameChanges c;
                c.enabled["lighting_two_colour"] = false;
                return c;
            };
        Session s(*s_runtime, o);
        auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        EXPECT_TRUE(s.frame().has_value());
        auto hdr = s_runtime->executor().readback("hdr");
        EXPECT_TRUE(hdr.has_value());
        return *hdr;
    };
    auto compareBall = [](const Image& a, const Image& b, double& mean, double& worst) {
        double sum = 0;
        size_t n = 0;
        worst = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            const double x = double((i / 4) % 128) - 64.0, y = double((i / 4) / 128) - 64.0;
            if (i % 4 == 3 || x * x + y * y > 40.0 * 40.0) continue;  // the ball's inside
            const double e = std::abs(double(a.pixels[i]) - b.pixels[i]) /
                             std::max(1e-3, std::abs(double(b.pixels[i])));
            sum += e;
            worst = std::max(worst, e);
            ++n;
        }
        mean = sum / double(n);
    };
    double mean = 0, worst = 0;
    // A metal: all specular, f0 = the base colour.
    Image gold = hdrOf("base_color = { 1.0, 0.766, 0.336 }, metal_mask = 1, smoothness = 0.6");
    Image goldTwo = hdrOf(
        "model = 'two_colour', diffuse_color = { 0, 0, 0 }, f0 = { 1.0, 0.766, 0.336 }, smoothness "
        "= 0.6");
    compareBall(goldTwo, gold, mean, worst);
    std::printf("metal: mean %.4f %%, worst %.4f %%\n", 100 * mean, 100 * worst);
    EXPECT_LT(mean, 0.005);
    EXPECT_LT(worst, 0.02);
    // A dielectric: diffuse = the base colour, f0 = 0.16 · 0.5² = 0.04 (8-bit linear: 10/255).
    Image red = hdrOf("base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.5");
    Image redTwo = hdrOf(
        "model = 'two_colour', diffuse_color = { 0.8, 0.05, 0.05 }, f0 = { 0.04, 0.04, 0.04 }, "
        "smoothness = 0.5");
    compareBall(redTwo, red, mean, worst);
    std::printf("dielectric: mean %.4f %%, worst %.4f %%\n", 100 * mean, 100 * worst);
    EXPECT_LT(mean, 0.01);
    EXPECT_LT(worst, 0.04);
    // Stencil routing: without its lighting pass the two-colour ball is black (no other path
    // touches it); the standard ball is lit by the standard path alone, so it does not change.
    Image unlit = hdrOf(
        "model = 'two_colour', diffuse_color = { 0.8, 0.05, 0.05 }, f0 = { 0.04, 0.04, 0.04 }, "
        "smoothness = 0.5",
        false);
    Image redNoTwoPass = hdrOf("base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.5", false);
    double lit = 0;
    for (size_t i = 0; i < unlit.pixels.size(); i += 4) {
        const double x = double((i / 4) % 128) - 64.0, y = double((i / 4) / 128) - 64.0;
        if (x * x + y * y > 40.0 * 40.0) continue;
        EXPECT_EQ(unlit.pixels[i], 0.0f);
        lit += redTwo.pixels[i];
    }
    EXPECT_GT(lit, 0.0);
    EXPECT_EQ(redNoTwoPass.pixels, red.pixels);
}

TEST_F(SceneRender, FullSunKeepsEveryHdrTargetFinite) {
    // Issue figure: the sun test scene (100 000 lux) has no infinities or NaNs in any HDR target.
    SessionOptions o;
    o.compile.outputWidth = W;
    o.compile.outputHeight = H;
    o.scene = kRoot + "/tests/gpu/scenes/sun.lua";
    o.captures = {"GB3", "hdr", "bloom_down1", "bloom_down3", "bloom_down5", "bloom_up1"};
    Session s(*s_runtime, o);
    auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    for (int f = 0; f < 4; ++f) ASSERT_TRUE(s.frame().has_value());
    for (const auto& name : o.captures) {
        auto img = s_runtime->executor().readback(name);
        ASSERT_TRUE(img.has_value()) << name;
        for (float v : img->pixels) ASSERT_TRUE(std::isfinite(v)) << name;
    }
    // The white floor in full sun: E·ρ/π·(diffuse term) ≈ 100 000 · 0.9 / π · cosθ ≈ 26 000 cd/m²,
    // far past half precision without pre-exposure; the metered EV100 lands near 15 (sunny 16).
    auto state = s_runtime->executor().readbackBuffer("exposure");
    ASSERT_TRUE(state.has_value());
    float ev = 0;
    std::memcpy(&ev, state->data(), sizeof ev);
    EXPECT_GT(ev, 13.5f);
    EXPECT_LT(ev, 17.5f);
}

TEST_F(SceneRender, BlendedMaterialsGoForwardOverTheLitImage) {
    // The glass pane of materials.lua (opacity 0.35) in front of the standard sphere: not in the
    // G-buffer (materialId behind it stays the sphere's), and at opacity 0 the image is unchanged.
    auto hdrWith = [&](const std::string& opacity, std::vector<std::string> captures) {
        const std::string file = std::string(RG_TEST_TMP) + "/forward_scene.lua";
        std::ifstream in(kRoot + "/tests/gpu/scenes/materials.lua");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        text.replace(text.find("opacity = 0.35"), 14, "opacity = " + opacity);
        std::ofstream(file) << text;
        SessionOptions o;
        o.compile.outputWidth = W;
        o.compile.outputHeight = H;
        o.scene = file;
        o.captures = std::move(captures);
        auto s = std::make_unique<Session>(*s_runtime, o);
        EXPECT_TRUE(s->load(kRoot + "/scripts/pipelines/deferred.lua").has_value());
        setManualExposure(*s);
        EXPECT_TRUE(s->frame().has_value());
        EXPECT_TRUE(s->frame().has_value());
        return s;
    };
    const glm::vec3 paneCentre{-0.6f, 0.5f, 1.0f};
    auto clear = hdrWith("0", {"GB0"});
    auto hidden = s_runtime->executor().readback("hdr");
    auto tinted = hdrWith("0.35", {"GB0", "GB1", "GB2", "GB3"});
    auto seen = s_runtime->executor().readback("hdr");
    ASSERT_TRUE(hidden.has_value() && seen.has_value());
    const glm::ivec2 px = pixelOf(*tinted, paneCentre);
    LayoutInfo info;
    auto g = gbufferAt(*tinted, px, info);
    EXPECT_EQ(g[static_cast<size_t>(info.find("materialId"))].u[0], 0u);  // the sphere behind
    EXPECT_NE(seen->at(uint32_t(px.x), uint32_t(px.y), 2),
              hidden->at(uint32_t(px.x), uint32_t(px.y), 2));
    (void)clear;
}

}  // namespace

TEST_F(SceneRender, LevelsOfDetailFollowTheProjectedErrorAndKeepTheImage) {
    // The default scene's 48-segment spheres carry a 24-segment level (graph/scene makeSphere).
    // Each frame the camera's passes take, per draw, the coarsest level whose error spans at most
    // a pixel at the nearest view depth of its box — computed here again from the camera: at
    // 1280×720 every sphere takes 24 segments, and with the camera 1.5 m from the front row the
    // spheres within ~7.7 m keep their full mesh.
    auto scene = loadSceneScript(kRoot + "/scripts/scenes/default.lua", {});
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    auto levels = [&](const Scene& sc, uint32_t w, uint32_t h) {
        auto gpu = passes::GpuScene::create(s_runtime->gpu(), sc);
        EXPECT_TRUE(gpu.has_value()) << gpu.error().describe();
        passes::GpuScene& g = **gpu;
        g.updateFrame(0, w, h);
        const Camera& c = sc.cameras.front();
        const glm::vec3 forward = glm::normalize(c.target - c.position);
        const float pixelsPerMetre =
            0.5f * float(h) / std::tan(0.5f * c.verticalFov);  // at a depth of 1 m
        std::vector<uint32_t> out;
        for (size_t d = 0; d < g.draws().size(); ++d) {
            const passes::DrawItem& item = g.draws()[d];
            uint32_t level = 0;
            while (level < item.lodCount && item.lods[level].firstIndex != g.viewLod(d).firstIndex)
                ++level;
            EXPECT_LT(level, item.lodCount) << "draw " << d;
            float nearest = 1e30f;
            for (int k = 0; k < 8; ++k)
                nearest = std::min(nearest,
                                   glm::dot(glm::vec3(k & 1 ? item.boundsMax.x : item.boundsMin.x,
                                                      k & 2 ? item.boundsMax.y : item.boundsMin.y,
                                                      k & 4 ? item.boundsMax.z : item.boundsMin.z) -
                                                c.position,
                                            forward));
            uint32_t expected = 0;
            for (uint32_t l = 1; l < item.lodCount; ++l)
                if (nearest > c.nearPlane && item.lods[l].error * pixelsPerMetre / nearest <= 1.0f)
                    expected = l;
            EXPECT_EQ(level, expected) << "draw " << d << " at " << w << "x" << h;
            if (item.lodCount > 1) out.push_back(level);
        }
        return out;
    };
    const auto hd = levels(*scene, 1280, 720);
    ASSERT_EQ(hd.size(), 49u);  // the spheres
    EXPECT_EQ(std::count(hd.begin(), hd.end(), 1u), 49);
    Scene close = *scene;
    close.cameras.front().position =
        glm::vec3(-3.3f, 0.45f, 4.8f);  // 1.5 m in front of the front row's first sphere
    close.cameras.front().target = glm::vec3(-3.3f, 0.45f, 3.3f);
    const auto near = levels(close, 1280, 720);
    EXPECT_GE(std::count(near.begin(), near.end(), 0u), 1)
        << "the spheres near the camera keep their full mesh";

    // The image with and without them (RG_LOD=0): silhouettes move by under a pixel and the
    // shading follows the coarser triangles' interpolated normals, which the mirror-like spheres'
    // reflections show most.
    const std::string file = kRoot + "/scripts/scenes/default.lua";
    const Image a = renderHdr(file, true, 640, 360), b = renderHdr(file, false, 640, 360);
    ASSERT_EQ(a.width, 640u);
    ASSERT_EQ(b.width, 640u);
    const RenderDifference d = greenDifference(a, b);
    std::printf(
        "with levels of detail: mean |difference| %.3f %% of the mean, %.2f %% of pixels off by "
        "more than 5 %%\n",
        100.0 * d.mean, 100.0 * d.share);
    EXPECT_LT(d.mean, 0.02);
    EXPECT_LT(d.share, 0.04);
}
