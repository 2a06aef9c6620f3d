// Moving objects by their numbers, on tests/gpu/scenes/motion.lua: a box gliding and turning
// along its path, a blended pane rising, a box standing still, before a wall. The motion target
// the G-buffer and forward passes write must be each surface's own screen motion since the last
// frame — found here independently, from where the pixel's surface point lay on the object's
// last-frame pose — zero where nothing moved, the pane's blended by its opacity; a perspective
// camera's motion must divide by depth as the projection does; TAA must follow the moving
// object rather than smear it; and the library must move a dynamic mesh it is told to move and
// refuse one declared static.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "image/image.h"
#include "runtime/runtime.h"
#include "runtime/session.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
const std::string kScene = kRoot + "/tests/gpu/scenes/motion.lua";
constexpr uint32_t S = 256;                  // square images
constexpr float kPixelsPerMetre = S / 4.0f;  // the orthographic camera is 4 m high
constexpr uint32_t kFrames = 20;             // the last at t = 19/60 s, the one before at 18/60

// The slider's pose at t inside its path's middle segment (0.25 .. 0.5 s), where the evenly
// spaced keys make it exactly linear: centre x from −0.5 m at 4 m/s, y 0.6; turned about Z from
// 22.5° at 90°/s.
glm::vec2 sliderCentre(double t) { return {float(-0.5 + 4.0 * (t - 0.25)), 0.6f}; }
float sliderAngle(double t) { return glm::radians(float(22.5 + 90.0 * (t - 0.25))); }
glm::vec2 rotate(glm::vec2 v, float a) {
    return {std::cos(a) * v.x - std::sin(a) * v.y, std::sin(a) * v.x + std::cos(a) * v.y};
}

// Where the surface point `now` (world xy, the slider's face) lay the frame before.
glm::vec2 sliderBefore(glm::vec2 now, double t, double tBefore, glm::vec2* local = nullptr) {
    const glm::vec2 l = rotate(now - sliderCentre(t), -sliderAngle(t));
    if (local) *local = l;
    return sliderCentre(tBefore) + rotate(l, sliderAngle(tBefore));
}

class Motion : public GpuFixture {
protected:
    static SessionOptions options(const std::map<std::string, std::string>& args) {
        return sceneOptions(kScene, args, S, S);
    }
    // Scene file `file`'s HDR at frame kFrames − 1, 320×180, without antialiasing (and without SSR
    // unless `ssr`).
    static Image stillHdr(const std::string& file, bool ssr) {
        SessionOptions o = sceneOptions(file, {}, 320, 180);
        o.params["antialiasing"] = Value(std::string("none"));
        if (!ssr) o.params["ssr_max_roughness"] = Value(0.0);
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", kFrames, {"hdr"});
        return r.images.count("hdr") ? r["hdr"] : Image();
    }
    static Readback render(const std::map<std::string, std::string>& args,
                           const std::vector<std::string>& textures, uint32_t frames = kFrames) {
        return renderAndRead(options(args), kRoot + "/scripts/pipelines/deferred.lua", frames,
                             textures);
    }
};

// The orthographic view: pixel centre ↔ world xy.
glm::vec2 worldOf(uint32_t px, uint32_t py) {
    return {(float(px) + 0.5f - S / 2.0f) / kPixelsPerMetre,
            (S / 2.0f - float(py) - 0.5f) / kPixelsPerMetre};
}

TEST_F(Motion, TheTargetHoldsEachSurfacesOwnMotion) {
    Readback r = render({}, {"motion"});
    ASSERT_TRUE(r.images.count("motion"));
    const Image& m = r["motion"];
    ASSERT_EQ(m.width, S);
    const double t = (kFrames - 1) / 60.0, tBefore = (kFrames - 2) / 60.0;
    const float margin = 2.0f / kPixelsPerMetre;
    double worstSlider = 0.0, worstStill = 0.0, worstPane = 0.0, meanSlider = 0.0;
    size_t slider = 0, still = 0, pane = 0;
    // The pane: 0.6 × 0.4 m, centre y from −0.8 m at 2 m/s, blended at opacity 0.5 over the
    // still wall (motion 0).
    const float paneY = float(-0.8 + 2.0 * (t - 0.25));
    const glm::vec2 paneMotion(0.0f, -0.5f * float(2.0 / 60.0) / 4.0f);  // uv y points down
    for (uint32_t py = 0; py < S; ++py)
        for (uint32_t px = 0; px < S; ++px) {
            const glm::vec2 p = worldOf(px, py);
            const glm::vec2 got(m.at(px, py, 0), m.at(px, py, 1));
            glm::vec2 local;
            const glm::vec2 before = sliderBefore(p, t, tBefore, &local);
            if (std::abs(local.x) < 0.25f - margin && std::abs(local.y) < 0.25f - margin) {
                const glm::vec2 want((p.x - before.x) / 4.0f, -(p.y - before.y) / 4.0f);
                worstSlider = std::max(worstSlider, double(glm::length(got - want)));
                meanSlider += got.x;
                ++slider;
            } else if (std::abs(p.x - 0.8f) < 0.3f - margin &&
                       std::abs(p.y - paneY) < 0.2f - margin) {
                worstPane = std::max(worstPane, double(glm::length(got - paneMotion)));
                ++pane;
            } else if (glm::length(p - glm::vec2(-1.2f, -1.0f)) < 0.15f ||  // the still box
                       (std::abs(p.x) > 1.8f && std::abs(p.y) > 1.6f)) {    // the wall's corners
                worstStill = std::max(worstStill, double(glm::length(got)));
                ++still;
            }
        }
    meanSlider /= double(std::max<size_t>(slider, 1));
    std::printf(
        "slider: %zu px, mean motion x %.5f uv (4 m/s at 60 frames/s: %.5f), worst error "
        "%.2e uv (%.3f px)\n",
        slider, meanSlider, 4.0 / 60.0 / 4.0, worstSlider, worstSlider * S);
    std::printf(
        "pane (blended, opacity 0.5): %zu px, worst error %.2e uv; still: %zu px, worst "
        "%.2e uv\n",
        pane, worstPane, still, worstStill);
    ASSERT_GT(slider, 500u);
    ASSERT_GT(pane, 200u);
    ASSERT_GT(still, 500u);
    EXPECT_NEAR(meanSlider, 4.0 / 60.0 / 4.0, 2e-4);
    EXPECT_LT(worstSlider, 1e-4);  // a 40th of a pixel: rg16f's steps at these values are ~1e-5
    EXPECT_LT(worstPane, 1e-4);
    EXPECT_EQ(worstStill, 0.0);
}

TEST_F(Motion, APerspectiveCamerasMotionDividesByDepth) {
    Readback r = render({{"perspective", "1"}}, {"motion"});
    ASSERT_TRUE(r.images.count("motion"));
    const Image& m = r["motion"];
    const double t = (kFrames - 1) / 60.0, tBefore = (kFrames - 2) / 60.0;
    const glm::mat4 viewProj = cameraViewProj({0, 0, 10}, {0, 0, 0}, 40.0f, S, S);
    const glm::mat4 inverse = glm::inverse(viewProj);
    auto uvOf = [&](glm::vec3 p) {
        const glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
        return glm::vec2(c) / c.w * 0.5f + 0.5f;
    };
    double worst = 0.0, mean = 0.0;
    size_t n = 0;
    for (uint32_t py = 0; py < S; ++py)
        for (uint32_t px = 0; px < S; ++px) {
            // The pixel's ray met with the slider's front face, the plane z = 0.25 m.
            const glm::vec2 ndc = (glm::vec2(px, py) + 0.5f) / float(S) * 2.0f - 1.0f;
            glm::vec4 a = inverse * glm::vec4(ndc, 0.0f, 1.0f),
                      b = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec3 near = glm::vec3(a) / a.w, far = glm::vec3(b) / b.w;
            const glm::vec3 p = near + (far - near) * ((0.25f - near.z) / (far.z - near.z));
            glm::vec2 local;
            const glm::vec2 before = sliderBefore(glm::vec2(p), t, tBefore, &local);
            if (std::abs(local.x) > 0.22f || std::abs(local.y) > 0.22f) continue;
            const glm::vec2 want = uvOf(p) - uvOf(glm::vec3(before, 0.25f));
            const glm::vec2 got(m.at(px, py, 0), m.at(px, py, 1));
            worst = std::max(worst, double(glm::length(got - want)));
            mean += got.x;
            ++n;
        }
    mean /= double(std::max<size_t>(n, 1));
    std::printf(
        "perspective: %zu px of the slider's face, mean motion x %.5f uv, worst error %.2e "
        "uv\n",
        n, mean, worst);
    ASSERT_GT(n, 200u);
    // 4/60 m at 9.75 m from the eye, a 40° field: ~0.0094 uv (orthographic, 4 m: 0.0167).
    EXPECT_NEAR(mean, 4.0 / 60.0 / (2.0 * 9.75 * std::tan(glm::radians(20.0))), 3e-4);
    EXPECT_LT(worst, 1e-4);
}

// TAA over the slider with a checkerboard on its face (4 × 4 cells of 8 px, white and dark),
// gliding 4.3 px a frame and turning: reprojected by the motion target, the history lands on the
// cells it showed last frame, so the resolved face keeps the un-antialiased frame's pattern, and
// the band the slider just left shows the wall, not its ghost. Figures against the same frame
// rendered without antialiasing (jitter off, as in every pixel-by-pixel test).
TEST_F(Motion, TaaFollowsAMovingObject) {
    TempFolder folder("motion_checker");
    const std::string checker = (folder.dir / "checker.png").string();
    {
        Image img(16, 16, 4);
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 16; ++x)
                for (int c = 0; c < 4; ++c)
                    img.at(x, y, c) = c == 3 || ((x / 4 + y / 4) % 2 == 0) ? 1.0f : 0.1f;
        ASSERT_TRUE(writePng(checker, img).has_value());
    }
    auto run = [&](const char* aa, const char* image) {
        SessionOptions o = options({{"checker", checker}});
        o.params["antialiasing"] = Value(std::string(aa));
        Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", kFrames, {image});
        return r.images.count(image) ? r[image] : Image();
    };
    const Image taa = run("taa", "taa"), none = run("none", "hdr");
    ASSERT_EQ(taa.width, S);
    ASSERT_EQ(none.width, S);
    const double t = (kFrames - 1) / 60.0;
    const float margin = 3.0f / kPixelsPerMetre;
    double faceDiff = 0.0, faceSum = 0.0, trailDiff = 0.0, trailSum = 0.0;
    for (uint32_t py = 0; py < S; ++py)
        for (uint32_t px = 0; px < S; ++px) {
            const glm::vec2 local = rotate(worldOf(px, py) - sliderCentre(t), -sliderAngle(t));
            const double a = taa.at(px, py, 0), b = none.at(px, py, 0);
            if (std::abs(local.x) < 0.25f - margin && std::abs(local.y) < 0.25f - margin) {
                faceDiff += std::abs(a - b), faceSum += b;
            } else if (local.x < -0.25f - margin &&
                       local.x > -0.25f - 3.0f * 4.27f / kPixelsPerMetre &&
                       std::abs(local.y) < 0.25f - margin) {
                trailDiff += std::abs(a - b), trailSum += b;  // where it was 1-3 frames ago
            }
        }
    const double face = faceDiff / faceSum, trail = trailDiff / trailSum;
    std::printf(
        "TAA on the moving checkerboard against the frame without antialiasing (red): "
        "face %.2f %%, the band it left %.2f %%\n",
        100.0 * face, 100.0 * trail);
    EXPECT_LT(face, 0.05);
    EXPECT_LT(trail, 0.02);
}

// A box moving along its path renders as the same box placed where the path has it at that frame:
// its draw, levels of detail and culling, the sun's cascades (culled on the GPU from the frame's
// boxes) and a point light's shadow views all follow it. The box placed at its first key instead
// shows what a stale pose would look like. SSR is off: it reflects the last frame's lit image, so
// the reflection of a shadow that moved lags a frame (the next test takes SSR on its own).
TEST_F(Motion, AMovingObjectRendersAsTheSameObjectPlacedThere) {
    TempFolder folder("motion_placed");
    auto scene = [&](const std::string& name, const std::string& box) {
        const std::string file = (folder.dir / (name + ".lua")).string();
        std::ofstream(file)
            << "local scene = require \"scene\"\n"
               "scene.material \"floor\" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }\n"
               "scene.plane \"floor\" { size = { 8, 8 }, material = \"floor\" }\n"
               "scene.material \"box\" { base_color = { 0.8, 0.3, 0.2 } }\n"
               "scene.box \"b\" { size = { 0.6, 0.6, 0.6 }, material = \"box\", "
            << box
            << " }\n"
               "scene.light \"sun\" { type = \"sun\", intensity = 20000, unit = \"lux\", "
               "direction = { -0.5, -0.8, -0.3 } }\n"
               "scene.light \"lamp\" { type = \"point\", intensity = 3000, unit = \"lm\", "
               "position = { 0.3, 1.2, 0.8 }, range = 6, shadow = true }\n"
               "scene.camera \"main\" { position = { 0, 3, 6 }, target = { 0, 0.3, 0 }, fov = 45, "
               "aperture = 4, shutter = 1 / 60, iso = 100 }\n";
        return file;
    };
    // 2 m/s along x and 120°/s about y between the keys at 0.25 and 0.5 s: at frame 19 (t = 19/60)
    // x = −1 + 2 · (19/60 − 1/4) = −0.8667 m, turned 30 + 120 · (1/15) = 38°.
    const std::string moving =
        scene("moving",
              "position = { -1.5, 0.3, 0 }, path = { { time = 0, rotation = { 0, 0, 0 } }, "
              "{ time = 0.25, position = { -1, 0.3, 0 }, rotation = { 0, 30, 0 } }, "
              "{ time = 0.5, position = { -0.5, 0.3, 0 }, rotation = { 0, 60, 0 } }, "
              "{ time = 0.75, position = { 0, 0.3, 0 }, rotation = { 0, 90, 0 } } }");
    const std::string placed =
        scene("placed", "position = { -0.8666667, 0.3, 0 }, rotation = { 0, 38, 0 }");
    const std::string first = scene("first", "position = { -1.5, 0.3, 0 }");
    const bool ssr = false;  // the next test's
    const Image a = stillHdr(moving, ssr), b = stillHdr(placed, ssr), c = stillHdr(first, ssr);
    ASSERT_EQ(a.width, 320u);
    const RenderDifference same = greenDifference(a, b), stale = greenDifference(c, b);
    std::printf(
        "moving against placed: mean %.1e, %.3f %% of pixels off by > 5 %%; the first "
        "key's pose against placed: %.2f %%, %.2f %%\n",
        same.mean, 100.0 * same.share, 100.0 * stale.mean, 100.0 * stale.share);
    EXPECT_LT(same.mean, 1e-6);  // the path's pose in float against the script's decimal
    EXPECT_EQ(same.share, 0.0);
    EXPECT_GT(stale.share, 0.02);  // what the comparison would see of a stale pose
}

// SSR of a moving object: a glowing post gliding over a mirror floor, against the post placed where
// the path has it. SSR fetches the hit's colour from the last frame's image and accumulates rays
// over frames; both reproject by the motion target (the hit's own motion, the reflecting texel's),
// so the reflection stands under the post, not a frame behind. What remains is the accumulation's
// trail at the reflection's back edge: the floor does not move while its reflection does, and the
// history is clamped to the box of this frame's rays, not rejected.
TEST_F(Motion, AMovingObjectsReflectionFollowsIt) {
    TempFolder folder("motion_mirror");
    auto scene = [&](const std::string& name, const std::string& post) {
        const std::string file = (folder.dir / (name + ".lua")).string();
        std::ofstream(file)
            << "local scene = require \"scene\"\n"
               "scene.environment \"black\" { kind = \"color\", color = { 1, 1, 1 }, intensity = "
               "0, "
               "unit = \"nits\" }\n"
               "scene.material \"mirror\" { base_color = { 0.9, 0.9, 0.9 }, metal_mask = 1, "
               "smoothness = 1 }\n"
               "scene.plane \"floor\" { size = { 8, 8 }, material = \"mirror\" }\n"
               "scene.material \"glow\" { base_color = { 0, 0, 0 }, emissive = { 40, 10, 5 } }\n"
               "scene.box \"post\" { size = { 0.3, 0.6, 0.3 }, material = \"glow\", "
            << post
            << " }\n"
               "scene.camera \"main\" { position = { 0, 1.2, 4 }, target = { -0.5, 0.2, 0 }, "
               "fov = 40, aperture = 2, shutter = 0.5, iso = 100 }\n";
        return file;
    };
    const std::string moving = scene(
        "moving",
        "position = { -1.5, 0.3, 0 }, path = { { time = 0 }, { time = 0.25, position = { -1, 0.3, "
        "0 } }, { time = 0.5, position = { -0.5, 0.3, 0 } }, { time = 0.75, position = { 0, 0.3, "
        "0 } } }");
    const std::string placed = scene("placed", "position = { -0.8666667, 0.3, 0 }");
    const Image a = stillHdr(moving, true), b = stillHdr(placed, true);
    ASSERT_EQ(a.width, 320u);
    const RenderDifference d = greenDifference(a, b);
    std::printf(
        "the moving post and its reflection against the post placed there: mean %.2f %%, "
        "%.2f %% of pixels off by > 5 %%\n",
        100.0 * d.mean, 100.0 * d.share);
    EXPECT_LT(d.mean, 0.065);  // 0.080 when SSR reprojected by the camera alone
    EXPECT_LT(d.share, 0.012);
}

// A node moving under an orthographic camera that stands still: the AO still accumulates over
// frames (the camera did not move, so nothing tells it to drop its history; the moving node's own
// texels are reprojected by their motion). Measured as the accumulated AO against the same frame
// with the history's share at 0: they differ where the frames' patterns average out.
TEST_F(Motion, AnOrthographicViewKeepsItsAoHistoryWhileANodeMoves) {
    TempFolder folder("motion_ortho_ao");
    const std::string file = (folder.dir / "ao.lua").string();
    std::ofstream(file)
        << "local scene = require \"scene\"\n"
           "scene.plane \"floor\" { size = { 8, 8 } }\n"
           "scene.box \"still\" { size = { 0.8, 0.8, 0.8 }, position = { 0.8, 0.4, 0 } }\n"
           "scene.box \"mover\" { size = { 0.2, 0.2, 0.2 }, position = { -2, 0.1, -2 },\n"
           "  path = { { time = 0 }, { time = 1, position = { -1, 0.1, -2 } } } }\n"
           "scene.light \"sun\" { type = \"sun\", intensity = 20000, unit = \"lux\", "
           "direction = { -0.5, -0.8, -0.3 } }\n"
           "scene.camera \"main\" { position = { 0, 4, 6 }, target = { 0, 0, 0 }, "
           "height = 5, aperture = 8, shutter = 1 / 125, iso = 100 }\n";
    auto ao = [&](double feedback) {
        SessionOptions o = sceneOptions(file, {}, 256, 192);
        o.params["ao_feedback"] = Value(feedback);
        Readback r =
            renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 12, {"ao_filtered"});
        return r.images.count("ao_filtered") ? r["ao_filtered"] : Image();
    };
    const Image kept = ao(0.9), fresh = ao(0.0);
    ASSERT_GT(kept.width, 0u);
    double diff = 0.0;
    for (uint32_t y = 0; y < kept.height; ++y)
        for (uint32_t x = 0; x < kept.width; ++x)
            diff += std::abs(kept.at(x, y, 0) - fresh.at(x, y, 0));
    diff /= double(kept.width) * kept.height;
    std::printf(
        "orthographic, a node moving: accumulated AO against one frame's, mean |difference| "
        "%.4f\n",
        diff);
    EXPECT_GT(diff, 1e-3);  // 0 when the history is dropped every frame
}

}  // namespace
