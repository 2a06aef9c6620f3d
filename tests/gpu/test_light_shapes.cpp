// The area lights' emissive shapes (seed 002 §4.8; graph/runtime/light_shapes.h): each drawn at
// its light's luminance, seed 000 tbl:12's lumens-to-nits for its shape, computed here from the
// table; hidden with `visible = false`; and nothing else changed by it — the shape neither
// shadows its own light (no shadow map, no ray cast sees it) nor lights the floor.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>

#include "runtime/runtime.h"
#include "runtime/session.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 320, H = 180;
constexpr double kPi = 3.14159265358979;

class LightShapes : public GpuFixture {
protected:
    // The scene's HDR in nits (pre-exposure divided out).
    // `frames`: SSR reflects the previous frame's image, so it needs a second.
    static Image render(const std::map<std::string, std::string>& args, uint32_t frames = 1) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/light_shapes.lua", args, W, H);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", frames, {"hdr"});
        if (r.images.empty()) return Image();
        Image hdr = r["hdr"];
        for (float& v : hdr.pixels) v /= r.preExposure;
        return hdr;
    }
    static glm::ivec2 at(glm::vec3 p) {
        return pixelOf(cameraViewProj({0, 1.6f, 5}, {0, 0.8f, 0}, 45.0f, W, H), W, H, p);
    }
    // The largest relative difference of the floor in front of the lights between two images
    // (twelve points, each checked lit).
    static double floorDifference(const Image& a, const Image& b) {
        double worst = 0.0;
        for (float x : {-2.4f, -0.8f, 0.8f, 2.4f})
            for (float z : {0.3f, 0.8f, 1.3f}) {
                const glm::ivec2 p = at({x, 0.0f, z});
                const double va = a.at(uint32_t(p.x), uint32_t(p.y), 1),
                             vb = b.at(uint32_t(p.x), uint32_t(p.y), 1);
                EXPECT_GT(vb, 0.1) << "the floor is lit at " << x << ", " << z;
                worst = std::max(worst, std::abs(va / vb - 1.0));
            }
        return worst;
    }
};

TEST_F(LightShapes, EachShapeShowsItsLightsLuminance) {
    const Image shown = render({}), hidden = render({{"visible", "0"}});
    ASSERT_EQ(shown.width, W);
    ASSERT_EQ(hidden.width, W);
    // tbl:12, 2000 lm: sphere Φ / (4π² r²), disk Φ / (π² r²), rect Φ / (π w h), tube
    // Φ / ((2π r l + 4π r²) π).
    const double lm = 2000.0;
    struct Shape {
        const char* name;
        glm::vec3 centre;
        double nits;
    } shapes[] = {
        {"sphere", {-2.4f, 1.0f, 0.2f}, lm / (4 * kPi * kPi * 0.2 * 0.2)},
        {"disk", {-0.8f, 1.0f, 0.0f}, lm / (kPi * kPi * 0.3 * 0.3)},
        {"rect", {0.8f, 1.0f, 0.0f}, lm / (kPi * 0.6 * 0.3)},
        {"tube", {2.4f, 1.0f, 0.05f}, lm / ((2 * kPi * 0.05 * 0.8 + 4 * kPi * 0.05 * 0.05) * kPi)},
    };
    for (const Shape& s : shapes) {
        const glm::ivec2 p = at(s.centre);
        const double got = shown.at(uint32_t(p.x), uint32_t(p.y), 1),
                     without = hidden.at(uint32_t(p.x), uint32_t(p.y), 1);
        std::printf("%s: %.1f nits at its centre (tbl:12: %.1f), %.3f hidden\n", s.name, got,
                    s.nits, without);
        EXPECT_NEAR(got / s.nits, 1.0, 0.02) << s.name;
        EXPECT_LT(without, 0.01 * s.nits) << s.name;
    }
    // The floor below the lights (rough, 0.3: no screen-space reflection of the shapes) is lit
    // the same with the shapes and without: they cast nothing and emit nothing onto it.
    const double worst = floorDifference(shown, hidden);
    std::printf("floor with the shapes against without: worst %.4f %%\n", 100 * worst);
    EXPECT_LT(worst, 1e-3);
}

// With every light's shadow map on, the shape around the light does not shadow it: the floor in
// front of the lights is lit as without the shapes (within 1 %). (The local maps start at the
// light's radius, past its shape, and the shape is no caster either; the ray casts' side is
// checked by the probe test below.)
TEST_F(LightShapes, AShapeCastsNoShadowOnItsLight) {
    const Image shown = render({{"shadow", "1"}}),
                hidden = render({{"shadow", "1"}, {"visible", "0"}});
    ASSERT_EQ(shown.width, W);
    ASSERT_EQ(hidden.width, W);
    const double worst = floorDifference(shown, hidden);
    std::printf("shadowed lights, floor with the shapes against without: worst %.4f %%\n",
                100 * worst);
    EXPECT_LT(worst, 0.01);
}

// A glossy floor reflects the shapes through SSR (the seed's §4.9.4 note: the emissive is then
// counted in the reflection too, next to the light's own specular): the floor under the sphere's
// mirror image is brighter with the shape shown.
TEST_F(LightShapes, ScreenSpaceReflectionsSeeTheShapes) {
    const Image shown = render({{"smoothness", "0.95"}}, 2),
                hidden = render({{"smoothness", "0.95"}, {"visible", "0"}}, 2);
    ASSERT_EQ(shown.width, W);
    // The sphere's mirror image in the floor: the point on the floor where the camera sees (−2.4, −1, 0).
    const glm::vec3 eye(0, 1.6f, 5), image(-2.4f, -1.0f, 0.0f);
    const float t = eye.y / (eye.y - image.y);
    const glm::ivec2 p = at(eye + (image - eye) * t);
    const double a = shown.at(uint32_t(p.x), uint32_t(p.y), 1),
                 b = hidden.at(uint32_t(p.x), uint32_t(p.y), 1);
    std::printf("glossy floor at the sphere's reflection: %.1f nits shown, %.1f hidden\n", a, b);
    EXPECT_GT(a, b * 1.05);
}

// The local probes capture the shapes (seed 002 §4.9.1.2: what the probe sees from its point):
// a sphere probe 2 m in front of the lights; its −Z face, along the direction of the disk's
// centre, holds the disk's luminance, and nothing there without the shape.
TEST_F(LightShapes, ALocalProbeCapturesTheShapes) {
    auto capture = [&](const char* visible, uint32_t face) {
        SessionOptions o = sceneOptions(kRoot + "/tests/gpu/scenes/light_shapes.lua",
                                        {{"visible", visible}, {"probe", "1"}}, W, H);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"hdr"});
        EXPECT_EQ(r.images.size(), 1u);
        auto img = rt().executor().readback("probe_radiance", face, 0);  // of cube 0
        EXPECT_TRUE(img.has_value());
        return img ? std::move(*img) : Image();
    };
    const Image shown = capture("1", 5), hidden = capture("0", 5);
    ASSERT_GT(shown.width, 0u);
    // −Z face: direction (−s, −t, −1) for uv = ((s + 1) / 2, (t + 1) / 2); the disk's centre seen
    // from (0, 1, 2) lies along (−0.8, 0, −2): s = 0.4, t = 0.
    const uint32_t x = uint32_t(0.7f * float(shown.width)), y = shown.height / 2;
    const double nits = 2000.0 / (kPi * kPi * 0.3 * 0.3);
    std::printf("probe capture along the disk: %.1f nits shown (tbl:12 %.1f), %.3f hidden\n",
                double(shown.at(x, y, 1)), nits, double(hidden.at(x, y, 1)));
    EXPECT_NEAR(shown.at(x, y, 1) / nits, 1.0, 0.02);
    EXPECT_LT(hidden.at(x, y, 1), 0.01 * nits);
    // The capture lights the floor with a shadow ray per light (lib/bvh.glsl): the shapes, which
    // hold the lights' centres, are not in the ray casts' BVH, so the floor under the probe (its
    // −Y face) is lit as without them.
    const Image floorShown = capture("1", 3), floorHidden = capture("0", 3);
    const uint32_t c = floorShown.width / 2;
    const double a = floorShown.at(c, c, 1), b = floorHidden.at(c, c, 1);
    std::printf("probe capture of the floor: %.3f nits with the shapes, %.3f without\n", a, b);
    EXPECT_GT(b, 0.1);
    EXPECT_NEAR(a / b, 1.0, 0.01);
}

}  // namespace
