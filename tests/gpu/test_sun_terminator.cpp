// The sun's shadow mask at the terminator (shaders/shadows/sun_mask.frag, lib/shadows.glsl's
// rgSunShadowIn) on tests/gpu/scenes/terminator.lua: a sphere and a box lit from the side, seen
// through an orthographic camera, so that each pixel is a ray the test intersects with the
// sphere and the box itself. The mask is read as it is written, N·L not applied: 0 on points
// that face away from the sun (their own surface occludes it), 1 on unoccluded points facing it,
// and the change within a shadow texel of the terminator — for the full- and half-resolution
// masks, at three sun heights, in every cascade.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include <glm/glm.hpp>

#include "runtime/session.h"
#include "image/image.h"

using namespace rg;

namespace {

const std::string kRoot = RG_SOURCE_ROOT;
constexpr uint32_t W = 256, H = 160;

// The scene's geometry (terminator.lua) and camera.
const glm::vec3 kCentre{1.2f, 1.0f, 0.0f};
constexpr float kRadius = 1.0f;
const glm::vec3 kBoxMin{-2.2f, 0.0f, -1.8f}, kBoxMax{-1.0f, 1.2f, -0.6f};

glm::vec3 towardsSun(double elevationDeg) {
    const double e = elevationDeg * M_PI / 180.0, a = M_PI / 6.0;
    return glm::normalize(glm::vec3(static_cast<float>(std::cos(e) * std::cos(a)),
                                    static_cast<float>(std::sin(e)),
                                    static_cast<float>(-std::cos(e) * std::sin(a))));
}

struct Camera {
    glm::vec3 position, forward, right, up;
    float halfW, halfH;
};
Camera camera(float back) {
    const glm::vec3 d = glm::normalize(glm::vec3(1.0f, 0.8f, 1.4f));
    Camera c;
    const glm::vec3 target(0.0f, 0.8f, 0.0f);
    c.position = target + d * (8.0f + back);
    c.forward = -d;  // glm::lookAt's basis
    c.right = glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0)));
    c.up = glm::cross(c.right, c.forward);
    c.halfH = 2.5f;
    c.halfW = c.halfH * static_cast<float>(W) / H;
    return c;
}

struct Hit {
    float t;
    glm::vec3 position, normal;
    int object;  // 0 the sphere, 1..6 the box's faces
};

std::optional<float> sphereT(glm::vec3 o, glm::vec3 d) {
    const glm::vec3 oc = o - kCentre;
    const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - kRadius * kRadius;
    const float disc = b * b - c;
    if (disc < 0) return std::nullopt;
    const float t = -b - std::sqrt(disc);
    return t > 1e-4f ? std::optional<float>(t) : std::nullopt;
}
std::optional<std::pair<float, int>> boxT(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
    float tNear = -1e30f, tFar = 1e30f;
    int face = 0;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-9f) {
            if (o[k] < lo[k] || o[k] > hi[k]) return std::nullopt;
            continue;
        }
        float t0 = (lo[k] - o[k]) / d[k], t1 = (hi[k] - o[k]) / d[k];
        int f = 2 * k + 1;  // the −k face
        if (t0 > t1) std::swap(t0, t1), f = 2 * k + 2;
        if (t0 > tNear) tNear = t0, face = f;
        tFar = std::min(tFar, t1);
    }
    if (tNear > tFar || tNear < 1e-4f) return std::nullopt;
    return std::pair{tNear, face};
}
// The nearest of the sphere and the box along the ray; `skip` leaves one of them out (0 the
// sphere, 1 the box).
std::optional<Hit> trace(glm::vec3 o, glm::vec3 d, int skip = -1) {
    std::optional<Hit> best;
    if (auto t = sphereT(o, d); t && skip != 0) {
        const glm::vec3 p = o + d * *t;
        best = Hit{*t, p, (p - kCentre) / kRadius, 0};
    }
    if (auto b = boxT(o, d, kBoxMin, kBoxMax); b && skip != 1 && (!best || b->first < best->t)) {
        glm::vec3 n(0.0f);
        const int k = (b->second - 1) / 2;
        n[k] = b->second % 2 ? -1.0f : 1.0f;
        best = Hit{b->first, o + d * b->first, n, b->second};
    }
    return best;
}

// The sun's cascades as sun_cascades.comp wrote them (lib/shadows.glsl's RgCascades).
struct Cascades {
    float splitFar[4], texelWorld[4];
    int used;
};
Cascades cascadesOf(const std::vector<uint8_t>& bytes) {
    Cascades c{};
    const float* f = reinterpret_cast<const float*>(bytes.data());
    std::memcpy(c.splitFar, f + 64, sizeof c.splitFar);
    std::memcpy(c.texelWorld, f + 68, sizeof c.texelWorld);
    c.used = static_cast<int>(f[76] + 0.5f);
    return c;
}

class Terminator : public GpuFixture {};

TEST_F(Terminator, TheSunsMaskFollowsTheSurfaceAtTheTerminator) {
    int checkedSphere = 0, checkedBox = 0, failures = 0;
    int cascadesSeen[4] = {0, 0, 0, 0};
    for (const double elevation : {15.0, 35.0, 60.0})
        for (const float back : {-6.0f, 0.0f, 20.0f})
            for (const char* mode : {"full", "half"}) {
                SessionOptions o = sceneOptions(
                    kRoot + "/tests/gpu/scenes/terminator.lua",
                    {{"elevation", std::to_string(elevation)}, {"back", std::to_string(back)}}, W,
                    H);
                o.params["sun_mask"] = Value(std::string(mode));
                const bool half = std::string(mode) == "half";
                const std::string mask = half ? "sun_visibility_half" : "sun_visibility";
                Readback r = renderAndRead(o, kRoot + "/scripts/pipelines/deferred.lua", 1, {mask},
                                           {"sun_cascades"});
                ASSERT_TRUE(r.images.count(mask) && r.buffers.count("sun_cascades"));
                const Image& m = r[mask];
                const Cascades cs = cascadesOf(r.buffers["sun_cascades"]);
                ASSERT_GE(cs.used, 1);
                if (elevation == 15.0 && !half)
                    std::printf("camera back %.0f m: cascades end at %.1f %.1f %.1f %.1f m\n", back,
                                cs.splitFar[0], cs.splitFar[1], cs.splitFar[2], cs.splitFar[3]);
                const Camera cam = camera(back);
                const glm::vec3 L = towardsSun(elevation);
                const int step = half ? 2 : 1;
                int away = 0, awayLit = 0, facing = 0, facingShadowed = 0;
                for (uint32_t my = 1; my + 1 < m.height; ++my)
                    for (uint32_t mx = 1; mx + 1 < m.width; ++mx) {
                        const uint32_t px = mx * step, py = my * step;
                        auto rayAt = [&](float x, float y) {
                            const float u = (x + 0.5f) / W * 2.0f - 1.0f;
                            const float v = 1.0f - (y + 0.5f) / H * 2.0f;
                            return trace(cam.position + cam.right * (u * cam.halfW) +
                                             cam.up * (v * cam.halfH),
                                         cam.forward);
                        };
                        const auto hit = rayAt(static_cast<float>(px), static_cast<float>(py));
                        if (!hit) continue;
                        // Away from the silhouettes: the neighbours see the same surface.
                        bool inside = true;
                        for (const auto& [dx, dy] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
                            const auto n = rayAt(
                                static_cast<float>(px) + static_cast<float>(dx * step) * 1.5f,
                                static_cast<float>(py) + static_cast<float>(dy * step) * 1.5f);
                            inside = inside && n && n->object == hit->object;
                        }
                        if (!inside) continue;
                        // Nothing else between the point and the sun (its own surface may be).
                        if (trace(hit->position, L, hit->object == 0 ? 0 : 1)) continue;
                        const float depth = glm::dot(hit->position - cam.position, cam.forward);
                        int ci = 0;
                        while (ci < cs.used - 1 && depth >= cs.splitFar[ci]) ++ci;
                        ++cascadesSeen[ci];
                        const float texel = cs.texelWorld[ci];
                        const float nl = glm::dot(hit->normal, L);
                        // Within a shadow texel of the terminator, as the light sees it (the
                        // sphere's points whose distance across the light from its outline is
                        // under one texel of their cascade), the mask may be anything; the box's
                        // faces have no terminator. (A quarter of a texel: one point of ~46 000
                        // off, at 35°.)
                        if (hit->object == 0 &&
                            kRadius * (1.0f - std::sqrt(std::max(0.0f, 1.0f - nl * nl))) <
                                1.0f * texel)
                            continue;
                        const float v = m.at(mx, my, 0);
                        (hit->object == 0 ? checkedSphere : checkedBox)++;
                        if (nl < 0) {
                            ++away;
                            awayLit += v > 0.02f;
                        } else {
                            ++facing;
                            facingShadowed += v < 0.98f;
                        }
                    }
                std::printf(
                    "elevation %2.0f°, camera back %4.1f m, %s mask: facing away %d, not 0 "
                    "at %d; facing %d, not 1 at %d\n",
                    elevation, back, mode, away, awayLit, facing, facingShadowed);
                EXPECT_GT(away, 50);
                EXPECT_GT(facing, 50);
                EXPECT_EQ(awayLit, 0) << elevation << "° " << mode << " back " << back;
                EXPECT_EQ(facingShadowed, 0) << elevation << "° " << mode << " back " << back;
                failures += awayLit + facingShadowed;
            }
    std::printf("checked %d sphere and %d box points; per cascade: %d %d %d %d\n", checkedSphere,
                checkedBox, cascadesSeen[0], cascadesSeen[1], cascadesSeen[2], cascadesSeen[3]);
    EXPECT_GT(cascadesSeen[0], 0);
    EXPECT_GT(cascadesSeen[1], 0);
    EXPECT_GT(cascadesSeen[2], 0);
}

}  // namespace
