#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "cadence.h"
#include "core/check.h"
#include "gpu/compile_scope.h"
#include "graphics_pipeline.h"
#include "passes.h"
#include "scene_pass.h"
#include "shader_program.h"

namespace rg::passes {

using namespace rg::gpu;

namespace {

// Copies, not pointers: a pass instance may outlive the GraphDesc it was prepared from (it is
// reused across incremental rebuilds).
std::vector<Access> accessesOf(const PassDesc& desc, std::initializer_list<Usage> usages) {
    std::vector<Access> out;
    for (const auto& a : desc.accesses)
        if (std::find(usages.begin(), usages.end(), a.usage) != usages.end()) out.push_back(a);
    return out;
}

Result<std::string> requireShader(const PassDesc& desc) {
    const Value& s = desc.params["shader"];
    if (!s.isString() || s.asString().empty())
        return fail(ErrorCode::InvalidInput,
                    passPrefix(desc) + "params.shader: expected the path of a GLSL file, got " +
                        s.typeName());
    return s.asString();
}

VkCompareOp parseCompare(const std::string& s, bool& ok) {
    ok = true;
    if (s == "never") return VK_COMPARE_OP_NEVER;
    if (s == "less") return VK_COMPARE_OP_LESS;
    if (s == "equal") return VK_COMPARE_OP_EQUAL;
    if (s == "less_equal") return VK_COMPARE_OP_LESS_OR_EQUAL;
    if (s == "greater") return VK_COMPARE_OP_GREATER;
    if (s == "not_equal") return VK_COMPARE_OP_NOT_EQUAL;
    if (s == "greater_equal") return VK_COMPARE_OP_GREATER_OR_EQUAL;
    if (s == "always") return VK_COMPARE_OP_ALWAYS;
    ok = false;
    return VK_COMPARE_OP_ALWAYS;
}

VkClearColorValue clearColor(const Value& v) {
    VkClearColorValue c{};
    if (v.isNumber()) {
        float f = static_cast<float>(v.asNumber());
        c.float32[0] = c.float32[1] = c.float32[2] = c.float32[3] = f;
    } else {
        const auto& l = v.asList();
        for (size_t i = 0; i < 4 && i < l.size(); ++i)
            c.float32[i] = static_cast<float>(l[i].asNumber());
    }
    return c;
}

VkClearColorValue clearColorFor(Format f, const Value& v) {
    VkClearColorValue c = clearColor(v);
    if (formatInfo(f).integer)
        for (int i = 0; i < 4; ++i)
            c.uint32[i] = static_cast<uint32_t>(std::max(0.0f, c.float32[i]));
    return c;
}

// ---------------------------------------------------------------------------------------------
// fullscreen: one triangle over the colour attachments, fragment shader from params.shader.
// params: shader, defines, clear (colour for attachments that do not load), blend ("alpha" |
// "additive"), stencil = { ref, compare, mask } (needs a depth/stencil attachment), bind, uniforms.
class FullscreenPass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        const PassDesc& desc = setup.desc;
        auto shader = requireShader(desc);
        if (!shader) return std::unexpected(shader.error());
        ShaderRequest vert;
        vert.path = "fullscreen.vert";
        const Value& depthState = desc.params["depth"];
        if (!depthState.isNil()) {
            char value[32];
            std::snprintf(value, sizeof value, "%.9g", depthState["value"].asNumber(0.0));
            vert.defines.emplace_back("RG_FULLSCREEN_DEPTH", value);
        }
        // A pass for frames whose camera moved (or stood still): its triangle is placed outside
        // the clip volume on the others, by the scene's Camera block (lib/scene.glsl's
        // temporal.x) in fullscreen.vert — the whole pass then costs its attachments' load and
        // store, where a branch in the fragment shader costs both sides on lavapipe.
        if (const Value& camera = desc.params["camera"]; !camera.isNil()) {
            if (!camera.isString() ||
                (camera.asString() != "moved" && camera.asString() != "still"))
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "params.camera: expected 'moved' or 'still', got " +
                                camera.typeName() +
                                (camera.isString() ? " '" + camera.asString() + "'" : ""));
            vert.defines.emplace_back("RG_FULLSCREEN_CAMERA",
                                      camera.asString() == "moved" ? "1" : "0");
        }
        ShaderRequest frag;
        frag.path = *shader;
        frag.stage = ShaderStage::Fragment;
        if (auto r = m_program.build(setup, {vert, frag}); !r) return r;

        m_colors = accessesOf(desc, {Usage::ColorAttachment});
        auto depth = accessesOf(desc, {Usage::DepthStencilAttachment, Usage::DepthStencilRead});
        if (!depth.empty()) m_depth = depth.front();
        if (m_colors.empty() && !m_depth)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) +
                            "a fullscreen pass needs at least one colour attachment in its writes");
        const auto& outputs = m_program.reflection().colorOutputs;
        for (uint32_t loc : outputs)
            if (loc >= m_colors.size())
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "the fragment shader writes location " +
                                std::to_string(loc) + " but the pass has " +
                                std::to_string(m_colors.size()) + " colour attachment(s)");
        const PhysicalResource* first =
            setup.resources.find(m_colors.empty() ? m_depth->resource : m_colors[0].resource);
        m_width = first->plan->width;
        m_height = first->plan->height;

        const Value& stencil = desc.params["stencil"];
        if (!stencil.isNil()) {
            if (!m_depth ||
                !formatInfo(setup.resources.find(m_depth->resource)->plan->format).stencil)
                return fail(
                    ErrorCode::InvalidInput,
                    passPrefix(desc) +
                        "params.stencil: the pass has no stencil attachment to test against");
            bool ok = false;
            m_stencilCompare = parseCompare(
                stencil["compare"].isString() ? stencil["compare"].asString() : "equal", ok);
            if (!ok)
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "params.stencil.compare: unknown '" +
                                stencil["compare"].asString() +
                                "', expected one of: 'never', 'less', 'equal', 'less_equal', "
                                "'greater', 'not_equal', 'greater_equal', 'always'");
            m_stencilRef = static_cast<uint32_t>(stencil["ref"].asNumber(0));
            m_stencilMask = static_cast<uint32_t>(stencil["mask"].asNumber(255));
            m_stencilTest = true;
        }
        if (!depthState.isNil()) {
            if (!m_depth ||
                !formatInfo(setup.resources.find(m_depth->resource)->plan->format).depth)
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) +
                                "params.depth: the pass has no depth attachment to test against");
            bool ok = false;
            m_depthCompare = parseCompare(
                depthState["compare"].isString() ? depthState["compare"].asString() : "less", ok);
            if (!ok)
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "params.depth.compare: unknown '" +
                                depthState["compare"].asString() +
                                "', expected one of: 'never', 'less', 'equal', 'less_equal', "
                                "'greater', 'not_equal', 'greater_equal', 'always'");
            m_depthWrite = depthState["write"].asBool(false);
            if (m_depthWrite && m_depth->usage != Usage::DepthStencilAttachment)
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) +
                                "params.depth.write: the depth buffer is read-only here; declare "
                                "it in writes to write depth");
            m_depthTest = true;
        }
        const std::string blend = desc.params["blend"].asString();
        if (!blend.empty() && blend != "alpha" && blend != "additive")
            return fail(ErrorCode::InvalidInput, passPrefix(desc) + "params.blend: unknown '" +
                                                     blend +
                                                     "', expected one of: 'alpha', 'additive'");
        // The triangle writes every pixel when no test can fail, nothing blends and the shader
        // cannot discard: the targets it does not load are then not cleared first (their clear
        // could never be seen), which spares a CPU rasteriser a pass over their memory
        // (tonemap ~0.5 ms, each bloom level ~0.2 at 1280×720 on lavapipe).
        m_writesEveryPixel = !m_stencilTest &&
                             (!m_depthTest || m_depthCompare == VK_COMPARE_OP_ALWAYS) &&
                             blend.empty() && !m_program.reflection().discards;
        return createPipeline(setup, blend);
    }

    void record(RecordContext& rc) override {
        std::vector<VkRenderingAttachmentInfo> colors;
        for (const Access& a : m_colors) {
            VkRenderingAttachmentInfo ai = colorAttachment(
                rc, a,
                m_writesEveryPixel ? VK_ATTACHMENT_LOAD_OP_DONT_CARE : VK_ATTACHMENT_LOAD_OP_CLEAR);
            ai.clearValue.color =
                clearColorFor(rc.resources.find(a.resource)->plan->format, rc.desc.params["clear"]);
            colors.push_back(ai);
        }
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {m_width, m_height}};
        ri.layerCount = 1;
        ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
        ri.pColorAttachments = colors.data();
        if (m_depth) {
            const PhysicalResource* r = rc.resources.find(m_depth->resource);
            bool readOnly = m_depth->usage == Usage::DepthStencilRead;
            depth.imageView = r->image->attachmentView();
            depth.imageLayout = readOnly ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                         : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
            const FormatInfo& fi = formatInfo(r->plan->format);
            // A depth-only target the triangle writes at every pixel needs no clear either (one
            // with stencil keeps it: the pass does not write the stencil).
            const bool overwritten = m_writesEveryPixel && m_depthWrite && !fi.stencil;
            depth.loadOp = readOnly || m_depth->load ? VK_ATTACHMENT_LOAD_OP_LOAD
                           : overwritten             ? VK_ATTACHMENT_LOAD_OP_DONT_CARE
                                                     : VK_ATTACHMENT_LOAD_OP_CLEAR;
            depth.storeOp = readOnly ? VK_ATTACHMENT_STORE_OP_NONE : VK_ATTACHMENT_STORE_OP_STORE;
            depth.clearValue.depthStencil = {1.0f, 0};
            if (fi.depth) ri.pDepthAttachment = &depth;
            if (fi.stencil) ri.pStencilAttachment = &depth;
        }
        vkCmdBeginRendering(rc.cmd, &ri);
        VkViewport vp{0, 0, static_cast<float>(m_width), static_cast<float>(m_height), 0, 1};
        VkRect2D sc{{0, 0}, {m_width, m_height}};
        vkCmdSetViewport(rc.cmd, 0, 1, &vp);
        vkCmdSetScissor(rc.cmd, 0, 1, &sc);
        if (m_stencilTest)
            vkCmdSetStencilReference(rc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, m_stencilRef);
        vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipeline.get());
        m_program.bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
        vkCmdDraw(rc.cmd, 3, 1, 0, 0);
        vkCmdEndRendering(rc.cmd);
    }

    std::vector<std::string> files() const override { return m_program.files(); }

private:
    Result<void> createPipeline(PassSetup& setup, const std::string& blend) {
        GraphicsPipelineDesc d;
        d.program = &m_program;
        for (const Access& a : m_colors) {
            Format f = setup.resources.find(a.resource)->plan->format;
            d.colorFormats.push_back(toVkFormat(f));
            d.blends.push_back(blendState(formatInfo(f).integer ? "" : blend));
        }
        if (m_depth) {
            Format f = setup.resources.find(m_depth->resource)->plan->format;
            if (formatInfo(f).depth) d.depthFormat = toVkFormat(f);
            if (formatInfo(f).stencil) d.stencilFormat = toVkFormat(f);
        }
        if (m_depthTest) {
            d.depthStencil.depthTestEnable = VK_TRUE;
            d.depthStencil.depthWriteEnable = m_depthWrite ? VK_TRUE : VK_FALSE;
            d.depthStencil.depthCompareOp = m_depthCompare;
        }
        if (m_stencilTest) {
            d.depthStencil.stencilTestEnable = VK_TRUE;
            VkStencilOpState op{};
            op.failOp = op.passOp = op.depthFailOp = VK_STENCIL_OP_KEEP;
            op.compareOp = m_stencilCompare;
            op.compareMask = m_stencilMask;
            d.depthStencil.front = d.depthStencil.back = op;
            d.dynamicStates.push_back(VK_DYNAMIC_STATE_STENCIL_REFERENCE);
        }
        auto pipeline = createGraphicsPipeline(setup.gpu, d);
        if (!pipeline) return std::unexpected(pipeline.error());
        m_pipeline = std::move(*pipeline);
        return {};
    }

    ShaderProgram m_program;
    OwnedPipeline m_pipeline;
    std::vector<Access> m_colors;
    std::optional<Access> m_depth;
    uint32_t m_width = 0, m_height = 0;
    bool m_stencilTest = false;
    VkCompareOp m_stencilCompare = VK_COMPARE_OP_ALWAYS;
    bool m_depthTest = false, m_depthWrite = false;
    bool m_writesEveryPixel = false;  // no test, no blend, no discard: the targets need no clear
    VkCompareOp m_depthCompare = VK_COMPARE_OP_LESS;
    uint32_t m_stencilRef = 0, m_stencilMask = 0xff;
};

// ---------------------------------------------------------------------------------------------
// compute: params.shader; params.groups = {x, y, z}, or params.dispatch = "resource" (work groups
// cover its width x height x layers); default: the first storage image it writes.
class ComputePass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        const PassDesc& desc = setup.desc;
        auto shader = requireShader(desc);
        if (!shader) return std::unexpected(shader.error());
        ShaderRequest req;
        req.path = *shader;
        req.stage = ShaderStage::Compute;
        if (auto r = m_cadence.parse(setup); !r) return r;
        const bool perMip = desc.params["per_mip"].asBool(false);
        const PhysicalResource* mipTarget = nullptr;
        if (perMip) {
            if (desc.params["groups"].isList())
                return fail(ErrorCode::InvalidInput, passPrefix(desc) +
                                                         "params.per_mip: the dispatch follows "
                                                         "each mip's size; give no params.groups");
            for (const Access& a : accessesOf(desc, {Usage::StorageWrite, Usage::StorageReadWrite}))
                if (const PhysicalResource* r = setup.resources.find(a.resource); r->image) {
                    if (mipTarget)
                        return fail(ErrorCode::InvalidInput,
                                    passPrefix(desc) +
                                        "params.per_mip: the pass writes two storage images ('" +
                                        mipTarget->plan->name + "', '" + a.resource +
                                        "'); a per-mip pass writes one");
                    mipTarget = r;
                }
            if (!mipTarget)
                return fail(ErrorCode::InvalidInput, passPrefix(desc) +
                                                         "params.per_mip: the pass writes no "
                                                         "storage image whose mips it could fill");
        }
        m_mips = mipTarget ? mipTarget->plan->mips : 1;
        if (auto r = m_program.build(setup, {req}, {}, m_mips); !r) return r;
        const auto& local = m_program.reflection().localSize;
        if (mipTarget) {
            m_mipGroups.clear();
            for (uint32_t m = 0; m < m_mips; ++m) {
                const uint32_t w = std::max(1u, mipTarget->plan->width >> m),
                               h = std::max(1u, mipTarget->plan->height >> m);
                m_mipGroups.push_back({(w + local[0] - 1) / local[0], (h + local[1] - 1) / local[1],
                                       mipTarget->plan->layers});
            }
        }
        const Value& groups = desc.params["groups"];
        if (groups.isList()) {
            const auto& g = groups.asList();
            for (size_t i = 0; i < 3; ++i)
                m_groups[i] = i < g.size() ? static_cast<uint32_t>(g[i].asNumber(1)) : 1;
        } else {
            std::string target = desc.params["dispatch"].asString();
            if (target.empty())
                for (const Access& a :
                     accessesOf(desc, {Usage::StorageWrite, Usage::StorageReadWrite}))
                    if (setup.resources.find(a.resource)->image) {
                        target = a.resource;
                        break;
                    }
            if (target.empty())
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) +
                                "params.dispatch: name the resource whose size the dispatch "
                                "covers, or give params.groups = {x, y, z}");
            const PhysicalResource* r = setup.resources.find(target);
            if (!r)
                return fail(ErrorCode::InvalidInput, passPrefix(desc) + "params.dispatch: '" +
                                                         target +
                                                         "' is not a resource this pass uses");
            uint32_t w = r->image ? r->plan->width : static_cast<uint32_t>(r->plan->bufferSize / 4);
            uint32_t h = r->image ? r->plan->height : 1;
            // One invocation per tile x tile texels (per-tile work such as light culling).
            const double tileParam = desc.params["tile"].asNumber(1);
            if (!(tileParam >= 1 && tileParam <= 4096))  // NaN too
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "params.tile: expected 1..4096 texels");
            if (const uint32_t tile = static_cast<uint32_t>(tileParam); tile > 1) {
                w = (w + tile - 1) / tile;
                h = (h + tile - 1) / tile;
            }
            m_groups = {(w + local[0] - 1) / local[0], (h + local[1] - 1) / local[1],
                        r->image ? r->plan->layers : 1};
        }
        VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        ci.stage = m_program.stageInfos()[0];
        ci.layout = m_program.layout();
        VkPipeline pipeline = VK_NULL_HANDLE;
        {
            gpu::UnlockedForCompile compiling;
            RG_VK_TRY(vkCreateComputePipelines(setup.gpu.device(), setup.gpu.pipelineCache(), 1,
                                               &ci, nullptr, &pipeline));
        }
        m_pipeline = OwnedPipeline(setup.gpu.device(), pipeline);
        return {};
    }

    void record(RecordContext& rc) override {
        if (!m_cadence.due(rc)) return;
        vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
        if (m_mipGroups.empty()) {
            m_program.bind(rc, VK_PIPELINE_BIND_POINT_COMPUTE);
            vkCmdDispatch(rc.cmd, m_groups[0], m_groups[1], m_groups[2]);
            return;
        }
        for (uint32_t m = 0; m < m_mips; ++m) {
            if (m > 0) {
                // The next mip may read this one (a chain through `<image>_previous`).
                VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
                mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
                mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
                mb.dstAccessMask =
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
                VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                dep.memoryBarrierCount = 1;
                dep.pMemoryBarriers = &mb;
                vkCmdPipelineBarrier2(rc.cmd, &dep);
            }
            m_program.bind(rc, VK_PIPELINE_BIND_POINT_COMPUTE, m);
            vkCmdDispatch(rc.cmd, m_mipGroups[m][0], m_mipGroups[m][1], m_mipGroups[m][2]);
        }
    }

    std::vector<std::string> files() const override { return m_program.files(); }

private:
    ShaderProgram m_program;
    OwnedPipeline m_pipeline;
    std::array<uint32_t, 3> m_groups{1, 1, 1};
    uint32_t m_mips = 1;
    std::vector<std::array<uint32_t, 3>> m_mipGroups;  // per_mip: the work groups of each mip
public:
    bool dueOnce(uint64_t epoch) const override { return m_cadence.dueOnce(epoch); }
    void restoredOnce(uint64_t epoch) override { m_cadence.restored(epoch); }

private:
    Cadence m_cadence;
};

// ---------------------------------------------------------------------------------------------
// clear: every CopyDst texture to params.value (colour) or params.depth / params.stencil;
// buffers are filled with zeros.
class ClearPass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        m_targets = accessesOf(setup.desc, {Usage::CopyDst});
        if (m_targets.empty())
            return fail(
                ErrorCode::InvalidInput,
                passPrefix(setup.desc) + "a clear pass needs at least one resource in its writes");
        return {};
    }
    void record(RecordContext& rc) override {
        for (const Access& a : m_targets) {
            const PhysicalResource* r = rc.resources.find(a.resource);
            if (r->buffer) {
                vkCmdFillBuffer(rc.cmd, r->buffer->buffer(), 0, VK_WHOLE_SIZE, 0);
                continue;
            }
            VkImageSubresourceRange range{aspectOf(r->plan->format), 0, VK_REMAINING_MIP_LEVELS, 0,
                                          VK_REMAINING_ARRAY_LAYERS};
            if (isDepthStencil(r->plan->format)) {
                VkClearDepthStencilValue v{
                    static_cast<float>(rc.desc.params["depth"].asNumber(1.0)),
                    static_cast<uint32_t>(rc.desc.params["stencil"].asNumber(0))};
                vkCmdClearDepthStencilImage(rc.cmd, r->image->image(),
                                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
            } else {
                VkClearColorValue v = clearColorFor(r->plan->format, rc.desc.params["value"]);
                vkCmdClearColorImage(rc.cmd, r->image->image(),
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
            }
        }
    }

private:
    std::vector<Access> m_targets;
};

// ---------------------------------------------------------------------------------------------
// copy: CopySrc -> CopyDst. Same size and format: an exact copy; otherwise a linear blit
// (nearest for integer and depth formats).
class CopyPass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        auto src = accessesOf(setup.desc, {Usage::CopySrc});
        auto dst = accessesOf(setup.desc, {Usage::CopyDst});
        if (src.size() != 1 || dst.size() != 1)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) +
                            "a copy pass reads exactly one resource and writes exactly one (has " +
                            std::to_string(src.size()) + " and " + std::to_string(dst.size()) +
                            ")");
        m_src = src[0].resource;
        m_dst = dst[0].resource;
        const PhysicalResource* s = setup.resources.find(m_src);
        const PhysicalResource* d = setup.resources.find(m_dst);
        if ((s->image == nullptr) != (d->image == nullptr))
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) + "cannot copy between a texture and a buffer ('" +
                            m_src + "' -> '" + m_dst + "')");
        if (s->image && isDepthStencil(s->plan->format) != isDepthStencil(d->plan->format))
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) + "format mismatch: cannot copy '" + m_src + "' (" +
                            std::string(formatName(s->plan->format)) + ") to '" + m_dst + "' (" +
                            std::string(formatName(d->plan->format)) + ")");
        return {};
    }
    void record(RecordContext& rc) override {
        const PhysicalResource* s = rc.resources.find(m_src);
        const PhysicalResource* d = rc.resources.find(m_dst);
        if (s->buffer) {
            VkBufferCopy region{0, 0, std::min(s->buffer->size(), d->buffer->size())};
            vkCmdCopyBuffer(rc.cmd, s->buffer->buffer(), d->buffer->buffer(), 1, &region);
            return;
        }
        const PlanResource& sp = *s->plan;
        const PlanResource& dp = *d->plan;
        VkImageAspectFlags aspect = aspectOf(sp.format);
        if (sp.width == dp.width && sp.height == dp.height && sp.format == dp.format) {
            VkImageCopy region{};
            region.srcSubresource = {aspect, 0, 0, std::min(sp.layers, dp.layers)};
            region.dstSubresource = region.srcSubresource;
            region.extent = {sp.width, sp.height, 1};
            vkCmdCopyImage(rc.cmd, s->image->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           d->image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            return;
        }
        VkImageBlit blit{};
        blit.srcSubresource = {aspect, 0, 0, 1};
        blit.dstSubresource = {aspectOf(dp.format), 0, 0, 1};
        blit.srcOffsets[1] = {static_cast<int32_t>(sp.width), static_cast<int32_t>(sp.height), 1};
        blit.dstOffsets[1] = {static_cast<int32_t>(dp.width), static_cast<int32_t>(dp.height), 1};
        bool nearest = formatInfo(sp.format).integer || isDepthStencil(sp.format);
        vkCmdBlitImage(rc.cmd, s->image->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       d->image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                       nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    }

private:
    std::string m_src, m_dst;
};

// ---------------------------------------------------------------------------------------------
// mips: the target (declared as a CopyDst that loads) gets mips 1..n-1 from mip 0, each a
// linear 2x downsample of the one before. All mips end in TRANSFER_DST, as the plan expects.
class MipsPass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        auto dst = accessesOf(setup.desc, {Usage::CopyDst});
        if (dst.size() != 1)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) + "a mips pass writes exactly one texture");
        m_target = dst[0].resource;
        const PhysicalResource* r = setup.resources.find(m_target);
        if (!r->image || formatInfo(r->plan->format).integer || isDepthStencil(r->plan->format))
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) + "'" + m_target +
                            "' must be a filterable colour texture to build mips");
        return m_cadence.parse(setup);
    }
    void record(RecordContext& rc) override {
        if (!m_cadence.due(rc)) return;
        const PhysicalResource* r = rc.resources.find(m_target);
        const PlanResource& p = *r->plan;
        VkImage img = r->image->image();
        int32_t w = static_cast<int32_t>(p.width), h = static_cast<int32_t>(p.height);
        for (uint32_t m = 1; m < p.mips; ++m) {
            // Mip m-1 becomes a blit source once written.
            imageBarrier(rc.cmd, img, VK_IMAGE_ASPECT_COLOR_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         m - 1, 1);
            int32_t nw = std::max(1, w / 2), nh = std::max(1, h / 2);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, p.layers};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, p.layers};
            blit.srcOffsets[1] = {w, h, 1};
            blit.dstOffsets[1] = {nw, nh, 1};
            vkCmdBlitImage(rc.cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            w = nw;
            h = nh;
        }
        if (p.mips > 1)
            imageBarrier(rc.cmd, img, VK_IMAGE_ASPECT_COLOR_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         0, p.mips - 1);
    }

private:
    std::string m_target;

public:
    bool dueOnce(uint64_t epoch) const override { return m_cadence.dueOnce(epoch); }
    void restoredOnce(uint64_t epoch) override { m_cadence.restored(epoch); }

private:
    Cadence m_cadence;
};

// ---------------------------------------------------------------------------------------------
// readback: copies mip 0 / layer 0 of its CopySrc into host memory, one buffer per frame slot;
// hostResult() decodes the newest finished copy.
class ReadbackPass final : public PassInstance {
public:
    Result<void> prepare(PassSetup& setup) override {
        auto src = accessesOf(setup.desc, {Usage::CopySrc});
        if (src.size() != 1)
            return fail(ErrorCode::InvalidInput,
                        passPrefix(setup.desc) +
                            "a readback pass reads exactly one resource (as a copy source)");
        m_source = src[0].resource;
        const PhysicalResource* r = setup.resources.find(m_source);
        m_plan = *r->plan;
        m_bytes = r->image ? uint64_t(m_plan.width) * m_plan.height * copyTexelBytes(m_plan.format)
                           : m_plan.bufferSize;
        for (uint32_t s = 0; s < setup.gpu.framesInFlight(); ++s) {
            auto buf = Buffer::create(setup.gpu, setup.desc.name + ".host", m_bytes,
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
            if (!buf) return std::unexpected(buf.error());
            m_host.push_back(std::move(*buf));
        }
        return {};
    }
    void record(RecordContext& rc) override {
        const PhysicalResource* r = rc.resources.find(m_source);
        Buffer& host = m_host[rc.frame.slot];
        if (r->buffer) {
            VkBufferCopy region{0, 0, m_bytes};
            vkCmdCopyBuffer(rc.cmd, r->buffer->buffer(), host.buffer(), 1, &region);
        } else {
            VkBufferImageCopy region{};
            VkImageAspectFlags aspect =
                formatInfo(m_plan.format).depth
                    ? static_cast<VkImageAspectFlags>(VK_IMAGE_ASPECT_DEPTH_BIT)
                    : aspectOf(m_plan.format);
            region.imageSubresource = {aspect, 0, 0, 1};
            region.imageExtent = {m_plan.width, m_plan.height, 1};
            vkCmdCopyImageToBuffer(rc.cmd, r->image->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   host.buffer(), 1, &region);
        }
        // Make the copy visible to the host once the frame's fence has signalled.
        memoryBarrier(rc.cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        m_lastSlot = static_cast<int>(rc.frame.slot);
    }
    std::optional<rg::Image> hostResult() const override {
        if (m_lastSlot < 0) return std::nullopt;
        rg::Image out;
        const void* data = m_host[static_cast<size_t>(m_lastSlot)].mapped();
        if (m_plan.kind == ResourceKind::Buffer) {
            out.width = static_cast<uint32_t>(m_bytes / 4);
            out.height = 1;
            out.channels = 1;
            out.pixels.resize(out.width);
            std::memcpy(out.pixels.data(), data, out.width * 4);
            return out;
        }
        out.width = m_plan.width;
        out.height = m_plan.height;
        out.channels = isDepthStencil(m_plan.format) ? 1 : formatInfo(m_plan.format).components;
        out.pixels.resize(size_t(out.width) * out.height * out.channels);
        decodeTexels(m_plan.format, data, size_t(out.width) * out.height, out.pixels.data());
        return out;
    }

private:
    std::string m_source;
    PlanResource m_plan;
    uint64_t m_bytes = 0;
    std::vector<Buffer> m_host;
    int m_lastSlot = -1;
};

template <class T>
PassKindInfo kind(PassKindSchema schema) {
    return PassKindInfo{std::move(schema), [] { return std::make_unique<T>(); }};
}

// Parameters every shader-driven kind takes.
std::vector<ParamSpec> shaderParams() {
    return {
        {"shader", "string",
         "GLSL file, relative to shaders/, the project root or the pipeline's folder"},
        {"defines", "table", "preprocessor defines: NAME = number, boolean or string"},
        {"switches", "table",
         "parameters compiled in as defines: PARAM = 'NAME' (a choice: its index; a boolean: 0 or "
         "1; a number: its value); changing one rebuilds the pass"},
        {"bind", "table", "maps a GLSL binding name to a resource name when they differ"},
        {"uniforms", "table", "values for the members of the shader's `Params` uniform block"},
        {"constants", "table", "values for push-constant members"},
        {"filter", "string", "'linear' (default) or 'nearest' sampling"},
    };
}

ParamSpec cadenceParam() {
    return {"cadence", "string",
            "'frame' (default): every frame; 'once': when (re)built or its persistent outputs were "
            "cleared (environment filtering, lookup tables)"};
}

std::vector<ParamSpec> plus(std::vector<ParamSpec> a, std::vector<ParamSpec> b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}  // namespace

void registerBuiltinPassKinds(PassRegistry& registry) {
    registry.add(kind<FullscreenPass>(
        {"fullscreen", PassType::Raster,
         "one triangle over the colour attachments; fragment shader from `shader`",
         plus(shaderParams(),
              {{"clear", "number|list", "clear colour of attachments that do not load (default 0)"},
               {"blend", "string", "'alpha' or 'additive'"},
               {"stencil", "table", "{ ref = N, compare = 'equal', mask = 255 }: stencil test"},
               {"depth", "table",
                "{ compare = 'less', value = 0, write = false }: depth test of the triangle at "
                "depth `value`"},
               {"camera", "string",
                "'moved' or 'still': draws only on frames whose scene camera moved (or stood "
                "still) since the last; on the others the triangle lies outside the clip volume "
                "and nothing is shaded"}}),
         Usage::Sampled, Usage::ColorAttachment}));
    registry.add(kind<ComputePass>(
        {"compute", PassType::Compute,
         "a compute shader dispatched over a resource's size or `groups`",
         plus(shaderParams(),
              {{"groups", "list", "{x, y, z} work groups"},
               {"dispatch", "string",
                "resource whose size the dispatch covers (default: first storage image written)"},
               {"tile", "integer",
                "one invocation per tile x tile texels of the dispatch resource (default 1)"},
               {"per_mip", "boolean",
                "one dispatch per mip of the storage image it writes, each binding that mip "
                "(`rg_mip` push constant)"},
               cadenceParam()}),
         Usage::Sampled, Usage::StorageWrite}));
    registry.add(kind<ClearPass>({"clear",
                                  PassType::Transfer,
                                  "clears what it writes to `value` (colour) or `depth`/`stencil`",
                                  {{"value", "number|list", "clear colour"},
                                   {"depth", "number", "depth clear value (default 1)"},
                                   {"stencil", "number", "stencil clear value (default 0)"}},
                                  Usage::CopySrc,
                                  Usage::CopyDst}));
    registry.add(kind<CopyPass>({"copy",
                                 PassType::Transfer,
                                 "copies or blits what it reads into what it writes",
                                 {},
                                 Usage::CopySrc,
                                 Usage::CopyDst}));
    registry.add(kind<MipsPass>({"mips",
                                 PassType::Transfer,
                                 "fills mips 1..n-1 of the texture it writes from mip 0",
                                 {cadenceParam()},
                                 Usage::CopySrc,
                                 Usage::CopyDst,
                                 /*writesLoad=*/true}));
    registry.add(scenePassKind());
    registry.add(
        kind<ReadbackPass>({"readback",
                            PassType::Transfer,
                            "copies what it reads to host memory every frame (a side effect)",
                            {},
                            Usage::CopySrc,
                            Usage::CopyDst}));
}

}  // namespace rg::passes
