// The `scene` pass kind's shadow maps (shadow = true, ShadowScenePass): depth only, every layer of
// the depth target from its view, drawn directly or through a culling pass's indirect commands.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "graphics_pipeline.h"
#include "passes.h"
#include "scene_pass_detail.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

namespace {

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

// shadow = true: depth only, from the light's view, into each layer of the depth target in turn
// (shadows/shadow.vert takes the matrix of the layer its push constant names from a buffer the
// pass reads); every opaque draw, both faces, with the rasteriser's depth bias. (One multiview
// pass for all layers was tried first: llvmpipe then misplaces triangles clipped at the map's
// edges in layer 0.)
Result<void> ShadowScenePass::prepareDraws(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    for (const Access& a : desc.accesses) {
        if (a.usage == Usage::ColorAttachment)
            return fail(ErrorCode::InvalidInput, passPrefix(desc) +
                                                     "a shadow 'scene' pass writes depth only; '" +
                                                     a.resource + "' is a colour target");
        if (a.usage == Usage::DepthStencilAttachment) m_depth = a;
    }
    if (!m_depth)
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "a shadow 'scene' pass writes a depth texture (d32f, one layer per view)");
    m_layers = sizeFromDepth(setup).layers;
    const Value& bias = desc.params["depth_bias"];
    if (!bias.isNil() && !(bias.isList() && bias.asList().size() == 2))
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) + "params.depth_bias: expected { constant, slope }");
    const std::string views =
        desc.params["views"].isString() ? desc.params["views"].asString() : "shader";
    if (views != "shader" && views != "lights")
        return fail(ErrorCode::InvalidInput, passPrefix(desc) + "params.views: unknown '" + views +
                                                 "', expected one of: 'shader', 'lights'");
    m_lightViews = views == "lights";
    // view = { first, count }: layer l of the target is view first + l of count (the matrix the
    // push constant names, the indirect buffer's slots): one cascade per pass, each into a map
    // of its own that the graph can alias with the next cascade's (scripts/shadows.lua).
    m_firstView = 0;
    m_viewCount = m_layers;
    if (const Value& view = desc.params["view"]; !view.isNil()) {
        if (!view.isList() || view.asList().size() != 2 || !view.asList()[0].isNumber() ||
            !view.asList()[1].isNumber())
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + "params.view: expected { first, count }");
        const double first = view.asList()[0].asNumber(0), count = view.asList()[1].asNumber(0);
        if (first < 0 || count < 1 || first != std::floor(first) || count != std::floor(count) ||
            first + m_layers > count)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + "params.view: { " + numberText(first) + ", " +
                            numberText(count) + " } does not hold the target's " +
                            std::to_string(m_layers) + " layer(s) from view 'first' on");
        if (m_lightViews)
            return fail(
                ErrorCode::InvalidInput,
                passPrefix(desc) +
                    "params.view: views = 'lights' places its own views; give one or the other");
        m_firstView = static_cast<uint32_t>(first);
        m_viewCount = static_cast<uint32_t>(count);
    }
    // cull: which winding, as the views' matrices land faces in the map, single-sided
    // materials' faces are not drawn with (double-sided ones always draw both).
    const std::string cull =
        desc.params["cull"].isString() ? desc.params["cull"].asString() : "none";
    if (cull != "none" && cull != "clockwise" && cull != "counter_clockwise")
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) + "params.cull: unknown '" + cull +
                        "', expected one of: 'none', 'clockwise', 'counter_clockwise'");
    // With the front face counter-clockwise: FRONT culls counter-clockwise faces, BACK clockwise ones.
    m_shadowCull = cull == "none"                ? VK_CULL_MODE_NONE
                   : cull == "counter_clockwise" ? VK_CULL_MODE_FRONT_BIT
                                                 : VK_CULL_MODE_BACK_BIT;
    // indirect = "buffer": a culling pass wrote an indirect command per view, caster batch and
    // level of detail (shaders/shadows/cascade_cull.comp), drawing the instances it lists (the
    // vertex shader built with RG_SHADOW_INSTANCES); a buffer without room for the scene's
    // batches (none) draws every caster directly.
    // A buffer the graph does not have (one that exists only for some scenes or parameters,
    // only_when, left with the pass's indirect reads): every caster drawn directly. A name the
    // pass does not read while it reads another indirect buffer is a mistake.
    m_indirect.clear();
    const bool readsIndirect =
        std::any_of(desc.accesses.begin(), desc.accesses.end(),
                    [](const Access& a) { return a.usage == Usage::IndirectRead; });
    if (desc.params["indirect"].isString() &&
        (setup.resources.find(desc.params["indirect"].asString()) || readsIndirect)) {
        m_indirect = desc.params["indirect"].asString();
        const bool read =
            std::any_of(desc.accesses.begin(), desc.accesses.end(), [&](const Access& a) {
                return a.resource == m_indirect && a.usage == Usage::IndirectRead;
            });
        if (!read)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + "params.indirect: '" + m_indirect +
                            "' must be among the pass's reads as an indirect buffer ({ \"" +
                            m_indirect + "\", as = \"indirect\" })");
    }
    Group g;
    g.info.name = "shadow";
    ShaderRequest vert;
    vert.path = desc.params["shader"].isString() ? desc.params["shader"].asString()
                : m_lightViews                   ? "shadows/local_shadow.vert"
                                                 : "shadows/shadow.vert";
    if (!m_indirect.empty()) vert.defines.emplace_back("RG_SHADOW_INSTANCES", "1");
    g.program = std::make_unique<ShaderProgram>();
    if (auto r = g.program->build(setup, {vert}); !r) return r;
    GraphicsPipelineDesc d;
    d.program = g.program.get();
    d.depthFormat = toVkFormat(m_depthFormat);
    // Positions only (the shader reads nothing else), from the same interleaved vertices.
    static const VkVertexInputBindingDescription binding{0, sizeof(Vertex),
                                                         VK_VERTEX_INPUT_RATE_VERTEX};
    static const VkVertexInputAttributeDescription position{
        0, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, position))};
    static const VkPipelineVertexInputStateCreateInfo positions{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        nullptr,
        0,
        1,
        &binding,
        1,
        &position};
    d.vertexInput = &positions;
    // params.cull, set per draw (double-sided materials draw both sides).
    d.cullMode = VK_CULL_MODE_NONE;
    d.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    d.dynamicStates = {VK_DYNAMIC_STATE_CULL_MODE};
    d.depthStencil.depthTestEnable = VK_TRUE;
    d.depthStencil.depthWriteEnable = VK_TRUE;
    d.depthStencil.depthCompareOp = VK_COMPARE_OP_LESS;
    if (bias.isList()) {
        d.depthBiasConstant = static_cast<float>(bias.asList()[0].asNumber(0));
        d.depthBiasSlope = static_cast<float>(bias.asList()[1].asNumber(0));
    }
    auto pipeline = createGraphicsPipeline(setup.gpu, d);
    if (!pipeline) return std::unexpected(pipeline.error());
    g.pipeline = std::move(*pipeline);
    for (size_t d = 0; d < sceneOf(setup)->draws().size(); ++d)
        if (sceneOf(setup)->draws()[d].castsShadows) g.draws.push_back(d);
    m_groups.push_back(std::move(g));
    return {};
}

void ShadowScenePass::recordDraws(RecordContext& rc) {
    const PhysicalResource* d = rc.resources.find(m_depth->resource);
    Group& g = m_groups.front();
    // views = "lights": the scene's shadow views this frame (GpuScene::updateFrame), each with
    // the casters its frustum meets; layers past them are neither cleared nor drawn (no
    // light reads them).
    const uint32_t layers =
        m_lightViews ? std::min(m_layers, sceneOf(rc)->shadowViewCount()) : m_layers;
    const PhysicalResource* indirect = m_indirect.empty() ? nullptr : rc.resources.find(m_indirect);
    const auto& batches = sceneOf(rc)->shadowBatches();
    // Commands per view: 4 levels per batch (cascade_cull.comp), when the buffer has room for them.
    const VkDeviceSize perView = 4 * batches.size();
    const bool batched =
        indirect && !batches.empty() &&
        indirect->plan->bufferSize >= m_viewCount * perView * kIndirectCommandBytes &&
        sceneOf(rc)->drawsGpuLists();
    // shadow.vert's push constants: a draw's world (all zero: a batch's instances) and the view.
    auto push = [&](const glm::mat4& world, uint32_t view) {
        const struct {
            glm::mat4 world;
            glm::vec4 view;
        } constants{world, glm::vec4(static_cast<float>(view))};
        vkCmdPushConstants(rc.cmd, g.program->layout(), VK_SHADER_STAGE_VERTEX_BIT, 0,
                           sizeof constants, &constants);
    };
    for (uint32_t layer = 0; layer < layers; ++layer) {
        const uint32_t view = m_firstView + layer;
        beginLayer(rc, VK_NULL_HANDLE, d->image->layerView(layer), VK_ATTACHMENT_STORE_OP_STORE);
        vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g.pipeline.get());
        g.program->bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
        if (batched) {
            // Per batch and level the instances the culling pass listed (instanceCount 0: none).
            push(glm::mat4(0.0f), view);
            for (size_t b = 0; b < batches.size(); ++b) {
                vkCmdSetCullMode(rc.cmd, batches[b].doubleSided ? VkCullModeFlags(VK_CULL_MODE_NONE)
                                                                : m_shadowCull);
                const uint32_t levels = sceneOf(rc)->draws()[batches[b].draws.front()].lodCount;
                for (uint32_t l = 0; l < std::min(levels, 4u); ++l)
                    vkCmdDrawIndexedIndirect(rc.cmd, indirect->buffer->buffer(),
                                             (view * perView + 4 * b + l) * kIndirectCommandBytes,
                                             1, kIndirectCommandBytes);
            }
            vkCmdEndRendering(rc.cmd);
            continue;
        }
        for (size_t i : m_lightViews ? sceneOf(rc)->shadowViewDraws(layer) : g.draws) {
            const DrawItem& item = sceneOf(rc)->draws()[i];
            vkCmdSetCullMode(rc.cmd, sceneOf(rc)->scene().materials[item.material].doubleSided
                                         ? VkCullModeFlags(VK_CULL_MODE_NONE)
                                         : m_shadowCull);
            push(item.world, view);
            // The camera's level of detail: a caster finer than its receiver (the G-buffer's
            // surface) would stand in front of it by up to the coarser one's error.
            const DrawLod& lod = sceneOf(rc)->viewLod(i);
            vkCmdDrawIndexed(rc.cmd, lod.indexCount, 1, lod.firstIndex, item.vertexOffset, 0);
        }
        vkCmdEndRendering(rc.cmd);
    }
}

}  // namespace rg::passes
