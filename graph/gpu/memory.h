// Device memory sub-allocation: large blocks per memory type, first-fit ranges inside them.
// Resources never get a vkAllocateMemory of their own. Host-visible blocks stay mapped.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "vk.h"

namespace rg::gpu {

class MemoryBlock;

// A range of a block; returns itself to the block when destroyed (move-only).
class Allocation {
public:
    Allocation() = default;
    Allocation(MemoryBlock* block, uint64_t offset, uint64_t size)
        : m_block(block), m_offset(offset), m_size(size) {}
    Allocation(const Allocation&) = delete;
    Allocation& operator=(const Allocation&) = delete;
    Allocation(Allocation&& o) noexcept { *this = std::move(o); }
    Allocation& operator=(Allocation&& o) noexcept;
    ~Allocation() { reset(); }

    void reset();
    VkDeviceMemory memory() const;
    uint64_t offset() const { return m_offset; }
    uint64_t size() const { return m_size; }
    void* mapped() const;  // nullptr unless host-visible
    explicit operator bool() const { return m_block != nullptr; }

private:
    MemoryBlock* m_block = nullptr;
    uint64_t m_offset = 0;
    uint64_t m_size = 0;
};

class MemoryBlock {
public:
    MemoryBlock(OwnedMemory memory, uint32_t typeIndex, uint64_t size, void* mapped);
    bool tryAllocate(uint64_t size, uint64_t alignment, uint64_t& offset);
    void free(uint64_t offset, uint64_t size);
    VkDeviceMemory memory() const { return m_memory.get(); }
    uint32_t typeIndex() const { return m_typeIndex; }
    uint64_t size() const { return m_size; }
    uint64_t used() const { return m_used; }
    void* mapped() const { return m_mapped; }

private:
    struct Range {
        uint64_t offset, size;
    };
    OwnedMemory m_memory;
    uint32_t m_typeIndex;
    uint64_t m_size;
    uint64_t m_used = 0;
    void* m_mapped;
    std::vector<Range> m_free;  // sorted by offset, coalesced
};

class Allocator {
public:
    static constexpr uint64_t kBlockSize = 64ull << 20;

    Allocator(VkPhysicalDevice physical, VkDevice device);
    Allocator(const Allocator&) = delete;
    Allocator& operator=(const Allocator&) = delete;

    // `required` / `preferred` are VkMemoryPropertyFlags.
    Result<Allocation> allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                                VkMemoryPropertyFlags preferred = 0);
    // A dedicated block for memory shared by aliased transients (it is the heap itself).
    Result<OwnedMemory> allocateHeap(uint64_t size, uint32_t memoryTypeBits, uint32_t& typeIndex);
    Result<uint32_t> findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                    VkMemoryPropertyFlags preferred) const;

    uint64_t blockBytes() const;  // device memory reserved in blocks
    size_t blockCount() const { return m_blocks.size(); }

private:
    VkDevice m_device;
    VkPhysicalDeviceMemoryProperties m_props{};
    std::vector<std::unique_ptr<MemoryBlock>> m_blocks;
};

}  // namespace rg::gpu
