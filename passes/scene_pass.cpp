// The `scene` pass kind: draws the scene's primitives into the pass's attachments, one pipeline
// per pipeline material (Lua rg.material) whose fragment shader rgraph generates from the
// material's G-buffer layout and its GLSL surface function; set 1 per texture set that materials
// share (arrays of the scene's images by shape: lavapipe has no descriptor indexing), a
// material's parameters at a dynamic offset or, drawn from the GPU's lists, a window of
// materials' read by index; the stencil buffer gets each material's stencil class.
// This file holds the kind (its schema and ScenePass, which picks the mode), what every mode draws
// with (SceneDraws), and the modes that draw from the camera: the G-buffer and forward passes.
#include <algorithm>
#include <cstring>
#include <iterator>
#include <limits>
#include <tuple>
#include <glm/glm.hpp>

#include "core/check.h"
#include "graphics_pipeline.h"
#include "passes.h"
#include "scene_pass.h"
#include "scene_pass_detail.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

Result<void> ScenePass::prepare(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    if (!setup.scene)
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) + "a 'scene' pass needs a scene (give --scene FILE)");
    const bool forward = desc.params["forward"].asBool();
    const bool shadow = desc.params["shadow"].asBool();
    const bool capture = desc.params["capture"].asBool();
    if (shadow && capture)
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "params.capture: a pass is a shadow pass or a probe capture, not both");
    if (forward && capture)
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "params.capture: a pass is a forward pass or a probe capture, not both");
    const bool lines = desc.params["lines"].asBool();
    if (lines && (shadow || capture || forward))
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "params.lines: a pass that draws the points and lines is "
                        "not also a " +
                        (shadow    ? "shadow pass"
                         : capture ? "probe capture"
                                   : "forward pass"));
    // A shadow pass ignores params.forward.
    if (lines)
        m_mode = std::make_unique<LinesScenePass>();
    else if (shadow)
        m_mode = std::make_unique<ShadowScenePass>();
    else if (capture)
        m_mode = std::make_unique<CaptureScenePass>();
    else if (forward)
        m_mode = std::make_unique<ForwardScenePass>();
    else
        m_mode = std::make_unique<GBufferScenePass>();
    return m_mode->prepare(setup);
}

Result<void> SceneDraws::prepare(PassSetup& setup) {
    if (auto r = m_cadence.parse(setup); !r) return r;
    return prepareDraws(setup);
}

void SceneDraws::record(RecordContext& rc) {
    if (!m_cadence.due(rc)) return;
    recordDraws(rc);
}

std::vector<std::string> SceneDraws::files() const {
    std::vector<std::string> out;
    for (const Group& g : m_groups)
        for (const auto& f : g.program->files()) out.push_back(f);
    return out;
}

Result<void> SceneDraws::findAttachments(const PassDesc& desc, bool depthRead,
                                         const char* missing) {
    for (const Access& a : desc.accesses) {
        if (a.usage == Usage::ColorAttachment) m_colors.push_back(a);
        if (a.usage == Usage::DepthStencilAttachment ||
            (depthRead && a.usage == Usage::DepthStencilRead))
            m_depth = a;
    }
    if (!m_depth) return fail(ErrorCode::InvalidInput, passPrefix(desc) + missing);
    return {};
}

std::vector<std::string> SceneDraws::colorNames() const {
    std::vector<std::string> out;
    for (const Access& a : m_colors) out.push_back(a.resource);
    return out;
}

const PlanResource& SceneDraws::sizeFromDepth(const PassSetup& setup) {
    const PhysicalResource* depth = setup.resources.find(m_depth->resource);
    m_width = depth->plan->width;
    m_height = depth->plan->height;
    m_depthFormat = depth->plan->format;
    return *depth->plan;
}

// Inside a render pass: the viewport and scissor over the target, the scene's vertices and indices.
void SceneDraws::bindViewAndGeometry(RecordContext& rc) const {
    VkViewport vp{0, 0, static_cast<float>(m_width), static_cast<float>(m_height), 0, 1};
    VkRect2D sc{{0, 0}, {m_width, m_height}};
    vkCmdSetViewport(rc.cmd, 0, 1, &vp);
    vkCmdSetScissor(rc.cmd, 0, 1, &sc);
    VkDeviceSize offset = 0;
    VkBuffer vb = sceneOf(rc)->vertexBuffer();
    vkCmdBindVertexBuffers(rc.cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(rc.cmd, sceneOf(rc)->indexBuffer(), 0, VK_INDEX_TYPE_UINT32);
}

// Begins rendering into one layer: `color` (if any) and `depth` cleared (colour to 0, depth to
// 1), the depth stored with `depthStore`; then the viewport and the scene's geometry.
void SceneDraws::beginLayer(RecordContext& rc, VkImageView color, VkImageView depth,
                            VkAttachmentStoreOp depthStore) const {
    VkRenderingAttachmentInfo c{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    c.imageView = color;
    c.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    c.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    c.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    d.imageView = depth;
    d.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    d.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    d.storeOp = depthStore;
    d.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {m_width, m_height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = color != VK_NULL_HANDLE ? 1u : 0u;
    ri.pColorAttachments = &c;
    ri.pDepthAttachment = &d;
    if (formatInfo(m_depthFormat).stencil) ri.pStencilAttachment = &d;
    vkCmdBeginRendering(rc.cmd, &ri);
    bindViewAndGeometry(rc);
}

// One pipeline: the scene vertex shader and `fragment` with RG_TEXTURES = `textures`.
Result<void> SceneDraws::addGroup(PassSetup& setup, const PassMaterial& info, std::string fragment,
                                  const std::string& name, uint32_t textures,
                                  std::vector<size_t> draws,
                                  const std::vector<std::string>& attachments) {
    ShaderRequest frag;
    frag.source = std::move(fragment);
    frag.virtualName = name;
    frag.stage = ShaderStage::Fragment;
    return addGroup(setup, info, "passes/scene.vert", std::move(frag), textures, std::move(draws),
                    attachments);
}

Result<void> SceneDraws::addGroup(PassSetup& setup, const PassMaterial& info,
                                  const std::string& vertex, ShaderRequest frag, uint32_t textures,
                                  std::vector<size_t> draws,
                                  const std::vector<std::string>& attachments) {
    Group g;
    g.info = info;
    ShaderRequest vert;
    vert.path = vertex;
    if (!m_motionTarget.empty() &&
        std::find(attachments.begin(), attachments.end(), m_motionTarget) != attachments.end())
        vert.defines.emplace_back("RG_MOTION", "1");
    if (m_cameraInstances) {
        vert.defines.emplace_back("RG_CAMERA_INSTANCES", "1");
        frag.defines.emplace_back("RG_CAMERA_INSTANCES", "1");  // the material per instance
        frag.defines.emplace_back("RG_MATERIAL_WINDOW",
                                  std::to_string(sceneOf(setup)->materialWindow()));
    }
    frag.defines.emplace_back("RG_TEXTURES", std::to_string(textures & kTextureBits));
    frag.defines.emplace_back("RG_ALPHA_MASK", (textures & kAlphaMaskVariant) ? "1" : "0");
    g.program = std::make_unique<ShaderProgram>();
    if (auto r = g.program->build(setup, {vert, frag}, {{1u, sceneOf(setup)->materialSetLayout()}});
        !r)
        return r;
    if (auto r = createPipeline(setup, g, attachments); !r) return r;
    g.draws = std::move(draws);
    m_groups.push_back(std::move(g));
    return {};
}

const VkVertexInputBindingDescription& detail::sceneVertexBinding() {
    static const VkVertexInputBindingDescription binding{0, sizeof(Vertex),
                                                         VK_VERTEX_INPUT_RATE_VERTEX};
    return binding;
}

const std::array<VkVertexInputAttributeDescription, 6>& detail::sceneVertexAttributes() {
    static const std::array<VkVertexInputAttributeDescription, 6> attrs = {
        {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, position))},
         {1, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, normal))},
         {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, tangent))},
         {3, 0, VK_FORMAT_R32G32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, uv0))},
         {4, 0, VK_FORMAT_R32G32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, uv1))},
         {5, 0, VK_FORMAT_R16G16B16A16_UNORM, static_cast<uint32_t>(offsetof(Vertex, color))}}};
    return attrs;
}

// The scene's vertex layout (graph/scene's Vertex), every attribute.
const VkPipelineVertexInputStateCreateInfo& SceneDraws::vertexInput() {
    static const VkPipelineVertexInputStateCreateInfo vi{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        nullptr,
        0,
        1,
        &sceneVertexBinding(),
        static_cast<uint32_t>(sceneVertexAttributes().size()),
        sceneVertexAttributes().data()};
    return vi;
}

Result<void> SceneDraws::createPipeline(PassSetup& setup, Group& g,
                                        const std::vector<std::string>& attachments) {
    GraphicsPipelineDesc d;
    d.program = g.program.get();
    for (const auto& name : attachments) {
        d.colorFormats.push_back(toVkFormat(setup.resources.find(name)->plan->format));
        d.blends.push_back(colorBlend(g, name));
    }
    d.depthFormat = toVkFormat(m_depthFormat);
    if (formatInfo(m_depthFormat).stencil) d.stencilFormat = toVkFormat(m_depthFormat);

    d.vertexInput = &vertexInput();
    // glTF front faces are counter-clockwise; the projection's y flip (Vulkan's y points
    // down) keeps them counter-clockwise as seen on screen, which is what Vulkan tests.
    // Culling is set per draw (double-sided materials).
    d.cullMode = VK_CULL_MODE_BACK_BIT;
    d.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    depthStencil(d, g);
    d.dynamicStates = {VK_DYNAMIC_STATE_STENCIL_REFERENCE, VK_DYNAMIC_STATE_CULL_MODE};
    auto pipeline = createGraphicsPipeline(setup.gpu, d);
    if (!pipeline) return std::unexpected(pipeline.error());
    g.pipeline = std::move(*pipeline);
    return {};
}

VkPipelineColorBlendAttachmentState SceneDraws::colorBlend(const Group& /*g*/,
                                                           const std::string& /*target*/) const {
    VkPipelineColorBlendAttachmentState b = blendState("", /*alphaKeepsDestination=*/true);
    b.colorWriteMask = 0xfu;
    return b;
}

void SceneDraws::depthStencil(GraphicsPipelineDesc& d, const Group& g) const {
    d.depthStencil.depthTestEnable = VK_TRUE;
    d.depthStencil.depthWriteEnable = VK_TRUE;
    d.depthStencil.depthCompareOp = VK_COMPARE_OP_LESS;
    if (formatInfo(m_depthFormat).stencil && g.info.stencilMask) {
        d.depthStencil.stencilTestEnable = VK_TRUE;
        VkStencilOpState op{};
        op.failOp = op.depthFailOp = VK_STENCIL_OP_KEEP;
        op.passOp = VK_STENCIL_OP_REPLACE;
        op.compareOp = VK_COMPARE_OP_ALWAYS;
        op.writeMask = g.info.stencilMask;
        d.depthStencil.front = d.depthStencil.back = op;
    }
}

void CameraScenePass::beginCamera(RecordContext& rc, const VkRenderingAttachmentInfo& depth) const {
    std::vector<VkRenderingAttachmentInfo> colors;
    for (const Access& a : m_colors)
        colors.push_back(colorAttachment(rc, a, VK_ATTACHMENT_LOAD_OP_CLEAR));
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {m_width, m_height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    ri.pColorAttachments = colors.data();
    ri.pDepthAttachment = &depth;
    if (formatInfo(m_depthFormat).stencil) ri.pStencilAttachment = &depth;
    vkCmdBeginRendering(rc.cmd, &ri);
    bindViewAndGeometry(rc);
}

template <typename DistanceOf>
CameraScenePass::DrawOrder CameraScenePass::inView(RecordContext& rc, std::vector<float>& distance,
                                                   DistanceOf distanceOf) const {
    DrawOrder order;
    distance.assign(sceneOf(rc)->draws().size(), 0.0f);
    for (size_t gi = 0; gi < m_groups.size(); ++gi)
        for (size_t i : m_groups[gi].draws) {
            if (!sceneOf(rc)->drawInView(i)) continue;
            distance[i] = distanceOf(sceneOf(rc)->draws()[i]);
            order.emplace_back(gi, i);
        }
    return order;
}

void CameraScenePass::drawGroups(RecordContext& rc, const DrawOrder& order) {
    const GpuScene& scene = *sceneOf(rc);
    const auto& draws = scene.draws();
    // The same mesh range (at the level of detail the camera takes) and material — the same
    // camera batch key: what a run of consecutive draws in the order must share to be one
    // instanced draw.
    auto sameRun = [&](size_t a, size_t b) {
        return scene.cameraBatchKey(a) == scene.cameraBatchKey(b);
    };
    size_t bound = SIZE_MAX;
    uint32_t boundMaterial = UINT32_MAX;
    for (size_t a = 0; a < order.size();) {
        const auto [gi, first] = order[a];
        size_t end = a + 1;
        while (end < order.size() && order[end].first == gi && sameRun(first, order[end].second))
            ++end;
        Group& g = m_groups[gi];
        if (gi != bound) {
            vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g.pipeline.get());
            g.program->bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
            vkCmdSetStencilReference(rc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK,
                                     g.info.stencilValue);  // unused when forward
            bound = gi;
            boundMaterial = UINT32_MAX;
        }
        const DrawItem& item = draws[first];
        if (item.material != boundMaterial) {
            // The material's texture set, its parameters at their offset (lib/material.glsl).
            scene.bindMaterial(rc.cmd, g.program->layout(), item.material);
            const bool doubleSided = scene.scene().materials[item.material].doubleSided;
            vkCmdSetCullMode(rc.cmd, doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
            boundMaterial = item.material;
        }
        // The level of detail for the camera (GpuScene::viewLod: at most a pixel of error).
        const DrawLod& lod = scene.viewLod(first);
        const auto count = static_cast<uint32_t>(end - a);
        // A draw that moves goes through the list even alone: its last frame's transform is
        // there (scene.vert's motion).
        bool moves = false;
        for (size_t k = a; k < end && !moves; ++k) moves = scene.drawMoves(order[k].second);
        auto [base, list] = count > 1 || moves ? scene.reserveInstances(rc.frame.slot, count, moves)
                                               : std::pair<uint32_t, uint32_t*>{0, nullptr};
        if (list) {
            // One instanced draw: scene.vert reads each instance's transform (all-zero push
            // constants say so) through this frame's instance list.
            for (size_t k = a; k < end; ++k) *list++ = static_cast<uint32_t>(order[k].second);
            const glm::vec4 zeros[8] = {};
            vkCmdPushConstants(rc.cmd, g.program->layout(),
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof zeros, zeros);
            vkCmdDrawIndexed(rc.cmd, lod.indexCount, count, lod.firstIndex, item.vertexOffset,
                             base);
        } else {
            for (size_t k = a; k < end; ++k) {
                const DrawItem& d = draws[order[k].second];
                // scene.vert's Draw: world, the normal matrix's three columns, the lightmap rect.
                glm::vec4 push[8] = {d.world[0],        d.world[1],        d.world[2],
                                     d.world[3],        d.normalMatrix[0], d.normalMatrix[1],
                                     d.normalMatrix[2], d.lightmapRect};
                vkCmdPushConstants(rc.cmd, g.program->layout(),
                                   VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                   sizeof push, push);
                vkCmdDrawIndexed(rc.cmd, lod.indexCount, 1, lod.firstIndex, d.vertexOffset, 0);
            }
        }
        a = end;
    }
    vkCmdEndRendering(rc.cmd);
}

Result<void> GBufferScenePass::prepareDraws(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    m_specularTarget = desc.params["lightmap_specular"].asString();
    m_motionTarget = desc.params["motion"].asString();
    if (auto r = findAttachments(desc, /*depthRead=*/false, kWritesDepth); !r) return r;
    const std::vector<std::string> attachments = colorNames();
    sizeFromDepth(setup);
    // indirect = "commands", indirect_count = "counts": a culling pass chose the draws on the GPU
    // (scripts/culling.lua) — while the pass reads both as indirect buffers (a buffer that exists
    // only for some scenes leaves the pass's reads with it), the device can start an indirect
    // draw at an instance and instancing is on (not RG_INSTANCING=0); otherwise the CPU chooses
    // them (the culling pass's work is then unused).
    auto readsIndirect = [&](const std::string& name) {
        return !name.empty() &&
               std::any_of(desc.accesses.begin(), desc.accesses.end(), [&](const Access& a) {
                   return a.resource == name && a.usage == Usage::IndirectRead;
               });
    };
    const std::string indirect = desc.params["indirect"].asString();
    const std::string indirectCount = desc.params["indirect_count"].asString();
    if (indirect.empty() != indirectCount.empty())
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "params.indirect and params.indirect_count: give both (the commands "
                        "and the count of each camera run's) or neither");
    m_indirect.clear();
    m_indirectCount.clear();
    m_cameraInstances =
        readsIndirect(indirect) && readsIndirect(indirectCount) && sceneOf(setup)->drawsGpuLists();
    if (m_cameraInstances) {
        m_indirect = indirect;
        m_indirectCount = indirectCount;
        if (setup.gpu.drawIndirectCount() && !m_countReset.buffer()) {
            auto reset = gpu::Buffer::create(setup.gpu, desc.name + ".count_reset", 24,
                                             VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, true);
            if (!reset) return std::unexpected(reset.error());
            const uint32_t words[6] = {0, 0, 0, 0, 0, 0xffffffffu};
            std::memcpy(reset->mapped(), words, sizeof words);
            m_countReset = std::move(*reset);
        }
    }
    for (const PassMaterial& info : desc.materials) {
        for (const auto& t : info.targets)
            if (std::find(attachments.begin(), attachments.end(), t) == attachments.end())
                return fail(ErrorCode::InvalidInput, passPrefix(desc) + "material '" + info.name +
                                                         "' writes layout '" + info.layout +
                                                         "' target '" + t +
                                                         "', which the pass does not write");
        // The scene's draws of this material, one shader variant per set of textures.
        auto variants = drawsByTextures(*sceneOf(setup), [&](const Material& m) {
            return m.model == info.name && m.alphaMode != AlphaMode::Blend;
        });
        // A forward-only material's shading reads what lies behind the surface: only the forward
        // pass draws it (its surface function is still compiled here, below, so it fails at load).
        if (info.forward && !variants.empty()) {
            const GpuScene& scene = *sceneOf(setup);
            const Material& example =
                scene.scene().materials[scene.draws()[variants.begin()->second.front()].material];
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + "scene material '" + example.name +
                            "' is of material '" + info.name + "' (" + info.origin +
                            "), which only the forward pass draws (forward = true: its shading "
                            "reads the frame behind it); make it blended (alpha = \"blend\")");
        }
        if (variants.empty())
            variants
                [kTextureBits |
                 kAlphaMaskVariant];  // no draws: still compiled, so a broken material fails at load
        for (auto& [mask, draws] : variants)
            if (auto r = addGroup(
                    setup, info,
                    fragmentSource(info, attachments, m_specularTarget, m_motionTarget),
                    "material_" + info.name + ".frag", mask, std::move(draws), attachments);
                !r)
                return r;
    }
    // The GPU path's draws: per group, its camera runs (GpuScene::CameraRun: materials of one
    // pipeline, cull mode, texture set and window of parameters), one indirect count draw each.
    m_groupRuns.assign(m_cameraInstances ? m_groups.size() : 0, {});
    for (size_t gi = 0; gi < m_groupRuns.size(); ++gi) {
        for (size_t d : m_groups[gi].draws) m_groupRuns[gi].push_back(sceneOf(setup)->cameraRun(d));
        std::sort(m_groupRuns[gi].begin(), m_groupRuns[gi].end());
        m_groupRuns[gi].erase(std::unique(m_groupRuns[gi].begin(), m_groupRuns[gi].end()),
                              m_groupRuns[gi].end());
    }
    return {};
}

void GBufferScenePass::recordDraws(RecordContext& rc) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = rc.resources.find(m_depth->resource)->image->attachmentView();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.loadOp = m_depth->load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    beginCamera(rc, depth);
    if (m_cameraInstances) {
        recordIndirect(rc);
        return;
    }
    // Per group (one pipeline bind each), front to back within it by the distance from the eye
    // to the draws' boxes, so the depth test rejects hidden fragments before they are shaded.
    const glm::vec3 eye = sceneOf(rc)->frameCamera().position;
    std::vector<float> distance;
    DrawOrder order = inView(rc, distance, [&](const DrawItem& item) {
        return glm::distance(glm::clamp(eye, item.boundsMin, item.boundsMax), eye);
    });
    // Draws that share a mesh range and material go together, as one instanced draw
    // (drawGroups): batches by their nearest draw, each batch's draws by their own distance.
    const GpuScene& scene = *sceneOf(rc);
    std::vector<float> nearest(scene.cameraBatchKeys(), std::numeric_limits<float>::max());
    for (const auto& [gi, i] : order) {
        float& n = nearest[scene.cameraBatchKey(i)];
        n = std::min(n, distance[i]);
    }
    struct Key {
        size_t group;
        float batchDistance;
        uint32_t batch;
        float distance;
        size_t draw;
    };
    std::vector<Key> keys;
    keys.reserve(order.size());
    for (const auto& [gi, i] : order) {
        const uint32_t b = scene.cameraBatchKey(i);
        keys.push_back({gi, nearest[b], b, distance[i], i});
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        return std::tie(a.group, a.batchDistance, a.batch, a.distance, a.draw) <
               std::tie(b.group, b.batchDistance, b.batch, b.distance, b.draw);
    });
    for (size_t k = 0; k < keys.size(); ++k) order[k] = {keys[k].group, keys[k].draw};
    drawGroups(rc, order);
}

// Per group (pipeline) its camera runs (GpuScene::CameraRun: the batches of its materials that
// share a cull mode, texture set and window of parameters, whatever the parameters), each one
// range of commands: as many as the culling pass counted (vkCmdDrawIndexedIndirectCount; every one
// of the run, one a call, where the device lacks it or the run is longer than its
// maxDrawIndirectCount — a command without instances draws nothing). The order is the batches',
// not front to back: the GPU chose the draws.
void GBufferScenePass::recordIndirect(RecordContext& rc) {
    const GpuScene& scene = *sceneOf(rc);
    const PhysicalResource* commands = rc.resources.find(m_indirect);
    const PhysicalResource* counts = rc.resources.find(m_indirectCount);
    const glm::vec4 zeros[8] = {};  // scene.vert: all-zero push constants, an instanced draw
    bool counted = false;           // a vkCmdDrawIndexedIndirectCount recorded
    for (size_t gi = 0; gi < m_groups.size(); ++gi) {
        Group& g = m_groups[gi];
        if (m_groupRuns[gi].empty()) continue;
        vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g.pipeline.get());
        g.program->bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
        vkCmdSetStencilReference(rc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, g.info.stencilValue);
        vkCmdPushConstants(rc.cmd, g.program->layout(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof zeros, zeros);
        for (uint32_t r : m_groupRuns[gi]) {
            const GpuScene::CameraRun& run = scene.cameraRuns()[r];
            const VkDeviceSize end =
                VkDeviceSize(run.firstCommand + run.commands) * kIndirectCommandBytes;
            if (run.commands == 0 || end > commands->plan->bufferSize ||
                VkDeviceSize(r + 1) * 4 > counts->plan->bufferSize)
                continue;  // a buffer without room for the scene's batches: sized for another
            // The run's textures and window of materials (lib/material.glsl: read by index).
            scene.bindTextureSet(rc.cmd, g.program->layout(), run.textureSet, run.firstMaterial);
            vkCmdSetCullMode(rc.cmd, run.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
            const VkDeviceSize offset = VkDeviceSize(run.firstCommand) * kIndirectCommandBytes;
            if (rc.gpu.drawIndirectCount() &&
                run.commands <= rc.gpu.properties().limits.maxDrawIndirectCount) {
                vkCmdDrawIndexedIndirectCount(rc.cmd, commands->buffer->buffer(), offset,
                                              counts->buffer->buffer(), VkDeviceSize(r) * 4,
                                              run.commands, kIndirectCommandBytes);
                counted = true;
            } else  // one command a call: a drawCount above 1 needs multiDrawIndirect
                for (uint32_t k = 0; k < run.commands; ++k)
                    vkCmdDrawIndexedIndirect(rc.cmd, commands->buffer->buffer(),
                                             offset + k * kIndirectCommandBytes, 1,
                                             kIndirectCommandBytes);
        }
    }
    // Lavapipe (Mesa 22.3) keeps the last count buffer for the command buffer's later indirect
    // draws without one (the shadow maps'): where this pass's last count was 0 they drew nothing.
    // A last count draw of one empty command, its count 2^32 − 1, leaves them their own counts
    // (after a count draw: its group's pipeline, sets and state are bound).
    if (m_countReset.buffer() && counted)
        vkCmdDrawIndexedIndirectCount(rc.cmd, m_countReset.buffer(), 0, m_countReset.buffer(), 20,
                                      1, kIndirectCommandBytes);
    vkCmdEndRendering(rc.cmd);
}

VkPipelineColorBlendAttachmentState GBufferScenePass::colorBlend(const Group& g,
                                                                 const std::string& target) const {
    VkPipelineColorBlendAttachmentState b = blendState("", /*alphaKeepsDestination=*/true);
    const bool ofLayout =
        std::find(g.info.targets.begin(), g.info.targets.end(), target) != g.info.targets.end();
    const bool filled = g.info.fills.empty() || std::find(g.info.fills.begin(), g.info.fills.end(),
                                                          target) != g.info.fills.end();
    // A material writes only the targets of its layout it fills (the fix-up pass does the rest).
    b.colorWriteMask =
        (ofLayout && filled) || target == m_specularTarget || target == m_motionTarget ? 0xfu : 0u;
    return b;
}

Result<void> CameraScenePass::findOverlayAttachments(const PassSetup& setup,
                                                     const std::string& mode) {
    const std::string missing =
        "a " + mode + " 'scene' pass reads the depth buffer ({ \"depth\", as = \"depth\" })";
    if (auto r = findAttachments(setup.desc, /*depthRead=*/true, missing.c_str()); !r) return r;
    // The HDR, and the motion target the forward pass may write beside it.
    const bool withMotion = m_colors.size() == 2 && m_colors[1].resource == m_motionTarget;
    if (m_colors.size() != 1 && !withMotion)
        return fail(
            ErrorCode::InvalidInput,
            passPrefix(setup.desc) + "a " + mode +
                " 'scene' pass writes one colour target (the HDR, loaded)" +
                (m_motionTarget.empty() ? ""
                                        : ", then its motion target '" + m_motionTarget + "'"));
    sizeFromDepth(setup);
    return {};
}

Result<void> ForwardScenePass::prepareDraws(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    m_motionTarget = desc.params["motion"].asString();
    if (auto r = findOverlayAttachments(setup, "forward"); !r) return r;
    const std::vector<std::string> attachments = colorNames();
    // One shader per material that has blended draws (and per set of textures); the draws
    // are sorted back to front across them when recorded.
    for (const PassMaterial& info : desc.materials) {
        auto variants = drawsByTextures(*sceneOf(setup), [&](const Material& m) {
            return m.model == info.name && m.alphaMode == AlphaMode::Blend;
        });
        if (variants.empty()) continue;
        const Material& example =
            sceneOf(setup)
                ->scene()
                .materials[sceneOf(setup)->draws()[variants.begin()->second.front()].material];
        const std::string who = "scene material '" + example.name +
                                "' is blended, so the forward pass shades it with material '" +
                                info.name + "' (" + info.origin + "), ";
        if (!info.fixup.empty())
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + who +
                            "which fills only part of its layout (the rest comes from the "
                            "fix-up pass '" +
                            info.fixup +
                            "'): a blended surface has no G-buffer to fix up; make it opaque "
                            "or use another material");
        if (info.shading.empty())
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + who +
                            "which has no lighting path with a shading function: give it a "
                            "path declared with rg.path { shading = \"file.glsl\" } "
                            "with vec3 rgShade(GBuffer_" +
                            info.layout + " g, vec3 position, vec3 V, ivec2 pixel)");
        for (auto& [mask, draws] : variants)
            if (auto r =
                    addGroup(setup, info, forwardSource(info, attachments, m_motionTarget),
                             "forward_" + info.name + ".frag", mask, std::move(draws), attachments);
                !r)
                return r;
    }
    return {};
}

void ForwardScenePass::recordDraws(RecordContext& rc) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = rc.resources.find(m_depth->resource)->image->attachmentView();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
    depth.clearValue.depthStencil = {1.0f, 0};
    beginCamera(rc, depth);
    // Back to front across every group (by the distance of the draws' origins to the camera),
    // switching shaders as needed.
    const glm::vec3 eye = sceneOf(rc)->frameCamera().position;
    std::vector<float> distance;
    DrawOrder order = inView(rc, distance, [&](const DrawItem& item) {
        return glm::distance(glm::vec3(item.world[3]), eye);
    });
    std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
        return distance[a.second] > distance[b.second];
    });
    drawGroups(rc, order);
}

// Over the lit HDR, src·α + dst·(1 − α), the HDR's alpha kept.
VkPipelineColorBlendAttachmentState ForwardScenePass::colorBlend(
    const Group& /*g*/, const std::string& /*target*/) const {
    VkPipelineColorBlendAttachmentState b = blendState("alpha", /*alphaKeepsDestination=*/true);
    b.colorWriteMask = 0xfu;
    return b;
}

// Tested against the opaque surfaces' depth, not written; no stencil classes.
void ForwardScenePass::depthStencil(GraphicsPipelineDesc& d, const Group& /*g*/) const {
    d.depthStencil.depthTestEnable = VK_TRUE;
    d.depthStencil.depthWriteEnable = VK_FALSE;
    d.depthStencil.depthCompareOp = VK_COMPARE_OP_LESS;
}

PassKindInfo scenePassKind() {
    return PassKindInfo{
        {"scene",
         PassType::Raster,
         "draws the scene's primitives with each selected material's generated G-buffer shader; "
         "writes stencil classes",
         {
             {"materials", "string|list",
              "pipeline materials to draw (default: every material that is not forward-only)"},
             {"forward", "boolean",
              "draw the blended (alpha = 'blend') materials, lit directly, over the colour target "
              "it "
              "loads"},
             {"lines", "boolean",
              "draw the scene's points and lines (glTF POINTS, LINES, LINE_LOOP, LINE_STRIP), "
              "unlit, one pixel wide, over the colour target it loads, tested against the depth "
              "buffer it reads"},
             {"paths", "string|list", "draw the materials of these lighting paths"},
             {"lightmap_specular", "written",
              "an attachment it writes that receives from every material the baked lightmap's "
              "specular radiance along the pixel's reflection (black without a lightmap)"},
             {"motion", "written",
              "an attachment it writes (rg16f) that receives each pixel's screen motion since "
              "the last frame, in uv units, from the draws' last world matrices and the last "
              "frame's camera (the G-buffer and forward passes; the forward pass blends it with "
              "the surface's opacity); its vertex shader gets RG_MOTION"},
             {"defines", "table",
              "preprocessor defines for its shaders (the forward pass: RG_IBL with "
              "scripts/ibl.lua's "
              "ibl.lit)"},
             {"switches", "table",
              "parameters compiled into its shaders as defines, as for the fullscreen kind "
              "(render_loop.lua: specular anti-aliasing); changing one rebuilds the pass"},
             {"shadow", "boolean",
              "depth only, into each layer of the depth target it writes, from the views its "
              "vertex "
              "shader computes (scripts/shadows.lua)"},
             {"capture", "boolean",
              "the scene's local light probes: every draw that is not blended into six layers per "
              "probe of the cube texture it writes (with a depth target of as many layers), "
              "diffuse "
              "only (scripts/probes.lua)"},
             {"cadence", "string",
              "'frame' (default) or 'once': record only after each build (a probe capture)"},
             {"fragment", "string", "capture: the fragment shader (default probes/capture.frag)"},
             {"shader", "string",
              "shadow: the vertex shader (default shadows/shadow.vert: the matrix of the layer its "
              "push constant names, from `sun_cascades`); capture: default probes/capture.vert"},
             {"depth_bias", "list", "shadow: { constant, slope } rasteriser depth bias"},
             {"cull", "string",
              "shadow: 'none' (default), 'clockwise' or 'counter_clockwise': single-sided "
              "materials' "
              "faces of that winding in the map are not drawn (the faces turned away from the "
              "light, "
              "for a closed mesh never the nearest)"},
             {"indirect", "string",
              "the G-buffer mode: a buffer it reads as { NAME, as = 'indirect' } holding a "
              "VkDrawIndexedIndirectCommand per camera batch (a mesh and material) and level of "
              "detail, each camera run's batches (the materials of one pipeline, cull mode, "
              "texture set and window of parameters) one range, written by a culling pass such "
              "as passes/camera_cull.comp with the instances each draws (a buffer it reads as "
              "storage `camera_instances`; scene.vert gets RG_CAMERA_INSTANCES): one indirect "
              "draw per camera run (scripts/culling.lua); without the read, the CPU culls and "
              "batches the draws. "
              "shadow: a buffer the pass reads as { NAME, as = 'indirect' } holding a "
              "VkDrawIndexedIndirectCommand per view, caster batch (GpuScene::shadowBatches) "
              "and level of detail (view-major), written by a culling pass such as "
              "shadows/cascade_cull.comp with the instances each draws (the vertex shader gets "
              "RG_SHADOW_INSTANCES): one instanced draw per batch and level; a buffer without "
              "room for the scene's batches draws every caster directly"},
             {"bind", "table",
              "maps a GLSL binding name to a resource name when they differ (the G-buffer's "
              "first phase: bind = { camera_instances = 'camera_early_instances' })"},
             {"indirect_count", "string",
              "the G-buffer mode, with indirect: a buffer it reads as { NAME, as = 'indirect' } "
              "holding per camera run how many of its range of commands to draw "
              "(vkCmdDrawIndexedIndirectCount)"},
             {"view", "list",
              "shadow: { first, count }: the target's layer l is view first + l of count (its "
              "matrix, "
              "its indirect slots), default { 0, the target's layers }: one cascade a pass, into a "
              "map of its own"},
             {"views", "string",
              "shadow: 'shader' (default: the layer's matrix is the vertex shader's business) or "
              "'lights' (the scene's local-light shadow views this frame, one per layer, each "
              "drawing "
              "only the casters its frustum meets; shader default shadows/local_shadow.vert)"},
         },
         Usage::Sampled,
         Usage::ColorAttachment},
        [] { return std::make_unique<ScenePass>(); }};
}

}  // namespace rg::passes
