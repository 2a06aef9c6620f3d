// The reference mode's ray-cast hierarchy (graph/scene/bvh.h): the nearest hit through the
// hierarchy equals the nearest hit over every triangle, for random rays through a scene of
// spheres and a box; every triangle is in exactly one leaf; the depth stays small.
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "scene/bvh.h"
#include "scene/scene.h"

namespace rg {
namespace {

float bruteForce(const std::vector<glm::vec3>& c, glm::vec3 o, glm::vec3 d, float tMax) {
    float best = tMax;
    for (size_t t = 0; t + 2 < c.size(); t += 3) {
        const glm::vec3 e1 = c[t + 1] - c[t], e2 = c[t + 2] - c[t], p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 s = o - c[t];
        const float u = glm::dot(s, p) / det;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) / det, h = glm::dot(e2, q) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && h > 0 && h < best) best = h;
    }
    return best;
}

TEST(Bvh, NearestHitEqualsBruteForce) {
    std::vector<glm::vec3> corners;
    auto add = [&](const Primitive& p, glm::vec3 offset) {
        for (uint32_t i : p.indices) corners.push_back(p.vertices[i].position + offset);
    };
    for (int i = 0; i < 5; ++i)
        add(makeSphere(0.4f, 24, 0),
            glm::vec3(static_cast<float>(i) - 2.0f, 0.4f, 0.3f * static_cast<float>(i)));
    add(makeBox(glm::vec3(1.0f), 0), glm::vec3(0.0f, 0.5f, -2.0f));
    const FlatBvh bvh = buildBvh(corners);
    ASSERT_EQ(bvh.triangleCount, corners.size() / 3);
    EXPECT_LE(bvh.depth, 16u);
    // Every triangle in exactly one leaf.
    std::vector<int> seen(bvh.triangleCount, 0);
    for (uint32_t n = 0; n < bvh.nodeCount; ++n) {
        const uint32_t count = std::bit_cast<uint32_t>(bvh.data[2 * n + 1].w),
                       first = std::bit_cast<uint32_t>(bvh.data[2 * n].w);
        for (uint32_t t = first; count > 0 && t < first + count; ++t) ++seen[t];
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int hits = 0;
    for (int k = 0; k < 4000; ++k) {
        const glm::vec3 o(3.0f * u(rng), 1.0f + u(rng), 3.0f * u(rng));
        const glm::vec3 d =
            glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, -0.2f, 0.0f));
        const float tMax = k % 2 ? 1e30f : 2.0f;
        const float a = traceBvh(bvh, o, d, tMax), b = bruteForce(corners, o, d, tMax);
        ASSERT_NEAR(a, b, 1e-4f * std::max(1.0f, b)) << k;
        if (b < tMax) ++hits;
    }
    std::printf("%u triangles, %u nodes, depth %u; %d of 4000 rays hit\n", bvh.triangleCount,
                bvh.nodeCount, bvh.depth, hits);
    EXPECT_GT(hits,
              300);  // 444: a tenth of the rays meet something, enough to compare nearest hits
}

TEST(Bvh, EmptySceneHasNoNodes) {
    const FlatBvh bvh = buildBvh({});
    EXPECT_EQ(bvh.nodeCount, 0u);
    EXPECT_EQ(traceBvh(bvh, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 5.0f), 5.0f);
}

}  // namespace
}  // namespace rg
