// Screen-space ambient occlusion (scripts/ao.lua, shaders/passes/gtao.frag; seed 002 §4.10.3) on
// tests/gpu/scenes/ao_corner.lua: a floor with two walls meeting at a corner, seen from above.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t N = 256;
const float kHalf = 10.0f * std::tan(20.0f * 3.14159265f / 180.0f);  // ±3.64 m around (2.5, 2.5)

uint32_t pixelOf(float world) {
    return static_cast<uint32_t>(((world - 2.5f) / kHalf * 0.5f + 0.5f) * N);
}

class Ao : public GpuFixture {
protected:
    static Image render(const std::map<std::string, std::string>& args,
                        const std::string& camera = "top", uint32_t frames = 1) {
        SessionOptions o;
        o.sceneArgs = args;
        o.camera = camera;
        o.compile.outputWidth = N;
        o.compile.outputHeight = N;
        o.scene = kRoot + "/tests/gpu/scenes/ao_corner.lua";
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", frames, {"ssao"});
        return r.images.empty() ? Image() : r["ssao"];
    }
};

TEST_F(Ao, CreaseAndCornerAreDarkerThanTheOpenFloor) {
    // At the base of a wall half the hemisphere is blocked (cosine-weighted: AO 0.5 for an infinite
    // wall); in the corner three quarters; 2.5 m from both walls (beyond the 1 m radius) nothing.
    Image ao = render({});
    ASSERT_EQ(ao.width, N);
    const float crease = ao.at(pixelOf(0.06f), pixelOf(3.0f), 0);
    const float corner = ao.at(pixelOf(0.06f), pixelOf(0.06f), 0);
    const float open = ao.at(pixelOf(4.5f), pixelOf(4.5f), 0);
    std::printf("AO: crease %.3f, corner %.3f, open floor %.3f\n", crease, corner, open);
    EXPECT_LT(crease, 0.75f);
    EXPECT_GT(crease, 0.35f);
    EXPECT_LT(corner, crease);
    EXPECT_GT(open, 0.98f);
    // It rises away from the wall: 0.06 m < 0.4 m < 1.5 m.
    EXPECT_LT(crease, ao.at(pixelOf(0.4f), pixelOf(3.0f), 0));
    EXPECT_LT(ao.at(pixelOf(0.4f), pixelOf(3.0f), 0), ao.at(pixelOf(1.5f), pixelOf(3.0f), 0));
}

TEST_F(Ao, AnOpenPlaneIsUnoccluded) {
    // Every pixel of an open floor, from above and from a low grazing view, within 3 % of 1 (the
    // 0.05 tangent-plane bias absorbs the depth buffer's reconstruction noise; measured 0.992 from
    // above, 0.980 from the low view).
    for (const char* camera : {"top", "low"}) {
        Image ao = render({{"open", "1"}}, camera);
        ASSERT_EQ(ao.width, N);
        float darkest = 1.0f;
        for (float v : ao.pixels) darkest = std::min(darkest, v);
        std::printf("open plane, camera %s: darkest AO %.4f\n", camera, darkest);
        EXPECT_GT(darkest, 0.97f) << camera;
    }
}

// The cosine-weighted visibility within `radius` of a point on the floor `x` metres from an
// infinitely long wall of height `height` (what GTAO estimates there, from the horizons within
// the radius): 1 − (1/π) ∫ over the directions that meet the wall within the radius of cos θ dω,
// by quadrature over θ (from the normal) and φ (around it; the wall lies towards φ = π).
double wallVisibility(double x, double radius, double height) {
    const int nTheta = 800, nPhi = 1600;
    const double pi = 3.14159265358979;
    double hidden = 0.0;
    for (int i = 0; i < nTheta; ++i) {
        const double theta = (i + 0.5) / nTheta * pi / 2;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = (j + 0.5) / nPhi * 2 * pi;
            const double dx = std::sin(theta) * std::cos(phi), dy = std::cos(theta);
            if (dx >= 0.0) continue;
            const double t = x / -dx;  // to the wall's face
            if (t <= radius && t * dy <= height)
                hidden += std::cos(theta) * std::sin(theta) * (pi / 2 / nTheta) * (2 * pi / nPhi);
        }
    }
    return 1.0 - hidden / pi;
}

// Over frames (ao_temporal.frag): gtao's directions and step offsets turn every frame and each
// frame is blended into the reprojected last, so after 8 still frames the AO beside a wall is
// closer to its exact value (wallVisibility) than one frame's 48 fixed directions get it.
TEST_F(Ao, AccumulatedOverFramesTheAoBesideAWallIsCloserToTheIntegral) {
    auto alongTheWall = [](const Image& ao, float distance) {  // the mean over 1..4 m of wall
        double sum = 0.0;
        uint32_t n = 0;
        for (uint32_t z = pixelOf(1.0f); z <= pixelOf(4.0f); ++z, ++n)
            sum += ao.at(pixelOf(distance), z, 0);
        return sum / n;
    };
    const Image one = render({}, "top", 1), eight = render({}, "top", 8);
    ASSERT_EQ(one.width, N);
    ASSERT_EQ(eight.width, N);
    double error1 = 0.0, error8 = 0.0;
    const float distances[] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.8f};
    for (float distance : distances) {
        const double exact = wallVisibility(distance, 1.0, 2.0);
        const double a1 = alongTheWall(one, distance), a8 = alongTheWall(eight, distance);
        std::printf("AO %.2f m from the wall: exact %.4f, 1 frame %.4f, 8 frames %.4f\n", distance,
                    exact, a1, a8);
        error1 += std::abs(a1 - exact) / std::size(distances);
        error8 += std::abs(a8 - exact) / std::size(distances);
    }
    std::printf("mean |error|: 1 frame %.4f, 8 frames %.4f\n", error1, error8);
    EXPECT_LT(error8, 0.7 * error1);
}

}  // namespace
