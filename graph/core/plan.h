// The compiled plan: ordered passes, physical resources with lifetimes and memory placement,
// and the barriers to record before each pass. Vulkan-free: the executor maps the sync enums
// below one-to-one onto VK_PIPELINE_STAGE_2_* / VK_ACCESS_2_* / VK_IMAGE_LAYOUT_*.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "graph.h"

namespace rg {

namespace stage {  // pipeline stage bits (synchronization2)
enum : uint32_t {
    None = 0,
    VertexShader = 1u << 0,
    FragmentShader = 1u << 1,
    ComputeShader = 1u << 2,
    EarlyFragmentTests = 1u << 3,
    LateFragmentTests = 1u << 4,
    ColorAttachmentOutput = 1u << 5,
    Copy = 1u << 6,  // transfer: copy, blit, clear
    Host = 1u << 7,
    AllCommands = 1u << 8,
    DrawIndirect = 1u << 9,
};
}  // namespace stage

namespace access {  // memory access bits (synchronization2)
enum : uint32_t {
    None = 0,
    ShaderSampledRead = 1u << 0,
    ShaderStorageRead = 1u << 1,
    ShaderStorageWrite = 1u << 2,
    UniformRead = 1u << 3,
    ColorAttachmentRead = 1u << 4,
    ColorAttachmentWrite = 1u << 5,
    DepthStencilRead = 1u << 6,
    DepthStencilWrite = 1u << 7,
    TransferRead = 1u << 8,
    TransferWrite = 1u << 9,
    HostRead = 1u << 10,
    HostWrite = 1u << 11,
    MemoryWrite = 1u << 12,
    IndirectCommandRead = 1u << 13,
};
}  // namespace access

enum class Layout : uint8_t {
    Undefined,
    General,  // storage images
    ColorAttachment,
    DepthStencilAttachment,
    DepthStencilReadOnly,
    ShaderReadOnly,
    TransferSrc,
    TransferDst,
};
const char* layoutName(Layout l);
std::string stageMaskName(uint32_t mask);   // "FragmentShader|ComputeShader"
std::string accessMaskName(uint32_t mask);  // "ShaderSampledRead|..."

// Memory requirement of one resource as the device reports it.
struct MemoryRequirements {
    uint64_t size = 0;
    uint64_t alignment = 1;
    uint32_t memoryTypeBits = ~0u;
};

struct Barrier {
    uint32_t resource = 0;  // index into Plan::resources
    uint32_t srcStages = stage::None;
    uint32_t srcAccess = access::None;
    uint32_t dstStages = stage::None;
    uint32_t dstAccess = access::None;
    Layout oldLayout = Layout::Undefined;  // textures only
    Layout newLayout = Layout::Undefined;
    int32_t aliasedFrom =
        -1;  // first use of memory last used by this resource (its contents are discarded)
};

// One access of a scheduled pass, resolved to the resource index and the state it needs.
struct PlanAccess {
    uint32_t resource = 0;
    Usage usage = Usage::Sampled;
    bool load = false;
    uint32_t stages = stage::None;
    uint32_t access = access::None;
    Layout layout = Layout::Undefined;
};

struct PlanPass {
    uint32_t desc = 0;  // index into GraphDesc::passes
    std::string name;
    std::string kind;
    PassType type = PassType::Raster;
    std::vector<PlanAccess> accesses;
    std::vector<Barrier> barriers;  // record these before the pass
};

struct CulledPass {
    std::string name;
    std::string
        reason;  // e.g. "disabled", "writes only 'ssao', which no kept pass reads and is not exported"
};

struct PlanResource {
    uint32_t desc = 0;  // index into GraphDesc::resources
    std::string name;
    ResourceKind kind = ResourceKind::Texture;
    Format format = Format::Undefined;
    uint32_t width = 0, height = 0, layers = 1, mips = 1;  // resolved against the output size
    bool cube = false;
    bool array = false;  // sampled as an array even with one layer (a scene_layers texture)
    uint64_t bufferSize = 0;
    uint32_t usageMask =
        0;  // bit (1 << Usage) for every usage in kept passes (image/buffer creation flags)
    bool transient = true;  // false for imported and exported resources
    bool imported = false;
    bool exported = false;
    bool persistent = false;
    int32_t firstPass = -1;  // index into Plan::passes of the first and last use
    int32_t lastPass = -1;
    MemoryRequirements memory;
    int32_t heap = -1;    // transient heap index; -1 = own allocation (imported / exported)
    uint64_t offset = 0;  // byte offset in its heap
    // State after the last pass (the executor starts readback / presentation from here).
    Layout finalLayout = Layout::Undefined;
    uint32_t finalStages = stage::None;
    uint32_t finalAccess = access::None;
};

// A block of memory that transient resources are placed in; one per memory-type class.
struct TransientHeap {
    uint32_t memoryTypeBits = ~0u;
    bool buffers = false;  // buffers and images never share a heap (no granularity worries)
    uint64_t size = 0;
};

struct StepTiming {
    std::string step;  // "validate", "cull", "schedule", "lifetimes", "alias", "barriers"
    double ms = 0.0;
};

struct Plan {
    uint32_t outputWidth = 0, outputHeight = 0;
    std::vector<PlanPass> passes;    // in execution order
    std::vector<CulledPass> culled;  // in declaration order
    std::vector<PlanResource>
        resources;  // only resources used by kept passes, in declaration order
    std::vector<TransientHeap> heaps;
    // Recorded after the last pass: imported and persistent textures go back to ShaderReadOnly,
    // the state every frame assumes they start in.
    std::vector<Barrier> finalBarriers;
    uint64_t transientBytesAliased = 0;    // sum of heap sizes
    uint64_t transientBytesUnaliased = 0;  // sum of transient sizes (aligned) without sharing
    std::vector<StepTiming> timings;

    int32_t findResource(const std::string& name) const;  // -1 when absent
    int32_t findPass(const std::string& name) const;
    std::string toDot() const;
    std::string toJson() const;
};

}  // namespace rg
