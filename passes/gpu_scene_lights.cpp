// The scene's lights as the shaders take them (convertLights: units, cones, IES profiles) and
// the local lights' shadow views each frame (ShadowViews).
#include "gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "core/light_units.h"
#include "gpu_scene_detail.h"
#include "lighting/area_lights.h"
#include "lighting/punctual.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

namespace {

bool sphereMeetsFrustum(const std::array<glm::vec4, 6>& planes, glm::vec3 centre, float radius) {
    for (const auto& q : planes)
        if (glm::dot(glm::vec3(q), centre) + q.w < -radius) return false;
    return true;
}

}  // namespace

uint32_t shadowViewsNeeded(const Light& l) {
    if (!l.castShadows || l.type == LightType::Directional) return 0;
    return l.type == LightType::Spot && l.outerAngle <= glm::radians(60.0f) ? 1 : 6;
}

uint32_t shadowViewCapacity(const Scene& scene) {
    uint32_t views = 0;
    for (size_t i = 0; i < scene.lights.size() && i < kMaxLights; ++i) {
        const uint32_t count = shadowViewsNeeded(scene.lights[i]);
        if (views + count <= kMaxShadowViews) views += count;
    }
    return views;
}

VkDeviceSize GpuScene::shadowViewBytes() const {
    return detail::kShadowLightViewsOffset +
           std::max<size_t>(m_scene.lights.size(), 1) * sizeof(glm::ivec4);
}

std::pair<uint32_t, uint32_t> GpuScene::shadowViewsOf(size_t light) const {
    if (light >= m_lightViews.size() || m_lightViews[light].y == 0) return {0, 0};
    return {static_cast<uint32_t>(m_lightViews[light].x),
            static_cast<uint32_t>(m_lightViews[light].y)};
}

const std::vector<size_t>& GpuScene::shadowViewDraws(uint32_t v) const {
    // The casters each view sees: the boxes that meet its frustum.
    if (m_shadowViewDraws.size() != m_shadowViewPlanes.size()) {
        m_shadowViewDraws.assign(m_shadowViewPlanes.size(), {});
        ++m_shadowViewWalks;
        for (size_t view = 0; view < m_shadowViewPlanes.size(); ++view)
            for (size_t d = 0; d < m_draws.size(); ++d)
                if (m_draws[d].castsShadows &&
                    boxMeetsFrustum(m_shadowViewPlanes[view], m_draws[d].boundsMin,
                                    m_draws[d].boundsMax))
                    m_shadowViewDraws[view].push_back(d);
    }
    return m_shadowViewDraws[v];
}

void GpuScene::updateShadowViews(uint32_t slot, const glm::mat4& cameraViewProj) {
    m_shadowViewDraws.clear();
    m_shadowViewPlanes.clear();
    m_lightViews.assign(std::max<size_t>(m_scene.lights.size(), 1), glm::ivec4(-1, 0, 0, 0));
    std::vector<GpuShadowView> views;
    const auto camera = frustumPlanes(cameraViewProj);
    // A light without a range reaches as far as the scene goes.
    const float sceneSize = glm::length(m_scene.boundsMax - m_scene.boundsMin);
    const float nearPlane = 0.05f;
    for (size_t i = 0; i < m_scene.lights.size() && i < kMaxLights; ++i) {
        const Light& l = m_scene.lights[i];
        const uint32_t count = shadowViewsNeeded(l);
        if (count == 0) continue;
        const float far = l.range > 0.0f ? l.range : std::max(sceneSize, 1.0f) * 2.0f;
        if (!sphereMeetsFrustum(camera, l.position, far))
            continue;  // its light does not reach the view
        const bool single = count == 1;
        if (views.size() + count > kMaxShadowViews) continue;
        // A cube's faces see a little past 90° so that filter taps near a face's edge stay on
        // its map (16 texels of a 1024 map); a spot's view covers its outer cone.
        const float tanHalf =
            single ? std::tan(std::min(l.outerAngle + glm::radians(2.0f), glm::radians(75.0f)))
                   : 1.0f / (1.0f - 32.0f / 1024.0f);
        const glm::mat4 proj =
            glm::perspectiveRH_ZO(2.0f * std::atan(tanHalf), 1.0f, nearPlane, far);
        static const glm::vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                          {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
        static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                         {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        m_lightViews[i] = glm::ivec4(static_cast<int>(views.size()), static_cast<int>(count), 0, 0);
        const float radius =
            std::max({l.radius, 0.5f * std::max(l.width, l.height), 0.5f * l.length});
        for (uint32_t f = 0; f < count; ++f) {
            const glm::vec3 axis = single ? l.direction : axes[f];
            const glm::vec3 up =
                single ? (std::abs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0))
                       : ups[f];
            GpuShadowView v;
            v.viewProj = proj * glm::lookAt(l.position, l.position + axis, up);
            v.position = glm::vec4(l.position, nearPlane);
            v.params = glm::vec4(far, tanHalf, radius, static_cast<float>(i));
            views.push_back(v);
            m_shadowViewPlanes.push_back(frustumPlanes(v.viewProj));
        }
    }
    auto* p = static_cast<uint8_t*>(m_shadowViewBuffers[slot].mapped());
    const glm::uvec4 header(static_cast<uint32_t>(views.size()), 0, 0, 0);
    std::memcpy(p, &header, sizeof header);
    if (!views.empty()) std::memcpy(p + 16, views.data(), views.size() * sizeof(GpuShadowView));
    std::memcpy(p + detail::kShadowLightViewsOffset, m_lightViews.data(),
                m_lightViews.size() * sizeof(glm::ivec4));
}

}  // namespace rg::passes
