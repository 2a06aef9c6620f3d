// Baked GI at run time (scripts/lightmap.lua, shaders/lib/lightmap.glsl): the deferred pipeline's
// render of the Cornell box, lit only by its baked lightmap (the ceiling light is `baked`), against
// a Monte Carlo reference image with indirect light computed here (tests/unit/gi_reference.h) from
// the same camera; the debug views of the lightmap; the pipeline switch.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>

#include "../unit/gi_reference.h"
#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "scene/scene.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t N = 128;

class LightmapRender : public GpuFixture {
protected:
    static SessionOptions options() {
        SessionOptions o;
        o.scene = kRoot + "/scripts/scenes/cornell.lua";
        o.compile.outputWidth = N;
        o.compile.outputHeight = N;
        o.params["exposure_mode"] = Value("manual");
        o.bakeLightmap = bake::bakeLightmap;
        return o;
    }
};

TEST_F(LightmapRender, CornellBoxMatchesAMonteCarloReferenceWithIndirectLight) {
    // The reference is Lambertian: the lightmap's specular reflection is left out here (the
    // furnace test below checks it).
    SessionOptions o = options();
    o.params["lightmap_specular"] = Value(false);
    // The reference has no screen-space AO (the lightmap holds the room's own occlusion): AO's
    // search shrunk to 5 cm. With it at its 1 m, the corners darken (the next test).
    o.params["ao_radius"] = Value(0.05);
    // Nor the ceiling light's panel: the reference's light is not a surface.
    o.params["light_shapes"] = Value(false);
    Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
    ASSERT_EQ(r.images.count("hdr"), 1u);
    const Image& hdr = r["hdr"];
    ASSERT_EQ(hdr.width, N);

    SceneScriptOptions so;
    so.projectRoot = kRoot;
    auto scene = loadSceneScript(kRoot + "/scripts/scenes/cornell.lua", so);
    ASSERT_TRUE(scene);
    const test::BruteForceGi truth(*scene);
    const Camera& cam = scene->cameras.at(0);
    const glm::vec3 fwd = glm::normalize(cam.target - cam.position),
                    right = glm::normalize(glm::cross(fwd, cam.up)), up = glm::cross(right, fwd);
    const float t = std::tan(cam.verticalFov * 0.5f);
    // Per pixel: the surface at the pixel's centre, its luminance Le + ρ/π E with E from 2 × 32
    // paths (two halves, to state the reference's own noise).
    std::vector<glm::vec3> refA(size_t(N) * N, glm::vec3(-1.0f)),
        refB(refA.size(), glm::vec3(-1.0f));
    std::mt19937 rng(11);
    for (uint32_t y = 0; y < N; ++y)
        for (uint32_t x = 0; x < N; ++x) {
            const float sx = ((float(x) + 0.5f) / float(N) * 2.0f - 1.0f) * t,
                        sy = (1.0f - (float(y) + 0.5f) / float(N) * 2.0f) * t;
            const glm::vec3 d = glm::normalize(fwd + right * sx + up * sy);
            const auto [i, dist] = truth.hit(cam.position, d, 1e30f);
            if (i < 0) continue;
            const auto& tri = truth.tris[size_t(i)];
            if (glm::dot(tri.n, d) > 0.0f) continue;
            const glm::vec3 p = cam.position + d * dist + tri.n * 1e-4f;
            refA[size_t(y) * N + x] =
                tri.emission + tri.albedo / float(test::kGiPi) *
                                   truth.irradiance(p, tri.n, 32, static_cast<uint32_t>(rng()));
            refB[size_t(y) * N + x] =
                tri.emission + tri.albedo / float(test::kGiPi) *
                                   truth.irradiance(p, tri.n, 32, static_cast<uint32_t>(rng()));
        }
    // Compared over 8×8-pixel blocks (each 4096 reference paths), over blocks whose 64 pixels all
    // hit the room and are above 1 % of the peak: the lightmap's error, not the reference's noise.
    auto lum = [](glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; };
    double peak = 0.0;
    for (const auto& c : refA) peak = std::max(peak, double(lum(c)));
    double sumErr = 0.0, sumNoise = 0.0, energyRender = 0.0, energyRef = 0.0, worst = 0.0;
    int blocks = 0;
    for (uint32_t by = 0; by < N; by += 8)
        for (uint32_t bx = 0; bx < N; bx += 8) {
            double render = 0.0, a = 0.0, b = 0.0;
            bool ok = true;
            for (uint32_t y = by; y < by + 8; ++y)
                for (uint32_t x = bx; x < bx + 8; ++x) {
                    const size_t i = size_t(y) * N + x;
                    if (refA[i].r < 0.0f) ok = false;
                    const glm::vec3 c(hdr.at(x, y, 0), hdr.at(x, y, 1), hdr.at(x, y, 2));
                    render += lum(c) / r.preExposure;
                    a += lum(refA[i]), b += lum(refB[i]);
                }
            const double ref = 0.5 * (a + b);
            if (!ok || ref / 64.0 < 0.01 * peak) continue;
            const double err = std::abs(render - ref) / ref;
            sumErr += err, worst = std::max(worst, err);
            sumNoise += std::abs(a - b) /
                        (a + b);  // the half-difference: one standard error of the mean, roughly
            energyRender += render, energyRef += ref;
            ++blocks;
        }
    ASSERT_GT(blocks, 100);
    const double mean = sumErr / blocks, noise = sumNoise / blocks,
                 energy = energyRender / energyRef - 1.0;
    std::printf(
        "Cornell box, lightmap render vs Monte Carlo reference (%d blocks of 8×8 px): mean error "
        "%.2f %%, worst block %.2f %%, "
        "energy %+.2f %%; the reference's own noise %.2f %%\n",
        blocks, mean * 100.0, worst * 100.0, energy * 100.0, noise * 100.0);
    EXPECT_LT(mean, 0.08);
    EXPECT_LT(std::abs(energy), 0.05);
}

TEST_F(LightmapRender, ViewsShowTheIrradianceAndEachLobe) {
    auto view = [&](const std::string& name) -> Result<Image> {
        SessionOptions o = options();
        o.view = name;
        Session s(*s_runtime, o);
        if (auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua"); !r)
            return std::unexpected(r.error());
        if (auto f = s.frame(); !f) return std::unexpected(f.error());
        return s_runtime->executor().readback("debug_view");
    };
    auto irr = view("lightmap");
    ASSERT_TRUE(irr) << irr.error().message;
    // Irradiance, not radiosity: on the red wall it is the light arriving (white-ish from the
    // panel, bounced green from across the room), not the wall's red.
    const uint32_t fx = 37, fy = 118, wx = 20, wy = 64;
    auto at = [](const Image& v, uint32_t x, uint32_t y) {
        return glm::vec3(v.at(x, y, 0), v.at(x, y, 1), v.at(x, y, 2));
    };
    const glm::vec3 floor = at(*irr, fx, fy), wall = at(*irr, wx, wy);
    std::printf("lightmap view: floor %.2f %.2f %.2f, red wall %.2f %.2f %.2f\n", floor.r, floor.g,
                floor.b, wall.r, wall.g, wall.b);
    EXPECT_GT(floor.g, 0.2f);
    EXPECT_GT(wall.g, 0.2f);
    EXPECT_LT(wall.r / wall.g, 1.2f);
    // One lobe: sg0 (the lobe nearest the normal) is lit on the floor; every lobe is in 0..1 once displayed.
    auto lobe = view("sg0");
    ASSERT_TRUE(lobe) << lobe.error().message;
    EXPECT_GT(at(*lobe, fx, fy).g, 0.05f);
    EXPECT_NE(at(*lobe, fx, fy), floor);
    auto bad = view("sg9");  // 9 lobes: sg0 .. sg8
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("sg0 .. sg8"), std::string::npos) << bad.error().message;
}

TEST_F(LightmapRender, SpecularIsThePrefilteredRadianceInAFurnace) {
    // Uniform 1-nit light over the hemisphere: the lightmap's specular term (the radiance SGs
    // integrated against the warped GGX lobe, normalised) is 1 for every roughness and view, but
    // where the lobe reaches below the horizon (grazing views of a rough plane).
    for (const char* smoothness : {"0.9", "0.5", "0.2"}) {
        SessionOptions o = options();
        o.scene = kRoot + "/tests/gpu/scenes/lightmap_furnace.lua";
        o.sceneArgs = {{"smoothness", smoothness}};
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1,
                                   {"lightmap_specular", "hdr"});
        ASSERT_EQ(r.images.count("lightmap_specular"), 1u);
        const Image& ld = r["lightmap_specular"];
        // Rows from the middle of the image (n·v ≈ 0.6) to its bottom (≈ 0.8).
        double sum = 0.0, lo = 1e9, hi = 0.0;
        int count = 0;
        for (uint32_t y = N / 2; y < N; y += 4)
            for (uint32_t x = N / 4; x < 3 * N / 4; x += 4) {
                const double v = ld.at(x, y, 1);
                sum += v, lo = std::min(lo, v), hi = std::max(hi, v), ++count;
            }
        std::printf("furnace, smoothness %s: lightmap specular %.3f (%.3f .. %.3f) nits\n",
                    smoothness, sum / count, lo, hi);
        EXPECT_NEAR(sum / count, 1.0, 0.06) << smoothness;
        EXPECT_GT(lo, 0.85) << smoothness;
        EXPECT_LT(hi, 1.1) << smoothness;
    }
}

// Seed 002 §4.10.3: the baked radiosity is occluded by min(baked AO, SSAO) as the probe's diffuse
// would be (materials/standard_shading.glsl, GB2.reserved = 1 where GB3 holds radiosity alone).
// The Cornell box lit by its lightmap only, its diffuse alone (no lightmap specular): each pixel's
// luminance with AO at its 1 m against the same with AO's search shrunk to 5 cm changes by the
// ratio of the two AO images (the `ssao` view, which takes the pipeline's --set parameters as the
// frame does), in the room's creases where AO is under 0.9.
TEST_F(LightmapRender, RadiosityIsOccludedByTheScreenSpaceAo) {
    auto frame = [&](double radius, const std::string& view) {
        SessionOptions o = options();
        o.params["lightmap_specular"] = Value(false);
        o.params["ao_radius"] = Value(radius);
        o.view = view;
        return renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1,
                             {view.empty() ? "hdr" : "debug_view"});
    };
    Readback aoOff = frame(0.05, "ssao"), on = frame(1.0, ""), off = frame(0.05, ""),
             aoOn = frame(1.0, "ssao");
    ASSERT_EQ(on.images.size(), 1u);
    ASSERT_EQ(aoOn.images.size(), 1u);
    double sum = 0.0, worst = 0.0, darkest = 1.0;
    int count = 0;
    for (uint32_t y = 2; y < N - 2; ++y)
        for (uint32_t x = 2; x < N - 2; ++x) {
            const double a = aoOn["debug_view"].at(x, y, 0), b = aoOff["debug_view"].at(x, y, 0);
            const double lumOff = off["hdr"].at(x, y, 1) / off.preExposure;
            if (a >= 0.9 || b < 0.5 || lumOff < 0.5) continue;
            const double ratio = (on["hdr"].at(x, y, 1) / on.preExposure) / lumOff;
            const double e = std::abs(ratio / (a / b) - 1.0);
            sum += e, worst = std::max(worst, e), darkest = std::min(darkest, ratio), ++count;
        }
    ASSERT_GT(count, 100);
    std::printf(
        "radiosity under AO: %d crease pixels, luminance ratio against the AO ratio: mean error "
        "%.2f %%, worst %.2f %%; darkest ratio %.2f\n",
        count, 100 * sum / count, 100 * worst, darkest);
    EXPECT_LT(sum / count, 0.02);
    EXPECT_LT(darkest, 0.8);  // the creases really darken (before: 1, the radiosity as baked)

    // The material's own AO counts once: min(0.5, SSAO ≈ 1), not 0.5 × min(0.5, …). The furnace's
    // open plane (ρ 0.8, E = π): radiosity 0.8 × 0.5 = 0.4 nits.
    SessionOptions o = options();
    o.scene = kRoot + "/tests/gpu/scenes/lightmap_furnace.lua";
    o.sceneArgs = {{"ao", "0.5"}};
    o.params["lightmap_specular"] = Value(false);
    Readback plane = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
    ASSERT_EQ(plane.images.size(), 1u);
    const double centre = plane["hdr"].at(N / 2, 3 * N / 4, 1) / plane.preExposure;
    std::printf("furnace plane of AO 0.5: %.3f nits (radiosity 0.4 and a little specular)\n",
                centre);
    EXPECT_NEAR(centre, 0.4, 0.04);
}

TEST_F(LightmapRender, ThePipelineSwitchTurnsItOff) {
    // lightmap = false: no radiosity, and the baked light is real-time again — direct light only.
    // The ceiling, which only bounced light reaches (the panel faces down, there is no
    // environment), goes black; the floor under the light stays lit.
    SessionOptions o = options();
    o.params["lightmap"] = Value(false);
    Readback off = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
    Readback on = renderAndRead(options(), kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
    ASSERT_EQ(off.images.count("hdr"), 1u);
    ASSERT_EQ(on.images.count("hdr"), 1u);
    auto nits = [](const Readback& r, uint32_t x, uint32_t y) {
        return r["hdr"].at(x, y, 1) / r.preExposure;
    };
    const uint32_t fx = 37, fy = 118,
                   cy = 4;  // the floor at (-0.5, 0, 0.5); the ceiling above the front
    std::printf(
        "with the lightmap: floor %.2f, ceiling %.2f nits; without: floor %.2f, ceiling %.3f "
        "nits\n",
        nits(on, fx, fy), nits(on, fx, cy), nits(off, fx, fy), nits(off, fx, cy));
    EXPECT_GT(nits(on, fx, cy), 2.0f);
    EXPECT_LT(nits(off, fx, cy), 0.01f);
    EXPECT_GT(nits(off, fx, fy), 5.0f);
}

}  // namespace
