// GPU images and buffers (RAII), and the mapping of the graph's Vulkan-free enums
// (Format, Layout, stage/access bits, Usage) to Vulkan.
#pragma once

#include <string>
#include <vector>

#include "context.h"
#include "core/plan.h"

namespace rg::gpu {

VkFormat toVkFormat(Format f);
VkImageLayout toVkLayout(Layout l);
VkPipelineStageFlags2 toVkStages(uint32_t stages);
VkAccessFlags2 toVkAccess(uint32_t access);
VkImageAspectFlags aspectOf(Format f);
VkImageUsageFlags imageUsageOf(uint32_t usageMask, Format f);
VkBufferUsageFlags bufferUsageOf(uint32_t usageMask);

struct ImageDesc {
    std::string name;
    Format format = Format::RGBA8Unorm;
    uint32_t width = 1, height = 1, layers = 1, mips = 1;
    bool cube = false;
    bool array = false;  // array views even with one layer
    VkImageUsageFlags usage = 0;
};

// An image with a view over all its mips/layers, plus one view per mip (for storage writes
// and render targets of single mips). Memory is either its own sub-allocation or a range of
// a transient heap owned by someone else (aliasing).
class Image {
public:
    Image() = default;
    static Result<Image> create(Context& ctx, const ImageDesc& desc);  // own memory
    static Result<Image> createPlaced(Context& ctx, const ImageDesc& desc, VkDeviceMemory heap,
                                      uint64_t offset);  // aliased
    static VkMemoryRequirements requirements(Context& ctx, const ImageDesc& desc);

    VkImage image() const { return m_image.get(); }
    VkImageView view() const { return m_view.get(); }  // all mips and layers
    VkImageView mipView(uint32_t mip) const { return m_mipViews[mip].get(); }
    VkImageView attachmentView() const { return m_attachmentView.get(); }  // mip 0, layer 0 (2D)
    // A depth/stencil format's stencil aspect, all mips and layers (a pass's `as = "stencil"`
    // read: usampler2D, the value in .r); null for other formats.
    VkImageView stencilView() const { return m_stencilView.get(); }
    // Mip 0, layer `layer` (2D): one layer of a layered target as an attachment.
    VkImageView layerView(uint32_t layer) const {
        return layer == 0 ? m_attachmentView.get() : m_layerViews[layer - 1].get();
    }
    const ImageDesc& desc() const { return m_desc; }
    explicit operator bool() const { return static_cast<bool>(m_image); }

private:
    Result<void> createViews(Context& ctx);
    ImageDesc m_desc;
    OwnedImage m_image;
    Allocation m_memory;
    OwnedImageView m_view;
    OwnedImageView m_attachmentView;
    OwnedImageView m_stencilView;
    std::vector<OwnedImageView> m_layerViews;  // layers 1..n-1 (layer 0 is m_attachmentView)
    std::vector<OwnedImageView> m_mipViews;
};

class Buffer {
public:
    Buffer() = default;
    // hostVisible: mapped, coherent (staging, readback, per-frame uniforms).
    static Result<Buffer> create(Context& ctx, const std::string& name, uint64_t size,
                                 VkBufferUsageFlags usage, bool hostVisible);
    static Result<Buffer> createPlaced(Context& ctx, const std::string& name, uint64_t size,
                                       VkBufferUsageFlags usage, VkDeviceMemory heap,
                                       uint64_t offset);
    static VkMemoryRequirements requirements(Context& ctx, uint64_t size, VkBufferUsageFlags usage);

    VkBuffer buffer() const { return m_buffer.get(); }
    uint64_t size() const { return m_size; }
    void* mapped() const { return m_memory.mapped(); }
    explicit operator bool() const { return static_cast<bool>(m_buffer); }

private:
    OwnedBuffer m_buffer;
    Allocation m_memory;
    uint64_t m_size = 0;
};

// One image-layout / memory barrier, recorded with vkCmdPipelineBarrier2.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout,
                  VkImageLayout newLayout, uint32_t baseMip = 0,
                  uint32_t mipCount = VK_REMAINING_MIP_LEVELS);

// One global memory barrier (every resource), recorded with vkCmdPipelineBarrier2.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Texels of `format` (tightly packed as vkCmdCopyImageToBuffer writes them) to float RGBA-ish:
// `components` floats per texel; sRGB is decoded to linear, unorm to [0,1], integers as values,
// depth as depth. Depth/stencil formats give depth only.
void decodeTexels(Format format, const void* src, size_t count, float* dst);
// Bytes of one texel as copied to a buffer (depth aspect only for depth/stencil formats).
uint32_t copyTexelBytes(Format format);

}  // namespace rg::gpu

namespace rg::gpu {
// Inverse of decodeTexels for the colour formats uploads support (unorm8, sRGB8, half,
// float, uint32); `components` floats per texel in, texels of `format` out. False when the
// format cannot be uploaded.
bool encodeTexels(Format format, const float* src, size_t count, void* dst);
}  // namespace rg::gpu
