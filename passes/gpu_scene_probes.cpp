// The scene's decals and local light probes as the shaders read them (lib/scene.glsl's Decals,
// lib/probes.glsl's Probes), and the environment's importance-sampling distribution
// (SceneEnvironmentCdf).
#include "gpu_scene.h"

#include <algorithm>
#include <cstring>

namespace rg::passes {

using namespace rg::gpu;

// std430 RgDecal (shaders/lib/scene.glsl).
struct GpuDecal {
    glm::mat4 worldToBox;
    glm::vec4 baseColorOpacity;  // rgb, opacity
    glm::vec4 params;            // smoothness, metalMask, reflectance, 0
    glm::vec4 flags;             // has base colour, smoothness, metal mask, reflectance (0/1)
    glm::vec4 axis;  // xyz: the box's +Y axis in world space (normal target); w: blend normal
};

Result<void> GpuScene::createDecals(Context& ctx) {
    std::vector<GpuDecal> decals;
    for (const Decal& d : m_scene.decals) {
        GpuDecal g{};
        g.worldToBox = glm::inverse(d.world);
        g.baseColorOpacity = glm::vec4(d.baseColor, d.opacity);
        g.params = glm::vec4(d.smoothness, d.metalMask, d.reflectance, 0.0f);
        g.flags = glm::vec4(d.hasBaseColor, d.hasSmoothness, d.hasMetalMask, d.hasReflectance);
        g.axis = glm::vec4(glm::normalize(glm::vec3(d.world[1])), d.normal ? 1.0f : 0.0f);
        decals.push_back(g);
    }
    auto buf = Buffer::create(ctx, "scene.decals",
                              16 + std::max<size_t>(1, decals.size()) * sizeof(GpuDecal),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    m_decals = std::move(*buf);
    auto* p = static_cast<uint8_t*>(m_decals.mapped());
    uint32_t header[4] = {static_cast<uint32_t>(decals.size()), 0, 0, 0};
    std::memcpy(p, header, 16);
    if (!decals.empty()) std::memcpy(p + 16, decals.data(), decals.size() * sizeof(GpuDecal));
    return {};
}

// std430 RgProbe (shaders/lib/probes.glsl).
struct GpuProbe {
    glm::vec4 positionShape;  // xyz: capture point and proxy centre; w: 0 sphere, 1 box
    glm::vec4 extentFade;     // xyz: box half extents (a sphere: its radius in x); w: fade (m)
    glm::vec4 axes[3];        // box: its local axes in world space (rows of world → local)
    glm::vec4 influence;      // xyz: the influence box's half extents (a sphere: its radius in x)
};

Result<void> GpuScene::createProbes(Context& ctx) {
    // §4.9.5: the composition takes local probes "from small to large" until the reflection is
    // complete; a scene's priority goes before size.
    const auto& probes = m_scene.probes;
    // Size: the volume it reflects in (its influence).
    auto volume = [](const Probe& p) {
        const glm::vec3 h = p.influenceHalfExtents();
        return p.box ? 8.0f * h.x * h.y * h.z : 4.18879f * h.x * h.x * h.x;
    };
    m_probeOrder.resize(probes.size());
    for (size_t i = 0; i < probes.size(); ++i) m_probeOrder[i] = i;
    std::stable_sort(m_probeOrder.begin(), m_probeOrder.end(), [&](size_t a, size_t b) {
        if (probes[a].priority != probes[b].priority)
            return probes[a].priority > probes[b].priority;
        return volume(probes[a]) < volume(probes[b]);
    });
    std::vector<GpuProbe> out;
    for (size_t i : m_probeOrder) {
        const Probe& p = probes[i];
        GpuProbe g{};
        g.positionShape = glm::vec4(p.position, p.box ? 1.0f : 0.0f);
        g.extentFade = glm::vec4(p.box ? 0.5f * p.size : glm::vec3(p.radius), p.fade);
        for (int a = 0; a < 3; ++a) g.axes[a] = glm::vec4(glm::normalize(p.rotation[a]), 0.0f);
        g.influence = glm::vec4(p.influenceHalfExtents(), 0.0f);
        out.push_back(g);
    }
    auto buf = Buffer::create(ctx, "scene.probes", 16 + kMaxProbes * sizeof(GpuProbe),
                              VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    m_probes = std::move(*buf);
    auto* bytes = static_cast<uint8_t*>(m_probes.mapped());
    std::memset(bytes, 0, 16 + kMaxProbes * sizeof(GpuProbe));
    const uint32_t header[4] = {static_cast<uint32_t>(out.size()), 0, 0, 0};
    std::memcpy(bytes, header, 16);
    if (!out.empty()) std::memcpy(bytes + 16, out.data(), out.size() * sizeof(GpuProbe));
    return {};
}

VkBuffer GpuScene::environmentCdfBuffer() const {
    auto buffer = makeEnvironmentCdfBuffer();
    return buffer ? *buffer : VK_NULL_HANDLE;  // ShaderProgram reports it (makeBindingBuffer)
}

Result<VkBuffer> GpuScene::makeEnvironmentCdfBuffer() const {
    if (m_environmentCdfBuffer.buffer() != VK_NULL_HANDLE) return m_environmentCdfBuffer.buffer();
    const glm::uvec4 header(m_environmentCdf.width, m_environmentCdf.height, 0u, 0u);
    const size_t bytes = sizeof header + m_environmentCdf.data.size() * sizeof(float);
    auto buf = Buffer::create(*m_ctx, "scene.environment_cdf", bytes,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    auto* p = static_cast<uint8_t*>(buf->mapped());
    std::memcpy(p, &header, sizeof header);
    std::memcpy(p + sizeof header, m_environmentCdf.data.data(),
                m_environmentCdf.data.size() * sizeof(float));
    m_environmentCdfBuffer = std::move(*buf);
    return m_environmentCdfBuffer.buffer();
}

}  // namespace rg::passes
