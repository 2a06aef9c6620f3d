// The `scene` pass kind's instances and the draw selection their files share. Internal to passes/.
// ScenePass is the kind's instance: it picks the mode from the parameters and hands the pass to
// one of four mode classes over SceneDraws, what every mode draws with (scene_pass.cpp, with the
// G-buffer and forward modes; scene_pass_capture.cpp: probe captures; scene_pass_shadow.cpp:
// shadow maps).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cadence.h"
#include "gpu_scene.h"
#include "graphics_pipeline.h"
#include "scene_pass_glsl.h"
#include "shader_program.h"

namespace rg::passes::detail {

// A scene material's shader variant: the textures it has, as lib/material.glsl's RG_TEXTURES bits
// (1, 2, 4, 8, 16: the five standard maps; 64 << i: its model's own texture i, Material::textures
// in order), and kAlphaMaskVariant when it is alpha-tested (RG_ALPHA_MASK). Only that variant may
// discard: a shader that can discard makes the rasteriser test and write depth after shading, so
// every fragment of an opaque draw would be shaded even where a nearer surface hides it (on
// lavapipe, 3× the G-buffer's cost in the default scene).
inline constexpr uint32_t kTextureBits = 31u | 448u, kAlphaMaskVariant = 32u;
inline uint32_t variantKey(const Material& m) {
    const std::vector<const TextureRef*> refs = m.textureRefs();
    uint32_t key = 0;
    for (size_t t = 0; t < refs.size() && t < 5 + kMaterialTextureSlots; ++t)
        if (refs[t]->valid()) key |= t < 5 ? 1u << t : 64u << (t - 5);
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

// The scene's vertex buffer binding and its attributes (graph/scene's Vertex) by shader location:
// 0 position, 1 normal, 2 tangent, 3 uv0, 4 uv1, 5 COLOR_0 (scene_pass.cpp).
const VkVertexInputBindingDescription& sceneVertexBinding();
const std::array<VkVertexInputAttributeDescription, 6>& sceneVertexAttributes();

// What every mode of the `scene` pass draws with: its groups of draws (one pipeline each, per
// material and shader variant), the attachments it draws into and their size, and its cadence
// (params.cadence). A mode prepares its groups (prepareDraws) and records them (recordDraws) in
// the frames the cadence lets it.
class SceneDraws : public gpu::PassInstance {
public:
    Result<void> prepare(PassSetup& setup) final;
    void record(RecordContext& rc) final;
    std::vector<std::string> files() const final;
    bool dueOnce(uint64_t epoch) const final { return m_cadence.dueOnce(epoch); }
    void restoredOnce(uint64_t epoch) final { m_cadence.restored(epoch); }

protected:
    struct Group {
        PassMaterial info;
        std::unique_ptr<ShaderProgram> program;
        gpu::OwnedPipeline pipeline;
        std::vector<size_t> draws;
    };

    virtual Result<void> prepareDraws(PassSetup& setup) = 0;
    virtual void recordDraws(RecordContext& rc) = 0;

    // The error of a pass without the depth buffer it writes (the G-buffer pass, a capture).
    static constexpr const char* kWritesDepth =
        "a 'scene' pass writes a depth buffer (a d32f or d32f_s8 resource)";
    // The colour targets the pass writes (m_colors) and its depth buffer (m_depth: the last one it
    // writes, or with `depthRead` also one it reads); `missing` is the error without one.
    Result<void> findAttachments(const PassDesc& desc, bool depthRead, const char* missing);
    // The colour targets' names, as addGroup takes them.
    std::vector<std::string> colorNames() const;
    // The size and format of what the pass draws, from its depth buffer; returns that buffer's
    // plan.
    const PlanResource& sizeFromDepth(const PassSetup& setup);

    void bindViewAndGeometry(RecordContext& rc) const;
    void beginLayer(RecordContext& rc, VkImageView color, VkImageView depth,
                    VkAttachmentStoreOp depthStore) const;
    Result<void> addGroup(PassSetup& setup, const PassMaterial& info, std::string fragment,
                          const std::string& name, uint32_t textures, std::vector<size_t> draws,
                          const std::vector<std::string>& attachments);
    Result<void> addGroup(PassSetup& setup, const PassMaterial& info, const std::string& vertex,
                          ShaderRequest frag, uint32_t textures, std::vector<size_t> draws,
                          const std::vector<std::string>& attachments);

    // What differs between the modes' pipelines (createPipeline): how a group's pipeline blends
    // into and writes the colour target `target` (default: as is, every channel), and its depth
    // and stencil state (default: depth tested and written, the material's stencil class
    // written where the depth format has a stencil).
    virtual VkPipelineColorBlendAttachmentState colorBlend(const Group& g,
                                                           const std::string& target) const;
    virtual void depthStencil(GraphicsPipelineDesc& d, const Group& g) const;

    static constexpr VkDeviceSize kIndirectCommandBytes = sizeof(VkDrawIndexedIndirectCommand);
    std::vector<Group> m_groups;
    std::vector<Access> m_colors;
    // params.motion (the G-buffer and forward modes): the screen motion's attachment, or "";
    // while the pass writes it, scene.vert gets RG_MOTION.
    std::string m_motionTarget;
    // The G-buffer's draws culled on the GPU: scene.vert reads the instance lists the culling
    // pass wrote (RG_CAMERA_INSTANCES).
    bool m_cameraInstances = false;
    std::optional<Access> m_depth;
    uint32_t m_width = 0, m_height = 0;
    Format m_depthFormat = Format::D32F;

private:
    static const VkPipelineVertexInputStateCreateInfo& vertexInput();
    Result<void> createPipeline(PassSetup& setup, Group& g,
                                const std::vector<std::string>& attachments);

    Cadence m_cadence;
};

// The modes that draw from the camera into the pass's colour targets and depth buffer, one
// rendering over all their groups (scene_pass.cpp).
class CameraScenePass : public SceneDraws {
protected:
    using DrawOrder = std::vector<std::pair<size_t, size_t>>;  // (group, draw)

    // Begins rendering into the colour targets (cleared unless loaded) and `depth`; then the
    // viewport and the scene's geometry.
    void beginCamera(RecordContext& rc, const VkRenderingAttachmentInfo& depth) const;
    // The groups' draws inside the camera's frustum, and in `distance` (by draw) each one's
    // distanceOf(item).
    template <typename DistanceOf>
    DrawOrder inView(RecordContext& rc, std::vector<float>& distance, DistanceOf distanceOf) const;
    // The attachments of a mode that draws over the one colour target it loads, tested against
    // the depth buffer it reads (forward, lines: `mode` names it in errors), and their size.
    Result<void> findOverlayAttachments(const PassSetup& setup, const std::string& mode);
    // Draws `order`, binding a group's pipeline where it changes, and ends the rendering.
    void drawGroups(RecordContext& rc, const DrawOrder& order);
};

// The default mode: the opaque and alpha-tested draws of each material into its G-buffer layout's
// targets, with its stencil class (scene_pass.cpp).
class GBufferScenePass final : public CameraScenePass {
    Result<void> prepareDraws(PassSetup& setup) override;
    void recordDraws(RecordContext& rc) override;
    VkPipelineColorBlendAttachmentState colorBlend(const Group& g,
                                                   const std::string& target) const override;

    std::string m_specularTarget;  // params.lightmap_specular: the lightmap's specular, or ""
    // params.indirect and params.indirect_count while the pass reads them (a culling pass wrote
    // them: shaders/passes/camera_cull.comp), else "": the draws are culled and batched on the
    // CPU. Per group, the camera runs its draws are in (one indirect-count draw each).
    std::string m_indirect, m_indirectCount;
    std::vector<std::vector<uint32_t>> m_groupRuns;
    // A command without instances and a count of 2^32 − 1 (recordIndirect's last count draw).
    gpu::Buffer m_countReset;
    // Draws every group's runs from the culling pass's commands.
    void recordIndirect(RecordContext& rc);
};

// forward = true: the blended draws, lit directly, over the colour target it loads, tested against
// the depth buffer it reads (scene_pass.cpp).
class ForwardScenePass final : public CameraScenePass {
    Result<void> prepareDraws(PassSetup& setup) override;
    void recordDraws(RecordContext& rc) override;
    VkPipelineColorBlendAttachmentState colorBlend(const Group& g,
                                                   const std::string& target) const override;
    void depthStencil(GraphicsPipelineDesc& d, const Group& g) const override;
};

// lines = true: the scene's points and lines (GpuScene::lineDraws), unlit, one pixel wide, over
// the colour target it loads, tested against the depth buffer it reads (scene_pass_lines.cpp).
class LinesScenePass final : public CameraScenePass {
    Result<void> prepareDraws(PassSetup& setup) override;
    void recordDraws(RecordContext& rc) override;
};

// shadow = true: depth only, each layer of the depth target from its view
// (scene_pass_shadow.cpp).
class ShadowScenePass final : public SceneDraws {
    Result<void> prepareDraws(PassSetup& setup) override;
    void recordDraws(RecordContext& rc) override;

    bool m_lightViews = false;  // the scene's local-light views rather than the shader's
    VkCullModeFlags m_shadowCull = VK_CULL_MODE_NONE;  // params.cull for single-sided materials
    std::string m_indirect;    // the buffer of indirect commands per layer and draw
    uint32_t m_layers = 1;     // the depth target's layers
    uint32_t m_firstView = 0;  // params.view, the view of the target's layer 0
    uint32_t m_viewCount = 1;  // the views the indirect buffer holds slots for
};

// capture = true: the scene's local light probes, each into six layers of the cube texture it
// writes (scene_pass_capture.cpp).
class CaptureScenePass final : public SceneDraws {
    Result<void> prepareDraws(PassSetup& setup) override;
    void recordDraws(RecordContext& rc) override;

    uint32_t m_layers = 1;  // the cube texture's layers, six per probe
};

// The `scene` kind's instance: checks that the pass has a scene and one mode, then prepares and
// records it as that mode's instance.
class ScenePass final : public gpu::PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override;
    void record(RecordContext& rc) override {
        if (m_mode) m_mode->record(rc);
    }
    std::vector<std::string> files() const override {
        return m_mode ? m_mode->files() : std::vector<std::string>{};
    }
    bool dueOnce(uint64_t epoch) const override { return m_mode && m_mode->dueOnce(epoch); }
    void restoredOnce(uint64_t epoch) override {
        if (m_mode) m_mode->restoredOnce(epoch);
    }

private:
    std::unique_ptr<SceneDraws> m_mode;
};

}  // namespace rg::passes::detail
