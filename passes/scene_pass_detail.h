// The `scene` pass kind's instance (scene_pass.cpp: the G-buffer and forward draws, pipelines and
// what every mode shares; scene_pass_capture.cpp: probe captures; scene_pass_shadow.cpp: shadow
// maps) and the draw selection its files share. Internal to passes/.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cadence.h"
#include "gpu_scene.h"
#include "scene_pass_glsl.h"
#include "shader_program.h"

namespace rg::passes::detail {

std::vector<MaterialInfo> materialsOf(const PassDesc& desc);

// A scene material's shader variant: the textures it has, as lib/material.glsl's RG_TEXTURES bits,
// and kAlphaMaskVariant when it is alpha-tested (RG_ALPHA_MASK). Only that variant may discard: a
// shader that can discard makes the rasteriser test and write depth after shading, so every
// fragment of an opaque draw would be shaded even where a nearer surface hides it (on lavapipe,
// 3× the G-buffer's cost in the default scene).
inline constexpr uint32_t kTextureBits = 31u, kAlphaMaskVariant = 32u;
inline uint32_t variantKey(const Material& m) {
    const TextureRef* refs[] = {&m.baseColorTex, &m.metallicRoughnessTex, &m.normalTex,
                                &m.occlusionTex, &m.emissiveTex};
    uint32_t key = 0;
    for (uint32_t t = 0; t < 5; ++t)
        if (refs[t]->valid()) key |= 1u << t;
    if (m.alphaMode == AlphaMode::Mask) key |= kAlphaMaskVariant;
    return key;
}

// The scene's draws whose materials `wanted` accepts, in the scene's order.
template <typename Wanted>
std::vector<size_t> drawsWhere(const GpuScene& scene, Wanted wanted) {
    std::vector<size_t> out;
    for (size_t d = 0; d < scene.draws().size(); ++d)
        if (wanted(scene.scene().materials[scene.draws()[d].material])) out.push_back(d);
    return out;
}

// The same, split by shader variant (variantKey: RG_TEXTURES, RG_ALPHA_MASK).
template <typename Wanted>
std::map<uint32_t, std::vector<size_t>> drawsByTextures(const GpuScene& scene, Wanted wanted) {
    std::map<uint32_t, std::vector<size_t>> out;
    for (size_t d : drawsWhere(scene, wanted))
        out[variantKey(scene.scene().materials[scene.draws()[d].material])].push_back(d);
    return out;
}

class ScenePass final : public gpu::PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override;
    void record(RecordContext& rc) override;
    std::vector<std::string> files() const override;

private:
    void bindViewAndGeometry(RecordContext& rc) const;
    void beginLayer(RecordContext& rc, VkImageView color, VkImageView depth,
                    VkAttachmentStoreOp depthStore) const;
    Result<void> addGroup(PassSetup& setup, const MaterialInfo& info, std::string fragment,
                          const std::string& name, uint32_t textures, std::vector<size_t> draws,
                          const std::vector<std::string>& attachments);
    Result<void> addGroup(PassSetup& setup, const MaterialInfo& info, const std::string& vertex,
                          ShaderRequest frag, uint32_t textures, std::vector<size_t> draws,
                          const std::vector<std::string>& attachments);

    struct Group {
        MaterialInfo info;
        std::unique_ptr<ShaderProgram> program;
        gpu::OwnedPipeline pipeline;
        std::vector<size_t> draws;
    };

    // capture = true (scene_pass_capture.cpp).
    Result<void> prepareCapture(PassSetup& setup, const std::vector<std::string>& attachments);
    void recordCapture(RecordContext& rc);
    // shadow = true (scene_pass_shadow.cpp).
    Result<void> prepareShadow(PassSetup& setup);
    void recordShadow(RecordContext& rc);

    static const VkPipelineVertexInputStateCreateInfo& vertexInput();
    Result<void> createPipeline(PassSetup& setup, Group& g,
                                const std::vector<std::string>& attachments);

    std::vector<Access> m_colors;
    std::optional<Access> m_depth;
    uint32_t m_width = 0, m_height = 0;
    Format m_depthFormat = Format::D32F;
    std::vector<Group> m_groups;
    bool m_forward = false;
    bool m_shadow = false;
    bool m_capture = false;  // the scene's light probes, once per build (cadence)
public:
    bool dueOnce(uint64_t epoch) const override { return m_cadence.dueOnce(epoch); }
    void restoredOnce(uint64_t epoch) override { m_cadence.restored(epoch); }

private:
    Cadence m_cadence;
    bool m_lightViews = false;  // shadow: the scene's local-light views rather than the shader's
    VkCullModeFlags m_shadowCull =
        VK_CULL_MODE_NONE;   // shadow: params.cull for single-sided materials
    std::string m_indirect;  // shadow: the buffer of indirect commands per layer and draw
    static constexpr VkDeviceSize kIndirectCommandBytes = sizeof(VkDrawIndexedIndirectCommand);
    uint32_t m_layers = 1;
    uint32_t m_firstView = 0;  // shadow: params.view, the view of the target's layer 0
    uint32_t m_viewCount = 1;  // shadow: the views the indirect buffer holds slots for
};

}  // namespace rg::passes::detail
