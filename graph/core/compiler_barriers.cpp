// barriers: the stages, access and layout of each access, and the barriers each pass needs from
// every resource's state simulated through the schedule.
#include "compiler_steps.h"

#include <algorithm>

namespace rg::compiler_steps {

// Layout a texture usage needs in a pass of this type (buffers: Undefined).
Layout usageLayout(Usage u, PassType type) {
    if (type == PassType::Transfer)
        return usageWrites(u) ? Layout::TransferDst : Layout::TransferSrc;
    switch (u) {
        case Usage::Sampled:
            return Layout::ShaderReadOnly;
        case Usage::UniformRead:
        case Usage::IndirectRead:
            return Layout::Undefined;
        case Usage::StorageRead:
        case Usage::StorageWrite:
        case Usage::StorageReadWrite:
            return Layout::General;
        case Usage::ColorAttachment:
            return Layout::ColorAttachment;
        case Usage::DepthStencilAttachment:
            return Layout::DepthStencilAttachment;
        case Usage::DepthStencilRead:
            return Layout::DepthStencilReadOnly;
        case Usage::CopySrc:
            return Layout::TransferSrc;
        case Usage::CopyDst:
            return Layout::TransferDst;
    }
    return Layout::Undefined;
}

namespace {

constexpr uint32_t kWriteAccessBits = access::ShaderStorageWrite | access::ColorAttachmentWrite |
                                      access::DepthStencilWrite | access::TransferWrite |
                                      access::HostWrite | access::MemoryWrite;

// Stages, access bits and layout an access needs, from its usage and the pass type.
void describeAccess(PlanAccess& a, PassType type, ResourceKind kind) {
    const uint32_t shaderStages = type == PassType::Compute
                                      ? stage::ComputeShader
                                      : stage::VertexShader | stage::FragmentShader;
    const bool texture = kind == ResourceKind::Texture;
    a.layout = texture ? usageLayout(a.usage, type) : Layout::Undefined;
    if (type == PassType::Transfer || a.usage == Usage::CopySrc || a.usage == Usage::CopyDst) {
        // Transfer passes (copy, blit, clear) touch everything through the transfer stage.
        a.stages = stage::Copy;
        a.access = (usageReads(a.usage, a.load) ? access::TransferRead : 0u) |
                   (usageWrites(a.usage) ? access::TransferWrite : 0u);
        return;
    }
    switch (a.usage) {
        case Usage::Sampled:
            a.stages = shaderStages;
            a.access = access::ShaderSampledRead;
            break;
        case Usage::UniformRead:
            a.stages = shaderStages;
            a.access = access::UniformRead;
            break;
        case Usage::StorageRead:
            a.stages = shaderStages;
            a.access = access::ShaderStorageRead;
            break;
        case Usage::StorageWrite:
            a.stages = shaderStages;
            a.access = access::ShaderStorageWrite;
            break;
        case Usage::StorageReadWrite:
            a.stages = shaderStages;
            a.access = access::ShaderStorageRead | access::ShaderStorageWrite;
            break;
        case Usage::ColorAttachment:
            a.stages = stage::ColorAttachmentOutput;
            a.access = access::ColorAttachmentWrite | (a.load ? access::ColorAttachmentRead : 0u);
            break;
        case Usage::DepthStencilAttachment:
            a.stages = stage::EarlyFragmentTests | stage::LateFragmentTests;
            a.access = access::DepthStencilWrite | (a.load ? access::DepthStencilRead : 0u);
            break;
        case Usage::DepthStencilRead:
            a.stages = stage::EarlyFragmentTests | stage::LateFragmentTests;
            a.access = access::DepthStencilRead;
            break;
        case Usage::IndirectRead:
            a.stages = stage::DrawIndirect;
            a.access = access::IndirectCommandRead;
            break;
        case Usage::CopySrc:
        case Usage::CopyDst:
            break;  // handled above
    }
}

// What is known about a resource between passes while planning barriers.
struct SyncState {
    Layout layout = Layout::Undefined;
    uint32_t writeStages = stage::None;  // last write
    uint32_t writeAccess = access::None;
    uint32_t readStages = stage::None;  // reads since the last write
    uint32_t readAccess = access::None;
    uint32_t visibleStages =
        stage::None;  // made visible to these by a barrier since the last write
    uint32_t visibleAccess = access::None;
};

}  // namespace

// barriers: simulate each resource's state through the schedule and emit what each pass needs.
void planBarriers(Compiler& c) {
    auto& resources = c.plan.resources;
    std::vector<SyncState> state(resources.size());
    for (size_t ri = 0; ri < resources.size(); ++ri) {
        if (!resources[ri].imported && !resources[ri].persistent) continue;
        // Whatever happened before the frame: assume any write, textures left ready for sampling.
        state[ri].layout = resources[ri].kind == ResourceKind::Texture ? Layout::ShaderReadOnly
                                                                       : Layout::Undefined;
        state[ri].writeStages = stage::AllCommands;
        state[ri].writeAccess = access::MemoryWrite;
    }

    struct Needed {
        uint32_t resource;
        uint32_t stages = 0, access = 0;
        Layout layout = Layout::Undefined;
        bool reads = false, writes = false;
    };
    for (uint32_t pi = 0; pi < c.plan.passes.size(); ++pi) {
        PlanPass& pass = c.plan.passes[pi];
        std::vector<Needed> needed;
        for (PlanAccess& a : pass.accesses)
            describeAccess(a, pass.type, resources[a.resource].kind);
        // A depth buffer both sampled and attached read-only is in DepthStencilReadOnly for both.
        for (PlanAccess& a : pass.accesses)
            if (a.usage == Usage::Sampled)
                for (const PlanAccess& b : pass.accesses)
                    if (b.resource == a.resource && b.usage == Usage::DepthStencilRead)
                        a.layout = Layout::DepthStencilReadOnly;
        for (PlanAccess& a : pass.accesses) {
            auto it = std::find_if(needed.begin(), needed.end(),
                                   [&](const Needed& n) { return n.resource == a.resource; });
            if (it == needed.end())
                it = needed.insert(needed.end(), Needed{a.resource, 0, 0, a.layout});
            it->stages |= a.stages;
            it->access |= a.access;
            it->reads = it->reads || usageReads(a.usage, a.load);
            it->writes = it->writes || usageWrites(a.usage);
        }
        for (const Needed& n : needed) {
            PlanResource& r = resources[n.resource];
            SyncState& s = state[n.resource];
            const bool texture = r.kind == ResourceKind::Texture;
            const bool layoutChange = texture && n.layout != s.layout;
            Barrier b;
            b.resource = n.resource;
            bool emit = false;
            if (r.transient && r.firstPass == static_cast<int32_t>(pi) &&
                !c.aliasPreds[n.resource].empty()) {
                // The memory held another resource: wait for all its users before reusing it.
                emit = true;
                b.aliasedFrom = c.aliasFrom[n.resource];
                for (uint32_t q : c.aliasPreds[n.resource]) {
                    b.srcStages |= resources[q].finalStages;
                    b.srcAccess |= resources[q].finalAccess;
                }
            }
            if (layoutChange || (n.writes && (s.writeStages | s.readStages) != 0)) {
                emit = true;  // transition, WAW or WAR
                b.srcStages |= s.writeStages | s.readStages;
                b.srcAccess |= s.writeAccess;
            } else if (n.reads && s.writeStages != 0 &&
                       ((n.stages & ~s.visibleStages) != 0 || (n.access & ~s.visibleAccess) != 0)) {
                emit = true;  // RAW not yet made visible to these stages
                b.srcStages |= s.writeStages;
                b.srcAccess |= s.writeAccess;
            }
            if (emit) {
                b.dstStages = n.stages;
                b.dstAccess = n.access;
                b.oldLayout = texture ? s.layout : Layout::Undefined;
                b.newLayout = texture ? n.layout : Layout::Undefined;
                pass.barriers.push_back(b);
            }

            if (n.writes) {
                s.writeStages = n.stages;
                s.writeAccess = n.access & kWriteAccessBits;
                s.readStages = s.readAccess = 0;
                s.visibleStages = s.visibleAccess = 0;
            } else if (layoutChange) {
                // The transition waited for every earlier access; only this pass's reads are pending.
                s.readStages = n.stages;
                s.readAccess = n.access;
                s.visibleStages = n.stages;
                s.visibleAccess = n.access;
            } else {
                s.readStages |= n.stages;
                s.readAccess |= n.access;
                if (emit) {
                    s.visibleStages |= n.stages;
                    s.visibleAccess |= n.access;
                }
            }
            if (texture) s.layout = n.layout;
            // Kept current so that later occupants of this memory can wait for it.
            r.finalLayout = s.layout;
            r.finalStages = s.writeStages | s.readStages;
            r.finalAccess = s.writeAccess | s.readAccess;
        }
    }
    // Imported and persistent textures end the frame as they start it: ready for sampling.
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        PlanResource& r = resources[ri];
        if ((!r.imported && !r.persistent) || r.kind != ResourceKind::Texture) continue;
        // Already there: a texture in ShaderReadOnly was not written since its last transition
        // (the executor's barrier at the start of each frame orders frames against each other).
        if (r.finalLayout == Layout::ShaderReadOnly) continue;
        if (r.firstPass < 0) continue;
        Barrier b;
        b.resource = ri;
        b.srcStages = r.finalStages;
        b.srcAccess = r.finalAccess & kWriteAccessBits;
        b.dstStages = stage::AllCommands;
        b.dstAccess = access::ShaderSampledRead;
        b.oldLayout = r.finalLayout;
        b.newLayout = Layout::ShaderReadOnly;
        c.plan.finalBarriers.push_back(b);
        r.finalLayout = Layout::ShaderReadOnly;
        r.finalStages = stage::AllCommands;
        r.finalAccess = access::ShaderSampledRead;
    }
}

}  // namespace rg::compiler_steps
