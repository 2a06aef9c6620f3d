// Image-based lighting (scripts/ibl.lua, shaders/ibl/, shaders/lib/ibl.glsl; seed 002 §4.9): the
// DFG table against the issue's values and against graph/lighting's independent integrators
// (visible-normal sampling, not the table's GGX half-vector sampling), and the white furnace: a
// uniform 1-nit probe must light each sphere to the BRDF's own directional albedo.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

#include <glm/glm.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "cli/accuracy_ibl.h"
#include "lighting/brdf.h"
#include "scene/environment.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;

// Bilinear lookup of the 128×128 table at (N·V, linear roughness), as the shaders sample it
// (clamped to the outer texel centres).
glm::vec3 dfgAt(const Image& t, float NdotV, float roughness) {
    auto coord = [](float v, uint32_t n) {
        return std::clamp(v * static_cast<float>(n) - 0.5f, 0.0f, static_cast<float>(n - 1));
    };
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
                        const std::string& pipeline = "deferred.lua",
                        const std::map<std::string, std::string>& args = {}) {
        SessionOptions o;
        o.sceneArgs = args;
        o.compile.outputWidth = w;
        o.compile.outputHeight = h;
        o.scene = kRoot + "/tests/gpu/scenes/" + scene;
        o.params["exposure_mode"] = Value("manual");
        o.paramsIfDeclared["taa_jitter"] = Value(false);   // pixels compared one by one
        o.paramsIfDeclared["specular_aa"] = Value(false);  // roughness as the scene gives it
        // The probe alone: the reference integrates it unoccluded, so screen-space AO (the spheres
        // occlude their neighbours) is reduced to a 5 cm search.
        o.params["ao_radius"] = Value(0.05);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/" + pipeline, frames,
                                   {"hdr", "dfg", "depth"});
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
    // The issue's values (height-correlated Smith, α = roughness²), each within 0.01.
    struct Row {
        float NdotV, roughness, x, y;
    };
    for (const Row& r :
         {Row{1, 1, 0.307f, 0.000f}, Row{0.5f, 0.5f, 0.835f, 0.022f}, Row{1, 0.5f, 0.915f, 0.000f},
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
            const float NdotV = (static_cast<float>(i) + 0.5f) / 128.0f,
                        r = (static_cast<float>(j) + 0.5f) / 128.0f;
            const double x = brdf::specularAlbedo(NdotV, r, 1.0f, 0.0f, 96);
            const double y = brdf::specularAlbedo(NdotV, r, 0.0f, 1.0f, 96);
            const double z = brdf::diffuseAlbedo(NdotV, r, 96);
            // 0.01: the issue's bound; measured worst 0.0083 (the table's 1024 Hammersley samples
            // against the integrators' 96² grid, and half-float storage).
            EXPECT_NEAR(f.dfg.at(i, j, 0), x, 0.01) << "texel " << i << ", " << j;
            EXPECT_NEAR(f.dfg.at(i, j, 1), y, 0.01) << "texel " << i << ", " << j;
            EXPECT_NEAR(f.dfg.at(i, j, 2), z, 0.01) << "texel " << i << ", " << j;
            worst = std::max({worst, std::abs(f.dfg.at(i, j, 0) - x),
                              std::abs(f.dfg.at(i, j, 1) - y), std::abs(f.dfg.at(i, j, 2) - z)});
        }
    std::printf("DFG table vs integrators: worst |difference| %.5f over 64 texels\n", worst);
    // w: the sheen lobe's directional albedo (Charlie, Neubelt) against the brute-force integral,
    // relative: it spans 0.01–1.5 over the table. From sheen roughness 0.3 up (below, the lobe
    // gathers at the horizon and the table's 1024 cosine-distributed samples miss it: there the
    // sheen is a thin rim and its scaling of the base small).
    double worstSheen = 0;
    for (uint32_t j = 39; j < 128; j += 16)
        for (uint32_t i = 3; i < 128; i += 16) {
            const float NdotV = (static_cast<float>(i) + 0.5f) / 128.0f,
                        r = (static_cast<float>(j) + 0.5f) / 128.0f;
            const double e = brdf::sheenAlbedo(NdotV, r);
            const double d = std::abs(f.dfg.at(i, j, 3) - e) / std::max(e, 0.05);
            EXPECT_LT(d, 0.03) << "texel " << i << ", " << j << ": " << f.dfg.at(i, j, 3)
                               << " against " << e;
            worstSheen = std::max(worstSheen, d);
        }
    std::printf("sheen albedo (w) vs the integral: worst relative difference %.4f over 48 texels\n",
                worstSheen);
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
    const float halfH = 40.0f * std::tan(8.5f * 3.14159265f / 360.0f),
                halfW = halfH * static_cast<float>(W) / static_cast<float>(H);
    std::printf(
        "white furnace, 1 nit: rendered / expected (expected = the BRDF's albedo at N·V = 1)\n");
    for (int metal = 0; metal <= 1; ++metal)
        for (int i = 0; i < 5; ++i) {
            const float wx = static_cast<float>(i - 2),
                        wy = static_cast<float>(metal == 0 ? -0.5 : 0.5);
            const uint32_t px =
                static_cast<uint32_t>((wx / halfW * 0.5f + 0.5f) * static_cast<float>(W));
            const uint32_t py =
                static_cast<uint32_t>((0.5f - wy / halfH * 0.5f) * static_cast<float>(H));
            const float r = static_cast<float>(i) / 4.0f;
            const double x = brdf::specularAlbedo(1.0f, r, 1.0f, 0.0f),
                         y = brdf::specularAlbedo(1.0f, r, 0.0f, 1.0f);
            const double expected = metal ? x + y : brdf::diffuseAlbedo(1.0f, r) + 0.04 * x + y;
            const float got = f.hdr.at(px, py, 1);
            std::printf("  %s roughness %.2f: %.4f / %.4f\n", metal ? "metal     " : "dielectric",
                        r, got, expected);
            EXPECT_NEAR(got / expected, 1.0, 0.02)
                << (metal ? "metal" : "dielectric") << " roughness " << r;
        }
}

TEST_F(Ibl, SplitSumAgainstTheReferenceUnderTheSky) {
    // The sphere grid under the clear sky (no light): the real-time probe (pre-filtered cube, SH
    // diffuse, DFG, dominant directions) against reference.lua's Monte Carlo integral of the same
    // environment through the same BRDF (64 frames × 4 BRDF samples). Mean relative error over the
    // spheres' pixels (depth < 1), per row and overall; the issue's bound is 5 %.
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
    const double dielectric = err[0] / n[0], metal = err[1] / n[1],
                 all = (err[0] + err[1]) / (n[0] + n[1]);
    std::printf(
        "IBL vs reference under the sky: mean relative error dielectric %.2f %%, metal %.2f %%, "
        "all %.2f %%; energy %+.2f %%\n",
        100 * dielectric, 100 * metal, 100 * all, 100 * (sumRt / sumRef - 1));
    EXPECT_LT(all, 0.05);
}

}  // namespace

// Seed 002 §4.9.2's distant probe against its definitions (graph/cli/accuracy_ibl.h, what
// `rgraph accuracy --ibl` prints): the pre-filtered mips against the split sum's definition
// (v = n) and the SH irradiance against the exact one, both integrated over every texel of the
// very cube the filter reads, so that the filtering alone is measured; under a synthetic sky of
// 10 nits with a 0.5° sun (the peaked source the analytic sky and the furnaces cannot show) and
// the shared HDRIs where present, their suns kept in the probe. Bounds: a mip whose lobe the cube
// resolves within 5 % in every direction, the narrower ones' mean within 2 %, the SH within 10 %
// where the irradiance is at least a quarter of its peak. Before the hot texels were taken out and
// the mips weighted by solid angle: up to +440 % (qwantani, mip 5, mean 72 %), +300 %
// (chinese_garden), 7.8 % (the synthetic sun; `rgraph accuracy --ibl` with RG_ROOT at those
// scripts fails it).
TEST_F(Ibl, PrefilteredProbeMatchesTheExactPrefilter) {
    IblAccuracyOptions o;
    o.environments = {"synthetic"};
    o.scratchDir = testing::TempDir();
    for (const char* hdri : {"qwantani_afternoon_puresky_1k.hdr", "chinese_garden_1k.hdr"}) {
        const std::string file = kRoot + "/../shared/assets/hdri/" + hdri;
        if (std::filesystem::exists(file))
            o.environments.push_back(file);
        else
            std::printf("skipped %s: ../shared/assets/hdri is not here\n", hdri);
    }
    auto r = runIblAccuracy(rt(), o);
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    std::printf("%s", iblAccuracyTable(*r).c_str());
    ASSERT_EQ(r->environments.size(), o.environments.size());
    for (const auto& e : r->environments) {
        EXPECT_LE(e.shLitWorst, kIblShLitBound) << e.name;
        ASSERT_EQ(e.mips.size(), 8u) << e.name << ": env_specular is 256², 9 mips";
        for (const auto& m : e.mips)
            EXPECT_TRUE(m.pass()) << e.name << " mip " << m.mip << ": worst " << m.worst
                                  << ", mean " << m.mean;
    }
    EXPECT_LE(r->dfgWorst, kIblDfgBound);
    EXPECT_TRUE(r->pass());
}

// Seed 002 §4.9.1.1 under an HDRI's sun (environment_sun.cpp): with `sun = "light"` the sun
// leaves the probe — no texel of the cube the lighting filters is left above 20 × its mean — and
// lights the scene as a sun light; with "keep" it stays in the probe. Counted once either way:
// the rough white sphere's centre facing the sun-lit side agrees between the two within 10 % (the
// order-2 SH's error on lit directions, ~7.5 %), where counting it twice would add ~80 %. A
// synthetic sky of 10 nits and a 2° sun of 40 000 nits (under the half-float cube's 65 504).
TEST_F(Ibl, AnHdrisSunIsTakenOutIntoALightAndCountedOnce) {
    const uint32_t w = 1024, h = 512;
    Image sky(w, h, 3);
    const glm::dvec3 toSun = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
    const double cosRadius = std::cos(2.0 * 3.14159265358979 / 180.0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const glm::dvec3 d(equirectDirection({float((x + 0.5) / w), float((y + 0.5) / h)}));
            for (uint32_t c = 0; c < 3; ++c)
                sky.at(x, y, c) = glm::dot(d, toSun) >= cosRadius ? 4e4f : 10.0f;
        }
    const std::string file = testing::TempDir() + "/hdri_sun.exr";
    ASSERT_TRUE(writeExr(file, {{"", {"R", "G", "B"}, sky}}).has_value());
    float centre[2] = {};
    for (int mode = 0; mode < 2; ++mode) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/furnace_grid.lua", {}, 160, 64);
        o.environment = file;
        o.environmentSun = mode ? "light" : "keep";
        o.params["ao_radius"] = Value(0.05);
        Readback r =
            renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 2, {"hdr", "env_source"});
        ASSERT_EQ(r.images.size(), 2u);
        // The rough dielectric (row 0, last column: x = 2, y = −0.5 m at 40 m, fov 8.5°): the
        // 3 × 3 pixels at its centre, in nits.
        const Image& hdr = r["hdr"];
        const double half = 40.0 * std::tan(4.25 * 3.14159265358979 / 180.0);  // metres
        const int cx = int(hdr.width / 2 + 2.0 / half * hdr.height / 2),
                  cy = int(hdr.height / 2 + 0.5 / half * hdr.height / 2);
        double sum = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) sum += hdr.at(uint32_t(cx + dx), uint32_t(cy + dy), 1);
        centre[mode] = float(sum / 9.0 / r.preExposure);
        // The cube the probe is filtered from: its brightest texel against its mean.
        double peak = 0.0, mean = 0.0;
        size_t n = 0;
        for (uint32_t f = 0; f < 6; ++f) {
            auto face = rt().executor().readback("env_source", f, 0);
            ASSERT_TRUE(face.has_value()) << face.error().describe();
            for (size_t i = 1; i < face->pixels.size(); i += face->channels, ++n) {
                peak = std::max(peak, double(face->pixels[i]));
                mean += face->pixels[i];
            }
        }
        mean /= double(n);
        std::printf(
            "sun %s: the rough sphere's centre %.1f nits, the cube's peak %.0f x its mean\n",
            mode ? "light" : "keep", double(centre[mode]), peak / mean);
        if (mode)
            EXPECT_LT(peak, 20.0 * mean);
        else
            EXPECT_GT(peak, 1000.0 * mean);
    }
    EXPECT_NEAR(centre[1] / centre[0], 1.0, 0.10);
}
