// A bounding volume hierarchy over world-space triangles, flattened for a shader (the reference
// mode's shadow rays, shaders/lib/bvh.glsl): median splits along the widest axis of the
// triangles' centroids, leaves of at most four triangles, nodes in depth-first order (a node's
// first child follows it). Layout, in vec4s (FlatBvh::data): per node two, (min.xyz, a) and
// (max.xyz, count) with a and count as uint bits — count > 0: a leaf of `count` triangles from
// triangle a; count = 0: the second child is node a — then three per triangle (its corners).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace rg {

struct FlatBvh {
    std::vector<glm::vec4> data;  // nodes, then triangles
    uint32_t nodeCount = 0, triangleCount = 0;
    uint32_t depth = 0;  // the deepest leaf (a shader's traversal stack must hold it)
};

// `corners`: three per triangle.
FlatBvh buildBvh(const std::vector<glm::vec3>& corners);

// The nearest hit along o + t d with 0 < t < tMax, or tMax when none (the shader's traversal on the
// CPU, for tests).
float traceBvh(const FlatBvh& bvh, glm::vec3 o, glm::vec3 d, float tMax);

}  // namespace rg
