// Executor: reading back after finish() — an exported texture's layer and mip, a buffer's bytes,
// and what a readback pass copied.
#include "executor.h"

#include <algorithm>
#include <cstring>

#include "executor_detail.h"

namespace rg::gpu {

Result<const PhysicalResource*> Executor::exportedResource(const std::string& name) {
    if (!m_built) return fail(ErrorCode::InvalidInput, "readback before the graph was built");
    const PhysicalResource* phys = m_built->table.find(name);
    if (!phys) {
        if (m_built->graph.findResource(name))
            return fail(
                ErrorCode::InvalidInput,
                "resource '" + name + "' is not written: no pass that runs writes or reads it");
        return fail(ErrorCode::NotFound, "no resource named '" + name + "'");
    }
    if (!phys->plan->exported && !phys->plan->imported && !phys->plan->persistent)
        return fail(ErrorCode::InvalidInput,
                    "resource '" + name + "' is transient: capture (export) it to read it back");
    if (auto r = finish(); !r) return std::unexpected(r.error());
    return phys;
}

Result<rg::Image> Executor::readback(const std::string& name, uint32_t layer, uint32_t mip,
                                     bool stencil) {
    auto found = exportedResource(name);
    if (!found) return std::unexpected(found.error());
    const PhysicalResource* phys = *found;
    if (!phys->image)
        return fail(ErrorCode::InvalidInput,
                    "resource '" + name + "' is a buffer: use readbackBuffer");
    const PlanResource& r = *phys->plan;
    if (layer >= std::max(r.layers, 1u) || mip >= std::max(r.mips, 1u))
        return fail(ErrorCode::InvalidInput,
                    "resource '" + name + "': no layer " + std::to_string(layer) + " / mip " +
                        std::to_string(mip) + " (it has " + std::to_string(r.layers) + " and " +
                        std::to_string(r.mips) + ")");
    const uint32_t width = std::max(r.width >> mip, 1u), height = std::max(r.height >> mip, 1u);
    if (stencil && !formatInfo(r.format).stencil)
        return fail(ErrorCode::InvalidInput, "resource '" + name + "' has no stencil");
    const uint32_t texelBytes = stencil ? 1u : copyTexelBytes(r.format);
    const size_t texels = size_t(width) * height;
    auto host = Buffer::create(m_ctx, name + ".readback", texels * texelBytes,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!host) return std::unexpected(host.error());
    VkImage image = phys->image->image();
    VkImageAspectFlags aspect = aspectOf(r.format);
    VkImageAspectFlags copyAspect =
        stencil                      ? static_cast<VkImageAspectFlags>(VK_IMAGE_ASPECT_STENCIL_BIT)
        : formatInfo(r.format).depth ? static_cast<VkImageAspectFlags>(VK_IMAGE_ASPECT_DEPTH_BIT)
                                     : aspect;
    Layout last =
        r.imported && r.finalLayout == Layout::Undefined ? Layout::ShaderReadOnly : r.finalLayout;
    auto sub = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        imageBarrier(
            cmd, image, aspect, toVkStages(r.finalStages) | VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
            toVkAccess(r.finalAccess), VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
            toVkLayout(last), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {copyAspect, mip, layer, 1};
        region.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host->buffer(), 1,
                               &region);
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     toVkLayout(last == Layout::Undefined ? Layout::General : last));
    });
    if (!sub) return std::unexpected(sub.error());
    rg::Image out;
    out.width = width;
    out.height = height;
    out.channels = isDepthStencil(r.format) ? 1 : formatInfo(r.format).components;
    out.pixels.resize(texels * out.channels);
    if (stencil) {
        const auto* bytes = static_cast<const uint8_t*>(host->mapped());
        for (size_t i = 0; i < texels; ++i) out.pixels[i] = static_cast<float>(bytes[i]);
    } else
        decodeTexels(r.format, host->mapped(), texels, out.pixels.data());
    return out;
}

Result<std::vector<uint8_t>> Executor::readbackBuffer(const std::string& name) {
    auto found = exportedResource(name);
    if (!found) return std::unexpected(found.error());
    const PhysicalResource* phys = *found;
    if (!phys->buffer)
        return fail(ErrorCode::InvalidInput, "resource '" + name + "' is a texture: use readback");
    const uint64_t size = phys->buffer->size();
    auto host =
        Buffer::create(m_ctx, name + ".readback", size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!host) return std::unexpected(host.error());
    VkBuffer src = phys->buffer->buffer();
    auto sub = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, src, host->buffer(), 1, &region);
    });
    if (!sub) return std::unexpected(sub.error());
    std::vector<uint8_t> out(size);
    std::memcpy(out.data(), host->mapped(), size);
    return out;
}

Result<rg::Image> Executor::passResult(const std::string& pass) {
    if (auto r = finish(); !r) return std::unexpected(r.error());
    int32_t index = m_built ? m_built->plan.findPass(pass) : -1;
    if (index < 0) return fail(ErrorCode::NotFound, "no kept pass named '" + pass + "'");
    auto result = m_built->instances[static_cast<size_t>(index)]->hostResult();
    if (!result)
        return fail(
            ErrorCode::InvalidInput,
            "pass '" + pass + "' has no host result (not a readback pass, or no frame ran)");
    return *result;
}

}  // namespace rg::gpu
