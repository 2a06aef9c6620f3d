// glTF animations (glTF 2.0 §3.11) onto moving scene nodes (graph/scene/gltf_load_animation.cpp):
// LINEAR, STEP and CUBICSPLINE keyframes of translation, rotation and scale, a parent's animation
// moving its children, looping, the animation chosen by name, a one-key pose that stands still,
// and broken samplers and channels refused naming the animation, the channel and the key. No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "scene_test_util.h"

namespace {
using namespace rg::test;

// A quad under a parent node: the parent slides along x (LINEAR, 0 → 2 m over 1 s, then back to
// 0 at 2 s), the child (the quad, 1 m above it) turns about y (STEP: 0° until 1 s, then 90°)
// and grows (CUBICSPLINE, scale 1 → 3 over 2 s, the first key's out-tangent 1/s, the second's
// in-tangent −2/s: unequal, so a swap or a tangent not scaled by the 2 s span shows).
GltfBuilder animatedQuad() {
    GltfBuilder g;
    addQuad(g, true);
    const int child = g.node({{"name", "quad"}, {"mesh", 0}, {"translation", {0, 1, 0}}});
    const int parent = g.node({{"name", "cart"}, {"children", {child}}});
    g.scene({parent});
    const int t3 = g.floats({0, 1, 2}, "SCALAR"), t2 = g.floats({0, 1}, "SCALAR"),
              tc = g.floats({0, 2}, "SCALAR");
    const int slide = g.floats({0, 0, 0, 2, 0, 0, 0, 0, 0}, "VEC3");
    const float h = std::sqrt(0.5f);
    const int turn = g.floats({0, 0, 0, 1, 0, h, 0, h}, "VEC4");
    // CUBICSPLINE: per key in-tangent, value, out-tangent.
    const int grow = g.floats({0, 0, 0, 1, 1, 1, 1, 1, 1, -2, -2, -2, 3, 3, 3, 0, 0, 0}, "VEC3");
    g.j["animations"] = json::array(
        {{{"name", "drive"},
          {"samplers",
           {{{"input", t3}, {"output", slide}},
            {{"input", t2}, {"output", turn}, {"interpolation", "STEP"}},
            {{"input", tc}, {"output", grow}, {"interpolation", "CUBICSPLINE"}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", parent}, {"path", "translation"}}}},
            {{"sampler", 1}, {"target", {{"node", child}, {"path", "rotation"}}}},
            {{"sampler", 2}, {"target", {{"node", child}, {"path", "scale"}}}}}}},
         {{"name", "idle"},
          {"samplers", {{{"input", t2}, {"output", turn}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", child}, {"path", "rotation"}}}}}}}});
    return g;
}

TEST(GltfAnimation, KeyframesMoveTheNodesAndTheirChildren) {
    const std::string dir = tmpDir("animation");
    const std::string file = animatedQuad().writeGltf(dir, "cart");
    auto scene = rg::loadGltf(file);
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 1u);
    const rg::Node& quad = scene->nodes[0];
    EXPECT_TRUE(quad.dynamic);
    ASSERT_TRUE(quad.animation);
    EXPECT_FLOAT_EQ(quad.animation->duration, 2.0f);
    // The first frame: the parent at x 0, the child 1 m up, unturned, at scale 1.
    expectNear(origin(quad.world), {0, 1, 0}, 1e-6f, "t = 0");
    // LINEAR translation of the parent carries the child: 1 m at 0.5 s, 2 m at 1 s, 1 m at 1.5 s.
    expectNear(origin(quad.at(0.5)), {1, 1, 0}, 1e-5f, "t = 0.5");
    expectNear(origin(quad.at(1.5)), {1, 1, 0}, 1e-5f, "t = 1.5");
    // STEP rotation: none before 1 s, 90° about y from 1 s (+x turns to −z).
    expectNear(glm::normalize(glm::vec3(quad.at(0.99)[0])), {1, 0, 0}, 1e-5f, "step: before");
    expectNear(glm::normalize(glm::vec3(quad.at(1.0)[0])), {0, 0, -1}, 1e-5f, "step: at the key");
    // CUBICSPLINE scale: §3.11's Hermite basis at u = t / 2 over the 2 s span, v0 = 1, b0 = 1,
    // v1 = 3, a1 = −2: 1.78125 at 0.5 s, 2.75 at 1 s.
    auto cubic = [](float t) {
        const float u = t / 2.0f, u2 = u * u, u3 = u2 * u;
        return (2 * u3 - 3 * u2 + 1) * 1.0f + (u3 - 2 * u2 + u) * 2.0f * 1.0f +
               (-2 * u3 + 3 * u2) * 3.0f + (u3 - u2) * 2.0f * -2.0f;
    };
    EXPECT_FLOAT_EQ(cubic(0.5f), 1.78125f);
    EXPECT_NEAR(glm::length(glm::vec3(quad.at(0.5)[1])), cubic(0.5f), 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(quad.at(1.0)[1])), 2.75f, 1e-5f);
    // It loops over its duration.
    expectNear(origin(quad.at(2.5)), origin(quad.at(0.5)), 1e-5f, "looped");
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("the file has 2 animations; the first plays"),
              std::string::npos)
        << scene->warnings[0];
    // Another by name; "none" stands still at the rest transforms.
    rg::GltfOptions o;
    o.animation = "idle";
    auto idle = rg::loadGltf(file, o);
    ASSERT_TRUE(idle) << errorOf(idle);
    expectNear(origin(idle->nodes[0].at(0.5)), {0, 1, 0}, 1e-6f, "idle: the cart stands");
    expectNear(glm::normalize(glm::vec3(idle->nodes[0].at(0.5)[0])),
               {std::cos(glm::radians(45.0f)), 0, -std::sin(glm::radians(45.0f))}, 1e-5f,
               "idle: slerped half way to 90°");
    o.animation = "none";
    auto still = rg::loadGltf(file, o);
    ASSERT_TRUE(still) << errorOf(still);
    EXPECT_FALSE(still->nodes[0].dynamic);
    o.animation = "dance";
    auto missing = rg::loadGltf(file, o);
    ASSERT_FALSE(missing);
    EXPECT_NE(
        missing.error().message.find("no animation 'dance' (the file has 2: 'drive', 'idle')"),
        std::string::npos)
        << missing.error().message;
}

TEST(GltfAnimation, ABrokenSamplerIsRefusedNamingItsKey) {
    const std::string dir = tmpDir("animation_bad");
    GltfBuilder g = animatedQuad();
    g.j["animations"][0]["samplers"][0]["input"] = g.floats({0, 2, 1}, "SCALAR");
    auto scene = rg::loadGltf(g.writeGltf(dir, "bad"));
    ASSERT_FALSE(scene);
    EXPECT_NE(scene.error().message.find("animation 0 'drive': sampler 0: input key 2 is 1, not "
                                         "after the key before (2)"),
              std::string::npos)
        << scene.error().message;
    GltfBuilder twice = animatedQuad();
    twice.j["animations"][0]["channels"].push_back(twice.j["animations"][0]["channels"][0]);
    auto repeated = rg::loadGltf(twice.writeGltf(dir, "twice"));
    ASSERT_FALSE(repeated);
    EXPECT_NE(repeated.error().message.find("channel 3: node 1 'cart''s translation is targeted by "
                                            "an earlier channel too"),
              std::string::npos)
        << repeated.error().message;
    GltfBuilder h = animatedQuad();
    h.j["animations"][0]["channels"][0]["target"]["path"] = "colour";
    auto path = rg::loadGltf(h.writeGltf(dir, "path"));
    ASSERT_FALSE(path);
    EXPECT_NE(path.error().message.find("channel 0: target path 'colour'"), std::string::npos)
        << path.error().message;
    // A name given for a file without animations is an error too.
    GltfBuilder plain;
    addQuad(plain, true);
    plain.scene({plain.node({{"mesh", 0}})});
    rg::GltfOptions o;
    o.animation = "walk";
    auto none = rg::loadGltf(plain.writeGltf(dir, "plain"), o);
    ASSERT_FALSE(none);
    EXPECT_NE(none.error().message.find("no animation 'walk' (the file has 0)"), std::string::npos)
        << none.error().message;
}

// An animation of one key per sampler (an exporter's pose) places the nodes and moves nothing:
// they stay static (a lightmap, probe captures and ray casts keep them).
TEST(GltfAnimation, AOneKeyPoseStandsStill) {
    const std::string dir = tmpDir("animation_pose");
    GltfBuilder g;
    addQuad(g, true);
    const int q = g.node({{"name", "q"}, {"mesh", 0}});
    g.scene({q});
    g.j["animations"] = json::array(
        {{{"samplers",
           {{{"input", g.floats({0}, "SCALAR")}, {"output", g.floats({0, 2, 0}, "VEC3")}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", q}, {"path", "translation"}}}}}}}});
    auto scene = rg::loadGltf(g.writeGltf(dir, "pose"));
    ASSERT_TRUE(scene) << errorOf(scene);
    EXPECT_FALSE(scene->nodes[0].dynamic);
    expectNear(origin(scene->nodes[0].world), {0, 2, 0}, 1e-6f, "posed");
}

}  // namespace
