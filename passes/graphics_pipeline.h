// The graphics pipeline both raster pass kinds build (fullscreen in builtin_kinds.cpp, scene in
// scene_pass.cpp): dynamic rendering into the given attachment formats, one viewport and scissor
// (always dynamic), filled primitives (triangle lists unless the description says otherwise), one
// sample. What differs between kinds — vertex input, topology, culling, depth/stencil, blending,
// further dynamic state — is in the description.
#pragma once

#include <vector>

#include "gpu/context.h"
#include "gpu/pass_kind.h"
#include "gpu/vk.h"
#include "shader_program.h"

namespace rg::passes {

struct GraphicsPipelineDesc {
    const ShaderProgram* program = nullptr;
    std::vector<VkFormat> colorFormats;
    std::vector<VkPipelineColorBlendAttachmentState> blends;  // one per colour attachment
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkFormat stencilFormat = VK_FORMAT_UNDEFINED;
    const VkPipelineVertexInputStateCreateInfo* vertexInput = nullptr;  // none: no vertex buffers
    // Line and point lists are one pixel wide (the vertex shader writes gl_PointSize = 1).
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkPipelineDepthStencilStateCreateInfo depthStencil{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    std::vector<VkDynamicState> dynamicStates;  // besides viewport and scissor
    // Depth bias in the rasteriser (shadow maps): constant (in units of the depth format's
    // resolution) and slope-scaled; off when both are 0.
    float depthBiasConstant = 0.0f, depthBiasSlope = 0.0f;
};

// The blend of a colour attachment: `alpha` src·α + dst·(1 − α), `additive` src + dst, none
// (write as is); `alphaKeepsDestination` leaves the target's alpha as it was (blending over an
// image whose alpha means something else).
VkPipelineColorBlendAttachmentState blendState(const std::string& mode,
                                               bool alphaKeepsDestination = false);

Result<gpu::OwnedPipeline> createGraphicsPipeline(
    gpu::Context& ctx, const GraphicsPipelineDesc& desc);  // through ctx's pipeline cache

// The colour attachment of access `a` for vkCmdBeginRendering: its image, stored; loaded when the
// access loads, else `notLoaded` (cleared, or don't-care where every pixel is written).
VkRenderingAttachmentInfo colorAttachment(const gpu::RecordContext& rc, const Access& a,
                                          VkAttachmentLoadOp notLoaded);

}  // namespace rg::passes
