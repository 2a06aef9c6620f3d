// The `scene` pass kind's points and lines (lines = true, LinesScenePass): the scene's glTF
// POINTS, LINES, LINE_LOOP and LINE_STRIP primitives (GpuScene::lineDraws), unlit as glTF viewers
// draw them — the material's base colour shown as glTF's emissive is, plus its emission
// (shaders/passes/lines.frag) — one pixel wide, over the HDR the pass loads, tested against the
// opaque surfaces' depth and not writing it. One pipeline per topology, blending and shader
// variant (the base colour and emissive textures, the alpha mask).
#include <array>
#include <map>
#include <string>
#include <tuple>

#include <glm/glm.hpp>

#include "scene_pass_detail.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

namespace {

// The scene's vertices as lines.vert reads them: position, the two uv sets and COLOR_0.
const VkPipelineVertexInputStateCreateInfo& lineVertexInput() {
    static const std::array<VkVertexInputAttributeDescription, 4> attrs = {
        sceneVertexAttributes()[0], sceneVertexAttributes()[3], sceneVertexAttributes()[4],
        sceneVertexAttributes()[5]};
    static const VkPipelineVertexInputStateCreateInfo vi{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        nullptr,
        0,
        1,
        &sceneVertexBinding(),
        static_cast<uint32_t>(attrs.size()),
        attrs.data()};
    return vi;
}

}  // namespace

Result<void> LinesScenePass::prepareDraws(PassSetup& setup) {
    if (auto r = findOverlayAttachments(setup, "lines"); !r) return r;
    const GpuScene& scene = *sceneOf(setup);
    // Blended last, so what they blend over is drawn; then points after lines, then the variant.
    std::map<std::tuple<bool, bool, uint32_t>, std::vector<size_t>> groups;
    for (size_t d = 0; d < scene.lineDraws().size(); ++d) {
        const LineDrawItem& item = scene.lineDraws()[d];
        const Material& m = scene.scene().materials[item.material];
        // Only the textures lines.frag samples tell variants apart.
        const uint32_t key = variantKey(m) & (1u | 16u | kAlphaMaskVariant);
        groups[{m.alphaMode == AlphaMode::Blend, item.points, key}].push_back(d);
    }
    // No points or lines: one pipeline still, so a broken shader or binding fails at load.
    if (groups.empty()) groups[{false, false, 1u | 16u}];
    const VkFormat color =
        toVkFormat(setup.resources.find(m_colors.front().resource)->plan->format);
    for (auto& [key, draws] : groups) {
        const auto [blended, points, textures] = key;
        Group g;
        ShaderRequest vert, frag;
        vert.path = "passes/lines.vert";
        frag.path = "passes/lines.frag";
        frag.defines = {{"RG_TEXTURES", std::to_string(textures & kTextureBits)},
                        {"RG_ALPHA_MASK", (textures & kAlphaMaskVariant) ? "1" : "0"},
                        {"RG_BASE_COLOR_EC", std::to_string(kGltfEmissiveEc)}};
        g.program = std::make_unique<ShaderProgram>();
        if (auto r = g.program->build(setup, {vert, frag}, {{1u, scene.materialSetLayout()}}); !r)
            return r;
        GraphicsPipelineDesc d;
        d.program = g.program.get();
        d.colorFormats = {color};
        // Over the lit HDR: blended materials src·α + dst·(1 − α), the others written; the HDR's
        // alpha kept.
        VkPipelineColorBlendAttachmentState b =
            blendState(blended ? "alpha" : "", /*alphaKeepsDestination=*/true);
        b.colorWriteMask = 0xfu;
        d.blends = {b};
        d.depthFormat = toVkFormat(m_depthFormat);
        if (formatInfo(m_depthFormat).stencil) d.stencilFormat = toVkFormat(m_depthFormat);
        d.vertexInput = &lineVertexInput();
        d.topology = points ? VK_PRIMITIVE_TOPOLOGY_POINT_LIST : VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        d.cullMode = VK_CULL_MODE_NONE;
        // Against the opaque surfaces' depth, not written; a line along a surface's edge stays.
        d.depthStencil.depthTestEnable = VK_TRUE;
        d.depthStencil.depthWriteEnable = VK_FALSE;
        d.depthStencil.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
        auto pipeline = createGraphicsPipeline(setup.gpu, d);
        if (!pipeline) return std::unexpected(pipeline.error());
        g.pipeline = std::move(*pipeline);
        g.draws = std::move(draws);
        m_groups.push_back(std::move(g));
    }
    return {};
}

void LinesScenePass::recordDraws(RecordContext& rc) {
    if (sceneOf(rc)->lineDraws().empty()) return;
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = rc.resources.find(m_depth->resource)->image->attachmentView();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
    beginCamera(rc, depth);
    const GpuScene& scene = *sceneOf(rc);
    for (const Group& g : m_groups) {
        vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g.pipeline.get());
        g.program->bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
        uint32_t boundMaterial = UINT32_MAX;
        for (size_t d : g.draws) {
            const LineDrawItem& item = scene.lineDraws()[d];
            if (item.material != boundMaterial) {
                scene.bindMaterial(rc.cmd, g.program->layout(), item.material);
                boundMaterial = item.material;
            }
            vkCmdPushConstants(rc.cmd, g.program->layout(),
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof item.world, &item.world);
            vkCmdDrawIndexed(rc.cmd, item.indexCount, 1, item.firstIndex, item.vertexOffset, 0);
        }
    }
    vkCmdEndRendering(rc.cmd);
}

}  // namespace rg::passes
