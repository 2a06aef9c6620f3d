// The sun's cascaded shadow map (scripts/shadows.lua, shaders/shadows/, lib/shadows.glsl; seed 002
// §4.10.4) on tests/gpu/scenes/shadow_box.lua: a unit box on a plane seen from straight above, so
// that every pixel is a known ground point and the shadow's extent follows from the geometry.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>

#include "cli/runtime.h"
#include "cli/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t N = 320;                                      // square image
const float kHalf = 12.0f * std::tan(15.0f * 3.14159265f / 180.0f);  // the ground the view spans: ±3.215 m

struct Frame {
    Image hdr;
    std::vector<uint8_t> cascades;  // lib/shadows.glsl's RgCascades
};

// Ground point of pixel (px, py): screen right is +x, screen up is −z.
float worldX(uint32_t px) { return ((static_cast<float>(px) + 0.5f) / N * 2.0f - 1.0f) * kHalf; }
float worldZ(uint32_t py) { return ((static_cast<float>(py) + 0.5f) / N * 2.0f - 1.0f) * kHalf; }

class Shadows : public GpuFixture {
protected:
    static Frame render(const std::map<std::string, std::string>& args, uint32_t frames = 1, const std::string& camera = "top",
                        bool sunShadows = true) {
        SessionOptions o;
        o.sceneArgs = args;
        o.camera = camera;
        o.params["sun_shadows"] = Value(sunShadows);
        o.compile.outputWidth = N;
        o.compile.outputHeight = N;
        o.scene = kRoot + "/tests/gpu/scenes/shadow_box.lua";
        o.params["exposure_mode"] = Value("manual");
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", frames, {"hdr"}, {"sun_cascades"});
        Frame out;
        if (r.images.empty() || r.buffers.empty()) return out;
        out.hdr = r["hdr"];
        out.cascades = r.buffers["sun_cascades"];
        return out;
    }

    // Every ground pixel (outside the box's footprint, with a margin) of a region: lit or in shadow.
    struct Count { int lit = 0, shadowed = 0, total = 0; };
    static Count classify(const Image& hdr, float litLevel, const std::function<bool(float, float)>& inside) {
        Count c;
        for (uint32_t py = 0; py < N; ++py)
            for (uint32_t px = 0; px < N; ++px) {
                const float x = worldX(px), z = worldZ(py);
                if (std::abs(x) < 0.55f && std::abs(z) < 0.55f) continue;  // the box (its top and sides)
                if (!inside(x, z)) continue;
                const float v = hdr.at(px, py, 1) / litLevel;
                ++c.total;
                if (v > 0.9f) ++c.lit;
                if (v < 0.1f) ++c.shadowed;
            }
        return c;
    }
};

TEST_F(Shadows, BoxShadowFallsWhereTheGeometryPutsIt) {
    // x45: the light travels along (−1, −1, 0); the box's top edge at 1 m throws the shadow 1 m
    // towards −x: ground in shadow for x ∈ [−1.5, −0.5], z ∈ [−0.5, 0.5]. z30: 30° up, travelling
    // towards +z: shadow for z ∈ [0.5, 0.5 + √3], x ∈ [−0.5, 0.5]. Margins of 8 cm around each edge
    // (four pixels; the sun's penumbra here is under 2 cm).
    struct Case { const char* sun; std::function<bool(float, float)> shadow, lit; };
    const float m = 0.08f, far = 0.5f + std::sqrt(3.0f);
    const Case cases[] = {
        {"x45", [=](float x, float z) { return x > -1.5f + m && x < -0.5f - m && std::abs(z) < 0.5f - m; },
         [=](float x, float z) { return x < -1.5f - m || x > 0.5f + m || std::abs(z) > 0.5f + m; }},
        {"z30", [=](float x, float z) { return z > 0.5f + m && z < far - m && std::abs(x) < 0.5f - m; },
         [=](float x, float z) { return z < -0.5f - m || z > far + m || std::abs(x) > 0.5f + m; }},
    };
    for (const Case& c : cases) {
        Frame f = render({{"sun", c.sun}});
        ASSERT_EQ(f.hdr.width, N);
        const float litLevel = f.hdr.at(5, 5, 1);  // a corner of the open ground
        ASSERT_GT(litLevel, 0.0f);
        const Count shadow = classify(f.hdr, litLevel, c.shadow), lit = classify(f.hdr, litLevel, c.lit);
        std::printf("sun %s: shadow region %d/%d dark, open ground %d/%d lit\n", c.sun, shadow.shadowed, shadow.total, lit.lit, lit.total);
        EXPECT_GT(shadow.total, 500);
        EXPECT_EQ(shadow.shadowed, shadow.total) << c.sun;
        EXPECT_EQ(lit.lit, lit.total) << c.sun;
    }
}

TEST_F(Shadows, NoAcneOnAnOpenPlaneUnderAGrazingSun) {
    // The plane alone, the sun 30° above it: every ground pixel lit, within 1 % of the corner's level
    // (the sun at 30° on a 0.5 grey: no shadow-map self-shadowing anywhere in view).
    Frame f = render({{"sun", "z30"}, {"box", "0"}});
    const float litLevel = f.hdr.at(N / 2, N / 2, 1);
    ASSERT_GT(litLevel, 0.0f);
    int acne = 0;
    float worst = 1.0f;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            const float v = f.hdr.at(px, py, 1) / litLevel;
            worst = std::min(worst, v);
            if (v < 0.99f) ++acne;
        }
    std::printf("open plane, sun 30° up: darkest pixel %.4f of the centre's\n", worst);
    EXPECT_EQ(acne, 0);
}

TEST_F(Shadows, NearCascadesAddNothingToAnOpenPlane) {
    // A low view over the open plane (the ground from 1.5 m on: every cascade, the nearest too),
    // for both suns: the image with the sun's shadows equals the one without within 1 %. (Drawing
    // all cascades in one multiview pass once put false shadows in the nearest cascade.)
    for (const char* sun : {"x45", "z30"}) {
        Frame lit = render({{"sun", sun}, {"box", "0"}}, 1, "near", true);
        Frame ref = render({{"sun", sun}, {"box", "0"}}, 1, "near", false);
        ASSERT_EQ(lit.hdr.width, N);
        int off = 0;
        for (size_t i = 1; i < lit.hdr.pixels.size(); i += 4)
            if (std::abs(lit.hdr.pixels[i] - ref.hdr.pixels[i]) > 0.01f * ref.hdr.pixels[i] + 1e-3f) ++off;
        EXPECT_EQ(off, 0) << sun;
    }
}

TEST_F(Shadows, ContactHasNoGapAndPenumbraGrowsWithTheSun) {
    // At the contact (the box's −x side, ground 2–4 cm from it) the ground is dark: no peter-panning
    // beyond 2 cm. The penumbra at the shadow's far edge (x = −1.5) for the real sun (0.27°) and a
    // sun 20× wider (5.3°): the 10–90 % transition along x, against the geometry: a disk light
    // casts a penumbra 2 tan σ · d wide (across the light; / sin 45° along the ground) for the
    // 1.41 m from the box's top edge to the ground, whose 10–90 % part is 0.687 of it (an edge
    // seen through a uniform disk).
    auto edgeWidth = [](const Image& hdr, float litLevel) {
        // Along the row through z = 0, from x = −2.5 to −0.6: where the ground crosses 10 % and 90 %.
        const uint32_t py = N / 2;
        float x10 = 0, x90 = 0;
        for (uint32_t px = 0; px < N; ++px) {
            const float x = worldX(px);
            if (x < -2.5f || x > -0.6f) continue;
            const float v = hdr.at(px, py, 1) / litLevel;
            if (v >= 0.9f) x90 = x;  // the last lit point going towards the box
            if (v >= 0.1f) x10 = x;
        }
        return x10 - x90;
    };
    Frame sharp = render({{"sun", "x45"}});
    Frame soft = render({{"sun", "x45"}, {"size", "20"}});
    const float litSharp = sharp.hdr.at(5, 5, 1), litSoft = soft.hdr.at(5, 5, 1);
    for (uint32_t px = 0; px < N; ++px) {
        const float x = worldX(px);
        if (x < -0.54f && x > -0.56f) {
            EXPECT_LT(sharp.hdr.at(px, N / 2, 1) / litSharp, 0.1f) << "contact at x " << x;
        }
    }
    const float wSharp = edgeWidth(sharp.hdr, litSharp), wSoft = edgeWidth(soft.hdr, litSoft);
    const float sigma = 20.0f * 0.2664f * 3.14159265f / 180.0f;
    const float predicted = 0.687f * 2.0f * std::tan(sigma) * std::sqrt(2.0f) / std::sqrt(0.5f);
    std::printf("penumbra at the far edge: sun 0.27° %.3f m, sun 5.3° %.3f m (geometric %.3f m)\n", wSharp, wSoft, predicted);
    EXPECT_LT(wSharp, 0.06f);
    EXPECT_GT(wSoft, 3.0f * wSharp);
    // Measured 0.322 m (+26 %): the ground here falls in the farthest cascade (1.7 cm texels), whose
    // texel-quantised edge and 1.5-texel normal offset add about 4 cm to the 10–90 % width.
    EXPECT_GT(wSoft, 0.75f * predicted);
    EXPECT_LT(wSoft, 1.3f * predicted);
}

TEST_F(Shadows, CascadesMoveByWholeTexelsWithTheCamera) {
    // The camera moved 3 mm along x (less than a texel of any cascade): each cascade's centre in the
    // light's frame moves by a whole number of texels (here 0 or 1), its size not at all.
    Frame a = render({{"sun", "x45"}});
    Frame b = render({{"sun", "x45"}, {"dx", "0.003"}});
    ASSERT_EQ(a.cascades.size(), b.cascades.size());
    ASSERT_GE(a.cascades.size(), 4u * 64u + 5u * 16u);
    auto floats = [](const std::vector<uint8_t>& bytes) {
        std::vector<float> f(bytes.size() / 4);
        std::memcpy(f.data(), bytes.data(), f.size() * 4);
        return f;
    };
    const auto fa = floats(a.cascades), fb = floats(b.cascades);
    const float count = fa[64 + 12];  // info.x
    ASSERT_GE(count, 3.0f);
    for (int c = 0; c < static_cast<int>(count); ++c) {
        const float texel = fa[64 + 4 + c];
        EXPECT_FLOAT_EQ(texel, fb[64 + 4 + c]) << "cascade " << c;
        // viewProj is column-major: [col][row]; column 3, rows 0 and 1 hold −cx / r and −cy / r,
        // and [0][0] = x.x / r: the translation in texels is Δ(col 3) · r / texel.
        const float* ma = &fa[16 * c];
        const float* mb = &fb[16 * c];
        const float r = texel * 2048.0f / 2.0f;
        for (int row = 0; row < 2; ++row) {
            const float shift = (mb[12 + row] - ma[12 + row]) * r / texel;
            EXPECT_NEAR(shift, std::round(shift), 1e-2f) << "cascade " << c << ", axis " << row;
        }
    }
}

}  // namespace
