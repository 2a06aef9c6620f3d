// Image-based lighting (scripts/ibl.lua, shaders/ibl/, shaders/lib/ibl.glsl; seed 002 §4.9): the
// DFG table against the values and against graph/lighting's independent integrators
// (visible-normal sampling, not the table's GGX half-vector sampling), and the white furnace: a
// uniform 1-nit probe must light each sphere to the BRDF's own directional albedo.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "cli/runtime.h"
#include "cli/session.h"
#include "image/image.h"
#include "lighting/brdf.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;

// Bilinear lookup of the 128×128 table at (N·V, linear roughness), as the shaders sample it
// (clamped to the outer texel centres).
glm::vec3 dfgAt(const Image& t, float NdotV, float roughness) {
    auto coord = [](float v, uint32_t n) { return std::clamp(v * static_cast<float>(n) - 0.5f, 0.0f, static_cast<float>(n - 1)); };
    const float x = coord(NdotV, t.width), y = coord(roughness, t.height);
    const uint32_t x0 = static_cast<uint32_t>(x), y0 = static_cast<uint32_t>(y);
    const uint32_t x1 = std::min(x0 + 1, t.width - 1), y1 = std::min(y0 + 1, t.height - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    glm::vec3 out;
    for (uint32_t c = 0; c < 3; ++c) {
        const float a = t.at(x0, y0, c) * (1 - fx) + t.at(x1, y0, c) * fx;
        const float b = t.at(x0, y1, c) * (1 - fx) + t.at(x1, y1, c) * fx;
        out[static_cast<int>(c)] = a * (1 - fy) + b * fy;
    }
    return out;
}

class Ibl : public GpuFixture {
protected:
    struct Frame {
        Image hdr;  // cd/m² (pre-exposure divided out)
        Image dfg;
        Image depth;
    };
    static Frame render(const std::string& scene, uint32_t w, uint32_t h, uint32_t frames = 2,
                        const std::string& pipeline = "deferred.lua", const std::map<std::string, std::string>& args = {}) {
        SessionOptions o;
        o.sceneArgs = args;
        o.compile.outputWidth = w;
        o.compile.outputHeight = h;
        o.scene = kRoot + "/tests/gpu/scenes/" + scene;
        o.params["exposure_mode"] = Value("manual");
        // The probe alone: the reference integrates it unoccluded, so screen-space AO (the spheres
        // occlude their neighbours) is reduced to a 5 cm search.
        o.params["ao_radius"] = Value(0.05);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/" + pipeline, frames, {"hdr", "dfg", "depth"});
        Frame out;
        if (r.images.size() != 3) return out;
        out.hdr = r["hdr"];
        for (float& v : out.hdr.pixels) v /= r.preExposure;
        out.dfg = r["dfg"];
        out.depth = r["depth"];
        return out;
    }
};

TEST_F(Ibl, DfgTableMatchesTheSeedValuesAndTheIntegrators) {
    Frame f = render("furnace_grid.lua", 64, 32, 1);
    ASSERT_EQ(f.dfg.width, 128u);
    ASSERT_EQ(f.dfg.height, 128u);
    // The values (height-correlated Smith, α = roughness²), each within 0.01.
    struct Row { float NdotV, roughness, x, y; };
    for (const Row& r : {Row{1, 1, 0.307f, 0.000f}, Row{0.5f, 0.5f, 0.835f, 0.022f}, Row{1, 0.5f, 0.915f, 0.000f},
                         Row{0.125f, 0.5f, 0.747f, 0.128f}, Row{0.5f, 1, 0.446f, 0.003f}}) {
        const glm::vec3 v = dfgAt(f.dfg, r.NdotV, r.roughness);
        EXPECT_NEAR(v.x, r.x, 0.01) << "N·V " << r.NdotV << ", roughness " << r.roughness;
        EXPECT_NEAR(v.y, r.y, 0.01) << "N·V " << r.NdotV << ", roughness " << r.roughness;
    }
    // Texel centres against the C++ integrators: x = specular albedo with F = 1 − Fc (f0 1, f90 0),
    // y with F = Fc (f0 0, f90 1), z = the renormalised Disney diffuse's albedo. Roughness ≥ 0.1
    // (below, standardAlpha's 1e-3 floor differs from the table's α = r²).
    double worst = 0;
    for (uint32_t j = 15; j < 128; j += 16)
        for (uint32_t i = 3; i < 128; i += 16) {
            const float NdotV = (static_cast<float>(i) + 0.5f) / 128.0f, r = (static_cast<float>(j) + 0.5f) / 128.0f;
            const double x = brdf::specularAlbedo(NdotV, r, 1.0f, 0.0f, 96);
            const double y = brdf::specularAlbedo(NdotV, r, 0.0f, 1.0f, 96);
            const double z = brdf::diffuseAlbedo(NdotV, r, 96);
            // 0.01: the bound; measured worst 0.0083 (the table's 1024 Hammersley samples
            // against the integrators' 96² grid, and half-float storage).
            EXPECT_NEAR(f.dfg.at(i, j, 0), x, 0.01) << "texel " << i << ", " << j;
            EXPECT_NEAR(f.dfg.at(i, j, 1), y, 0.01) << "texel " << i << ", " << j;
            EXPECT_NEAR(f.dfg.at(i, j, 2), z, 0.01) << "texel " << i << ", " << j;
            worst = std::max({worst, std::abs(f.dfg.at(i, j, 0) - x), std::abs(f.dfg.at(i, j, 1) - y), std::abs(f.dfg.at(i, j, 2) - z)});
        }
    std::printf("DFG table vs integrators: worst |difference| %.5f over 64 texels\n", worst);
}

TEST_F(Ibl, WhiteFurnaceGivesTheBrdfAlbedo) {
    // 1 nit everywhere: at N·V = 1 the split sum is exact (LD = 1 at every mip, SH irradiance = π),
    // so each sphere centre shows its directional albedo: dielectric z + 0.04 x + y (f90 = 1 for
    // f0 = 0.04), metal x + y (f0 = f90 = 1). How far that is from the probe's 1 nit is the BRDF's
    // own energy balance, not the IBL's error: single scattering loses up to 69 % for a metal at
    // roughness 1, the renormalised Disney diffuse 30 % (seed 000 Figure 9). The bound (2 %) covers
    // half-float storage, the table's 1024 samples and the centre pixel's N·V ≈ 0.999; measured
    // worst 1.6 % (metal, roughness 1, where the table is steepest), the rest ≤ 0.3 %.
    const uint32_t W = 320, H = 64;
    Frame f = render("furnace_grid.lua", W, H);
    ASSERT_EQ(f.hdr.width, W);
    // The sky: the environment itself, 1 nit.
    EXPECT_NEAR(f.hdr.at(2, 2, 1), 1.0f, 0.002f);
    // Sphere centres on screen: fov 8.5° at 40 m shows ±2.97 m vertically; x by the aspect ratio.
    const float halfH = 40.0f * std::tan(8.5f * 3.14159265f / 360.0f), halfW = halfH * static_cast<float>(W) / static_cast<float>(H);
    std::printf("white furnace, 1 nit: rendered / expected (expected = the BRDF's albedo at N·V = 1)\n");
    for (int metal = 0; metal <= 1; ++metal)
        for (int i = 0; i < 5; ++i) {
            const float wx = static_cast<float>(i - 2), wy = static_cast<float>(metal == 0 ? -0.5 : 0.5);
            const uint32_t px = static_cast<uint32_t>((wx / halfW * 0.5f + 0.5f) * static_cast<float>(W));
            const uint32_t py = static_cast<uint32_t>((0.5f - wy / halfH * 0.5f) * static_cast<float>(H));
            const float r = static_cast<float>(i) / 4.0f;
            const double x = brdf::specularAlbedo(1.0f, r, 1.0f, 0.0f), y = brdf::specularAlbedo(1.0f, r, 0.0f, 1.0f);
            const double expected = metal ? x + y : brdf::diffuseAlbedo(1.0f, r) + 0.04 * x + y;
            const float got = f.hdr.at(px, py, 1);
            std::printf("  %s roughness %.2f: %.4f / %.4f\n", metal ? "metal     " : "dielectric", r, got, expected);
            EXPECT_NEAR(got / expected, 1.0, 0.02) << (metal ? "metal" : "dielectric") << " roughness " << r;
        }
}

TEST_F(Ibl, SplitSumAgainstTheReferenceUnderTheSky) {
    // The sphere grid under the clear sky (no light): the real-time probe (pre-filtered cube, SH
    // diffuse, DFG, dominant directions) against reference.lua's Monte Carlo integral of the same
    // environment through the same BRDF (64 frames × 4 BRDF samples). Mean relative error over the
    // spheres' pixels (depth < 1), per row and overall; the bound is 5 %.
    const uint32_t W = 200, H = 48;
    const std::map<std::string, std::string> sky{{"environment", "sky"}};
    Frame rt = render("furnace_grid.lua", W, H, 2, "deferred.lua", sky);
    Frame ref = render("furnace_grid.lua", W, H, 64, "reference.lua", sky);
    ASSERT_EQ(rt.hdr.width, W);
    ASSERT_EQ(ref.hdr.width, W);
    double err[2] = {0, 0}, sumRt = 0, sumRef = 0;
    int n[2] = {0, 0};
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            if (rt.depth.at(x, y, 0) >= 1.0f) continue;
            const int row = y < H / 2 ? 1 : 0;  // metals on top
            for (uint32_t c = 0; c < 3; ++c) {
                const double a = rt.hdr.at(x, y, c), b = ref.hdr.at(x, y, c);
                err[row] += std::abs(a - b) / std::max(b, 1e-3);
                sumRt += a;
                sumRef += b;
            }
            n[row] += 3;
        }
    ASSERT_GT(n[0], 300);
    ASSERT_GT(n[1], 300);
    const double dielectric = err[0] / n[0], metal = err[1] / n[1], all = (err[0] + err[1]) / (n[0] + n[1]);
    std::printf("IBL vs reference under the sky: mean relative error dielectric %.2f %%, metal %.2f %%, all %.2f %%; energy %+.2f %%\n",
                100 * dielectric, 100 * metal, 100 * all, 100 * (sumRt / sumRef - 1));
    EXPECT_LT(all, 0.05);
}

}  // namespace
