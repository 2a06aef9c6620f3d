// Local light probes (scripts/probes.lua, shaders/probes/, lib/probes.glsl, lib/ibl.glsl's
// composition; seed 002 §4.9.1.2, §4.9.5, appendix F) on tests/gpu/scenes/probes.lua: a mirror
// floor under a red emissive box.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
const std::string kScene = kRoot + "/tests/gpu/scenes/probes.lua";
constexpr uint32_t W = 240, H = 160;

// The pixel a world point lands on with the scene's "main" camera.
glm::ivec2 pixelOf(glm::vec3 p) {
    return rg::pixelOf(cameraViewProj(glm::vec3(0, 2, 6), glm::vec3(0), 40.0f, W, H), W, H, p);
}

class Probes : public GpuFixture {
protected:
    // The lit HDR in nits, SSR kept from finding anything (a 10 cm ray) so the probes reflect.
    // With the screen-space AO in `ao` (1 open) and the composition pass's result in `reflection`.
    static Image lit(const std::string& probes, Image* ao = nullptr, Image* reflection = nullptr) {
        SessionOptions o = sceneOptions(kScene, {{"probes", probes}}, W, H);
        o.params["ssr_distance"] = Value(0.1);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1,
                                   {"hdr", "ssao", "reflection"});
        if (r.images.size() != 3) return {};
        Image hdr = r["hdr"];
        for (float& v : hdr.pixels) v /= r.preExposure;
        if (ao) *ao = r["ssao"];
        if (reflection) *reflection = r["reflection"];
        return hdr;
    }
    // The `probes` debug view from straight above (N × N): which probe reflects each floor point.
    static constexpr uint32_t N = 200;
    static Image probeView(const std::string& probes) {
        SessionOptions o = sceneOptions(kScene, {{"probes", probes}}, N, N);
        o.camera = "top";
        o.view = "probes";
        Session s(*s_runtime, o);
        auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r) return {};
        auto f = s.frame();
        EXPECT_TRUE(f.has_value()) << f.error().describe();
        auto view = s_runtime->executor().readback("debug_view");
        EXPECT_TRUE(view.has_value());
        return view ? std::move(*view) : Image{};
    }
    // The view's colour at floor point (x, z).
    static glm::vec3 at(const Image& view, float x, float z) {
        const float half = 12.0f * std::tan(glm::radians(30.0f));
        const uint32_t px = static_cast<uint32_t>((x / half * 0.5f + 0.5f) * N),
                       py = static_cast<uint32_t>((z / half * 0.5f + 0.5f) * N);
        return {view.at(px, py, 0), view.at(px, py, 1), view.at(px, py, 2)};
    }
};

// shaders/passes/probe_view.frag's palette: the first probe in the composition's order, the second, the distant probe.
const glm::vec3 kFirst(0.9f, 0.2f, 0.2f), kSecond(0.2f, 0.8f, 0.2f), kDistant(0.18f);

void expectColour(glm::vec3 got, glm::vec3 want, const char* where) {
    EXPECT_NEAR(got.r, want.r, 0.01f) << where;
    EXPECT_NEAR(got.g, want.g, 0.01f) << where;
    EXPECT_NEAR(got.b, want.b, 0.01f) << where;
}

TEST_F(Probes, TheHigherPriorityGoesFirstThenTheSmaller) {
    // "right" (priority 2) before "left" (priority 1): where both hold the floor (x = 0: 1.80 m
    // from either centre, inside the fade) the right one alone; each alone on its own side;
    // outside both, the distant probe.
    Image v = probeView("priority");
    ASSERT_EQ(v.width, N);
    expectColour(at(v, 0.0f, 0.0f), kFirst, "both (x = 0)");
    expectColour(at(v, 3.5f, 0.0f), kFirst, "right alone (x = 3.5)");
    expectColour(at(v, -3.5f, 0.0f), kSecond, "left alone (x = -3.5)");
    expectColour(at(v, 0.0f, 3.2f), kDistant, "neither (z = 3.2)");
    expectColour(at(v, 5.0f, 0.0f), kDistant, "neither (x = 5)");
    // The same priority: the smaller first. x = 1 is inside both; x = −3 in the big one only.
    Image s = probeView("size");
    ASSERT_EQ(s.width, N);
    expectColour(at(s, 1.0f, 0.0f), kFirst, "both: the small one");
    expectColour(at(s, -3.0f, 0.0f), kSecond, "the big one alone");
    expectColour(at(s, 0.0f, 4.2f), kDistant, "neither");
    // Across the small one's fade (its disc's edge at x = 1 + 1.73) its weight falls and the big
    // one takes the rest: the two colours always sum to one probe's worth, no distant probe.
    const glm::vec3 edge = at(s, 1.0f + 1.62f, 0.0f);
    EXPECT_GT(edge.r, kSecond.r + 0.02f);
    EXPECT_GT(edge.g, kFirst.g + 0.02f);
    EXPECT_NEAR(edge.b, 0.2f, 0.01f);  // both palette entries have blue 0.2
    // An influence volume larger than the proxy: a sphere of radius 1 reflecting within 3 m.
    Image i = probeView("influence");
    ASSERT_EQ(i.width, N);
    expectColour(at(i, 2.4f, 0.0f), kFirst, "inside the influence, outside the proxy");
    expectColour(at(i, 3.2f, 0.0f), kDistant, "outside the influence");
}

TEST_F(Probes, TheComposedReflectionTakesTheHigherPriorityProbe) {
    // Radiance, not the debug view: the box's mirror image lies inside two probes that both saw
    // something there — the front one the red box, the back one the green wall behind it. With
    // the front probe first the reflection is red; with the back probe first, green.
    const glm::ivec2 m = pixelOf(glm::vec3(0.0f, -0.5f, -1.5f));
    Image front = lit("front_first"), back = lit("back_first");
    ASSERT_EQ(front.width, W);
    ASSERT_EQ(back.width, W);
    const float rf = front.at(m.x, m.y, 0), gf = front.at(m.x, m.y, 1), rb = back.at(m.x, m.y, 0),
                gb = back.at(m.x, m.y, 1);
    std::printf(
        "mirror image: front probe first %.0f %.0f (red, green), back probe first %.0f %.0f\n", rf,
        gf, rb, gb);
    EXPECT_GT(rf, 3.0f * gf);
    EXPECT_GT(gb, 3.0f * rb);
}

TEST_F(Probes, TheCaptureReflectsWhatTheProbeSaw) {
    // The box's mirror image in the floor (the front face's centre (0, 0.5, −1.5) mirrored to
    // (0, −0.5, −1.5)), SSR out of the way: without a local probe the floor reflects the sky there;
    // with the probe in front of the box, the red box as the capture shaded it — diffuse only,
    // lit by the sky's SH plus its 200 nits of emission: as the camera sees its front face without
    // the screen-space AO the capture does not have (and the face's small specular) — times the
    // mirror's f0 of 0.95.
    Image ao, reflection, reflectionNone;
    Image none = lit("none", nullptr, &reflectionNone), one = lit("one", &ao, &reflection);
    ASSERT_EQ(none.width, W);
    ASSERT_EQ(one.width, W);
    const glm::ivec2 m = pixelOf(glm::vec3(0.0f, -0.5f, -1.5f));
    const float r0 = none.at(m.x, m.y, 0), g0 = none.at(m.x, m.y, 1), b0 = none.at(m.x, m.y, 2);
    const float r1 = one.at(m.x, m.y, 0), g1 = one.at(m.x, m.y, 1), b1 = one.at(m.x, m.y, 2);
    std::printf(
        "mirror image of the box at (%d, %d): without a probe %.1f %.1f %.1f nits, with it %.1f "
        "%.1f %.1f\n",
        m.x, m.y, r0, g0, b0, r1, g1, b1);
    EXPECT_GT(b0, r0);          // the sky
    EXPECT_GT(r1, 10.0f * g1);  // the red box
    const glm::ivec2 b = pixelOf(glm::vec3(0.0f, 0.5f, -1.5f));
    ASSERT_EQ(ao.width, W);
    const float boxRed = one.at(b.x, b.y, 0), boxAo = ao.at(b.x, b.y, 0);
    std::printf(
        "the box's front face at (%d, %d): %.1f nits red, AO %.3f; mirrored / (direct / AO) %.3f\n",
        b.x, b.y, boxRed, boxAo, r1 / (boxRed / boxAo));
    EXPECT_NEAR(r1 / (boxRed / boxAo), 0.95f,
                0.06f);  // measured 0.924: the floor's specular occlusion by the box
    // The composition pass (scripts/reflections.lua): there the probe covered the reflection
    // entirely (its alpha), without the probe nothing but the distant probe did.
    ASSERT_EQ(reflection.width, W);
    std::printf("composition at the mirror image: covered %.3f with the probe, %.3f without\n",
                reflection.at(m.x, m.y, 3), reflectionNone.at(m.x, m.y, 3));
    EXPECT_GT(reflection.at(m.x, m.y, 3), 0.95f);
    EXPECT_EQ(reflectionNone.at(m.x, m.y, 3), 0.0f);
    // Outside the probe's box (x > 2 m) nothing changes: the same arithmetic, bit for bit.
    int outside = 0;
    for (uint32_t y = H / 2; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            // The floor point under pixel (x, y): far enough right of the box proxy's x = 2 face.
            const glm::vec4 ndc((static_cast<float>(x) + 0.5f) / W * 2.0f - 1.0f,
                                (static_cast<float>(y) + 0.5f) / H * 2.0f - 1.0f, 0.5f, 1.0f);
            glm::vec4 w =
                glm::inverse(cameraViewProj(glm::vec3(0, 2, 6), glm::vec3(0), 40.0f, W, H)) * ndc;
            const glm::vec3 dir = glm::normalize(glm::vec3(w) / w.w - glm::vec3(0, 2, 6));
            if (dir.y >= 0.0f) continue;
            const glm::vec3 floor = glm::vec3(0, 2, 6) + dir * (2.0f / -dir.y);
            if (floor.x < 2.3f) continue;
            ++outside;
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(one.at(x, y, c), none.at(x, y, c)) << x << ", " << y;
            ASSERT_EQ(reflection.at(x, y, 3), 0.0f) << x << ", " << y;  // the distant probe's alone
        }
    EXPECT_GT(outside, 500);
}

}  // namespace
