// The CPU scene's generated data: mip chains (box filter, sRGB filtered as linear light) and the
// generated sphere, plane and box, with the sphere's levels of detail. No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "scene_test_util.h"

namespace {

using namespace rg::test;

// ---------------------------------------------------------------------------------------------
// Mips

TEST(Mips, ChainSizesDownToOneByOne) {
    rg::SceneImage img;
    img.pixels = rg::Image(5, 3, 4);
    rg::generateMips(img);
    ASSERT_EQ(img.mipLevels, 3u);
    ASSERT_EQ(img.mips.size(), 2u);
    EXPECT_EQ(img.level(1).width, 2u);
    EXPECT_EQ(img.level(1).height, 1u);
    EXPECT_EQ(img.level(2).width, 1u);
    EXPECT_EQ(img.level(2).height, 1u);
    rg::SceneImage tall;
    tall.pixels = rg::Image(1, 16, 1);
    rg::generateMips(tall);
    EXPECT_EQ(tall.mipLevels, 5u);
    EXPECT_EQ(tall.level(4).height, 1u);
}

TEST(Mips, BoxFilterAveragesAreaWeighted) {
    // 4x4 ramp: level 1 texels are 2x2 means, level 2 the mean of all.
    rg::SceneImage img;
    img.pixels = rg::Image(4, 4, 1);
    for (uint32_t i = 0; i < 16; ++i) img.pixels.pixels[i] = float(i);
    rg::generateMips(img);
    EXPECT_FLOAT_EQ(img.level(1).at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(img.level(1).at(1, 1, 0), (10 + 11 + 14 + 15) / 4.0f);
    EXPECT_FLOAT_EQ(img.level(2).at(0, 0, 0), 7.5f);
    // Odd width: 3 -> 1 covers all three texels equally (no texel dropped).
    rg::SceneImage odd;
    odd.pixels = rg::Image(3, 1, 1);
    odd.pixels.pixels = {0, 3, 9};
    rg::generateMips(odd);
    EXPECT_FLOAT_EQ(odd.level(1).at(0, 0, 0), 4.0f);
}

TEST(Mips, SrgbImagesAreFilteredAsLinearLightAlphaStaysLinear) {
    rg::SceneImage img;
    img.srgb = true;
    img.pixels = rg::Image(2, 2, 4);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x) {
            const float v = (x + y) % 2 ? 1.0f : 0.0f;  // checkerboard black / white
            for (uint32_t c = 0; c < 3; ++c) img.pixels.at(x, y, c) = v;
            img.pixels.at(x, y, 3) = v;
        }
    rg::generateMips(img);
    // Half the light: srgbEncode(0.5) = 0.735, not the code-value mean 0.5.
    EXPECT_NEAR(img.level(1).at(0, 0, 0), 0.7353569f, 1e-5f);
    EXPECT_FLOAT_EQ(img.level(1).at(0, 0, 3), 0.5f);
}

// ---------------------------------------------------------------------------------------------
// Generated meshes

void checkMesh(const rg::Primitive& p, const std::string& what) {
    ASSERT_FALSE(p.indices.empty()) << what;
    for (size_t t = 0; t < p.indices.size(); t += 3) {
        const rg::Vertex &a = p.vertices[p.indices[t]], &b = p.vertices[p.indices[t + 1]],
                         &c = p.vertices[p.indices[t + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::length(face), 0.0f) << what << " degenerate triangle " << t / 3;
        // Counter-clockwise seen from the side the normals point to.
        EXPECT_GT(glm::dot(face, a.normal + b.normal + c.normal), 0.0f)
            << what << " triangle " << t / 3;
    }
    // The analytic tangents agree with what generateTangents derives from the uvs.
    rg::Primitive derived = p;
    rg::generateTangents(derived);
    for (size_t i = 0; i < p.vertices.size(); ++i) {
        const rg::Vertex& v = p.vertices[i];
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f) << what;
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-5f) << what;
        EXPECT_EQ(v.tangent.w, derived.vertices[i].tangent.w) << what << " vertex " << i;
        // Pole vertices of a sphere have no uv gradient of their own: only compare away from them.
        if (std::fabs(v.normal.y) < 0.99f) {
            EXPECT_GT(glm::dot(glm::vec3(v.tangent), glm::vec3(derived.vertices[i].tangent)), 0.95f)
                << what << " vertex " << i;
        }
    }
}

TEST(Meshes, SpherePlaneAndBoxAreClosedCcwAndTheirTangentsMatchTheUvs) {
    auto sphere = rg::makeSphere(0.5f, 16, 0);
    EXPECT_EQ(sphere.vertices.size(), 17u * 9u);
    EXPECT_EQ(sphere.indices.size(), (16u * 8u * 2u - 2u * 16u) * 3u);
    for (const auto& v : sphere.vertices) EXPECT_NEAR(glm::length(v.position), 0.5f, 1e-6f);
    checkMesh(sphere, "sphere");
    checkMesh(rg::makePlane(2, 3, 0), "plane");
    checkMesh(rg::makeBox({1, 2, 3}, 0), "box");
    auto box = rg::makeBox({1, 2, 3}, 0);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const auto& v : box.vertices) lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
    expectNear(lo, {-0.5f, -1, -1.5f}, 0, "box min");
    expectNear(hi, {0.5f, 1, 1.5f}, 0, "box max");
}

}  // namespace

TEST(SceneGeometry, SphereLevelsOfDetailDropRowsAndStayWithinTheirError) {
    // A 96-segment sphere carries 48- and 24-segment levels over the same vertices (12 segments
    // would be under the floor of 24). Each level's triangles are the full grid's every 2nd / 4th
    // ring and segment, so every corner is a vertex of the sphere; the stated error bounds how far
    // the sphere bulges above any triangle (the plane's distance from the centre).
    const float radius = 0.45f;
    const rg::Primitive p = rg::makeSphere(radius, 96, 0);
    ASSERT_EQ(p.lods.size(), 2u);
    EXPECT_EQ(rg::makeSphere(radius, 48, 0).lods.size(), 1u);  // 24 segments only
    EXPECT_EQ(p.indices.size(),
              size_t(3 * (96 * 48 * 2 - 2 * 96)));  // the poles' rows have one triangle a quad
    const uint32_t row = 97;
    float previous = 0.0f;
    for (size_t l = 0; l < p.lods.size(); ++l) {
        const uint32_t stride = 2u << l, segments = 96 / stride, rings = 48 / stride;
        const rg::PrimitiveLod& lod = p.lods[l];
        EXPECT_EQ(lod.indices.size(), size_t(3 * (segments * rings * 2 - 2 * segments)))
            << "level " << l + 1;
        EXPECT_GT(lod.error, previous);
        previous = lod.error;
        float bulge = 0.0f;
        for (size_t t = 0; t + 2 < lod.indices.size(); t += 3) {
            glm::vec3 c[3];
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t v = lod.indices[t + k];
                ASSERT_EQ(v / row % stride, 0u) << "ring of vertex " << v;
                ASSERT_EQ(v % row % stride, 0u) << "segment of vertex " << v;
                c[k] = p.vertices[v].position;
            }
            const glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
            ASSERT_GT(glm::length(n), 0.0f) << "degenerate triangle at " << t;
            // Outward-facing (counter-clockwise seen from outside), as the full mesh's.
            EXPECT_GT(glm::dot(n, c[0] + c[1] + c[2]), 0.0f);
            bulge = std::max(bulge, radius - std::abs(glm::dot(glm::normalize(n), c[0])));
        }
        std::printf("level %zu: %u segments, %zu triangles, error %.2f mm, largest bulge %.2f mm\n",
                    l + 1, segments, lod.indices.size() / 3, lod.error * 1e3f, bulge * 1e3f);
        EXPECT_LE(bulge, lod.error);
        EXPECT_GT(bulge, 0.5f * lod.error);  // and the bound is not loose by more than 2x
    }
    // A sphere whose grid cannot drop every other ring has none (30 segments: 15 rings).
    EXPECT_TRUE(rg::makeSphere(1.0f, 30, 0).lods.empty());
}
