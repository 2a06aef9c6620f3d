// The sun's cascaded shadow map (scripts/shadows.lua, shaders/shadows/, lib/shadows.glsl; seed 002
// §4.10.4) on tests/gpu/scenes/shadow_box.lua: a unit box on a plane seen from straight above, so
// that every pixel is a known ground point and the shadow's extent follows from the geometry.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "passes/gpu_scene.h"
#include "scene/scene.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t N = 320;  // square image
const float kHalf =
    12.0f * std::tan(15.0f * 3.14159265f / 180.0f);  // the ground the view spans: ±3.215 m

struct Frame {
    Image hdr;
    std::vector<uint8_t> cascades;  // lib/shadows.glsl's RgCascades
};

// Ground point of pixel (px, py): screen right is +x, screen up is −z.
float worldX(uint32_t px) { return ((static_cast<float>(px) + 0.5f) / N * 2.0f - 1.0f) * kHalf; }
float worldZ(uint32_t py) { return ((static_cast<float>(py) + 0.5f) / N * 2.0f - 1.0f) * kHalf; }

class Shadows : public GpuFixture {
protected:
    static Frame render(const std::map<std::string, std::string>& args, uint32_t frames = 1,
                        const std::string& camera = "top", bool sunShadows = true,
                        const std::string& sunMask = "auto") {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/shadow_box.lua", args, N, N);
        o.camera = camera;
        o.params["sun_shadows"] = Value(sunShadows);
        o.params["sun_mask"] = Value(sunMask);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", frames, {"hdr"},
                                   {"sun_cascades"});
        Frame out;
        if (r.images.empty() || r.buffers.empty()) return out;
        out.hdr = r["hdr"];
        out.cascades = r.buffers["sun_cascades"];
        return out;
    }

    // Every ground pixel (outside the box's footprint, with a margin) of a region: lit or in shadow.
    struct Count {
        int lit = 0, shadowed = 0, total = 0;
    };
    static Count classify(const Image& hdr, float litLevel,
                          const std::function<bool(float, float)>& inside) {
        Count c;
        for (uint32_t py = 0; py < N; ++py)
            for (uint32_t px = 0; px < N; ++px) {
                const float x = worldX(px), z = worldZ(py);
                if (std::abs(x) < 0.55f && std::abs(z) < 0.55f)
                    continue;  // the box (its top and sides)
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
    struct Case {
        const char* sun;
        std::function<bool(float, float)> shadow, lit;
    };
    const float m = 0.08f, far = 0.5f + std::sqrt(3.0f);
    const Case cases[] = {
        {"x45",
         [=](float x, float z) { return x > -1.5f + m && x < -0.5f - m && std::abs(z) < 0.5f - m; },
         [=](float x, float z) { return x < -1.5f - m || x > 0.5f + m || std::abs(z) > 0.5f + m; }},
        {"z30",
         [=](float x, float z) { return z > 0.5f + m && z < far - m && std::abs(x) < 0.5f - m; },
         [=](float x, float z) { return z < -0.5f - m || z > far + m || std::abs(x) > 0.5f + m; }},
    };
    for (const Case& c : cases) {
        Frame f = render({{"sun", c.sun}});
        ASSERT_EQ(f.hdr.width, N);
        const float litLevel = f.hdr.at(5, 5, 1);  // a corner of the open ground
        ASSERT_GT(litLevel, 0.0f);
        const Count shadow = classify(f.hdr, litLevel, c.shadow),
                    lit = classify(f.hdr, litLevel, c.lit);
        std::printf("sun %s: shadow region %d/%d dark, open ground %d/%d lit\n", c.sun,
                    shadow.shadowed, shadow.total, lit.lit, lit.total);
        EXPECT_GT(shadow.total, 500);
        EXPECT_EQ(shadow.shadowed, shadow.total) << c.sun;
        EXPECT_EQ(lit.lit, lit.total) << c.sun;
    }
}

// cast_shadows = false takes an object out of the shadow maps and nothing else: the ground's own
// depth there changes no shadow (the box's falls as before), the box's leaves the ground lit.
TEST_F(Shadows, AnObjectThatCastsNoShadowLeavesTheMapsOnly) {
    const float m = 0.08f;
    auto shadowRegion = [=](float x, float z) {
        return x > -1.5f + m && x < -0.5f - m && std::abs(z) < 0.5f - m;
    };
    for (const char* cast : {"ground", "box"}) {
        Frame f = render({{"sun", "x45"}, {"cast", cast}});
        ASSERT_EQ(f.hdr.width, N);
        const float litLevel = f.hdr.at(5, 5, 1);
        ASSERT_GT(litLevel, 0.0f);
        const Count c = classify(f.hdr, litLevel, shadowRegion);
        std::printf("%s casts no shadow: the box's shadow region %d dark, %d lit of %d\n", cast,
                    c.shadowed, c.lit, c.total);
        EXPECT_GT(c.total, 500);
        if (std::string(cast) == "ground")
            EXPECT_EQ(c.shadowed, c.total);
        else
            EXPECT_EQ(c.lit, c.total);
    }
}

TEST_F(Shadows, AnOrthographicCameraSeesTheSameShadow) {
    // The top view through an orthographic camera (scene.camera { height = ... }: the same ground
    // extent, so the same pixel ↔ ground map): every pass that rebuilds positions from depth
    // (lighting, SSR, GTAO, the cascades' fit, the sky) takes the parallel projection. The shadow
    // of the x45 sun falls where the geometry puts it and the open ground is lit — evenly, since
    // V is the same for every pixel (within 0.1 %).
    Frame f = render({{"sun", "x45"}}, 1, "ortho");
    ASSERT_EQ(f.hdr.width, N);
    const float litLevel = f.hdr.at(5, 5, 1);
    ASSERT_GT(litLevel, 0.0f);
    const float m = 0.08f;
    const Count shadow = classify(f.hdr, litLevel, [=](float x, float z) {
        return x > -1.5f + m && x < -0.5f - m && std::abs(z) < 0.5f - m;
    });
    const Count lit = classify(f.hdr, litLevel, [=](float x, float z) {
        return x < -1.5f - m || x > 0.5f + m || std::abs(z) > 0.5f + m;
    });
    std::printf("orthographic: shadow region %d/%d dark, open ground %d/%d lit\n", shadow.shadowed,
                shadow.total, lit.lit, lit.total);
    EXPECT_GT(shadow.total, 500);
    EXPECT_EQ(shadow.shadowed, shadow.total);
    EXPECT_EQ(lit.lit, lit.total);
    // Far from the box (no AO, no shadow): the same luminance everywhere.
    float lo = litLevel, hi = litLevel;
    for (uint32_t py = 0; py < N; py += 4)
        for (uint32_t px = 0; px < N; px += 4)
            if (std::abs(worldX(px)) > 2.2f && std::abs(worldZ(py)) > 2.2f) {
                lo = std::min(lo, f.hdr.at(px, py, 1));
                hi = std::max(hi, f.hdr.at(px, py, 1));
            }
    EXPECT_LT(hi / lo - 1.0f, 1e-3f);
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
            if (std::abs(lit.hdr.pixels[i] - ref.hdr.pixels[i]) > 0.01f * ref.hdr.pixels[i] + 1e-3f)
                ++off;
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
    std::printf("penumbra at the far edge: sun 0.27° %.3f m, sun 5.3° %.3f m (geometric %.3f m)\n",
                wSharp, wSoft, predicted);
    EXPECT_LT(wSharp, 0.06f);
    EXPECT_GT(wSoft, 3.0f * wSharp);
    // Measured 0.322 m (+26 %): the ground here falls in the farthest cascade (1.7 cm texels), whose
    // texel-quantised edge and 1.5-texel normal offset add about 4 cm to the 10–90 % width.
    EXPECT_GT(wSoft, 0.75f * predicted);
    EXPECT_LT(wSoft, 1.3f * predicted);
}

TEST_F(Shadows, TheHalfResolutionMaskKeepsTheShadowsPlaceAndEdges) {
    // sun_mask = "half" (the default from 720 rows up) filters the sun's PCSS at every other pixel
    // of every other row and the lighting upsamples it by depth: the box's shadow falls where the
    // geometry puts it, as with the per-pixel mask; at the pixels the half mask samples (even x
    // and y) the two agree, and elsewhere they differ only along the shadow's edges.
    Frame full = render({{"sun", "x45"}}, 1, "top", true, "full");
    Frame half = render({{"sun", "x45"}}, 1, "top", true, "half");
    Frame automatic = render({{"sun", "x45"}});  // 320 rows: full resolution
    ASSERT_EQ(full.hdr.width, N);
    ASSERT_EQ(half.hdr.width, N);
    ASSERT_EQ(automatic.hdr.width, N);
    const float lit = full.hdr.at(5, 5, 1);
    ASSERT_GT(lit, 0.0f);
    EXPECT_EQ(half.hdr.at(5, 5, 1), lit);
    const float m = 0.08f;
    const Count shadow = classify(half.hdr, lit, [=](float x, float z) {
        return x > -1.5f + m && x < -0.5f - m && std::abs(z) < 0.5f - m;
    });
    const Count open = classify(half.hdr, lit, [=](float x, float z) {
        return x < -1.5f - m || x > 0.5f + m || std::abs(z) > 0.5f + m;
    });
    EXPECT_GT(shadow.total, 500);
    EXPECT_EQ(shadow.shadowed, shadow.total);
    EXPECT_EQ(open.lit, open.total);
    int sampled = 0, sampledOff = 0, between = 0, betweenOff = 0, autoOff = 0;
    double meanDiff = 0.0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            const float d = std::abs(half.hdr.at(px, py, 1) - full.hdr.at(px, py, 1)) / lit;
            meanDiff += d;
            const bool off = d > 0.05f;
            if (px % 2 == 0 && py % 2 == 0) {
                ++sampled;
                sampledOff += off;
            } else {
                ++between;
                betweenOff += off;
            }
            autoOff += automatic.hdr.at(px, py, 1) != full.hdr.at(px, py, 1);
        }
    meanDiff /= static_cast<double>(N) * N;
    std::printf(
        "half mask against full: mean |diff| %.4f of the lit level; over 5 %%: %d of %d sampled "
        "pixels, %d of %d between\n",
        meanDiff, sampledOff, sampled, betweenOff, between);
    EXPECT_EQ(autoOff, 0) << "auto at 320 rows is the full-resolution mask";
    EXPECT_LE(sampledOff, sampled / 1000);  // ≤ 0.1 %
    EXPECT_LT(betweenOff, between / 100);   // < 1 %: the edges
    EXPECT_LT(meanDiff, 0.002);
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

TEST_F(Shadows, CascadesSkipTheCastersBesideThem) {
    // sun_cull's indirect commands (scripts/shadows.lua): the shadow box from above, the light along
    // (−1, −1, 0). The nearest cascade covers the view 0–3 m from a camera 12 m up: the ground far
    // below along the light falls in it, the box (7 m across the light from that slice) does not;
    // the farthest cascade reaches the ground around the box and draws both. Draws and caster
    // batches: 0 the ground, 1 the box (a mesh each), one level of detail each.
    SessionOptions o =
        sceneOptions(kRoot + "/tests/gpu/scenes/shadow_box.lua", {{"sun", "x45"}}, N, N);
    Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"},
                               {"sun_shadow_draws", "sun_shadow_instances"});
    ASSERT_EQ(r.buffers.count("sun_shadow_draws"), 1u);
    ASSERT_EQ(r.buffers.count("sun_shadow_instances"), 1u);
    auto wordsOf = [&](const std::string& name) {
        const auto& bytes = r.buffers[name];
        std::vector<uint32_t> words(bytes.size() / 4);
        std::memcpy(words.data(), bytes.data(), words.size() * 4);
        return words;
    };
    const std::vector<uint32_t> words = wordsOf("sun_shadow_draws"),
                                list = wordsOf("sun_shadow_instances");
    // Commands of 5 words per cascade (3), batch and level (4): one word to spare.
    const size_t batches = words.size() / 5 / 3 / 4;
    ASSERT_EQ(batches, 2u);
    auto word = [&](size_t cascade, size_t batch, size_t k) {
        return words[((cascade * batches + batch) * 4 + 0) * 5 + k];
    };
    EXPECT_EQ(word(0, 0, 0), 6u);   // the plane: two triangles
    EXPECT_EQ(word(2, 1, 0), 36u);  // the box: twelve
    EXPECT_EQ(word(0, 0, 1), 1u);   // instances
    EXPECT_EQ(word(0, 1, 1), 0u);
    EXPECT_EQ(word(2, 0, 1), 1u);
    EXPECT_EQ(word(2, 1, 1), 1u);
    // Each drawn command's one instance is its caster: draw 0, draw 1.
    for (size_t c : {0u, 2u})
        for (size_t b = 0; b < 2; ++b)
            if (word(c, b, 1) == 1u) {
                ASSERT_LT(word(c, b, 4), list.size());
                EXPECT_EQ(list[word(c, b, 4)], b) << "cascade " << c;
            }
}

// ---- Local lights (tests/gpu/scenes/local_shadow_box.lua): a point light and a spot over the box ----

namespace {

// Whether the segment from ground point (x, 0, z) to the light at L meets the unit box grown by
// `grow` metres on every side (slab test).
bool boxBetween(float x, float z, glm::vec3 L, float grow) {
    const glm::vec3 o(x, 0.0f, z), d = L - o;
    const glm::vec3 lo(-0.5f - grow, -grow, -0.5f - grow),
        hi(0.5f + grow, 1.0f + grow, 0.5f + grow);
    float t0 = 0.0f, t1 = 1.0f;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-9f) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

class LocalShadows : public GpuFixture {
protected:
    static Image render(const std::map<std::string, std::string>& args) {
        SessionOptions o =
            sceneOptions(kRoot + "/tests/gpu/scenes/local_shadow_box.lua", args, N, N);
        // The lights' shadows alone: a sphere light's shape would be the brightest pixel.
        o.params["light_shapes"] = Value(false);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
        return r.images.empty() ? Image{} : r["hdr"];
    }
    // Per ground pixel: the image with the box over the one without (both shadowed), where the
    // light reaches the ground (over 1 % of the brightest pixel without the box).
    static std::vector<float> ratios(const Image& with, const Image& without) {
        float peak = 0.0f;
        for (uint32_t i = 0; i < N * N; ++i) peak = std::max(peak, without.pixels[4 * i + 1]);
        std::vector<float> r(N * N, -1.0f);
        for (uint32_t i = 0; i < N * N; ++i)
            if (without.pixels[4 * i + 1] > 0.01f * peak)
                r[i] = with.pixels[4 * i + 1] / without.pixels[4 * i + 1];
        return r;
    }
};

TEST_F(LocalShadows, TheSunsMaskBesideALampsMaps) {
    // A sun (scene.args.sun = 1: 45° up, travelling along −x) over the lamp's scene: the sun's mask
    // passes and the lamp's cube map in one frame. What the sun adds is its light where the box does
    // not stand between the ground and it, and none where it does; the lamp's shadow is the same
    // in both images and cancels.
    const Image lamp = render({}), both = render({{"sun", "1"}});
    ASSERT_EQ(lamp.width, N);
    ASSERT_EQ(both.width, N);
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    float peak = 0.0f;
    for (uint32_t i = 0; i < N * N; ++i)
        peak = std::max(peak, both.pixels[4 * i + 1] - lamp.pixels[4 * i + 1]);
    ASSERT_GT(peak, 0.0f);
    int shadowTotal = 0, shadowDark = 0, litTotal = 0, litLit = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            const float x = worldX(px), z = worldZ(py);
            if (std::abs(x) < 0.58f && std::abs(z) < 0.58f) continue;
            const float added =
                both.pixels[4 * (py * N + px) + 1] - lamp.pixels[4 * (py * N + px) + 1];
            const glm::vec3 sun = glm::vec3(x, 0.0f, z) + 50.0f * toSun;
            if (boxBetween(x, z, sun, -0.08f)) {
                ++shadowTotal;
                if (added < 0.05f * peak) ++shadowDark;
            } else if (!boxBetween(x, z, sun, 0.08f)) {
                ++litTotal;
                if (added > 0.5f * peak) ++litLit;
            }
        }
    EXPECT_GT(shadowTotal, 100);
    EXPECT_GE(shadowDark, shadowTotal * 95 / 100) << shadowDark << " of " << shadowTotal;
    EXPECT_GE(litLit, litTotal * 95 / 100) << litLit << " of " << litTotal;
}

TEST_F(LocalShadows, ShadowFallsWhereTheGeometryPutsIt) {
    // The light at (−1.5, 2.5, 0): a ground point is in shadow when the segment to the light meets
    // the box. Margins of 8 cm (four pixels) each way around the predicted edge; the box's own
    // footprint is left out.
    const glm::vec3 L(-1.5f, 2.5f, 0.0f);
    for (const char* light : {"point", "spot"}) {
        const Image with = render({{"light", light}}),
                    without = render({{"light", light}, {"box", "0"}});
        ASSERT_EQ(with.width, N);
        ASSERT_EQ(without.width, N);
        const auto r = ratios(with, without);
        int shadowTotal = 0, shadowDark = 0, litTotal = 0, litLit = 0;
        for (uint32_t py = 0; py < N; ++py)
            for (uint32_t px = 0; px < N; ++px) {
                const float x = worldX(px), z = worldZ(py), v = r[py * N + px];
                if (v < 0.0f || (std::abs(x) < 0.58f && std::abs(z) < 0.58f)) continue;
                if (boxBetween(x, z, L, -0.08f)) {
                    ++shadowTotal;
                    if (v < 0.1f) ++shadowDark;
                } else if (!boxBetween(x, z, L, 0.08f)) {
                    ++litTotal;
                    if (v > 0.98f) ++litLit;
                }
            }
        // The contact: the nearest ground seen beyond the box's far side (+x) along z = 0 — from
        // 12 m up the top face hides it to 4.5 cm from the base — is in shadow, to 10 cm: no
        // peter-panning a camera can see.
        int contact = 0, contactDark = 0;
        for (uint32_t px = 0; px < N; ++px) {
            const float x = worldX(px), v = r[(N / 2) * N + px];
            if (x < 0.55f || x > 0.60f || v < 0.0f) continue;
            ++contact;
            if (v < 0.1f) ++contactDark;
        }
        EXPECT_GT(contact, 0) << light;
        EXPECT_EQ(contactDark, contact) << light << ": contact";
        std::printf(
            "%s light: shadow region %d/%d dark, open ground %d/%d lit, contact %d/%d dark\n",
            light, shadowDark, shadowTotal, litLit, litTotal, contactDark, contact);
        EXPECT_GT(shadowTotal, 1500) << light;
        EXPECT_EQ(shadowDark, shadowTotal) << light;
        EXPECT_GT(litTotal, 10000) << light;
        EXPECT_EQ(litLit, litTotal) << light;
    }
}

TEST_F(LocalShadows, NoAcneUnderAGrazingLight) {
    // The plane alone under a point light 0.4 m above it: at 3 m the light grazes the ground at
    // 7.6°. Every pixel the light reaches is as bright with the shadow map as without (1 %).
    for (const char* light : {"point", "spot"}) {
        const Image on = render({{"light", light}, {"box", "0"}, {"y", "0.4"}});
        const Image off = render({{"light", light}, {"box", "0"}, {"y", "0.4"}, {"shadow", "0"}});
        const auto r = ratios(on, off);
        int lit = 0, acne = 0;
        float worst = 1.0f;
        for (float v : r) {
            if (v < 0.0f) continue;
            ++lit;
            worst = std::min(worst, v);
            if (v < 0.99f) ++acne;
        }
        std::printf(
            "%s light 0.4 m over an open plane: %d pixels lit, darkest %.4f of the unshadowed\n",
            light, lit, worst);
        EXPECT_GT(lit, 10000) << light;
        EXPECT_EQ(acne, 0) << light;
    }
}

TEST_F(LocalShadows, PenumbraGrowsWithTheLightsRadius) {
    // Along z = 0 the shadow's far edge is the box's top edge (0.5, 1, 0) projected from the light
    // at (−1.5, 2.5): x = 1.833. A sphere light of radius R casts a penumbra 2R (d_r − d_b) / d_b
    // wide across the ray (d_b = 2.5 m to the edge, d_r = 4.167 m to the ground), 1/sin θ wider
    // along the ground (sin θ = 2.5 / 4.167): 2.22 R; its 10–90 % part for a sphere (a disk seen
    // edge on) is about 0.69 of it. Point light: the edge within 6 cm.
    auto edge = [](const std::vector<float>& r) {
        float x10 = 0, x90 = 0;
        for (uint32_t px = 0; px < N; ++px) {
            const float x = worldX(px), v = r[(N / 2) * N + px];
            if (x < 1.0f || x > 3.0f || v < 0.0f) continue;
            if (v <= 0.1f) x10 = x;  // the last dark point going away from the box
            if (v <= 0.9f) x90 = x;
        }
        return x90 - x10;
    };
    const Image sharp = render({}), sharp0 = render({{"box", "0"}});
    const Image soft = render({{"radius", "0.2"}}),
                soft0 = render({{"box", "0"}, {"radius", "0.2"}});
    const float wSharp = edge(ratios(sharp, sharp0)), wSoft = edge(ratios(soft, soft0));
    const float predicted = 0.69f * 2.22f * 0.2f;
    std::printf(
        "penumbra at the far edge: point light %.3f m, sphere of 0.2 m %.3f m (geometric %.3f m)\n",
        wSharp, wSoft, predicted);
    EXPECT_LT(wSharp, 0.06f);
    // Measured 0.301 m against 0.306 m.
    EXPECT_GT(wSoft, 0.8f * predicted);
    EXPECT_LT(wSoft, 1.25f * predicted);
}

TEST_F(LocalShadows, ViewsFollowTheLightsInViewAndDrawOnlyTheirCasters) {
    // The culling GpuScene::updateFrame does each frame, on the scene itself: a point light gets six
    // views while its range reaches the camera's view and none once it does not; each face draws
    // only the casters its frustum meets (the box sits beside the light: +x sees it, −x does not).
    SceneScriptOptions so;
    so.args = {{"light", "point"}};
    auto scene = loadSceneScript(kRoot + "/tests/gpu/scenes/local_shadow_box.lua", so);
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    ASSERT_EQ(scene->lights.size(), 1u);
    auto gpu = passes::GpuScene::create(rt().gpu(), *scene);
    ASSERT_TRUE(gpu.has_value()) << gpu.error().describe();
    (*gpu)->updateFrame(0, N, N);
    ASSERT_EQ((*gpu)->shadowViewCount(), 6u);
    EXPECT_EQ((*gpu)->shadowViewsOf(0), (std::pair<uint32_t, uint32_t>{0u, 6u}));
    // Draws: the ground (0) and the box (1). The light at (−1.5, 2.5, 0): the box is towards +x
    // and −y; the ground is below (−y) and reaches every side face.
    auto sees = [&](uint32_t view, size_t draw) {
        const auto& d = (*gpu)->shadowViewDraws(view);
        return std::find(d.begin(), d.end(), draw) != d.end();
    };
    EXPECT_TRUE(sees(0, 1));   // +x: the box
    EXPECT_FALSE(sees(1, 1));  // −x: not the box
    EXPECT_FALSE(sees(2, 0));  // +y: nothing above
    EXPECT_FALSE(sees(2, 1));
    EXPECT_TRUE(sees(3, 0));  // −y: the ground and the box
    EXPECT_TRUE(sees(3, 1));
    // Far from the view (range 30 m, 100 m away behind the camera's frustum): no views.
    Scene away = *scene;
    away.lights[0].position = glm::vec3(100.0f, 2.5f, 0.0f);
    auto gpuAway = passes::GpuScene::create(rt().gpu(), std::move(away));
    ASSERT_TRUE(gpuAway.has_value()) << gpuAway.error().describe();
    (*gpuAway)->updateFrame(0, N, N);
    EXPECT_EQ((*gpuAway)->shadowViewCount(), 0u);
    EXPECT_EQ((*gpuAway)->shadowViewsOf(0).second, 0u);
}

TEST_F(LocalShadows, PenumbraMatchesTheReferenceShadowRays) {
    // The sphere light of 0.2 m over the box, real time against scripts/pipelines/reference.lua with
    // reference_shadows (shadow rays through the scene's triangles, the light sampled by solid
    // angle): the 10–90 % width of the shadow's far edge along z = 0, the box-over-no-box ratio
    // averaged over the 15 rows around z = 0 to quiet the reference's noise (64 frames × 4 samples).
    auto render = [](const std::string& pipeline, const std::map<std::string, std::string>& args,
                     uint32_t frames) {
        SessionOptions o =
            sceneOptions(kRoot + "/tests/gpu/scenes/local_shadow_box.lua", args, N, N);
        if (pipeline == "reference") {
            o.params["reference_shadows"] = Value(true);
            o.params["reference_forward"] = Value(false);
        }
        Readback r =
            renderAndRead(o, kRoot + "/scripts/pipelines/" + pipeline + ".lua", frames, {"hdr"});
        return r.images.empty() ? Image{} : r["hdr"];
    };
    auto width = [](const Image& with, const Image& without) {
        float x10 = 0, x90 = 0;
        for (uint32_t px = 0; px < N; ++px) {
            const float x = worldX(px);
            if (x < 1.0f || x > 3.0f) continue;
            float a = 0, b = 0;
            for (uint32_t py = N / 2 - 7; py <= N / 2 + 7; ++py) {
                a += with.at(px, py, 1);
                b += without.at(px, py, 1);
            }
            const float v = a / b;
            if (v <= 0.1f) x10 = x;
            if (v <= 0.9f) x90 = x;
        }
        return x90 - x10;
    };
    const std::map<std::string, std::string> box = {{"radius", "0.2"}},
                                             none = {{"radius", "0.2"}, {"box", "0"}};
    const Image rt = render("deferred", box, 1), rt0 = render("deferred", none, 1);
    const Image ref = render("reference", box, 64), ref0 = render("reference", none, 64);
    ASSERT_EQ(ref.width, N);
    ASSERT_EQ(ref0.width, N);
    const float wRt = width(rt, rt0), wRef = width(ref, ref0);
    // The reference's umbra: the ground right behind the box, far from any edge, gets nothing.
    const float umbra = ref.at(N / 2 + static_cast<uint32_t>(0.9f / (2.0f * kHalf) * N), N / 2, 1);
    std::printf(
        "penumbra at the far edge, sphere light 0.2 m: real time %.3f m, reference %.3f m; "
        "reference umbra %.3g\n",
        wRt, wRef, umbra);
    EXPECT_EQ(umbra, 0.0f);
    EXPECT_NEAR(wRt / wRef, 1.0f, 0.2f);
}

TEST_F(LocalShadows, TheMapsHoldTheFacesTowardsTheLight) {
    // shadows.lua's shadow_local draws only the faces towards the light (cull = "counter_clockwise"
    // for its views' winding). The point light's −y face (the `shadow:lamp` view's lower left cell)
    // looks straight down at the floor 2.5 m below: white at 1 − 2.5 / 30 (near, over the range).
    // With the winding wrong the floor, a plane facing the light, would be culled: black.
    SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/local_shadow_box.lua", {}, 300, 200);
    o.view = "shadow:lamp";
    Session s(rt(), o);
    ASSERT_TRUE(s.load(kRoot + "/scripts/pipelines/deferred.lua").has_value());
    ASSERT_TRUE(s.frame().has_value());
    auto view = rt().executor().readback("debug_view");
    ASSERT_TRUE(view.has_value());
    const float centre = view->at(50, 150, 0);  // the middle of the cell below on the left
    EXPECT_NEAR(centre, 1.0f - 2.5f / 30.0f, 0.01f);
}

TEST_F(LocalShadows, TheMapHasTheLayersTheScenesLightsNeed) {
    // local_shadow is declared with scene_layers = "shadow_views", at most 6 layers of 1024²: a
    // point light's cube gets six, a spot of 55° one, a scene without shadowed local lights one
    // 1×1 layer (24 MiB less transient memory); the spot's single layer is still sampled as an array
    // (the validation layer checks the view type the shader declares). The spot's shadow is drawn:
    // it darkens the ground beyond the box.
    struct Case {
        const char* light;
        const char* shadow;
        uint32_t layers, size;
    };
    for (const Case& c :
         {Case{"point", "1", 6, 1024}, Case{"spot", "1", 1, 1024}, Case{"point", "0", 1, 1}}) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/local_shadow_box.lua",
                                        {{"light", c.light}, {"shadow", c.shadow}}, N, N);
        Session s(*s_runtime, o);
        auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
        ASSERT_TRUE(r.has_value()) << r.error().describe();
        ASSERT_TRUE(s.frame().has_value());
        const Plan& plan = s_runtime->executor().plan();
        const int32_t i = plan.findResource("local_shadow");
        ASSERT_GE(i, 0);
        const PlanResource& res = plan.resources[static_cast<size_t>(i)];
        std::printf("%s light, shadow %s: local_shadow %ux%u, %u layer(s)\n", c.light, c.shadow,
                    res.width, res.height, res.layers);
        EXPECT_EQ(res.layers, c.layers) << c.light;
        EXPECT_EQ(res.width, c.size) << c.light;
        EXPECT_TRUE(res.array);
    }
    const Image with = render({{"light", "spot"}}),
                without = render({{"light", "spot"}, {"box", "0"}});
    ASSERT_EQ(with.width, N);
    int dark = 0;
    for (float v : ratios(with, without)) dark += v >= 0.0f && v < 0.1f;
    EXPECT_GT(dark, 1000);
}

// Seed 002 §4.10.4: a light's shadow darkens all it reflects. A glossy metal floor under a
// shadowed area light of each shape, its highlight at the image's centre, and a box on the light's
// path to that point: the highlight goes dark under both area-light models (LTC, the default,
// used to leave its specular lobe unshadowed — the highlight as bright with the box as without).
TEST_F(LocalShadows, AreaLightHighlightsAreShadowedUnderEveryModel) {
    constexpr uint32_t S = 96;
    for (const char* model : {"ltc", "frostbite"})
        for (const char* light : {"sphere", "disk", "rect", "tube"}) {
            auto centre = [&](bool box) {
                SessionOptions o =
                    sceneOptions(kRoot + "/tests/gpu/scenes/area_specular_shadow.lua",
                                 {{"light", light}, {"box", box ? "1" : "0"}}, S, S);
                o.environment = "none";  // the light alone
                o.params["area_lights"] = Value(model);
                Readback r =
                    renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
                if (r.images.empty()) return -1.0f;
                const Image& img = r["hdr"];
                float sum = 0.0f;  // the 2x2 pixels around the centre, green
                for (uint32_t y = S / 2 - 1; y <= S / 2; ++y)
                    for (uint32_t x = S / 2 - 1; x <= S / 2; ++x)
                        sum += img.pixels[4 * (y * S + x) + 1];
                return sum / 4.0f;
            };
            const float open = centre(false), blocked = centre(true);
            std::printf("%s %s light: highlight %.4g open, %.4g behind the box (%.3f)\n", model,
                        light, open, blocked, blocked / open);
            ASSERT_GT(open, 0.0f) << model << " " << light;
            EXPECT_LT(blocked, 0.05f * open) << model << " " << light;
        }
}
