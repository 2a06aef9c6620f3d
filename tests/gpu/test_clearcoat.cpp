// The clear coat's own normal (materials/clearcoat.lua, glTF KHR_materials_clearcoat): the coat
// lobe lies about the vertex normal — or the coat's normal map — not the base's normal map. Two
// tiles seen head on by an orthographic camera, each with a base normal map tilted 30°, a black
// base and a coat of roughness 0.5, under a sun straight from the camera (L = V): the first tile's
// coat (the vertex normal) peaks at N·H = 1; the second's, given the same tilted map as its
// clearcoatNormalTexture, sits 30° off its peak. Everything else (the base's lobes under 1 − Fc,
// Fc at L·H = 1 for both) is the same, so the difference of the tiles is the difference of the two
// coat lobes the GGX formulas give.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "image/image.h"
#include "lighting/brdf.h"
#include "runtime/runtime.h"
#include "runtime/session.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 640, H = 128;

class ClearCoat : public GpuFixture {};

TEST_F(ClearCoat, TheCoatLiesAboutItsOwnNormalNotTheBaseMap) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rgraph_clearcoat";
    std::filesystem::create_directories(dir);
    // A tangent-space normal tilted 30° about the tangent's bitangent, in 8 bits.
    const float tilt = glm::radians(30.0f);
    Image map(4, 4, 4);
    for (size_t i = 0; i < 16; ++i) {
        map.pixels[i * 4 + 0] = std::round((std::sin(tilt) * 0.5f + 0.5f) * 255.0f) / 255.0f;
        map.pixels[i * 4 + 1] = 128.0f / 255.0f;
        map.pixels[i * 4 + 2] = std::round((std::cos(tilt) * 0.5f + 0.5f) * 255.0f) / 255.0f;
        map.pixels[i * 4 + 3] = 1.0f;
    }
    ASSERT_TRUE(writePng((dir / "tilt.png").string(), map).has_value());
    const glm::vec3 stored = glm::vec3(map.pixels[0], map.pixels[1], map.pixels[2]) * 2.0f - 1.0f;
    const float cosTilt = glm::normalize(stored).z;  // the tilt the shader decodes
    std::ofstream(dir / "scene.lua") << R"(local scene = require "scene"
for i, own in ipairs({ false, true }) do
  scene.material("coat" .. i) { base_color = { 0, 0, 0 }, smoothness = 0.0, model = "clear_coat",
    normal_map = "tilt.png", params = { coatStrength = 1.0, coatSmoothness = 0.5 },
    textures = own and { coatNormalMap = "tilt.png" } or nil }
  scene.box("tile" .. i) { size = { 0.8, 0.8, 0.2 }, position = { (i - 1.5) * 2.0, 0, 0 }, material = "coat" .. i }
end
scene.environment "black" { kind = "color", color = { 1, 1, 1 }, intensity = 0, unit = "nits" }
scene.light "sun" { type = "sun", direction = { 0, 0, -1 }, intensity = 1000, unit = "lux" }
scene.camera "main" { position = { 0, 0, 10 }, target = { 0, 0, 0 }, height = 1.2, aperture = 2, shutter = 0.5, iso = 100 }
)";
    SessionOptions o = sceneOptions((dir / "scene.lua").string(), {}, W, H);
    Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 2, {"hdr"});
    ASSERT_FALSE(r.images.empty());
    const Image& hdr = r["hdr"];
    // Tile i's face (1 m either side of the centre; the camera shows 6 m across), 9×9 pixels.
    auto centre = [&](int i) {
        const int cx =
            static_cast<int>((static_cast<float>(i) * 2.0f - 1.0f) / 6.0f * W + W / 2.0f);
        double sum = 0.0;
        for (int dy = -4; dy <= 4; ++dy)
            for (int dx = -4; dx <= 4; ++dx)
                sum += hdr.at(static_cast<uint32_t>(cx + dx), static_cast<uint32_t>(H / 2 + dy), 1);
        return sum / 81.0 / r.preExposure;
    };
    // The coat lobe, E⊥ · D · Vis · Fc / π · ⟨n·l⟩, with N·L = N·V = N·H = cos of the coat normal's
    // tilt and Fc = F_Schlick(0.04, 1, L·H = 1) = 0.04.
    const float alpha = 0.5f * 0.5f;
    auto coat = [&](float c) {
        return 1000.0 * brdf::D_GGX(c, alpha) * brdf::V_SmithGGXCorrelated(c, c, alpha) * 0.04 /
               3.14159265358979 * c;
    };
    const double vertexCoat = centre(0), mappedCoat = centre(1);
    std::printf(
        "coat about the vertex normal %.3f cd/m², about the tilted map %.3f; the lobes "
        "differ by %.3f, GGX: %.3f\n",
        vertexCoat, mappedCoat, vertexCoat - mappedCoat, coat(1.0f) - coat(cosTilt));
    EXPECT_NEAR(vertexCoat - mappedCoat, coat(1.0f) - coat(cosTilt),
                0.03 * (coat(1.0f) - coat(cosTilt)));
    EXPECT_GT(vertexCoat, 2.0 * mappedCoat);  // with the base's map the peak would be lost
}

}  // namespace
