// compile(): validate -> cull -> schedule -> lifetimes -> alias -> barriers (Granite's bake()
// as named steps; Filament's reference-count culling). See graph.h for the ordering model.
// Each step is in its own file (compiler_steps.h); here the order, the timings and the estimate.
#include "compiler.h"

#include <algorithm>
#include <chrono>
#include <type_traits>

#include "compiler_steps.h"

namespace rg {

namespace {

using compiler_steps::alignUp;
using compiler_steps::Compiler;

constexpr uint64_t kTextureAlignment = 64 * 1024;
constexpr uint64_t kBufferAlignment = 256;  // common minStorageBufferOffsetAlignment upper bound

template <class Fn>
auto timed(Plan& plan, const char* step, Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&] {
        const std::chrono::duration<double, std::milli> ms =
            std::chrono::steady_clock::now() - start;
        plan.timings.push_back({step, ms.count()});
    };
    if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        finish();
    } else {
        auto r = fn();
        finish();
        return r;
    }
}

}  // namespace

MemoryRequirements estimateMemoryRequirements(const PlanResource& r) {
    MemoryRequirements m;
    if (r.kind == ResourceKind::Buffer) {
        m.alignment = kBufferAlignment;
        m.size = alignUp(r.bufferSize, kBufferAlignment);
        return m;
    }
    uint64_t texels = 0;
    const uint32_t mips = std::max(r.mips, 1u);
    for (uint32_t level = 0; level < mips; ++level)
        texels +=
            static_cast<uint64_t>(std::max(r.width >> level, 1u)) * std::max(r.height >> level, 1u);
    m.alignment = kTextureAlignment;
    m.size = alignUp(texels * formatInfo(r.format).bytesPerTexel * std::max(r.layers, 1u),
                     kTextureAlignment);
    return m;
}

Result<Plan> compile(const GraphDesc& graph, const CompileOptions& options) {
    Compiler c(graph, options);
    c.plan.outputWidth = options.outputWidth;
    c.plan.outputHeight = options.outputHeight;
    if (auto s = timed(c.plan, "validate", [&] { return validate(c); }); !s)
        return std::unexpected(std::move(s.error()));
    timed(c.plan, "cull", [&] { cull(c); });
    timed(c.plan, "schedule", [&] { schedule(c); });
    timed(c.plan, "lifetimes", [&] { computeLifetimes(c); });
    timed(c.plan, "alias", [&] { alias(c); });
    timed(c.plan, "barriers", [&] { planBarriers(c); });
    return std::move(c.plan);
}

}  // namespace rg
