// The scene on the GPU: one vertex and one index buffer for every primitive, the images with
// their mip chains, a descriptor set per material (set 1 of scene draws, see
// shaders/lib/material.glsl), and per frame slot the camera uniforms and the light list
// (shaders/lib/scene.glsl), lights converted to cd / lux once here (seed 000 tbl:9, eq:17).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/context.h"
#include "gpu/resources.h"
#include "scene/scene.h"

namespace rg::passes {

struct DrawItem {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t material = 0;  // index into Scene::materials
    glm::mat4 world{1.0f};
    glm::mat4 normalMatrix{1.0f};
};

// Binding slots of the scene's camera and lights in set 0 (shaders/lib/scene.glsl).
inline constexpr uint32_t kCameraBinding = 15;
inline constexpr uint32_t kLightsBinding = 14;
inline constexpr uint32_t kMaxLights = 256;

class GpuScene {
public:
    static Result<std::unique_ptr<GpuScene>> create(gpu::Context& ctx, Scene scene);
    ~GpuScene();

    const Scene& scene() const { return m_scene; }
    const std::vector<DrawItem>& draws() const { return m_draws; }
    VkBuffer vertexBuffer() const { return m_vertices.buffer(); }
    VkBuffer indexBuffer() const { return m_indices.buffer(); }
    VkDescriptorSetLayout materialSetLayout() const { return m_materialLayout.get(); }
    VkDescriptorSet materialSet(uint32_t material) const { return m_materialSets[material]; }

    // The camera the frame renders with (the scene's first, or `name`).
    const Camera& camera() const { return m_scene.cameras.at(m_camera); }
    Result<void> selectCamera(const std::string& name);
    // Writes frame slot `slot`'s camera for an output of width x height.
    void updateFrame(uint32_t slot, uint32_t width, uint32_t height);
    VkBuffer cameraBuffer(uint32_t slot) const { return m_cameraBuffers[slot].buffer(); }
    VkBuffer lightBuffer(uint32_t slot) const { return m_lightBuffers[slot].buffer(); }
    uint32_t lightCount() const { return m_lightCount; }

private:
    GpuScene() = default;
    Result<void> uploadGeometry(gpu::Context& ctx);
    Result<void> uploadImages(gpu::Context& ctx);
    Result<void> createMaterials(gpu::Context& ctx);
    Result<void> createFrameData(gpu::Context& ctx);

    Scene m_scene;
    gpu::Context* m_ctx = nullptr;
    std::vector<DrawItem> m_draws;
    gpu::Buffer m_vertices, m_indices;
    std::vector<gpu::Image> m_images;
    gpu::Image m_white, m_flatNormal;  // defaults for missing textures
    std::vector<gpu::OwnedSampler> m_samplers;
    gpu::OwnedSampler m_defaultSampler;
    gpu::OwnedDescriptorSetLayout m_materialLayout;
    gpu::OwnedDescriptorPool m_pool;
    std::vector<gpu::Buffer> m_materialBuffers;
    std::vector<VkDescriptorSet> m_materialSets;
    std::vector<gpu::Buffer> m_cameraBuffers, m_lightBuffers;
    uint32_t m_lightCount = 0;
    size_t m_camera = 0;
};

}  // namespace rg::passes
