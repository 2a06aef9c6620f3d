#include "scene/bvh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

namespace rg {

namespace {

struct Builder {
    const std::vector<glm::vec3>& corners;
    std::vector<uint32_t> order;  // triangle indices, permuted into leaf order
    std::vector<glm::vec4> nodes;
    uint32_t depth = 0;

    glm::vec3 centroid(uint32_t t) const {
        return (corners[3 * t] + corners[3 * t + 1] + corners[3 * t + 2]) / 3.0f;
    }

    void build(uint32_t first, uint32_t count, uint32_t level) {
        depth = std::max(depth, level);
        glm::vec3 lo(INFINITY), hi(-INFINITY), clo(INFINITY), chi(-INFINITY);
        for (uint32_t i = first; i < first + count; ++i) {
            const uint32_t t = order[i];
            for (int k = 0; k < 3; ++k) {
                lo = glm::min(lo, corners[3 * t + k]);
                hi = glm::max(hi, corners[3 * t + k]);
            }
            clo = glm::min(clo, centroid(t));
            chi = glm::max(chi, centroid(t));
        }
        const size_t self = nodes.size();
        nodes.push_back(glm::vec4(lo, 0.0f));
        nodes.push_back(glm::vec4(hi, 0.0f));
        const glm::vec3 extent = chi - clo;
        // A leaf: few triangles, or centroids that cannot be told apart, or deep enough.
        if (count <= 4 || std::max({extent.x, extent.y, extent.z}) <= 0.0f || level >= 40) {
            nodes[self].w = std::bit_cast<float>(first);
            nodes[self + 1].w = std::bit_cast<float>(count);
            return;
        }
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const uint32_t half = count / 2;
        std::nth_element(
            order.begin() + first, order.begin() + first + half, order.begin() + first + count,
            [&](uint32_t a, uint32_t b) { return centroid(a)[axis] < centroid(b)[axis]; });
        build(first, half, level + 1);
        nodes[self].w =
            std::bit_cast<float>(static_cast<uint32_t>(nodes.size() / 2));  // the second child
        nodes[self + 1].w = std::bit_cast<float>(0u);
        build(first + half, count - half, level + 1);
    }
};

// Möller–Trumbore: t of the hit, or −1.
float rayTriangle(glm::vec3 o, glm::vec3 d, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) return -1.0f;
    const float inv = 1.0f / det;
    const glm::vec3 s = o - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return glm::dot(e2, q) * inv;
}

}  // namespace

FlatBvh buildBvh(const std::vector<glm::vec3>& corners) {
    FlatBvh out;
    out.triangleCount = static_cast<uint32_t>(corners.size() / 3);
    if (out.triangleCount == 0) return out;
    Builder b{corners, {}, {}, 0};
    b.order.resize(out.triangleCount);
    std::iota(b.order.begin(), b.order.end(), 0u);
    b.build(0, out.triangleCount, 0);
    out.nodeCount = static_cast<uint32_t>(b.nodes.size() / 2);
    out.depth = b.depth;
    out.data = std::move(b.nodes);
    for (uint32_t t : b.order)
        for (int k = 0; k < 3; ++k) out.data.push_back(glm::vec4(corners[3 * t + k], 1.0f));
    return out;
}

float traceBvh(const FlatBvh& bvh, glm::vec3 o, glm::vec3 d, float tMax) {
    if (bvh.nodeCount == 0) return tMax;
    const glm::vec3 inv = 1.0f / d;
    std::vector<uint32_t> stack;
    uint32_t node = 0;
    float best = tMax;
    while (true) {
        const glm::vec4 a = bvh.data[2 * node], b = bvh.data[2 * node + 1];
        const glm::vec3 t0 = (glm::vec3(a) - o) * inv, t1 = (glm::vec3(b) - o) * inv;
        const glm::vec3 tn = glm::min(t0, t1), tf = glm::max(t0, t1);
        const float enter = std::max({tn.x, tn.y, tn.z, 0.0f}),
                    exit = std::min({tf.x, tf.y, tf.z, best});
        if (enter <= exit) {
            const uint32_t count = std::bit_cast<uint32_t>(b.w),
                           first = std::bit_cast<uint32_t>(a.w);
            if (count == 0) {
                stack.push_back(first);
                node = node + 1;
                continue;
            }
            for (uint32_t t = first; t < first + count; ++t) {
                const size_t base = 2 * size_t(bvh.nodeCount) + 3 * size_t(t);
                const float h =
                    rayTriangle(o, d, glm::vec3(bvh.data[base]), glm::vec3(bvh.data[base + 1]),
                                glm::vec3(bvh.data[base + 2]));
                if (h > 0.0f && h < best) best = h;
            }
        }
        if (stack.empty()) return best;
        node = stack.back();
        stack.pop_back();
    }
}

}  // namespace rg
