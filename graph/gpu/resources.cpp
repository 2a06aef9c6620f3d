#include "resources.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/check.h"

namespace rg::gpu {

VkFormat toVkFormat(Format f) {
    switch (f) {
        case Format::R8Unorm:
            return VK_FORMAT_R8_UNORM;
        case Format::RG8Unorm:
            return VK_FORMAT_R8G8_UNORM;
        case Format::RGBA8Unorm:
            return VK_FORMAT_R8G8B8A8_UNORM;
        case Format::RGBA8Srgb:
            return VK_FORMAT_R8G8B8A8_SRGB;
        case Format::RGB10A2Unorm:
            return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
        case Format::R11G11B10F:
            return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
        case Format::R16F:
            return VK_FORMAT_R16_SFLOAT;
        case Format::RG16F:
            return VK_FORMAT_R16G16_SFLOAT;
        case Format::RGBA16F:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case Format::R32F:
            return VK_FORMAT_R32_SFLOAT;
        case Format::RG32F:
            return VK_FORMAT_R32G32_SFLOAT;
        case Format::RGBA32F:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
        case Format::R8Uint:
            return VK_FORMAT_R8_UINT;
        case Format::R32Uint:
            return VK_FORMAT_R32_UINT;
        case Format::RGBA32Uint:
            return VK_FORMAT_R32G32B32A32_UINT;
        case Format::D16:
            return VK_FORMAT_D16_UNORM;
        case Format::D32F:
            return VK_FORMAT_D32_SFLOAT;
        case Format::D24S8:
            return VK_FORMAT_D24_UNORM_S8_UINT;
        case Format::D32FS8:
            return VK_FORMAT_D32_SFLOAT_S8_UINT;
        default:
            return VK_FORMAT_UNDEFINED;
    }
}

VkImageLayout toVkLayout(Layout l) {
    switch (l) {
        case Layout::Undefined:
            return VK_IMAGE_LAYOUT_UNDEFINED;
        case Layout::General:
            return VK_IMAGE_LAYOUT_GENERAL;
        case Layout::ColorAttachment:
            return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        case Layout::DepthStencilAttachment:
            return VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        case Layout::DepthStencilReadOnly:
            return VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
        case Layout::ShaderReadOnly:
            return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        case Layout::TransferSrc:
            return VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        case Layout::TransferDst:
            return VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    }
    return VK_IMAGE_LAYOUT_UNDEFINED;
}

VkPipelineStageFlags2 toVkStages(uint32_t s) {
    VkPipelineStageFlags2 f = 0;
    if (s & stage::VertexShader) f |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    if (s & stage::FragmentShader) f |= VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    if (s & stage::ComputeShader) f |= VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    if (s & stage::EarlyFragmentTests) f |= VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT;
    if (s & stage::LateFragmentTests) f |= VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    if (s & stage::ColorAttachmentOutput) f |= VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    if (s & stage::Copy) f |= VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    if (s & stage::Host) f |= VK_PIPELINE_STAGE_2_HOST_BIT;
    if (s & stage::AllCommands) f |= VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    if (s & stage::DrawIndirect) f |= VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
    return f;
}

VkAccessFlags2 toVkAccess(uint32_t a) {
    VkAccessFlags2 f = 0;
    if (a & access::ShaderSampledRead) f |= VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    if (a & access::ShaderStorageRead) f |= VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    if (a & access::ShaderStorageWrite) f |= VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    if (a & access::UniformRead) f |= VK_ACCESS_2_UNIFORM_READ_BIT;
    if (a & access::ColorAttachmentRead) f |= VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
    if (a & access::ColorAttachmentWrite) f |= VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    if (a & access::DepthStencilRead) f |= VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    if (a & access::DepthStencilWrite) f |= VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    if (a & access::TransferRead) f |= VK_ACCESS_2_TRANSFER_READ_BIT;
    if (a & access::TransferWrite) f |= VK_ACCESS_2_TRANSFER_WRITE_BIT;
    if (a & access::HostRead) f |= VK_ACCESS_2_HOST_READ_BIT;
    if (a & access::HostWrite) f |= VK_ACCESS_2_HOST_WRITE_BIT;
    if (a & access::MemoryWrite) f |= VK_ACCESS_2_MEMORY_WRITE_BIT;
    if (a & access::IndirectCommandRead) f |= VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
    return f;
}

VkImageAspectFlags aspectOf(Format f) {
    const auto& info = formatInfo(f);
    VkImageAspectFlags a = 0;
    if (info.depth) a |= VK_IMAGE_ASPECT_DEPTH_BIT;
    if (info.stencil) a |= VK_IMAGE_ASPECT_STENCIL_BIT;
    return a ? a : static_cast<VkImageAspectFlags>(VK_IMAGE_ASPECT_COLOR_BIT);
}

VkImageUsageFlags imageUsageOf(uint32_t mask, Format f) {
    auto has = [&](Usage u) { return (mask & (1u << static_cast<uint32_t>(u))) != 0; };
    // Every image may be read back or cleared by the executor, and has views (which need a
    // view-compatible usage even for an image only copied to and from).
    VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                              VK_IMAGE_USAGE_SAMPLED_BIT;
    if (has(Usage::StorageRead) || has(Usage::StorageWrite) || has(Usage::StorageReadWrite))
        usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    if (has(Usage::ColorAttachment)) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (has(Usage::DepthStencilAttachment) || has(Usage::DepthStencilRead))
        usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    (void)f;
    return usage;
}

VkBufferUsageFlags bufferUsageOf(uint32_t mask) {
    auto has = [&](Usage u) { return (mask & (1u << static_cast<uint32_t>(u))) != 0; };
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (has(Usage::UniformRead)) usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (has(Usage::StorageRead) || has(Usage::StorageWrite) || has(Usage::StorageReadWrite))
        usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (has(Usage::IndirectRead)) usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    return usage;
}

namespace {

VkImageCreateInfo imageInfo(const ImageDesc& d) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.flags = d.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = toVkFormat(d.format);
    info.extent = {d.width, d.height, 1};
    info.mipLevels = d.mips;
    info.arrayLayers = d.layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = d.usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    return info;
}

VkImageView makeView(VkDevice device, VkImage image, const ImageDesc& d, VkImageViewType type,
                     uint32_t baseMip, uint32_t mips, uint32_t layers, VkResult& result) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image;
    info.viewType = type;
    info.format = toVkFormat(d.format);
    VkImageAspectFlags aspect = aspectOf(d.format);
    // A sampled view of a depth/stencil image sees depth only.
    if (aspect & VK_IMAGE_ASPECT_DEPTH_BIT) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    info.subresourceRange = {aspect, baseMip, mips, 0, layers};
    VkImageView view = VK_NULL_HANDLE;
    result = vkCreateImageView(device, &info, nullptr, &view);
    return view;
}

// Lavapipe reports 16-byte alignment for images, but llvmpipe's rasteriser reads and writes them
// with aligned 256-bit vector instructions: an image bound 16 bytes into a block (after a small
// buffer) crashed the JIT code with a general-protection fault. Every image — own allocation or
// placed in a transient heap — is aligned to 64 bytes, as llvmpipe aligns its own textures.
constexpr VkDeviceSize kMinImageAlignment = 64;

}  // namespace

VkMemoryRequirements Image::requirements(Context& ctx, const ImageDesc& desc) {
    VkImageCreateInfo info = imageInfo(desc);
    VkDeviceImageMemoryRequirements q{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    q.pCreateInfo = &info;
    VkMemoryRequirements2 out{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceImageMemoryRequirements(ctx.device(), &q, &out);
    out.memoryRequirements.alignment =
        std::max(out.memoryRequirements.alignment, kMinImageAlignment);
    return out.memoryRequirements;
}

Result<void> Image::createViews(Context& ctx) {
    VkDevice dev = ctx.device();
    VkResult r = VK_SUCCESS;
    VkImageViewType all =
        m_desc.cube ? (m_desc.layers > 6 ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE)
        : m_desc.layers > 1 || m_desc.array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                            : VK_IMAGE_VIEW_TYPE_2D;
    m_view = OwnedImageView(
        dev, makeView(dev, m_image.get(), m_desc, all, 0, m_desc.mips, m_desc.layers, r));
    RG_VK_TRY(r);
    if (formatInfo(m_desc.format).stencil) {
        VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        info.image = m_image.get();
        info.viewType = all;
        info.format = toVkFormat(m_desc.format);
        info.subresourceRange = {VK_IMAGE_ASPECT_STENCIL_BIT, 0, m_desc.mips, 0, m_desc.layers};
        VkImageView v = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateImageView(dev, &info, nullptr, &v));
        m_stencilView = OwnedImageView(dev, v);
    }
    // Attachment view keeps both aspects of a depth/stencil format.
    {
        VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        info.image = m_image.get();
        info.viewType = VK_IMAGE_VIEW_TYPE_2D;
        info.format = toVkFormat(m_desc.format);
        info.subresourceRange = {aspectOf(m_desc.format), 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateImageView(dev, &info, nullptr, &v));
        m_attachmentView = OwnedImageView(dev, v);
        for (uint32_t layer = 1; layer < m_desc.layers; ++layer) {
            info.subresourceRange.baseArrayLayer = layer;
            VkImageView lv = VK_NULL_HANDLE;
            RG_VK_TRY(vkCreateImageView(dev, &info, nullptr, &lv));
            m_layerViews.emplace_back(dev, lv);
        }
    }
    for (uint32_t m = 0; m < m_desc.mips; ++m) {
        VkImageViewType t =
            m_desc.layers > 1 || m_desc.array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
        m_mipViews.emplace_back(dev,
                                makeView(dev, m_image.get(), m_desc, t, m, 1, m_desc.layers, r));
        RG_VK_TRY(r);
    }
    ctx.setName(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(m_image.get()), m_desc.name);
    return {};
}

Result<Image> Image::create(Context& ctx, const ImageDesc& desc) {
    Image img;
    img.m_desc = desc;
    VkImageCreateInfo info = imageInfo(desc);
    if (info.format == VK_FORMAT_UNDEFINED)
        return fail(ErrorCode::Unsupported,
                    "image '" + desc.name + "': format has no Vulkan format");
    VkImage image = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateImage(ctx.device(), &info, nullptr, &image));
    img.m_image = OwnedImage(ctx.device(), image);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image, &req);
    req.alignment = std::max(req.alignment, kMinImageAlignment);  // see kMinImageAlignment
    auto mem = ctx.allocator().allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!mem) mem = ctx.allocator().allocate(req, 0);
    if (!mem) return std::unexpected(mem.error());
    img.m_memory = std::move(*mem);
    RG_VK_TRY(vkBindImageMemory(ctx.device(), image, img.m_memory.memory(), img.m_memory.offset()));
    if (auto r = img.createViews(ctx); !r) return std::unexpected(r.error());
    return img;
}

Result<Image> Image::createPlaced(Context& ctx, const ImageDesc& desc, VkDeviceMemory heap,
                                  uint64_t offset) {
    Image img;
    img.m_desc = desc;
    VkImageCreateInfo info = imageInfo(desc);
    VkImage image = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateImage(ctx.device(), &info, nullptr, &image));
    img.m_image = OwnedImage(ctx.device(), image);
    RG_VK_TRY(vkBindImageMemory(ctx.device(), image, heap, offset));
    if (auto r = img.createViews(ctx); !r) return std::unexpected(r.error());
    return img;
}

VkMemoryRequirements Buffer::requirements(Context& ctx, uint64_t size, VkBufferUsageFlags usage) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VkDeviceBufferMemoryRequirements q{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
    q.pCreateInfo = &info;
    VkMemoryRequirements2 out{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceBufferMemoryRequirements(ctx.device(), &q, &out);
    return out.memoryRequirements;
}

Result<Buffer> Buffer::create(Context& ctx, const std::string& name, uint64_t size,
                              VkBufferUsageFlags usage, bool hostVisible) {
    Buffer b;
    b.m_size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VkBuffer buf = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateBuffer(ctx.device(), &info, nullptr, &buf));
    b.m_buffer = OwnedBuffer(ctx.device(), buf);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device(), buf, &req);
    VkMemoryPropertyFlags required =
        hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                    : 0;
    VkMemoryPropertyFlags preferred =
        hostVisible ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    auto mem = ctx.allocator().allocate(req, required, preferred);
    if (!mem) return std::unexpected(mem.error());
    b.m_memory = std::move(*mem);
    RG_VK_TRY(vkBindBufferMemory(ctx.device(), buf, b.m_memory.memory(), b.m_memory.offset()));
    ctx.setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buf), name);
    return b;
}

Result<Buffer> Buffer::createPlaced(Context& ctx, const std::string& name, uint64_t size,
                                    VkBufferUsageFlags usage, VkDeviceMemory heap,
                                    uint64_t offset) {
    Buffer b;
    b.m_size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VkBuffer buf = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateBuffer(ctx.device(), &info, nullptr, &buf));
    b.m_buffer = OwnedBuffer(ctx.device(), buf);
    RG_VK_TRY(vkBindBufferMemory(ctx.device(), buf, heap, offset));
    ctx.setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buf), name);
    return b;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout,
                  VkImageLayout newLayout, uint32_t baseMip, uint32_t mipCount) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = oldLayout;
    b.newLayout = newLayout;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, baseMip, mipCount, 0, VK_REMAINING_ARRAY_LAYERS};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

namespace {

// Exact, by moving the bits (a normal half's exponent rebiased from 15 to 127, its mantissa
// widened); subnormals are mant · 2⁻²⁴, exact in a float. std::ldexp per value made a 1280×720
// RGBA16F readback ~45 ms of `rgraph render`'s writing; this is a few.
float halfToFloat(uint16_t h) {
    const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu,
                   mant = h & 0x3ffu;
    if (exp == 0) {
        const float v = static_cast<float>(mant) * 5.9604644775390625e-8f;  // 2⁻²⁴
        return sign ? -v : v;
    }
    const uint32_t bits = sign | (exp == 31 ? 0x7f800000u | (mant ? 0x400000u : 0u)
                                            : (exp + 112u) << 23 | mant << 13);
    return std::bit_cast<float>(bits);
}

// Unsigned 11/10-bit floats of B10G11R11 (5-bit exponent, no sign).
float smallFloat(uint32_t bits, uint32_t mantBits) {
    uint32_t exp = bits >> mantBits, mant = bits & ((1u << mantBits) - 1);
    if (exp == 0) return std::ldexp(static_cast<float>(mant), -14 - static_cast<int>(mantBits));
    if (exp == 31) return mant ? NAN : INFINITY;
    return std::ldexp(static_cast<float>(mant | (1u << mantBits)),
                      static_cast<int>(exp) - 15 - static_cast<int>(mantBits));
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

uint32_t copyTexelBytes(Format f) {
    switch (f) {
        case Format::D24S8:
        case Format::D32FS8:
            return 4;  // depth aspect alone
        default:
            return formatInfo(f).bytesPerTexel;
    }
}

void decodeTexels(Format format, const void* src, size_t count, float* dst) {
    const auto* b = static_cast<const uint8_t*>(src);
    const uint32_t n = formatInfo(format).components;
    for (size_t i = 0; i < count; ++i) {
        switch (format) {
            case Format::R8Unorm:
            case Format::RG8Unorm:
            case Format::RGBA8Unorm:
                for (uint32_t c = 0; c < n; ++c) dst[i * n + c] = b[i * n + c] / 255.0f;
                break;
            case Format::RGBA8Srgb:
                for (uint32_t c = 0; c < 4; ++c) {
                    float v = b[i * 4 + c] / 255.0f;
                    dst[i * 4 + c] = c < 3 ? srgbToLinear(v) : v;
                }
                break;
            case Format::RGB10A2Unorm: {
                uint32_t v;
                std::memcpy(&v, b + i * 4, 4);
                dst[i * 4 + 0] = static_cast<float>(v & 1023u) / 1023.0f;
                dst[i * 4 + 1] = static_cast<float>((v >> 10) & 1023u) / 1023.0f;
                dst[i * 4 + 2] = static_cast<float>((v >> 20) & 1023u) / 1023.0f;
                dst[i * 4 + 3] = static_cast<float>(v >> 30) / 3.0f;
                break;
            }
            case Format::R11G11B10F: {
                uint32_t v;
                std::memcpy(&v, b + i * 4, 4);
                dst[i * 3 + 0] = smallFloat(v & 0x7ffu, 6);
                dst[i * 3 + 1] = smallFloat((v >> 11) & 0x7ffu, 6);
                dst[i * 3 + 2] = smallFloat(v >> 22, 5);
                break;
            }
            case Format::R16F:
            case Format::RG16F:
            case Format::RGBA16F:
                for (uint32_t c = 0; c < n; ++c) {
                    uint16_t h;
                    std::memcpy(&h, b + (i * n + c) * 2, 2);
                    dst[i * n + c] = halfToFloat(h);
                }
                break;
            case Format::R32F:
            case Format::RG32F:
            case Format::RGBA32F:
            case Format::D32F:
                std::memcpy(dst + i * n, b + i * n * 4, n * 4);
                break;
            case Format::R8Uint:
                dst[i] = b[i];
                break;
            case Format::R32Uint:
            case Format::RGBA32Uint:
                for (uint32_t c = 0; c < n; ++c) {
                    uint32_t v;
                    std::memcpy(&v, b + (i * n + c) * 4, 4);
                    dst[i * n + c] = static_cast<float>(v);
                }
                break;
            case Format::D16: {
                uint16_t v;
                std::memcpy(&v, b + i * 2, 2);
                dst[i] = static_cast<float>(v) / 65535.0f;
                break;
            }
            case Format::D24S8: {
                uint32_t v;
                std::memcpy(&v, b + i * 4, 4);
                dst[i] = static_cast<float>(v & 0xffffffu) / 16777215.0f;
                break;
            }
            case Format::D32FS8:
                std::memcpy(dst + i, b + i * 4, 4);
                break;
            default:
                RG_CHECK(false) << "decodeTexels: unhandled format " << formatName(format);
        }
    }
}

}  // namespace rg::gpu

namespace rg::gpu {

namespace {

uint16_t floatToHalf(float f) {
    uint32_t x;
    std::memcpy(&x, &f, 4);
    uint32_t sign = (x >> 16) & 0x8000u;
    int32_t exp = static_cast<int32_t>((x >> 23) & 0xffu) - 127 + 15;
    uint32_t mant = x & 0x7fffffu;
    if (((x >> 23) & 0xffu) == 0xffu)
        return static_cast<uint16_t>(sign | 0x7c00u | (mant ? 0x200u : 0u));
    if (exp >= 31) return static_cast<uint16_t>(sign | 0x7c00u);
    if (exp <= 0) {
        if (exp < -10) return static_cast<uint16_t>(sign);
        mant |= 0x800000u;
        uint32_t shift = static_cast<uint32_t>(14 - exp);
        uint32_t h = mant >> shift;
        uint32_t rem = mant & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (h & 1u))) ++h;  // round to nearest even
        return static_cast<uint16_t>(sign | h);
    }
    uint32_t h = (static_cast<uint32_t>(exp) << 10) | (mant >> 13);
    uint32_t rem = mant & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;
    return static_cast<uint16_t>(sign | h);
}

uint8_t unorm8(float v) {
    v = v < 0.f ? 0.f : v > 1.f ? 1.f : v;
    return static_cast<uint8_t>(std::lround(v * 255.0f));
}

float linearToSrgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

bool encodeTexels(Format format, const float* src, size_t count, void* dst) {
    auto* b = static_cast<uint8_t*>(dst);
    const uint32_t n = formatInfo(format).components;
    const size_t total = count * n;
    switch (format) {
        case Format::R8Unorm:
        case Format::RG8Unorm:
        case Format::RGBA8Unorm:
            for (size_t i = 0; i < total; ++i) b[i] = unorm8(src[i]);
            return true;
        case Format::RGBA8Srgb:
            for (size_t i = 0; i < total; ++i)
                b[i] = unorm8(i % 4 == 3 ? src[i] : linearToSrgb(src[i]));
            return true;
        case Format::R16F:
        case Format::RG16F:
        case Format::RGBA16F:
            for (size_t i = 0; i < total; ++i) {
                uint16_t h = floatToHalf(src[i]);
                std::memcpy(b + i * 2, &h, 2);
            }
            return true;
        case Format::R32F:
        case Format::RG32F:
        case Format::RGBA32F:
            std::memcpy(b, src, total * 4);
            return true;
        case Format::R32Uint:
        case Format::RGBA32Uint:
            for (size_t i = 0; i < total; ++i) {
                auto v = static_cast<uint32_t>(src[i] < 0 ? 0 : src[i]);
                std::memcpy(b + i * 4, &v, 4);
            }
            return true;
        default:
            return false;
    }
}

}  // namespace rg::gpu
