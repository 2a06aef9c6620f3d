// A game team's material package used as a team would (materials/examples/toon, copied to a
// folder outside the repository): its own layout, stencil class, lighting path (deferred and
// forward) and decal behaviour on top of the default pipeline; and five more materials with
// their own lighting paths on top of the four built-ins (seed 000 §3.2: materialId + stencil-
// routed lighting paths; §3.3: decals restricted to the parameters a material shares).
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "layout/layout.h"
#include "lua/lua_host.h"

using namespace rg;
namespace fs = std::filesystem;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 192, H = 160;
constexpr float kPi = 3.14159265358979f;

// Seen from straight above: two thin toon slabs (grey tint 0.5, two bands, no wrap, no rim), the
// left one opaque (G-buffer + the toon lighting pass), the right one blended at opacity 1 (the
// forward pass, generated from the toon path's shading), a decal painting red over the left
// slab's far half, and a 10 000 lux sun at cos 0.6 to the slabs' normal. No environment.
const char* kToonScene = R"(local scene = require "scene"
scene.material "grey" { model = "toon", base_color = { 0.5, 0.5, 0.5 }, params = { toonBands = 2, toonWrap = 0, toonRim = 0 } }
scene.material "glass" { model = "toon", base_color = { 0.5, 0.5, 0.5 }, alpha = "blend", opacity = 1, params = { toonBands = 2, toonWrap = 0, toonRim = 0 } }
scene.box "opaque" { size = { 1, 0.02, 1.6 }, position = { -0.7, 0, 0 }, material = "grey" }
scene.box "blended" { size = { 1, 0.02, 1.6 }, position = { 0.7, 0, 0 }, material = "glass" }
scene.decal "paint" { position = { -0.7, 0, -0.5 }, size = { 1.2, 0.4, 0.6 }, base_color = { 0.9, 0.1, 0.1 }, smoothness = 1, metal_mask = 1, opacity = 1 }
scene.light "sun" { type = "sun", intensity = 10000, unit = "lux", direction = { -0.8, -0.6, 0 } }
scene.camera "main" { position = { 0, 4, 0.001 }, target = { 0, 0, 0 }, fov = 40, aperture = 16, shutter = 1 / 125, iso = 100 }
)";

class MaterialPackage : public GpuFixture {
protected:
    static glm::ivec2 px(glm::vec3 p) {
        return pixelOf(cameraViewProj(glm::vec3(0, 4, 0.001f), glm::vec3(0), 40.0f, W, H), W, H, p);
    }
};

TEST_F(MaterialPackage, ToonRendersFromAFolderOutsideTheRepository) {
    TempFolder tmp("toon");
    for (const auto& e : fs::directory_iterator(kRoot + "/materials/examples/toon"))
        fs::copy(e.path(), tmp.dir / e.path().filename());
    std::ofstream(tmp.dir / "test_scene.lua") << kToonScene;
    SessionOptions o = sceneOptions((tmp.dir / "test_scene.lua").string(), {}, W, H);
    Readback r = renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 1,
                               {"hdr", "GB0", "GB1", "GB2", "GB3"});
    ASSERT_EQ(r.images.size(), 5u);
    auto nits = [&](glm::vec3 p, int c) {
        glm::ivec2 q = px(p);
        return r["hdr"].at(q.x, q.y, c) / r.preExposure;
    };
    // Two bands, N·L = 0.6: ceil(0.6 · 2) / 2 = 1, so the slab takes the whole E/π · tint (a
    // Lambert surface would give 0.6 of it: the toon path, not the standard one, lit it).
    const float toon = 0.5f / kPi * 10000.0f;  // 1591.5 nits
    const glm::vec3 opaque(-0.7f, 0.01f, 0.45f), blended(0.7f, 0.01f, 0.3f),
        painted(-0.7f, 0.01f, -0.5f);
    EXPECT_NEAR(nits(opaque, 1), toon, toon * 0.01f) << "deferred toon lighting";
    EXPECT_NEAR(nits(blended, 1), toon, toon * 0.01f)
        << "forward toon shading (generated from the path's rgShade)";
    // The decal painted the toon's tint (its channels = { baseColor = "tint" }) and nothing else:
    // bands, wrap and the spare channels are the toon's own and stay as they were; decoded with
    // the toon layout as the package declares it.
    LuaHost host(luaHostOptionsWithoutDevice());
    auto pipeline = host.load((tmp.dir / "pipeline.lua").string());
    ASSERT_TRUE(pipeline.has_value()) << pipeline.error().message;
    auto layout = std::find_if(pipeline->layouts.begin(), pipeline->layouts.end(),
                               [](auto& l) { return l.name == "toon"; });
    ASSERT_NE(layout, pipeline->layouts.end());
    LayoutInfo info = *analyzeLayout(*layout);
    auto gbuffer = [&](glm::vec3 p) {
        glm::ivec2 q = px(p);
        std::vector<TexelValue> texels;
        for (const auto& t : info.desc.targets) {
            const Image& img = r[t.name];
            texels.push_back(texelFromFloats(
                t.format, &img.pixels[(size_t(q.y) * W + q.x) * img.channels], img.channels));
        }
        auto values = unpackTexel(info, texels);
        return [values, &info](const char* n) { return values[static_cast<size_t>(info.find(n))]; };
    };
    auto clean = gbuffer(opaque), paint = gbuffer(painted);
    EXPECT_EQ(clean("materialId").u[0], 3u);  // the id the default loop leaves free
    EXPECT_EQ(paint("materialId").u[0], 3u);
    const float q = 0.5f / 255 + 1e-4f;  // the sRGB 8-bit encoding's bound
    EXPECT_NEAR(srgbEncode(clean("tint").v[0]), srgbEncode(0.5f), q);
    EXPECT_NEAR(srgbEncode(paint("tint").v[0]), srgbEncode(0.9f),
                q);  // opacity 1: the decal's colour
    EXPECT_NEAR(srgbEncode(paint("tint").v[1]), srgbEncode(0.1f), q);
    for (const char* own : {"steps", "spare"}) EXPECT_EQ(paint(own).u[0], clean(own).u[0]) << own;
    for (const char* own : {"wrap", "rim", "ao"})
        EXPECT_EQ(paint(own).v[0], clean(own).v[0]) << own;
    EXPECT_EQ(paint("reserved").v[0],
              clean("reserved").v[0]);  // where the disney layout's MetalMask would go
    EXPECT_EQ(clean("steps").u[0], 2u);
    // Lit red by the same bands: E/π · 0.9 in red.
    EXPECT_NEAR(nits(painted, 0), 0.9f / kPi * 10000.0f, 0.9f / kPi * 10000.0f * 0.01f);
}

// The debug views decode each pixel with its own material's layout: the toon's tint is its base
// colour, and it has no smoothness (striped magenta, not a value).
TEST_F(MaterialPackage, DebugViewsDecodeTheToonLayout) {
    TempFolder tmp("toon_views");
    for (const auto& e : fs::directory_iterator(kRoot + "/materials/examples/toon"))
        fs::copy(e.path(), tmp.dir / e.path().filename());
    std::ofstream(tmp.dir / "test_scene.lua") << kToonScene;
    auto view = [&](const std::string& name) {
        SessionOptions o = sceneOptions((tmp.dir / "test_scene.lua").string(), {}, W, H);
        o.view = name;
        Session s(*s_runtime, o);
        auto r = s.load((tmp.dir / "pipeline.lua").string());
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r) return Image{};
        auto f = s.frame();
        EXPECT_TRUE(f.has_value()) << f.error().describe();
        auto img = s_runtime->executor().readback("debug_view");
        EXPECT_TRUE(img.has_value());
        return img ? std::move(*img) : Image{};
    };
    Image base = view("basecolor"), smooth = view("smoothness");
    ASSERT_FALSE(base.pixels.empty());
    ASSERT_FALSE(smooth.pixels.empty());
    glm::ivec2 q = px(glm::vec3(-0.7f, 0.01f, 0.45f));
    EXPECT_NEAR(base.at(q.x, q.y, 0), srgbEncode(0.5f), 2.0f / 255);
    // Stripes: every pixel of the slab is magenta (1, 0, 1) or black.
    int magenta = 0;
    for (int dy = 0; dy < 8; ++dy) {
        const float rch = smooth.at(q.x, q.y + dy, 0), g = smooth.at(q.x, q.y + dy, 1),
                    b = smooth.at(q.x, q.y + dy, 2);
        EXPECT_EQ(g, 0.0f);
        EXPECT_EQ(rch, b);
        magenta += rch > 0.5f;
    }
    EXPECT_GT(magenta, 0);
}

// `--capture gbuffer.X` decodes each pixel with its own material's layout: the toon's tint is
// its base colour, its `steps` are its own, and a channel its layout lacks is NaN, not a value.
TEST_F(MaterialPackage, ChannelCapturesDecodeEachPixelsLayout) {
    TempFolder tmp("toon_captures");
    for (const auto& e : fs::directory_iterator(kRoot + "/materials/examples/toon"))
        fs::copy(e.path(), tmp.dir / e.path().filename());
    std::ofstream(tmp.dir / "test_scene.lua")
        << std::string(kToonScene) +
               "scene.material \"std\" { base_color = { 0.2, 0.4, 0.6 }, smoothness = 0.7 }\n"
               "scene.box \"standard\" { size = { 0.4, 0.02, 0.4 }, position = { 0, 0, 0 }, "
               "material = \"std\" }\n";
    SessionOptions o = sceneOptions((tmp.dir / "test_scene.lua").string(), {}, W, H);
    o.captures = {"gbuffer.baseColor", "gbuffer.smoothness", "toon.steps"};
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load((tmp.dir / "pipeline.lua").string()).has_value());
    ASSERT_TRUE(s.frame().has_value());
    std::map<std::string, Image> images;
    for (const auto& c : s.channelCaptures()) {
        auto img = s.channelImage(c);
        ASSERT_TRUE(img.has_value()) << img.error().message;
        images[c.name] = std::move(*img);
    }
    ASSERT_EQ(images.size(), 3u);
    const glm::ivec2 toon = px(glm::vec3(-0.7f, 0.01f, 0.45f)),
                     standard = px(glm::vec3(0.0f, 0.01f, 0.0f));
    const float q = 0.5f / 255 + 1e-4f;
    EXPECT_NEAR(srgbEncode(images["gbuffer.baseColor"].at(toon.x, toon.y, 0)), srgbEncode(0.5f),
                q);  // the tint
    EXPECT_NEAR(srgbEncode(images["gbuffer.baseColor"].at(standard.x, standard.y, 2)),
                srgbEncode(0.6f), q);
    EXPECT_TRUE(
        std::isnan(images["gbuffer.smoothness"].at(toon.x, toon.y, 0)));  // the toon has none
    EXPECT_NEAR(images["gbuffer.smoothness"].at(standard.x, standard.y, 0), 0.7f,
                0.5f / 1023 + 1e-5f);
    EXPECT_EQ(images["toon.steps"].at(toon.x, toon.y, 0), 2.0f);
    EXPECT_TRUE(std::isnan(images["toon.steps"].at(standard.x, standard.y, 0)));  // a disney pixel
}

// The local probe captures a material as its own surface function and layout give it, not as
// the scene material's standard parameters: a "painted" material whose surface function glows
// green whatever the scene says (here a red, red-glowing box) is green in the mirror floor's
// reflection, which comes from the probe (SSR kept from finding anything).
TEST_F(MaterialPackage, ProbeCaptureShadesTheMaterialsOwnSurface) {
    TempFolder tmp("painted");
    std::ofstream(tmp.dir / "painted.lua") << R"(local rg = require "rg"
require "disney"
rg.material "painted" { id = 3, layout = "disney", path = "standard", surface = "painted.glsl" }
)";
    std::ofstream(tmp.dir / "painted.glsl") << R"(GBuffer_disney rgSurface(RgSurface s) {
    GBuffer_disney g;
    g.normal = s.normal; g.smoothness = 0.3; g.materialId = RG_MATERIAL_ID;
    g.baseColor = vec3(0.05, 0.8, 0.05); g.materialData = 0u; g.normalExtra = 0u; g.reserved = 0.0;
    g.metalMask = 0.0; g.reflectance = 0.5; g.ao = 1.0; g.emissive = vec3(10.0, 200.0, 10.0);
    return g;
}
)";
    std::ofstream(tmp.dir / "pipeline.lua")
        << "require \"pipelines.deferred\"\nrequire \"painted\"\n";
    std::ofstream(tmp.dir / "scene.lua") << R"(local scene = require "scene"
scene.material "mirror" { base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 1 }
scene.plane "floor" { size = { 20, 20 }, material = "mirror" }
scene.material "red" { model = "painted", base_color = { 0.8, 0.05, 0.05 }, emissive = { 200, 10, 10 } }
scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, -2 }, material = "red" }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 2, 6 }, target = { 0, 0, 0 }, fov = 40, aperture = 4, shutter = 1 / 60, iso = 100 }
scene.probe "front" { shape = "box", position = { 0, 0.5, -1 }, size = { 4, 3, 6 }, fade = 0.25 }
)";
    SessionOptions o = sceneOptions((tmp.dir / "scene.lua").string(), {}, W, H);
    o.params["ssr_distance"] = Value(0.1);
    Readback r = renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 1, {"hdr"});
    ASSERT_EQ(r.images.size(), 1u);
    const glm::mat4 viewProj = cameraViewProj(glm::vec3(0, 2, 6), glm::vec3(0), 40.0f, W, H);
    const glm::ivec2 mirror = pixelOf(viewProj, W, H, glm::vec3(0.0f, -0.5f, -1.5f)),
                     face = pixelOf(viewProj, W, H, glm::vec3(0.0f, 0.5f, -1.5f));
    const Image& hdr = r["hdr"];
    EXPECT_GT(hdr.at(face.x, face.y, 1),
              10.0f * hdr.at(face.x, face.y, 0));  // the camera sees it green
    EXPECT_GT(hdr.at(mirror.x, mirror.y, 1),
              10.0f * hdr.at(mirror.x, mirror.y, 0));  // and so did the probe
}

// A blended clear coat goes through the forward shader generated from its path's shading
// function, whose local variables share the names of the material's parameters (coatStrength,
// coatSmoothness): the parameter names reach the surface function only. Lit by the coat: brighter
// than the same blended surface without a coat.
TEST_F(MaterialPackage, BlendedClearCoatIsShadedByItsPath) {
    TempFolder tmp("coat");
    auto render = [&](double strength) {
        std::ofstream(tmp.dir / "scene.lua")
            << "local scene = require \"scene\"\n"
               "scene.material \"glaze\" { model = \"clear_coat\", base_color = { 0.5, 0.1, 0.1 }, "
               "alpha = \"blend\", opacity = 1,\n"
               "    params = { coatStrength = "
            << strength
            << ", coatSmoothness = 0.9 } }\n"
               "scene.box \"slab\" { size = { 1, 0.02, 1 }, position = { 0, 0, 0 }, material = "
               "\"glaze\" }\n"
               "scene.light \"sun\" { type = \"sun\", intensity = 10000, unit = \"lux\", direction "
               "= { 0, -0.6, -0.8 } }\n"
               "scene.camera \"main\" { position = { 0, 4, 0.001 }, target = { 0, 0, 0 }, fov = "
               "40, aperture = 16, shutter = 1 / 125, iso = 100 }\n";
        SessionOptions o = sceneOptions((tmp.dir / "scene.lua").string(), {}, W, H);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
        if (r.images.empty()) return -1.0f;
        glm::ivec2 q = px(glm::vec3(0.0f, 0.01f, 0.0f));
        return r["hdr"].at(q.x, q.y, 0) / r.preExposure;
    };
    const float bare = render(0.0), coated = render(1.0);
    ASSERT_GT(bare, 0.0f);
    EXPECT_TRUE(std::isfinite(coated));
    EXPECT_NE(coated, bare);
}

// Five more materials in one pipeline on top of the four built-ins, each with a lighting path
// of its own (a shading function that returns 100 · k nits, so each sphere shows which pass lit
// it): declared from a folder outside the repository; identities and stencil values assigned and shown.
TEST_F(MaterialPackage, FiveMoreMaterialsEachLitByItsOwnPath) {
    TempFolder tmp("five");
    std::ofstream(tmp.dir / "flat.lua") << R"(local rg = require "rg"
require "disney"
for k = 1, 5 do
    rg.stencil("lit_flat" .. k) { doc = "flat " .. k }
    rg.path("flat" .. k) { stencil = "lit_flat" .. k, shading = "flat_shading.glsl" }
    -- Its identity: its class's value (the pixel's stencil names it wherever the G-buffer is read).
    rg.material("flat" .. k) { layout = "disney", path = "flat" .. k, surface = "materials/standard.glsl" }
    rg.pass("lighting_flat" .. k) {
        kind = "fullscreen", shader = "flat_lighting.frag", defines = { FLAT_K = k },
        reads = { { "depth", as = "depth" }, { "exposure", as = "storage" } },
        writes = { { "hdr", load = true } }, stencil = { class = "lit_flat" .. k },
        insert = { after = "lighting_standard" },
    }
end
)";
    std::ofstream(tmp.dir / "flat_shading.glsl")
        << "vec3 rgShade(GBuffer_disney g, vec3 position, vec3 V, ivec2 pixel) { return vec3(100.0 "
           "* float(FLAT_K)); }\n";
    std::ofstream(tmp.dir / "flat_lighting.frag") << R"(#version 460
#include "lib/exposure.glsl"
#include "gbuffer_disney.glsl"
#include "flat_shading.glsl"
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params { float initial_ev100; } params;
void main() {
    GBuffer_disney g;
    color = vec4(rgShade(g, vec3(0.0), vec3(0.0, 0.0, 1.0), ivec2(gl_FragCoord.xy)) * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}
)";
    std::ofstream(tmp.dir / "pipeline.lua") << "require \"pipelines.deferred\"\nrequire \"flat\"\n";
    std::ofstream(tmp.dir / "scene.lua") << R"(local scene = require "scene"
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 } }
scene.plane "floor" { size = { 8, 8 }, material = "floor" }
for k = 1, 5 do
    scene.material("m" .. k) { model = "flat" .. k, base_color = { 0.5, 0.5, 0.5 } }
    scene.sphere("s" .. k) { radius = 0.25, position = { (k - 3) * 0.6, 0.3, 0 }, material = "m" .. k }
end
scene.light "sun" { type = "sun", intensity = 10000, unit = "lux", direction = { -0.3, -0.8, -0.5 } }
scene.camera "main" { position = { 0, 4, 0.001 }, target = { 0, 0, 0 }, fov = 40, aperture = 16, shutter = 1 / 125, iso = 100 }
)";
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load((tmp.dir / "pipeline.lua").string());
    ASSERT_TRUE(p.has_value()) << p.error().message;
    ASSERT_EQ(p->materials.size(), 11u);
    for (int k = 1; k <= 5; ++k) {
        auto c = std::find_if(p->stencilClasses.begin(), p->stencilClasses.end(),
                              [&](auto& x) { return x.name == "lit_flat" + std::to_string(k); });
        ASSERT_NE(c, p->stencilClasses.end());
        EXPECT_EQ(
            c->value,
            4u + static_cast<uint32_t>(
                     k));  // after lit_standard 1, lit_clearcoat 2, lit_two_colour 3, lit_sheen 4
        EXPECT_EQ(c->mask, 0x0Fu);
    }
    const std::string text = describeMaterialSystem(*p);
    for (int k = 1; k <= 5; ++k) {
        char line[64];
        std::snprintf(line, sizeof line, "0x%02X lit_flat%d", 4 + k, k);
        EXPECT_NE(text.find(line), std::string::npos) << text;
        EXPECT_EQ(p->materials[static_cast<size_t>(5 + k)].identity, 4u + static_cast<uint32_t>(k));
    }
    EXPECT_NE(text.find("0x09 mask 0x0F  lit_flat5"), std::string::npos) << text;
    EXPECT_NE(text.find("free: 6 of 15 classes"), std::string::npos) << text;
    EXPECT_NE(text.find("free: 244 of 255"), std::string::npos) << text;  // 11 values taken

    SessionOptions o = sceneOptions((tmp.dir / "scene.lua").string(), {}, W, H);
    Readback r = renderAndRead(o, (tmp.dir / "pipeline.lua").string(), 1, {"hdr"});
    ASSERT_EQ(r.images.size(), 1u);
    for (int k = 1; k <= 5; ++k) {
        glm::ivec2 q = px(glm::vec3(float(k - 3) * 0.6f, 0.55f, 0.0f));
        EXPECT_NEAR(r["hdr"].at(q.x, q.y, 1) / r.preExposure, 100.0f * float(k), 0.5f * float(k))
            << "flat" << k;
    }
}

}  // namespace
