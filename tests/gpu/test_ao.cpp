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
                        const std::string& camera = "top") {
        SessionOptions o;
        o.sceneArgs = args;
        o.camera = camera;
        o.compile.outputWidth = N;
        o.compile.outputHeight = N;
        o.scene = kRoot + "/tests/gpu/scenes/ao_corner.lua";
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {"ssao"});
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

}  // namespace
