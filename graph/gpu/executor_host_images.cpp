// Executor: the host's data and images in and out — contents uploaded into an imported texture
// (setImport), and the host images blitted in at a frame's start or out at its end.
#include "executor.h"

#include "executor_detail.h"

namespace rg::gpu {

Result<void> Executor::setImport(const std::string& name, const rg::Image& data) {
    m_importData[name] = data;
    if (!m_built) return {};
    const PhysicalResource* phys = m_built->table.find(name);
    if (!phys) return {};  // not used by the current plan
    if (!phys->image)
        return fail(ErrorCode::Unsupported,
                    "imported resource '" + name + "': only textures can be uploaded");
    const PlanResource& r = *phys->plan;
    if (data.width != r.width || data.height != r.height)
        return fail(ErrorCode::InvalidInput,
                    "imported resource '" + name + "' is " + std::to_string(r.width) + "x" +
                        std::to_string(r.height) + " but the data is " +
                        std::to_string(data.width) + "x" + std::to_string(data.height));
    const uint32_t comps = formatInfo(r.format).components;
    const size_t texels = size_t(r.width) * r.height;
    std::vector<float> src(texels * comps, 0.0f);
    for (size_t i = 0; i < texels; ++i)
        for (uint32_t c = 0; c < comps; ++c)
            src[i * comps + c] =
                c < data.channels ? data.pixels[i * data.channels + c] : (c == 3 ? 1.0f : 0.0f);
    const size_t bytes = texels * formatInfo(r.format).bytesPerTexel;
    auto staging =
        Buffer::create(m_ctx, name + ".staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    if (!encodeTexels(r.format, src.data(), texels, staging->mapped()))
        return fail(ErrorCode::Unsupported, "imported resource '" + name +
                                                "': cannot upload format '" +
                                                std::string(formatName(r.format)) + "'");
    VkImage image = phys->image->image();
    VkImageAspectFlags aspect = aspectOf(r.format);
    uint32_t mips = r.mips;
    return m_ctx.submitNow([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, mips);
        VkBufferImageCopy region{};
        region.imageSubresource = {aspect, 0, 0, 1};
        region.imageExtent = {r.width, r.height, 1};
        vkCmdCopyBufferToImage(cmd, staging->buffer(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, mips);
    });
}

void Executor::setHostImport(const std::string& name, const HostImage& image) {
    if (image.image)
        m_hostImports[name] = image;
    else
        m_hostImports.erase(name);
}
void Executor::setHostExport(const std::string& name, const HostImage& image) {
    if (image.image)
        m_hostExports[name] = image;
    else
        m_hostExports.erase(name);
}

// The host's images in or out: a blit each (nearest, equal sizes: a copy with format conversion),
// the host image from and back to its own layout; an import overwrites the imported texture and
// leaves it ShaderReadOnly (where every frame expects it), an export reads a texture from its
// final layout and puts it back there.
Result<void> Executor::recordHostCopies(VkCommandBuffer cmd, bool imports) {
    for (const auto& [name, host] : imports ? m_hostImports : m_hostExports) {
        const PhysicalResource* phys = m_built->table.find(name);
        const std::string what =
            std::string(imports ? "host image imported as '" : "host image exported from '") +
            name + "'";
        if (!phys || !phys->image)
            return fail(ErrorCode::InvalidInput, what + ": the plan has no texture of that name");
        const PlanResource& r = *phys->plan;
        if (imports && !r.imported)
            return fail(ErrorCode::InvalidInput,
                        what + ": declare it imported (rg.resource { import = true })");
        if (!imports && !r.exported && !r.persistent && !r.imported)
            return fail(ErrorCode::InvalidInput,
                        what +
                            ": it is transient (its memory is reused within the frame): export it "
                            "(capture it, or Renderer::keep)");
        if (host.width != r.width || host.height != r.height)
            return fail(ErrorCode::InvalidInput,
                        what + ": the host image is " + std::to_string(host.width) + "x" +
                            std::to_string(host.height) + ", the texture " +
                            std::to_string(r.width) + "x" + std::to_string(r.height));
        const VkImageAspectFlags aspect = aspectOf(r.format);
        VkImage graph = phys->image->image();
        const VkImageLayout graphBefore =
            imports ? VK_IMAGE_LAYOUT_UNDEFINED : toVkLayout(r.finalLayout);
        const VkImageLayout graphAfter =
            imports ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : toVkLayout(r.finalLayout);
        VkImage src = imports ? host.image : graph, dst = imports ? graph : host.image;
        const VkImageLayout srcLayout = imports ? host.layout : graphBefore,
                            dstLayout = imports ? graphBefore : host.layout;
        constexpr auto all = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        constexpr auto rw = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        imageBarrier(cmd, src, aspect, all, rw, VK_PIPELINE_STAGE_2_BLIT_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT, srcLayout,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        imageBarrier(
            cmd, dst, aspect, all, rw, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
            imports ? VK_IMAGE_LAYOUT_UNDEFINED : dstLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkImageBlit blit{};
        blit.srcSubresource = {aspect, 0, 0, 1};
        blit.dstSubresource = {aspect, 0, 0, 1};
        blit.srcOffsets[1] =
            blit.dstOffsets[1] = {static_cast<int32_t>(r.width), static_cast<int32_t>(r.height), 1};
        vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        imageBarrier(cmd, src, aspect, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                     all, rw, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     imports ? host.layout : graphAfter);
        imageBarrier(cmd, dst, aspect, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     all, rw, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     imports ? graphAfter : host.layout);
    }
    return {};
}

}  // namespace rg::gpu
