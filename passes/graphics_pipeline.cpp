#include "graphics_pipeline.h"

#include "gpu/compile_scope.h"

namespace rg::passes {

VkPipelineColorBlendAttachmentState blendState(const std::string& mode,
                                               bool alphaKeepsDestination) {
    VkPipelineColorBlendAttachmentState b{};
    b.colorWriteMask = 0xf;
    if (mode.empty()) return b;
    const bool alpha = mode == "alpha";
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = alpha ? VK_BLEND_FACTOR_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
    b.dstColorBlendFactor = alpha ? VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.srcAlphaBlendFactor = alphaKeepsDestination ? VK_BLEND_FACTOR_ZERO : VK_BLEND_FACTOR_ONE;
    b.dstAlphaBlendFactor =
        alphaKeepsDestination || !alpha ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.alphaBlendOp = VK_BLEND_OP_ADD;
    return b;
}

VkRenderingAttachmentInfo colorAttachment(const gpu::RecordContext& rc, const Access& a,
                                          VkAttachmentLoadOp notLoaded) {
    VkRenderingAttachmentInfo ai{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    ai.imageView = rc.resources.find(a.resource)->image->attachmentView();
    ai.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    ai.loadOp = a.load ? VK_ATTACHMENT_LOAD_OP_LOAD : notLoaded;
    ai.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return ai;
}

Result<gpu::OwnedPipeline> createGraphicsPipeline(gpu::Context& ctx,
                                                  const GraphicsPipelineDesc& desc) {
    VkDevice device = ctx.device();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;
    rendering.stencilAttachmentFormat = desc.stencilFormat;
    VkPipelineVertexInputStateCreateInfo noVertices{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = desc.topology;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = desc.cullMode;
    rs.frontFace = desc.frontFace;
    rs.lineWidth = 1.0f;
    rs.depthBiasEnable =
        desc.depthBiasConstant != 0.0f || desc.depthBiasSlope != 0.0f ? VK_TRUE : VK_FALSE;
    rs.depthBiasConstantFactor = desc.depthBiasConstant;
    rs.depthBiasSlopeFactor = desc.depthBiasSlope;
    VkPipelineMultisampleStateCreateInfo ms{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendStateCreateInfo cb{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<uint32_t>(desc.blends.size());
    cb.pAttachments = desc.blends.data();
    std::vector<VkDynamicState> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    dyn.insert(dyn.end(), desc.dynamicStates.begin(), desc.dynamicStates.end());
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = static_cast<uint32_t>(dyn.size());
    dy.pDynamicStates = dyn.data();

    VkGraphicsPipelineCreateInfo gp{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gp.pNext = &rendering;
    gp.stageCount = static_cast<uint32_t>(desc.program->stageInfos().size());
    gp.pStages = desc.program->stageInfos().data();
    gp.pVertexInputState = desc.vertexInput ? desc.vertexInput : &noVertices;
    gp.pInputAssemblyState = &ia;
    gp.pViewportState = &vp;
    gp.pRasterizationState = &rs;
    gp.pMultisampleState = &ms;
    gp.pDepthStencilState = &desc.depthStencil;
    gp.pColorBlendState = &cb;
    gp.pDynamicState = &dy;
    gp.layout = desc.program->layout();
    VkPipeline pipeline = VK_NULL_HANDLE;
    {
        gpu::UnlockedForCompile compiling;
        RG_VK_TRY(
            vkCreateGraphicsPipelines(device, ctx.pipelineCache(), 1, &gp, nullptr, &pipeline));
    }
    return gpu::OwnedPipeline(device, pipeline);
}

}  // namespace rg::passes
