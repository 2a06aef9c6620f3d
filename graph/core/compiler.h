// compile(): GraphDesc -> Plan as named steps, each a function (compiler.cpp runs them in order):
//   validate (compiler_validate.cpp) -> cull -> schedule (compiler_cull.cpp) -> lifetimes -> alias
//   (compiler_lifetimes.cpp) -> barriers (compiler_barriers.cpp).
// No Vulkan: memory requirements come from a callback (the GPU layer asks the device;
// tests use estimateMemoryRequirements).
#pragma once

#include <functional>

#include "plan.h"
#include "result.h"

namespace rg {

using MemoryRequirementsFn = std::function<MemoryRequirements(const PlanResource&)>;

struct CompileOptions {
    uint32_t outputWidth = 1280;
    uint32_t outputHeight = 720;
    bool alias = true;                        // share memory between non-overlapping transients
    MemoryRequirementsFn memoryRequirements;  // default: estimateMemoryRequirements
    // The plan this one replaces (a reconfiguration: passes toggled, a parameter that changes the
    // graph): a transient of the same name, size and memory class keeps its heap offset when no
    // resource live beside it is there, and a heap keeps its size when the new one fits in it, so
    // the executor reuses the images and the passes over them. Unset: the tightest packing.
    const Plan* previous = nullptr;
};

// Size = texels * bytes per texel over all mips and layers, rounded to 64 KiB alignment.
// Buffers: size rounded up to 256 bytes, 256-byte alignment.
MemoryRequirements estimateMemoryRequirements(const PlanResource& r);

// Errors are ErrorCode::InvalidInput with the first problem in declaration order (resources,
// then passes, then versions, then cycles); a message is prefixed with "origin: " when the pass
// or resource it names has an origin. Culling keeps side-effect passes, writers of exported or
// imported resources, and what they need through RAW, WAW and `after` edges (not WAR).
// compile() keeps no global state; the plan owns no GPU objects.
Result<Plan> compile(const GraphDesc& graph, const CompileOptions& options);

}  // namespace rg
