// The transmission material (materials/transmission.lua, glTF KHR_materials_transmission and
// KHR_materials_volume) by its numbers, on tests/gpu/scenes/transmission.lua: glass tiles turned
// 45° in front of an edge, seen by an orthographic camera. The edge seen through 0.5 m of IOR 1.5
// must move by Snell's refraction of the view ray over that thickness; its light must be
// attenuated by Beer–Lambert's attenuationColor^(thickness / attenuationDistance); a rough tile
// must blur it; and in a uniform furnace every tile must vanish (what the specular lobe reflects
// plus what is transmitted is the environment).
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>

#include "image/image.h"
#include "runtime/runtime.h"
#include "runtime/session.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 640, H = 256;
constexpr float kPixelsPerMetre = H / 2.4f;       // the camera's height is 2.4 m
constexpr float kTileY[3] = {0.7f, 0.0f, -0.7f};  // thin, thick, rough

class Transmission : public GpuFixture {
protected:
    // The HDR in cd/m² (the pre-exposure divided out).
    static Image render(const std::map<std::string, std::string>& args) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/transmission.lua", args, W, H);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 2, {"hdr"});
        if (r.images.empty()) return Image();
        Image hdr = r["hdr"];
        for (float& v : hdr.pixels) v /= r.preExposure;
        return hdr;
    }
    // Channel c at world x across tile `tile`'s face, averaged over 9 rows about its centre.
    static float at(const Image& hdr, int tile, float x, int c = 1) {
        const int px =
            static_cast<int>(std::floor(static_cast<float>(W) / 2 + x * kPixelsPerMetre));
        const int py = static_cast<int>(static_cast<float>(H) / 2 - kTileY[tile] * kPixelsPerMetre);
        double sum = 0.0;
        for (int dy = -4; dy <= 4; ++dy)
            sum += hdr.at(static_cast<uint32_t>(px), static_cast<uint32_t>(py + dy), c);
        return static_cast<float>(sum / 9.0);
    }
    // The mean of channel c over world x in [x0, x1] across the tile.
    static float mean(const Image& hdr, int tile, float x0, float x1, int c = 1) {
        double sum = 0.0;
        int n = 0;
        for (float x = x0; x <= x1; x += 1.0f / kPixelsPerMetre, ++n) sum += at(hdr, tile, x, c);
        return static_cast<float>(sum / n);
    }
    // Where, scanning right across the tile's face (|x| < 0.26 m), the light first falls below
    // half of `plateau`: in pixels from the image's centre, interpolated between pixels.
    static float edge(const Image& hdr, int tile, float plateau) {
        const int py = static_cast<int>(static_cast<float>(H) / 2 - kTileY[tile] * kPixelsPerMetre);
        auto row = [&](int px) {
            double sum = 0.0;
            for (int dy = -4; dy <= 4; ++dy)
                sum += hdr.at(static_cast<uint32_t>(px), static_cast<uint32_t>(py + dy), 1);
            return static_cast<float>(sum / 9.0);
        };
        const int from = static_cast<int>(W / 2 - 0.26f * kPixelsPerMetre);
        const int to = static_cast<int>(W / 2 + 0.26f * kPixelsPerMetre);
        for (int px = from; px < to; ++px) {
            const float a = row(px), b = row(px + 1), half = 0.5f * plateau;
            if (a >= half && b < half)
                return static_cast<float>(px) + (a - half) / (a - b) + 0.5f - W / 2.0f;
        }
        return NAN;
    }
};

TEST_F(Transmission, TheEdgeMovesByTheRefractionAndDimsByBeerLambert) {
    const Image hdr = render({});
    ASSERT_EQ(hdr.width, W);
    // Thin-walled: the edge where it is; its bright side the wall's 10 nits times 1 − the
    // specular albedo at N·V = cos 45°.
    const float thinPlateau = mean(hdr, 0, -0.22f, -0.06f);
    const float thinEdge = edge(hdr, 0, thinPlateau);
    std::printf("thin glass: %.3f cd/m² left of the edge, the edge at %.2f px\n", thinPlateau,
                thinEdge);
    EXPECT_GT(thinPlateau, 8.0f);
    EXPECT_LT(thinPlateau, 10.0f);
    EXPECT_NEAR(thinEdge, 0.0f, 1.0f);
    // 0.5 m of IOR 1.5: the view ray refracted into the tile leaves it 0.5 m along glm::refract's
    // direction, so the wall's edge is seen displaced by that direction's x.
    const glm::vec3 N(std::sin(glm::radians(45.0f)), 0.0f, std::cos(glm::radians(45.0f)));
    const glm::vec3 refracted = glm::refract(glm::vec3(0, 0, -1), N, 1.0f / 1.5f);
    const float expected = -refracted.x * 0.5f * kPixelsPerMetre;
    // The thick tile's plateau, per channel, against the thin one's: attenuationColor^(0.5/0.25).
    const float attenuation[3] = {0.5f, 0.8f, 1.0f};
    for (int c = 0; c < 3; ++c) {
        const float ratio = mean(hdr, 1, -0.22f, 0.0f, c) / mean(hdr, 0, -0.22f, -0.06f, c);
        const float beer = attenuation[c] * attenuation[c];
        std::printf("  channel %d: thick / thin %.4f, Beer-Lambert %.4f\n", c, ratio, beer);
        EXPECT_NEAR(ratio, beer, 0.02f * beer) << "channel " << c;
    }
    const float thickEdge = edge(hdr, 1, mean(hdr, 1, -0.22f, 0.0f));
    std::printf("thick glass: the edge moved %.2f px, Snell's law %.2f px\n", thickEdge - thinEdge,
                expected);
    EXPECT_NEAR(thickEdge - thinEdge, expected, 1.0f);
    // Roughness 0.5 reads a coarse mip: the edge spread over many pixels — its steepest step a
    // fraction of the smooth tile's.
    auto steepest = [&](int tile) {
        float most = 0.0f;
        for (float x = -0.24f; x < 0.24f; x += 1.0f / kPixelsPerMetre)
            most = std::max(most,
                            std::abs(at(hdr, tile, x) - at(hdr, tile, x + 1.0f / kPixelsPerMetre)));
        return most;
    };
    std::printf("steepest step across the edge: smooth %.3f, rough %.3f cd/m²\n", steepest(0),
                steepest(2));
    EXPECT_LT(steepest(2), 0.25f * steepest(0));
    EXPECT_GT(at(hdr, 2, -0.24f), at(hdr, 2, 0.24f));  // still brighter on the wall's side
}

TEST_F(Transmission, InAFurnaceTheGlassVanishes) {
    const Image hdr = render({{"furnace", "1"}});
    ASSERT_EQ(hdr.width, W);
    for (int tile = 0; tile < 3; ++tile) {
        const float centre = mean(hdr, tile, -0.1f, 0.1f);
        std::printf("furnace of 1 nit: tile %d %.4f cd/m²\n", tile, centre);
        EXPECT_NEAR(centre, 1.0f, 0.02f) << "tile " << tile;
    }
}

TEST_F(Transmission, AnOpaqueTransmissionIsRefusedNamingTheMaterial) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "rgraph_transmission_opaque";
    std::filesystem::create_directories(dir);
    const std::string scene = (dir / "glass.lua").string();
    std::ofstream(scene) << "local scene = require \"scene\"\n"
                            "scene.material \"glass\" { model = \"transmission\" }\n"
                            "scene.box \"pane\" { material = \"glass\" }\n";
    Session s(rt(), sceneOptions(scene, {}, 64, 64));
    auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
    ASSERT_FALSE(r.has_value());
    EXPECT_NE(r.error().describe().find("scene material 'glass' is of material 'transmission'"),
              std::string::npos)
        << r.error().describe();
    EXPECT_NE(r.error().describe().find("alpha = \"blend\""), std::string::npos);
}

}  // namespace
