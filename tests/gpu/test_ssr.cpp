// Screen-space reflections and their composition (scripts/ssr.lua, shaders/ssr/; seed 002 §4.9.4,
// §4.9.5) on tests/gpu/scenes/ssr_mirror.lua: a mirror floor under a red (emissive) box.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 240, H = 160;

struct Frame {
    Image hdr;  // pre-exposed, as the HDR target holds it
    Image ssr;  // nits
    float preExposure = 1.0f;
};

// The pixel a world point lands on with the scene's "main" camera.
glm::ivec2 pixelOf(glm::vec3 p) {
    return rg::pixelOf(cameraViewProj(glm::vec3(0, 2, 6), glm::vec3(0), 40.0f, W, H), W, H, p);
}

// The SSR at full-resolution pixel (x, y): `ssr` is traced at half resolution (scripts/ssr.lua),
// one ray per 2×2 pixels (accumulated over frames: the block).
float ssrAt(const Image& ssr, int x, int y, int c) {
    return ssr.at(static_cast<uint32_t>(x / 2), static_cast<uint32_t>(y / 2), c);
}

class Ssr : public GpuFixture {
protected:
    static Frame render(const std::map<std::string, std::string>& args, double distance = 20.0) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/ssr_mirror.lua", args, W, H);
        o.params["ssr_distance"] = Value(distance);
        // Two frames: the second reflects the first's lit image.
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 2, {"hdr", "ssr"});
        Frame out;
        if (r.images.size() != 2) return out;
        out.hdr = r["hdr"];
        out.ssr = r["ssr"];
        out.preExposure = r.preExposure;
        return out;
    }
};

TEST_F(Ssr, ReflectionLandsWhereTheMirrorPutsIt) {
    Frame box = render({});
    Frame none = render({{"box", "0"}});
    ASSERT_EQ(box.ssr.width, W / 2);
    // The box's mirror image: the floor point under the box's front face centre seen from the
    // camera reflects (0, 0.5, −1.5) — the face's image below the floor is (0, −0.5, −1.5).
    const glm::ivec2 m = pixelOf(glm::vec3(0.0f, -0.5f, -1.5f));
    const glm::ivec2 boxPx = pixelOf(glm::vec3(0.0f, 0.5f, -1.5f));
    ASSERT_GT(m.y, boxPx.y);  // the reflection is below the box on screen
    const float a = ssrAt(box.ssr, m.x, m.y, 3), r = ssrAt(box.ssr, m.x, m.y, 0),
                g = ssrAt(box.ssr, m.x, m.y, 1);
    std::printf(
        "mirror image at pixel (%d, %d): confidence %.3f, colour %.3g %.3g; without the box: "
        "confidence %.3f\n",
        m.x, m.y, a, r, g, ssrAt(none.ssr, m.x, m.y, 3));
    EXPECT_GT(a, 0.8f);
    EXPECT_GT(r, 5.0f * g);  // the red box
    // The reflected colour is the box as the previous frame lit it (the mirror's f0 ≈ 0.95), in
    // nits: SSR divides the pre-exposure out, as the probes it is blended with are.
    const float boxRed = box.hdr.at(boxPx.x, boxPx.y, 0) / box.preExposure;
    EXPECT_NEAR(r / boxRed, 1.0f, 0.15f);
    // Without the box the ray meets only sky: no hit, the probe reflects.
    EXPECT_EQ(ssrAt(none.ssr, m.x, m.y, 3), 0.0f);
    // Where the reflected rays leave the screen (the floor at the top of the image reflects what is
    // above and behind the view), the confidence is 0 and the image is the probe's, with or
    // without the box (1 %).
    int checked = 0;
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; x += 7) {
            // Pixels whose 2×2 neighbourhood of half-resolution rays all missed (the composition
            // filters them bilinearly).
            bool missed = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int sx = std::clamp(static_cast<int>(x) + dx, 0, static_cast<int>(W) - 1),
                              sy = std::clamp(static_cast<int>(y) + dy, 0, static_cast<int>(H) - 1);
                    missed = missed && ssrAt(box.ssr, sx, sy, 3) == 0.0f &&
                             ssrAt(none.ssr, sx, sy, 3) == 0.0f;
                }
            if (!missed) continue;
            if (std::abs(static_cast<int>(x) - m.x) < 40)
                continue;  // away from the box and its image
            ++checked;
            EXPECT_NEAR(box.hdr.at(x, y, 1), none.hdr.at(x, y, 1),
                        0.01f * none.hdr.at(x, y, 1) + 1e-4f)
                << x << ", " << y;
        }
        if (checked > 200) break;
    }
    EXPECT_GT(checked, 50);
}

TEST_F(Ssr, ClearCoatAndTwoColourPathsTakeTheReflection) {
    // The same mirror made of the clear-coat and the two-colour materials, each lit by its own
    // lighting pass: with SSR the box's mirror image is the red box; with rays too short to reach
    // it (10 cm) the same pixel reflects the sky.
    const glm::ivec2 m = pixelOf(glm::vec3(0.0f, -0.5f, -1.5f));
    for (const char* floor : {"clear_coat", "two_colour"}) {
        Frame with = render({{"floor", floor}}), without = render({{"floor", floor}}, 0.1);
        ASSERT_EQ(with.hdr.width, W) << floor;
        ASSERT_EQ(without.hdr.width, W) << floor;
        const float r = with.hdr.at(m.x, m.y, 0), g = with.hdr.at(m.x, m.y, 1),
                    b = with.hdr.at(m.x, m.y, 2);
        const float r0 = without.hdr.at(m.x, m.y, 0), b0 = without.hdr.at(m.x, m.y, 2);
        std::printf(
            "%s: the mirror image with SSR %.3g %.3g %.3g, without %.3g .. %.3g (pre-exposed)\n",
            floor, r, g, b, r0, b0);
        EXPECT_GT(ssrAt(with.ssr, m.x, m.y, 3), 0.8f) << floor;
        EXPECT_GT(r, 5.0f * g) << floor;
        EXPECT_GT(b0, r0) << floor;
    }
}

// A texel premultiplied by its confidence (what the composition weighs), red and confidence.
glm::vec2 premultiplied(const Image& im, uint32_t x, uint32_t y) {
    const float a = im.at(x, y, 3);
    return a < 0.0f ? glm::vec2(-1.0f) : glm::vec2(im.at(x, y, 0) * a, a);
}

TEST_F(Ssr, TemporalAccumulationHoldsTheWholeBlock) {
    // `ssr` traces one corner of each 2×2 block a frame (ssr/ssr_pixel.glsl), `ssr_temporal`
    // accumulates them: after a dozen still frames each texel should hold the mean of its block's
    // four rays — the last four frames' traces, one per corner — far closer than any single
    // frame's ray, which steps the box's mirrored edges by two pixels.
    SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/ssr_mirror.lua", {}, W, H);
    o.captures = {"ssr", "ssr_trace"};
    Session s(*s_runtime, o);
    ASSERT_TRUE(s.load(kRoot + "/scripts/pipelines/deferred.lua").has_value());
    constexpr int kFrames = 12;
    std::vector<Image> traces, resolved;
    for (int f = 0; f < kFrames; ++f) {
        auto fr = s.frame();
        ASSERT_TRUE(fr.has_value()) << fr.error().describe();
        auto trace = s_runtime->executor().readback("ssr_trace");
        auto ssr = s_runtime->executor().readback("ssr");
        ASSERT_TRUE(trace && ssr);
        traces.push_back(std::move(*trace));
        resolved.push_back(std::move(*ssr));
    }
    const uint32_t w = traces[0].width, h = traces[0].height;
    // The first frame has no lit image to reflect yet: every ray is unknown (−1) and `ssr` holds
    // nothing; the second takes those rays whole (nothing accumulated to blend with), so the
    // reflection does not fade in.
    int unknown = 0, equal = 0, hits = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            EXPECT_EQ(resolved[0].at(x, y, 3), 0.0f);
            unknown += traces[0].at(x, y, 3) < 0.0f;
            const float a = traces[1].at(x, y, 3);
            if (a <= 0.0f || traces[0].at(x, y, 3) >= 0.0f) continue;
            ++hits;
            equal += std::abs(resolved[1].at(x, y, 3) - a) <= 1e-3f &&
                     std::abs(resolved[1].at(x, y, 0) - traces[1].at(x, y, 0)) <=
                         2e-3f * traces[1].at(x, y, 0) + 1e-3f;
        }
    EXPECT_GT(unknown, 100);
    // Once the lit image has a history, every ray knows (an unknown one would empty its texel).
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            ASSERT_GE(traces.back().at(x, y, 3), 0.0f) << x << ", " << y;
    EXPECT_GT(hits, 50);
    EXPECT_EQ(equal, hits);
    // The reference: the mean of the last four traces (each corner once), premultiplied.
    double single = 0.0, accumulated = 0.0, change = 0.0, traceChange = 0.0;
    int counted = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            glm::vec2 ref(0.0f);
            for (int k = kFrames - 4; k < kFrames; ++k)
                ref += 0.25f * premultiplied(traces[k], x, y);
            if (ref.y <= 0.0f) continue;
            ++counted;
            for (int k = kFrames - 4; k < kFrames; ++k)
                single += 0.25 * std::abs(premultiplied(traces[k], x, y).x - ref.x);
            accumulated += std::abs(premultiplied(resolved[kFrames - 1], x, y).x - ref.x);
            change += std::abs(premultiplied(resolved[kFrames - 1], x, y).x -
                               premultiplied(resolved[kFrames - 2], x, y).x);
            traceChange += std::abs(premultiplied(traces[kFrames - 1], x, y).x -
                                    premultiplied(traces[kFrames - 2], x, y).x);
        }
    ASSERT_GT(counted, 100);
    single /= counted, accumulated /= counted, change /= counted, traceChange /= counted;
    std::printf(
        "%d texels reflecting: mean |red x confidence - the block's mean| %.3g for one frame's "
        "ray, "
        "%.3g accumulated (%.2fx); frame-to-frame change %.3g accumulated, %.3g traced\n",
        counted, single, accumulated, accumulated / single, change, traceChange);
    EXPECT_GT(single, 0.0);
    EXPECT_LT(accumulated, 0.4 * single);
    EXPECT_LT(change, 0.4 * traceChange);
}

}  // namespace
