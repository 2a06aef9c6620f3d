// A pixel's material is its stencil value (MaterialDesc::identity): rendered on lavapipe with the
// validation layer. A layout that keeps the normal in GB2 instead of GB0 casts and receives the
// sun's shadows and reflects (SSR) as the standard layout does; 64 materials over ten lighting
// paths of their own layouts coexist in the default pipeline, each decoded, lit and painted by
// decals as its own declaration says; the skin example package's wrapped diffuse gathers what
// Lambert does and reaches further round the terminator in red than in blue.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

#include "image/image.h"
#include "lua/lua_host.h"
#include "lua/pipeline.h"
#include "runtime/runtime.h"
#include "runtime/session.h"

using namespace rg;
namespace fs = std::filesystem;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;

class MaterialIdentity : public GpuFixture {};

// The standard material's parameters in another layout, shaded by the standard path's rgShade:
// metal mask and reflectance in GB0, the base colour in GB1, the normal (octahedral, 16 bits
// where the disney layout has 20), smoothness and AO in GB2.
const char* kMovedPackage = R"(local rg = require "rg"
local lighting = require "lighting"
local ibl = require "ibl"
local probes = require "probes"
local ssr = require "ssr"
local reflections = require "reflections"
local ao = require "ao"
local shadows = require "shadows"
require "disney"
rg.layout "moved" {
    { "GB0", "rgb10a2",    { "metalMask:unorm:10", "reflectance:unorm:10", "pad:unorm:10", "spare:uint:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "unused:uint:8" } },
    { "GB2", "rgba8",      { "normal:oct:16", "smoothness:unorm:8", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3" } },
}
rg.stencil "lit_moved" {}
rg.path "moved" { stencil = "lit_moved", shading = "moved_shading.glsl" }
rg.material "moved" { layout = "moved", path = "moved", surface = "moved.glsl",
                      decals = { "normal", "baseColor", "smoothness", "metalMask", "reflectance" } }
rg.pass "lighting_moved" (reflections.lit(ssr.lit(shadows.masked(ao.lit(probes.lit(ibl.lit(
    lighting.path_pass { path = "moved", class = "lit_moved" })))))))
lighting.per_class("lighting_moved", "lit_moved")
)";
const char* kMovedSurface = R"(GBuffer_moved rgSurface(RgSurface s) {
    GBuffer_moved g;
    g.metalMask = s.metalMask; g.reflectance = s.reflectance; g.pad = 0.0; g.spare = 0u;
    g.baseColor = s.baseColor; g.unused = 0u;
    g.normal = s.normal; g.smoothness = s.smoothness; g.ao = s.ao;
    g.emissive = s.emissive;
    return g;
}
)";
const char* kMovedShading = R"(#include "gbuffer_disney.glsl"
#include "materials/standard_shading.glsl"
vec3 rgShade(GBuffer_moved g, vec3 position, vec3 V, ivec2 pixel) {
    GBuffer_disney d;
    d.normal = g.normal; d.smoothness = g.smoothness; d.materialId = 0u;
    d.baseColor = g.baseColor; d.materialData = 0u; d.normalExtra = 0u;
    d.reserved = 0.0; d.metalMask = g.metalMask; d.reflectance = g.reflectance; d.ao = g.ao;
    d.emissive = g.emissive;
    return rgShade(d, position, V, pixel);
}
)";
// A smooth floor that reflects two spheres (SSR) and receives their shadows from a low sun; every
// material of scene.args.model.
const char* kMovedScene = R"(local scene = require "scene"
local model = scene.args.model
scene.material "floor" { model = model, base_color = { 0.3, 0.3, 0.3 }, smoothness = 0.92 }
scene.material "red" { model = model, base_color = { 0.8, 0.1, 0.1 }, smoothness = 0.5 }
scene.material "gold" { model = model, base_color = { 1.0, 0.77, 0.34 }, metal_mask = 1, smoothness = 0.8 }
scene.plane "floor" { size = { 8, 8 }, material = "floor" }
scene.sphere "a" { radius = 0.45, position = { -0.6, 0.45, 0 }, material = "red" }
scene.sphere "b" { radius = 0.45, position = { 0.6, 0.45, -0.4 }, material = "gold" }
scene.light "sun" { type = "sun", intensity = 20000, unit = "lux", direction = { -0.6, -0.45, -0.66 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.2, 3.2 }, target = { 0, 0.3, 0 }, fov = 50, aperture = 16, shutter = 1 / 125, iso = 100 }
)";

TEST_F(MaterialIdentity, ALayoutWithTheNormalInGB2CastsAndReflectsAsTheStandardOne) {
    TempFolder tmp("moved");
    std::ofstream(tmp.dir / "moved.lua") << kMovedPackage;
    std::ofstream(tmp.dir / "moved.glsl") << kMovedSurface;
    std::ofstream(tmp.dir / "moved_shading.glsl") << kMovedShading;
    std::ofstream(tmp.dir / "pipeline.lua")
        << "require \"pipelines.deferred\"\nrequire \"moved\"\n";
    std::ofstream(tmp.dir / "scene.lua") << kMovedScene;
    constexpr uint32_t w = 160, h = 120;
    auto render = [&](const char* model) {
        SessionOptions o = sceneOptions((tmp.dir / "scene.lua").string(), {{"model", model}}, w, h);
        return renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 2,
                             {"hdr", "sun_visibility", "ssr"});
    };
    const Readback standard = render("standard"), moved = render("moved");
    ASSERT_EQ(standard.images.size(), 3u);
    ASSERT_EQ(moved.images.size(), 3u);
    // The sun's mask: the same pixels shadowed (the normal offsets the lookups and ends the sun at
    // the terminator; decoded from GB0 as the disney layout, the moved pixels' normal would be
    // their metal mask and reflectance, one direction for the whole floor).
    const Image &vs = standard["sun_visibility"], &vm = moved["sun_visibility"];
    size_t differ = 0, shadowed = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            shadowed += vs.at(x, y, 0) < 0.5f;
            differ += std::abs(vs.at(x, y, 0) - vm.at(x, y, 0)) > 0.1f;
        }
    EXPECT_GT(shadowed, size_t(w * h / 40)) << "the scene has shadows to compare";
    EXPECT_LT(differ, size_t(w * h / 500)) << differ << " of " << w * h << " pixels";
    // The reflection SSR traced: as much of it, within the 16-bit normal's quantisation (its
    // tilt, a fraction of a degree, moves hits across the spheres' edges, so pixels are not
    // compared one by one); and the lit image, mean difference relative to the mean.
    auto sum = [](const Image& a) {
        double s = 0;
        for (size_t i = 0; i < a.pixels.size(); i += a.channels)
            for (uint32_t c = 0; c < 3; ++c) s += a.pixels[i + c];
        return s;
    };
    auto meanDiff = [](const Image& a, const Image& b) {
        double d = 0, s = 0;
        for (size_t i = 0; i < a.pixels.size(); i += a.channels)
            for (uint32_t c = 0; c < 3; ++c) {
                d += std::abs(a.pixels[i + c] - b.pixels[i + c]);
                s += std::abs(a.pixels[i + c]);
            }
        return s > 0 ? d / s : 1.0;
    };
    ASSERT_GT(sum(standard["ssr"]), 0.0) << "SSR found hits to compare";
    const double ssr = sum(moved["ssr"]) / sum(standard["ssr"]),
                 hdr = meanDiff(standard["hdr"], moved["hdr"]);
    EXPECT_NEAR(ssr, 1.0, 0.05);
    EXPECT_LT(hdr, 0.02);
    std::printf(
        "moved layout: %zu of %u mask pixels differ; ssr sum ratio %.4f; hdr %.4f mean "
        "relative\n",
        differ, w * h, ssr, hdr);
}

// Ten lighting paths, each with a layout of its own (odd ones keep the normal in GB0, even ones in
// GB2; a tag channel holds the path's number k), six materials on each with other decals — 60
// materials beside the default loop's six, 66 in one pipeline (the scene draws 64 of them: every
// one but the sheen and transmission materials). Each path's rgShade returns
// (1000 · baseColor.r, 100 · tag, 0) nits, so a sphere's pixel says which layout decoded it and
// which pass lit it.
const char* kManyPackage = R"(local rg = require "rg"
local lighting = require "lighting"
require "disney"
local decals = { { "normal" }, { "baseColor" }, { "normal", "baseColor" }, { "smoothness" },
                 { "baseColor", "smoothness" }, false }
for k = 1, 10 do
    local normalTarget = { "normal:oct:20", "smoothness:unorm:10", "spare:uint:2" }
    local other = { "w" .. k .. ":unorm:10x3", "spare:uint:2" }
    local gb2 = { "normal:oct:16", "smoothness:unorm:8", "ao:unorm:8" }
    rg.layout("many" .. k) {
        { "GB0", "rgb10a2", k % 2 == 1 and normalTarget or other },
        { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "tag:uint:8" } },
        { "GB2", "rgba8", k % 2 == 1 and { "w" .. k .. ":unorm:8x3", "ao:unorm:8" } or gb2 },
        { "GB3", "rgba16f", { "emissive:float:16x3" } },
    }
    rg.stencil("lit_many" .. k) {}
    rg.path("many" .. k) { stencil = "lit_many" .. k, shading = "many" .. k .. "_shading.glsl" }
    for j = 1, 6 do
        rg.material("m" .. k .. "_" .. j) { layout = "many" .. k, path = "many" .. k,
                                             surface = "many" .. k .. ".glsl", decals = decals[j] }
    end
    rg.pass("lighting_many" .. k) (lighting.path_pass { path = "many" .. k, class = "lit_many" .. k })
    lighting.per_class("lighting_many" .. k, "lit_many" .. k)
end
)";

TEST_F(MaterialIdentity, SixtyFourMaterialsDecodeLightAndTakeDecalsEachAsDeclared) {
    TempFolder tmp("many");
    std::ofstream(tmp.dir / "many.lua") << kManyPackage;
    for (int k = 1; k <= 10; ++k) {
        const std::string l = "many" + std::to_string(k), w = "w" + std::to_string(k);
        std::ofstream(tmp.dir / (l + ".glsl"))
            << "GBuffer_" << l << " rgSurface(RgSurface s) {\n    GBuffer_" << l
            << " g;\n    g.normal = s.normal; g.smoothness = s.smoothness; g.spare = 0u;\n    g."
            << w << " = vec3(0.0); g.baseColor = s.baseColor; g.tag = " << k
            << "u; g.ao = s.ao; g.emissive = s.emissive;\n    return g;\n}\n";
        std::ofstream(tmp.dir / (l + "_shading.glsl"))
            << "vec3 rgShade(GBuffer_" << l
            << " g, vec3 position, vec3 V, ivec2 pixel) {\n    return vec3(1000.0 * "
               "g.baseColor.r, 100.0 * float(g.tag), 0.0);\n}\n";
    }
    std::ofstream(tmp.dir / "pipeline.lua") << "require \"pipelines.deferred\"\nrequire \"many\"\n";
    // An 8 × 8 grid seen from above: the 60 materials (base colour red 0.2 + 0.1 · (j − 1)), then
    // the four built-ins; a decal over the grid paints base colour 0.9 where a material lets it.
    std::ostringstream scene;
    scene << "local scene = require \"scene\"\n";
    for (int i = 0; i < 64; ++i) {
        const int k = i / 6 + 1, j = i % 6 + 1;
        const std::string model = i < 60
                                      ? "m" + std::to_string(k) + "_" + std::to_string(j)
                                      : std::vector<std::string>{"standard", "clear_coat",
                                                                 "two_colour", "foliage"}[i - 60];
        const float red = i < 60 ? 0.2f + 0.1f * float(j - 1) : 0.5f;
        scene << "scene.material \"s" << i << "\" { model = \"" << model << "\", "
              << (model == "two_colour" ? "diffuse_color" : "base_color") << " = { " << red
              << ", 0.5, 0.5 } }\nscene.sphere \"b" << i << "\" { radius = 0.2, position = { "
              << (float(i % 8) - 3.5f) * 0.5f << ", 0.2, " << (float(i / 8) - 3.5f) * 0.5f
              << " }, material = \"s" << i << "\" }\n";
    }
    scene
        << "scene.decal \"paint\" { position = { 0, 0.2, 0 }, size = { 4.2, 0.5, 4.2 }, base_color "
           "= { 0.9, 0.9, 0.9 }, opacity = 1 }\n"
           "scene.light \"sun\" { type = \"sun\", intensity = 10000, unit = \"lux\", direction = "
           "{ 0, -1, 0 } }\n"
           "scene.camera \"main\" { position = { 0, 6, 0.001 }, target = { 0, 0, 0 }, fov = 45, "
           "aperture = 16, shutter = 1 / 125, iso = 100 }\n";
    std::ofstream(tmp.dir / "scene.lua") << scene.str();

    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load((tmp.dir / "pipeline.lua").string());
    ASSERT_TRUE(p.has_value()) << p.error().message;
    ASSERT_EQ(p->materials.size(), 66u);
    std::set<uint32_t> identities;
    for (const MaterialDesc& m : p->materials) identities.insert(m.identity);
    EXPECT_EQ(identities.size(), 66u) << "every material decodes otherwise: one identity each";
    const std::string text = describeMaterialSystem(*p);
    EXPECT_EQ(text.rfind("material identities", 0), 0u) << "identities come first";
    EXPECT_NE(text.find("free: 189 of 255"), std::string::npos) << text;
    EXPECT_NE(text.find("free: 1 of 15 classes"), std::string::npos) << text;

    constexpr uint32_t size = 256;
    SessionOptions o = sceneOptions((tmp.dir / "scene.lua").string(), {}, size, size);
    Readback r = renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 1, {"hdr"});
    ASSERT_EQ(r.images.size(), 1u);
    const glm::mat4 vp = cameraViewProj(glm::vec3(0, 6, 0.001f), glm::vec3(0), 45.0f, size, size);
    int wrong = 0;
    for (int i = 0; i < 60; ++i) {
        const int k = i / 6 + 1, j = i % 6 + 1;
        const bool painted = j == 2 || j == 3 || j == 5;
        const float red = painted ? 0.9f : 0.2f + 0.1f * float(j - 1);
        const glm::ivec2 q =
            pixelOf(vp, size, size,
                    glm::vec3((float(i % 8) - 3.5f) * 0.5f, 0.4f, (float(i / 8) - 3.5f) * 0.5f));
        const float r0 = r["hdr"].at(q.x, q.y, 0) / r.preExposure,
                    g0 = r["hdr"].at(q.x, q.y, 1) / r.preExposure;
        // The 8-bit sRGB base colour's step near 0.2..0.9: under 0.4 %.
        const bool ok =
            std::abs(r0 - 1000.0f * red) < 5.0f && std::abs(g0 - 100.0f * float(k)) < 0.5f;
        wrong += !ok;
        EXPECT_TRUE(ok) << "m" << k << "_" << j << ": (" << r0 << ", " << g0 << ") nits, expected ("
                        << 1000.0f * red << ", " << 100 * k << ")";
    }
    // On the CPU (--capture gbuffer.baseColor: the stencil read back names each pixel's layout)
    // and on the GPU (--view basecolor, sRGB-encoded): the same base colours.
    o.captures = {"gbuffer.baseColor"};
    o.view = "basecolor";
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load((tmp.dir / "pipeline.lua").string()).has_value());
    ASSERT_TRUE(s.frame().has_value());
    ASSERT_EQ(s.channelCaptures().size(), 1u);
    auto captured = s.channelImage(s.channelCaptures()[0]);
    ASSERT_TRUE(captured.has_value()) << captured.error().message;
    auto view = s_runtime->executor().readback("debug_view");
    ASSERT_TRUE(view.has_value()) << view.error().message;
    int wrongDecodes = 0;
    for (int i = 0; i < 60; ++i) {
        const int j = i % 6 + 1;
        const float red = j == 2 || j == 3 || j == 5 ? 0.9f : 0.2f + 0.1f * float(j - 1);
        const glm::ivec2 q =
            pixelOf(vp, size, size,
                    glm::vec3((float(i % 8) - 3.5f) * 0.5f, 0.4f, (float(i / 8) - 3.5f) * 0.5f));
        const float cpu = srgbEncode(captured->at(q.x, q.y, 0)), gpu = view->at(q.x, q.y, 0);
        const bool ok = std::abs(cpu - srgbEncode(red)) < 0.6f / 255 &&
                        std::abs(gpu - srgbEncode(red)) < 1.6f / 255;
        wrongDecodes += !ok;
        EXPECT_TRUE(ok) << "sphere " << i << ": " << cpu << " (capture), " << gpu
                        << " (view), expected " << srgbEncode(red);
    }
    std::printf("64 materials: %zu identities, %d of 60 spheres lit wrong, %d decoded wrong\n",
                identities.size(), wrong, wrongDecodes);
}

// The skin package from a folder outside the repository: two flat slabs seen from above, one of
// skin with scatter 0 (p = 1: Lambert), one with the package's scatter colour (1, 0.45, 0.3), under
// a 10 000 lux sun at c = N·L = 0.2 and no environment. Their difference per channel is the
// wrapped response less Lambert's (the specular lobe, the same on both, cancels):
// base/π · E⊥ · ((p + 1)/2 · c^p − c), p = 1 − 0.75 · scatter — near the terminator red gains
// most. And the response gathers what Lambert does: ∫ R dω over the hemisphere is π for each p.
TEST_F(MaterialIdentity, SkinWrapsRedFurthestAndGathersWhatLambertDoes) {
    constexpr double kPi = 3.14159265358979;
    for (double p : {1.0, 0.25, 0.6625, 0.775}) {
        double integral = 0;  // ∫ (p + 1)/2 · cos^p θ dω, midpoint rule over θ
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double t = (i + 0.5) * (kPi / 2) / n;
            integral +=
                (p + 1) / 2 * std::pow(std::cos(t), p) * 2 * kPi * std::sin(t) * (kPi / 2) / n;
        }
        EXPECT_NEAR(integral, kPi, 1e-5) << "p = " << p;
    }
    TempFolder tmp("skin");
    for (const auto& e : fs::directory_iterator(kRoot + "/materials/examples/skin"))
        fs::copy(e.path(), tmp.dir / e.path().filename());
    const double c = 0.2, s = std::sqrt(1 - c * c);
    std::ostringstream scene;
    scene << "local scene = require \"scene\"\n"
             "scene.material \"lambert\" { model = \"skin\", base_color = { 0.5, 0.5, 0.5 }, "
             "smoothness = 0.5, params = { scatterR = 0, scatterG = 0, scatterB = 0 } }\n"
             "scene.material \"skin\" { model = \"skin\", base_color = { 0.5, 0.5, 0.5 }, "
             "smoothness = 0.5 }\n"
             "scene.box \"a\" { size = { 1, 0.02, 1.6 }, position = { -0.7, 0, 0 }, material = "
             "\"lambert\" }\n"
             "scene.box \"b\" { size = { 1, 0.02, 1.6 }, position = { 0.7, 0, 0 }, material = "
             "\"skin\" }\n"
             "scene.light \"sun\" { type = \"sun\", intensity = 10000, unit = \"lux\", direction "
             "= { 0, "
          << -c << ", " << -s
          << " } }\n"
             "scene.camera \"main\" { position = { 0, 4, 0.001 }, target = { 0, 0, 0 }, fov = 40, "
             "aperture = 16, shutter = 1 / 125, iso = 100 }\n";
    std::ofstream(tmp.dir / "test_scene.lua") << scene.str();
    constexpr uint32_t w = 192, h = 160;
    SessionOptions o = sceneOptions((tmp.dir / "test_scene.lua").string(), {}, w, h);
    Readback r = renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 1, {"hdr"});
    ASSERT_EQ(r.images.size(), 1u);
    const glm::mat4 vp = cameraViewProj(glm::vec3(0, 4, 0.001f), glm::vec3(0), 40.0f, w, h);
    const glm::ivec2 qa = pixelOf(vp, w, h, glm::vec3(-0.7f, 0.01f, 0.3f)),
                     qb = pixelOf(vp, w, h, glm::vec3(0.7f, 0.01f, 0.3f));
    const double e = 0.5 / kPi * 10000.0;  // base/π · E⊥, 1591.5 nits
    const double scatter[3] = {1.0, 0.45, 0.3};
    double gain[3];
    for (int ch = 0; ch < 3; ++ch) {
        const double p = 1 - 0.75 * scatter[ch];
        const double expected = e * ((p + 1) / 2 * std::pow(c, p) - c);
        gain[ch] = (r["hdr"].at(qb.x, qb.y, ch) - r["hdr"].at(qa.x, qa.y, ch)) / r.preExposure;
        EXPECT_NEAR(gain[ch], expected, 0.01 * e) << "channel " << ch;
        // The Lambert slab: base/π · E⊥ · c, plus a specular lobe under 10 % of it.
        const double lambert = r["hdr"].at(qa.x, qa.y, ch) / r.preExposure;
        EXPECT_GT(lambert, e * c);
        EXPECT_LT(lambert, 1.1 * e * c);
    }
    EXPECT_GT(gain[0], gain[1]);
    EXPECT_GT(gain[1], gain[2]);
    std::printf(
        "skin at N.L = 0.2: +%.1f +%.1f +%.1f nits over Lambert (expected %.1f %.1f %.1f)\n",
        gain[0], gain[1], gain[2], e * (0.625 * std::pow(c, 0.25) - c),
        e * (0.83125 * std::pow(c, 0.6625) - c), e * (0.8875 * std::pow(c, 0.775) - c));
}

}  // namespace
