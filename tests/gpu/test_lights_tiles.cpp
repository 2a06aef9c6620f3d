// Per-tile light culling on the GPU (scripts/lighting.lua, shaders/passes/light_culling.comp): the
// culling changes no pixel, and the tile lists follow the lights per pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lights_fixture.h"

using namespace rg;
using namespace rg::test;

namespace {

// ---- Light culling per screen tile (scripts/lighting.lua, shaders/passes/light_culling.comp) -----

// How many values of image `a` differ from reference `b`'s (the same size), and `b`'s sum.
size_t differing(const Image& a, const Image& b, double& sum) {
    size_t differ = 0;
    sum = 0;
    for (size_t i = 0; i < b.pixels.size(); ++i) {
        differ += a.pixels[i] != b.pixels[i];
        sum += b.pixels[i];
    }
    return differ;
}

// The many-lights scene rendered with the default pipeline at manual exposure; `tiled` false
// swaps in a lighting module whose passes loop over every light (no culling pass).
struct TiledFrame {
    Image hdr;
    std::vector<uint32_t> tiles;    // light_tiles, when tiled
    std::vector<uint32_t> froxels;  // light_froxel_counts, when tiled
    std::vector<uint32_t> lists;    // light_froxels, when tiled
};
// The last of `frames` frames (from the second on, the camera is jittered for TAA). `edits`:
// replacements in scripts/lighting.lua (the module copied beside the pipeline).
TiledFrame renderManyLights(Runtime& rt, uint32_t lights, bool tiled, uint32_t w, uint32_t h,
                            bool ranged = true, bool glass = false, int frames = 1,
                            const std::vector<std::pair<std::string, std::string>>& edits = {},
                            bool lamp = false) {
    std::string pipeline = kRoot + "/scripts/pipelines/deferred.lua";
    if (!edits.empty()) {
        const std::string dir = std::string(RG_TEST_TMP) + "/lighting_edited";
        std::filesystem::create_directories(dir);
        std::ofstream(dir + "/deferred.lua") << readFile(pipeline);
        std::string module = readFile(kRoot + "/scripts/lighting.lua");
        for (const auto& [from, to] : edits) {
            const size_t at = module.find(from);
            EXPECT_NE(at, std::string::npos) << "scripts/lighting.lua: no '" << from << "'";
            if (at != std::string::npos) module.replace(at, from.size(), to);
        }
        std::ofstream(dir + "/lighting.lua") << module;
        pipeline = dir + "/deferred.lua";
    }
    if (!tiled) {
        const std::string dir = std::string(RG_TEST_TMP) + "/untiled";
        std::filesystem::create_directories(dir);
        std::ofstream(dir + "/deferred.lua") << readFile(pipeline);
        // The lighting module with `tiled` adding nothing: no pass reads the tile lists, so the
        // graph culls both culling passes and the shaders loop over every light.
        std::string module = readFile(kRoot + "/scripts/lighting.lua");
        const std::string tiledBody =
            "return lighting.extend(pass, { { \"light_tiles\", as = \"storage\" } }, "
            "\"RG_LIGHT_TILES\")";
        const size_t at = module.find(tiledBody);
        EXPECT_NE(at, std::string::npos) << "scripts/lighting.lua: lighting.tiled changed";
        if (at != std::string::npos) module.replace(at, tiledBody.size(), "return pass");
        // And lighting.clustered (the forward pass's froxel lists) too.
        const std::string clusteredBody = "function lighting.clustered(pass)\n";
        const size_t c = module.find(clusteredBody);
        EXPECT_NE(c, std::string::npos) << "scripts/lighting.lua: lighting.clustered changed";
        if (c != std::string::npos)
            module.insert(c + clusteredBody.size(), "    if true then return pass end\n");
        std::ofstream(dir + "/lighting.lua") << module;
        pipeline = dir + "/deferred.lua";
    }
    SessionOptions o;
    o.compile.outputWidth = w;
    o.compile.outputHeight = h;
    o.scene = kRoot + "/scripts/scenes/many_lights.lua";
    o.sceneArgs["lights"] = std::to_string(lights);
    o.sceneArgs["ranged"] = ranged ? "1" : "0";
    o.sceneArgs["glass"] = glass ? "1" : "0";
    o.sceneArgs["lamp"] = lamp ? "1" : "0";
    o.params["exposure_mode"] = Value("manual");
    if (tiled) o.captures = {"light_tiles", "light_froxel_counts", "light_froxels"};
    Session s(rt, o);
    TiledFrame out;
    auto r = s.load(pipeline);
    EXPECT_TRUE(r.has_value()) << r.error().describe();
    if (!r) return out;
    const auto& planned = rt.executor().plan().passes;
    const bool culls = std::any_of(planned.begin(), planned.end(),
                                   [](const auto& p) { return p.name == "light_culling"; });
    EXPECT_EQ(culls, tiled);
    const bool bins = std::any_of(planned.begin(), planned.end(),
                                  [](const auto& p) { return p.name == "light_froxels"; });
    EXPECT_EQ(bins, tiled);
    for (int k = 0; k < frames; ++k) {
        auto fr = s.frame();
        EXPECT_TRUE(fr.has_value()) << fr.error().describe();
    }
    auto hdr = rt.executor().readback("hdr");
    EXPECT_TRUE(hdr.has_value());
    if (hdr) out.hdr = std::move(*hdr);
    if (tiled) {
        auto buf = rt.executor().readbackBuffer("light_tiles");
        EXPECT_TRUE(buf.has_value());
        if (buf) {
            out.tiles.resize(buf->size() / 4);
            std::memcpy(out.tiles.data(), buf->data(), out.tiles.size() * 4);
        }
        auto counts = rt.executor().readbackBuffer("light_froxel_counts");
        EXPECT_TRUE(counts.has_value());
        if (counts) {
            out.froxels.resize(counts->size() / 4);
            std::memcpy(out.froxels.data(), counts->data(), out.froxels.size() * 4);
        }
        auto lists = rt.executor().readbackBuffer("light_froxels");
        EXPECT_TRUE(lists.has_value());
        if (lists) {
            out.lists.resize(lists->size() / 4);
            std::memcpy(out.lists.data(), lists->data(), out.lists.size() * 4);
        }
    }
    return out;
}

TEST_F(Lights, TileCullingChangesNoPixel) {
    // A light left out of a tile's list is one whose range window is zero at every surface of the
    // tile, and the lists keep the scene's order: the culled image is the unculled one, bit for bit.
    // 300 lights without a range reach every pixel: listed once, globally, not per tile (a tile
    // list holds 62), so none is lost. A blended pane is lit in the forward pass from its
    // fragments' froxels (lighting.clustered), in the same order. The third frame of one case is
    // jittered (the froxels' columns are not, the tiles' frusta are: a shaded pixel centre stays
    // inside its column while the jitter is under half a pixel).
    const struct {
        uint32_t n;
        bool ranged, glass;
        int frames;
    } cases[] = {{16u, true, false, 1},
                 {256u, true, true, 1},
                 {4096u, true, true, 1},
                 {4096u, true, true, 3},
                 {300u, false, false, 1}};
    for (const auto& [n, ranged, glass, frames] : cases) {
        TiledFrame culled = renderManyLights(rt(), n, true, 200, 120, ranged, glass, frames);
        TiledFrame all = renderManyLights(rt(), n, false, 200, 120, ranged, glass, frames);
        ASSERT_EQ(culled.hdr.pixels.size(), all.hdr.pixels.size());
        double sum = 0;
        const size_t differ = differing(culled.hdr, all.hdr, sum);
        std::printf("%u %s lights%s, frame %d: %zu of %zu values differ\n", n,
                    ranged ? "ranged" : "unranged",
                    glass ? " (a blended pane lit in the forward pass)" : "", frames, differ,
                    all.hdr.pixels.size());
        EXPECT_EQ(differ, 0u) << n << " lights";
        EXPECT_GT(sum, 0.0);
    }
}

TEST_F(Lights, ALightAcrossTheFrameReachesEveryFroxel) {
    // A share of the binning that would test more froxels than RG_FROXEL_LARGE_WORK leaves its
    // light to the pass of large lights, whose every invocation takes a share of the columns:
    // lavapipe ends a shader's loops after 65 535 iterations in all, and one invocation binning a
    // light across 14 400 columns × 16 slices lost the columns past ~3 800 without a word. Here
    // with 8-pixel columns at 1280×720 and 4 work groups (the binning's shares are one a light
    // from 129 lights on), the many-lights scene and its lamp, whose range reaches every froxel:
    // every froxel's list ends with the lamp (the last light), and every list is strictly
    // ascending (sorted after both passes, no light binned by both).
    const uint32_t n = 300;
    TiledFrame f =
        renderManyLights(rt(), n, true, 1280, 720, true, false, 1,
                         {{"lighting.coarse_tile = 32", "lighting.coarse_tile = 8"},
                          {"lighting.froxel_words = 128", "lighting.froxel_words = 16"},
                          {"lighting.froxel_groups = 256", "lighting.froxel_groups = 4"}},
                         true);
    ASSERT_GE(f.froxels.size(), 4u);
    const uint32_t columns = f.froxels[0] * f.froxels[1], slices = f.froxels[2],
                   stride = f.froxels[3];
    ASSERT_EQ(columns, 160u * 90u);
    ASSERT_EQ(stride, 16u);
    ASSERT_GE(f.froxels.size(), 4 + size_t(columns) * slices);
    ASSERT_GE(f.lists.size(), size_t(columns) * slices * stride);
    size_t without = 0, overflowed = 0, unordered = 0;
    for (size_t froxel = 0; froxel < size_t(columns) * slices; ++froxel) {
        const uint32_t count = f.froxels[4 + froxel];
        overflowed += count > 2 * stride;
        auto entry = [&](uint32_t k) {
            return (f.lists[froxel * stride + k / 2] >> (k % 2 * 16)) & 0xFFFFu;
        };
        const uint32_t held = std::min(count, 2 * stride);
        for (uint32_t k = 1; k < held; ++k) unordered += entry(k - 1) >= entry(k);
        without += held == 0 || entry(held - 1) != n;
    }
    std::printf(
        "%u columns x %u slices: %zu froxels without the lamp, %zu overflowed, %zu pairs "
        "out of order\n",
        columns, slices, without, overflowed, unordered);
    EXPECT_EQ(overflowed, 0u);
    EXPECT_EQ(without, 0u);
    EXPECT_EQ(unordered, 0u);
}

TEST_F(Lights, LightsReadThroughTexelsChangeNoPixel) {
    // The light loops read a light's fields through a texel buffer over the Lights block
    // (lib/scene.glsl rgLight) where the device allows; RG_LIGHT_TEXELS=0 reads the block itself.
    // Ranged lights of every type (a spot with an IES profile among them) in the tiles' lists, a
    // sun in the global list and a blended pane lit from its froxels: the same image bit for bit.
    const std::string scene = kScenes + "lights_every_type.lua";
    const Frame texels = render(scene);
    setenv("RG_LIGHT_TEXELS", "0", 1);
    const Frame block = render(scene);
    unsetenv("RG_LIGHT_TEXELS");
    EXPECT_TRUE(texels.lightTexels) << "lavapipe's texel buffers hold the scene's lights";
    EXPECT_FALSE(block.lightTexels) << "RG_LIGHT_TEXELS=0";
    ASSERT_EQ(texels.hdr.pixels.size(), block.hdr.pixels.size());
    double sum = 0;
    const size_t differ = differing(texels.hdr, block.hdr, sum);
    std::printf("every light type, through texels and the block: %zu of %zu values differ\n",
                differ, block.hdr.pixels.size());
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(sum, 0.0);
}

TEST_F(Lights, TileListsFollowLightsPerPixelNotLightsInTheScene) {
    // light_tiles: header (tiles x, tiles y, stride, tile size), then per tile the count and the
    // light indices, ascending (the lights that reach every pixel are the scene's GlobalLights). The many-lights scene keeps ~4 lights over each floor point at any
    // count, so the mean list grows far slower than the scene's lights.
    constexpr uint32_t w = 1280, h = 720;
    std::vector<double> means;
    for (uint32_t n : {16u, 64u, 256u, 1024u, 16384u}) {
        TiledFrame f = renderManyLights(rt(), n, true, w, h);
        ASSERT_GE(f.tiles.size(), 4u);
        const uint32_t tx = f.tiles[0], ty = f.tiles[1], stride = f.tiles[2];
        EXPECT_EQ(tx, (w + 3) / 4);
        EXPECT_EQ(ty, (h + 3) / 4);
        EXPECT_EQ(f.tiles[3], 4u);
        EXPECT_EQ(stride, 32u);  // scripts/lighting.lua: 128 B per 4x4 tile
        ASSERT_GE(f.tiles.size(), 4u + size_t(tx) * ty * stride);
        double total = 0;
        uint32_t lit = 0, most = 0, incomplete = 0, overflowing = 0;
        for (uint32_t t = 0; t < tx * ty; ++t) {
            const uint32_t* list = &f.tiles[4 + size_t(t) * stride];
            incomplete += list[0] >> 31;  // under a full froxel (RG_TILE_INCOMPLETE)
            const uint32_t count = list[0] & 0x7FFFFFFFu;
            // Two 16-bit light indices per word after the count (lib/light_tiles.glsl).
            const uint32_t capacity = 2 * (stride - 1);
            overflowing += count > capacity;
            auto light = [&](uint32_t k) { return (list[1 + k / 2] >> (16 * (k % 2))) & 0xFFFFu; };
            for (uint32_t k = 0; k < std::min(count, capacity); ++k) {
                EXPECT_LT(light(k), n);
                if (k > 0) {
                    EXPECT_LT(light(k - 1), light(k)) << "tile " << t;
                }
            }
            if (count > 0) {
                total += count;
                ++lit;
            }
            most = std::max(most, count);
        }
        ASSERT_GT(lit, 0u);
        if (n <= 1024) means.push_back(total / lit);
        // The froxels the fine tiles merge from: their lists' mean length over the froxels reached.
        double froxelTotal = 0;
        uint32_t froxelsReached = 0;
        for (size_t k = 4; k < f.froxels.size(); ++k)
            if (f.froxels[k] > 0) froxelTotal += f.froxels[k], ++froxelsReached;
        std::printf("      froxels: %u reached, mean %.1f lights\n", froxelsReached,
                    froxelTotal / std::max(1u, froxelsReached));
        std::printf(
            "%5u lights: %u of %u tiles reached, mean %.1f lights per reached tile, most %u; %u "
            "tiles over their list's 62, %u under a full froxel\n",
            n, lit, tx * ty, total / lit, most, overflowing, incomplete);
        // At 16 384 (16 lights per m² of floor: a 4x4 tile across a sphere's silhouette spans the
        // floor behind it) a few lists fill up.
        EXPECT_LE(incomplete + overflowing, n <= 1024 ? 0u : tx * ty / 200) << n << " lights";
        EXPECT_LT(total / lit, 0.75 * n + 8.0);
        // A tile across a sphere's silhouette spans the floor behind it: its frustum's side
        // planes keep the lights its slanting box holds beyond them out (at 16 384: most 82 with
        // the box alone, 25 with the planes).
        if (n == 16384) {
            EXPECT_LE(most, 40u);
        }
    }
    // 64x the lights, under 2x the lights per tile (measured 2.8 -> 3.8 at 1280x720 with 4x4 tiles;
    // 2.9 -> 5.2 with 8x8, 3.1 -> 8.3 with 16x16): the scene's ranges shrink as 1/sqrt(n), but a tile also reaches the
    // lights around its own footprint (about 0.05-0.15 m of floor here), and tiles across a
    // sphere's silhouette span its depth.
    const auto [lo, hi] = std::minmax_element(means.begin(), means.end());
    EXPECT_LT(*hi, 2.0 * *lo);
    EXPECT_LT(means.back(), 0.01 * 1024);
}

TEST_F(Lights, SixtyFiveThousandLightsGoThroughTheFroxels) {
    // The most lights a scene may have (shaders/lib/limits.h): the Lights buffer is sized by the
    // scene, and the froxel binning takes each light once. The many-lights scene's 65 536 lights
    // at 320x180: the tiles list lights from the whole range of indices (the scene's rows run
    // from the far edge of the floor, index 0, to the near one), ascending, each within the scene.
    constexpr uint32_t n = 65536, w = 320, h = 180;
    TiledFrame f = renderManyLights(rt(), n, true, w, h);
    ASSERT_GE(f.tiles.size(), 4u);
    const uint32_t tx = f.tiles[0], ty = f.tiles[1], stride = f.tiles[2];
    ASSERT_GE(f.tiles.size(), 4u + size_t(tx) * ty * stride);
    const uint32_t capacity = 2 * (stride - 1);
    uint32_t highest = 0, lit = 0, incomplete = 0;
    for (uint32_t t = 0; t < tx * ty; ++t) {
        const uint32_t* list = &f.tiles[4 + size_t(t) * stride];
        const uint32_t count = list[0] & 0x7FFFFFFFu;  // lib/light_tiles.glsl RG_TILE_INCOMPLETE
        incomplete += (list[0] >> 31) != 0;
        auto light = [&](uint32_t k) { return (list[1 + k / 2] >> (16 * (k % 2))) & 0xFFFFu; };
        for (uint32_t k = 0; k < std::min(count, capacity); ++k) {
            highest = std::max(highest, light(k));
            if (k > 0) {
                EXPECT_LT(light(k - 1), light(k)) << "tile " << t;
            }
        }
        lit += count > 0;
    }
    std::printf(
        "%u lights at %ux%u: %u of %u tiles lit, highest index %u, %u tiles under a full froxel\n",
        n, w, h, lit, tx * ty, highest, incomplete);
    EXPECT_GT(lit, tx * ty / 4);
    EXPECT_GE(highest, n - 2048);  // the near rows' lights are there
    double sum = 0;
    for (float v : f.hdr.pixels) sum += v;
    EXPECT_GT(sum, 0.0);
}

}  // namespace
