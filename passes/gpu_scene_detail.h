// Helpers the gpu_scene*.cpp files share (internal to passes/): frustum tests and the size of
// the ShadowViews block.
#pragma once

#include <algorithm>
#include <array>

#include <glm/glm.hpp>

#include "gpu_scene.h"

namespace rg::passes::detail {

// The six planes (a, b, c, d: inside where a x + b y + c z + d >= 0) of a clip-space frustum
// with depth 0..1 (Gribb & Hartmann), normalised.
inline std::array<glm::vec4, 6> frustumPlanes(const glm::mat4& m) {
    const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]), r1(m[0][1], m[1][1], m[2][1], m[3][1]),
        r2(m[0][2], m[1][2], m[2][2], m[3][2]), r3(m[0][3], m[1][3], m[2][3], m[3][3]);
    std::array<glm::vec4, 6> p = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
    for (auto& q : p) q /= std::max(glm::length(glm::vec3(q)), 1e-20f);
    return p;
}

// False when the box lies wholly outside one of the planes (its corner furthest along the
// plane's normal is behind it); conservative near the frustum's edges.
inline bool boxMeetsFrustum(const std::array<glm::vec4, 6>& planes, glm::vec3 lo, glm::vec3 hi) {
    for (const auto& q : planes) {
        const glm::vec3 corner(q.x >= 0 ? hi.x : lo.x, q.y >= 0 ? hi.y : lo.y,
                               q.z >= 0 ? hi.z : lo.z);
        if (glm::dot(glm::vec3(q), corner) + q.w < 0.0f) return false;
    }
    return true;
}

// Where the ShadowViews block's per-light table starts: after a uvec4 header and the views.
inline constexpr size_t kShadowLightViewsOffset =
    16 + size_t(kMaxShadowViews) * sizeof(GpuShadowView);

}  // namespace rg::passes::detail
