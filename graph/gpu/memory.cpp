#include "memory.h"

#include <algorithm>

#include "core/check.h"

namespace rg::gpu {

namespace {
uint64_t alignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }
}  // namespace

Allocation& Allocation::operator=(Allocation&& o) noexcept {
    if (this != &o) {
        reset();
        m_block = std::exchange(o.m_block, nullptr);
        m_offset = o.m_offset;
        m_size = o.m_size;
    }
    return *this;
}

void Allocation::reset() {
    if (m_block) m_block->free(m_offset, m_size);
    m_block = nullptr;
}

VkDeviceMemory Allocation::memory() const { return m_block ? m_block->memory() : VK_NULL_HANDLE; }

void* Allocation::mapped() const {
    if (!m_block || !m_block->mapped()) return nullptr;
    return static_cast<char*>(m_block->mapped()) + m_offset;
}

MemoryBlock::MemoryBlock(OwnedMemory memory, uint32_t typeIndex, uint64_t size, void* mapped)
    : m_memory(std::move(memory)), m_typeIndex(typeIndex), m_size(size), m_mapped(mapped) {
    m_free.push_back({0, size});
}

bool MemoryBlock::tryAllocate(uint64_t size, uint64_t alignment, uint64_t& offset) {
    for (size_t i = 0; i < m_free.size(); ++i) {
        Range r = m_free[i];
        uint64_t start = alignUp(r.offset, alignment);
        if (start + size > r.offset + r.size) continue;
        // Split the free range into the part before (alignment padding) and after.
        std::vector<Range> pieces;
        if (start > r.offset) pieces.push_back({r.offset, start - r.offset});
        if (start + size < r.offset + r.size)
            pieces.push_back({start + size, r.offset + r.size - (start + size)});
        m_free.erase(m_free.begin() + static_cast<std::ptrdiff_t>(i));
        m_free.insert(m_free.begin() + static_cast<std::ptrdiff_t>(i), pieces.begin(),
                      pieces.end());
        offset = start;
        m_used += size;
        return true;
    }
    return false;
}

void MemoryBlock::free(uint64_t offset, uint64_t size) {
    auto it = std::lower_bound(m_free.begin(), m_free.end(), offset,
                               [](const Range& r, uint64_t o) { return r.offset < o; });
    it = m_free.insert(it, {offset, size});
    // Coalesce with the neighbours.
    if (it + 1 != m_free.end() && it->offset + it->size == (it + 1)->offset) {
        it->size += (it + 1)->size;
        m_free.erase(it + 1);
    }
    if (it != m_free.begin() && (it - 1)->offset + (it - 1)->size == it->offset) {
        (it - 1)->size += it->size;
        m_free.erase(it);
    }
    m_used -= size;
}

Allocator::Allocator(VkPhysicalDevice physical, VkDevice device) : m_device(device) {
    vkGetPhysicalDeviceMemoryProperties(physical, &m_props);
}

Result<uint32_t> Allocator::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                           VkMemoryPropertyFlags preferred) const {
    int best = -1;
    for (uint32_t i = 0; i < m_props.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        VkMemoryPropertyFlags f = m_props.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (best < 0) best = static_cast<int>(i);
    }
    if (best < 0)
        return fail(ErrorCode::Device,
                    "no Vulkan memory type with the required properties (flags " +
                        std::to_string(required) + ", type bits " + std::to_string(typeBits) + ")");
    return static_cast<uint32_t>(best);
}

Result<Allocation> Allocator::allocate(const VkMemoryRequirements& req,
                                       VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred) {
    auto type = findMemoryType(req.memoryTypeBits, required, preferred);
    if (!type) return std::unexpected(type.error());
    for (auto& block : m_blocks) {
        uint64_t offset = 0;
        if (block->typeIndex() == *type && block->tryAllocate(req.size, req.alignment, offset))
            return Allocation(block.get(), offset, req.size);
    }
    uint64_t size = std::max(kBlockSize, alignUp(req.size, 1ull << 20));
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = *type;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    RG_VK_TRY(vkAllocateMemory(m_device, &info, nullptr, &mem));
    OwnedMemory owned(m_device, mem);
    void* mapped = nullptr;
    if (m_props.memoryTypes[*type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
        RG_VK_TRY(vkMapMemory(m_device, mem, 0, VK_WHOLE_SIZE, 0, &mapped));
    m_blocks.push_back(std::make_unique<MemoryBlock>(std::move(owned), *type, size, mapped));
    uint64_t offset = 0;
    RG_CHECK(m_blocks.back()->tryAllocate(req.size, req.alignment, offset));
    return Allocation(m_blocks.back().get(), offset, req.size);
}

Result<OwnedMemory> Allocator::allocateHeap(uint64_t size, uint32_t memoryTypeBits,
                                            uint32_t& typeIndex) {
    auto type = findMemoryType(memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    if (!type) type = findMemoryType(memoryTypeBits, 0, 0);
    if (!type) return std::unexpected(type.error());
    typeIndex = *type;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = *type;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    RG_VK_TRY(vkAllocateMemory(m_device, &info, nullptr, &mem));
    return OwnedMemory(m_device, mem);
}

uint64_t Allocator::blockBytes() const {
    uint64_t total = 0;
    for (const auto& b : m_blocks) total += b->size();
    return total;
}

}  // namespace rg::gpu
