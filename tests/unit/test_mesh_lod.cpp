// Levels of detail from meshoptimizer (graph/scene/mesh_lod.h): each level's error is the
// deviation measured against the full mesh — checked here by brute force over every triangle —
// the chain coarsens, open borders stay, small primitives keep none, and a second build of the
// same geometry comes from the cache.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scene/mesh_lod.h"
#include "scene/scene.h"

using namespace rg;

namespace {

// The distance from p to triangle abc by brute force: the nearest of the plane's foot (when it
// falls inside) and the three edges' nearest points.
float pointTriangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    const glm::vec3 foot = p - n * glm::dot(p - a, n);
    auto inside = [&](glm::vec3 u, glm::vec3 v) {
        return glm::dot(glm::cross(v - u, foot - u), n) >= 0;
    };
    if (inside(a, b) && inside(b, c) && inside(c, a)) return std::abs(glm::dot(p - a, n));
    auto edge = [&](glm::vec3 u, glm::vec3 v) {
        const float t = glm::clamp(glm::dot(p - u, v - u) / glm::dot(v - u, v - u), 0.0f, 1.0f);
        return glm::length(p - (u + t * (v - u)));
    };
    return std::min({edge(a, b), edge(b, c), edge(c, a)});
}

// The largest distance from `from`'s vertices, triangle centres and edge midpoints to `to`.
float bruteDeviation(const Primitive& p, const std::vector<uint32_t>& from,
                     const std::vector<uint32_t>& to) {
    auto nearest = [&](glm::vec3 q) {
        float best = std::numeric_limits<float>::max();
        for (size_t t = 0; t + 2 < to.size(); t += 3)
            best = std::min(
                best, pointTriangle(q, p.vertices[to[t]].position, p.vertices[to[t + 1]].position,
                                    p.vertices[to[t + 2]].position));
        return best;
    };
    float worst = 0;
    for (size_t t = 0; t + 2 < from.size(); t += 3) {
        const glm::vec3 a = p.vertices[from[t]].position, b = p.vertices[from[t + 1]].position,
                        c = p.vertices[from[t + 2]].position;
        for (glm::vec3 q :
             {a, b, c, (a + b + c) / 3.0f, (a + b) * 0.5f, (b + c) * 0.5f, (c + a) * 0.5f})
            worst = std::max(worst, nearest(q));
    }
    return worst;
}

Scene sceneOf(Primitive p) {
    Scene s;
    s.meshes.push_back(Mesh{"m", {std::move(p)}});
    return s;
}

}  // namespace

TEST(MeshLod, LevelsCoarsenAndTheirErrorIsTheMeasuredDeviation) {
    Primitive sphere = makeSphere(1.0f, 45, 0);  // 45 segments: no exact levels of its own
    ASSERT_TRUE(sphere.lods.empty());
    Scene s = sceneOf(sphere);
    const LodStats stats = buildMeshLods(s);
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_GE(p.lods.size(), 2u);
    EXPECT_EQ(stats.primitives, 1u);
    size_t previous = p.indices.size();
    float previousError = 0.0f;
    for (size_t l = 0; l < p.lods.size(); ++l) {
        const PrimitiveLod& lod = p.lods[l];
        EXPECT_LE(float(lod.indices.size()), 0.85f * float(previous)) << "level " << l;
        EXPECT_GT(lod.error, previousError) << "level " << l;
        // Both ways: the full mesh against the level's surface, and the level's triangles against
        // the full surface. buildMeshLods samples the full mesh at its dropped vertices and
        // triangle centres only (not its edges' midpoints): within 10 % of every sample here.
        const float brute = std::max(bruteDeviation(p, p.indices, lod.indices),
                                     bruteDeviation(p, lod.indices, p.indices));
        EXPECT_LE(lod.error, brute + 1e-5f) << "level " << l;
        EXPECT_GE(lod.error, 0.9f * brute) << "level " << l;
        // The grid's nearest-triangle search against brute force, sample for sample.
        EXPECT_NEAR(meshDeviation(p.vertices, lod.indices, p.indices),
                    bruteDeviation(p, lod.indices, p.indices), 1e-5f)
            << "level " << l;
        // A likeness: the simplifier's estimate was held under 2 % of the extent (2 m), and the
        // measured deviation stays within a few times that.
        EXPECT_LT(lod.error, 0.15f);
        previous = lod.indices.size();
        previousError = lod.error;
        std::printf("level %zu: %zu triangles, error %.5f m\n", l + 1, lod.indices.size() / 3,
                    lod.error);
    }
    // Again: from the cache, the same levels.
    Scene again = sceneOf(sphere);
    EXPECT_EQ(buildMeshLods(again).cached, 1u);
    ASSERT_EQ(again.meshes[0].primitives[0].lods.size(), p.lods.size());
    EXPECT_EQ(again.meshes[0].primitives[0].lods.back().indices, p.lods.back().indices);
}

TEST(MeshLod, OpenBordersStayAndSmallPrimitivesKeepNone) {
    // A 32 × 32 grid of quads on the XZ plane (2048 triangles): flat, so every level has error 0,
    // and its border vertices are all still used by every level.
    Primitive grid;
    const int n = 32;
    for (int z = 0; z <= n; ++z)
        for (int x = 0; x <= n; ++x) {
            Vertex v;
            v.position = glm::vec3(float(x) / n, 0.0f, float(z) / n);
            v.normal = glm::vec3(0, 1, 0);
            grid.vertices.push_back(v);
        }
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) {
            const uint32_t i = uint32_t(z * (n + 1) + x);
            grid.indices.insert(grid.indices.end(),
                                {i, i + n + 1, i + 1, i + 1, i + n + 1, i + n + 2});
        }
    Scene s = sceneOf(grid);
    buildMeshLods(s);
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_FALSE(p.lods.empty());
    for (const PrimitiveLod& lod : p.lods) {
        EXPECT_LT(lod.error, 1e-5f);
        std::vector<bool> used(p.vertices.size(), false);
        for (uint32_t i : lod.indices) used[i] = true;
        for (size_t i = 0; i < p.vertices.size(); ++i) {
            const glm::vec3 q = p.vertices[i].position;
            const bool border = q.x == 0.0f || q.x == 1.0f || q.z == 0.0f || q.z == 1.0f;
            if (border) {
                EXPECT_TRUE(used[i]) << "border vertex " << i << " dropped";
            }
        }
    }
    // A box: 12 triangles, no levels.
    Scene box = sceneOf(makeBox(glm::vec3(1.0f), 0));
    EXPECT_EQ(buildMeshLods(box).primitives, 0u);
    EXPECT_TRUE(box.meshes[0].primitives[0].lods.empty());
}
