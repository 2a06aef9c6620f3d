// lifetimes and alias: one PlanResource per resource a kept pass uses, with its size and first and
// last pass, and the transients placed in heaps, sharing memory where lifetimes do not meet.
#include "compiler_steps.h"

#include <algorithm>

namespace rg::compiler_steps {

namespace {

uint64_t resolvedBufferSize(const BufferDesc& b, const CompileOptions& o) {
    if (b.tileSize == 0) return b.size;
    const uint64_t tx = (o.outputWidth + b.tileSize - 1) / b.tileSize,
                   ty = (o.outputHeight + b.tileSize - 1) / b.tileSize;
    return b.size + tx * ty * b.tileBytes;
}

uint32_t resolvedLayers(const TextureDesc& t) { return t.cube && t.layers <= 1 ? 6u : t.layers; }

bool lifetimesIntersect(const PlanResource& a, const PlanResource& b) {
    return a.firstPass <= b.lastPass && b.firstPass <= a.lastPass;
}

bool rangesOverlap(const PlanResource& a, const PlanResource& b) {
    return a.offset < b.offset + b.memory.size && b.offset < a.offset + a.memory.size;
}

}  // namespace

// lifetimes: one PlanResource per resource a kept pass uses; resolved sizes, usages, first/last pass.
void computeLifetimes(Compiler& c) {
    const auto& resources = c.graph.resources;
    std::vector<bool> used(resources.size(), false);
    for (uint32_t pi : c.order)
        for (uint32_t ri : c.accessResource[pi]) used[ri] = true;

    c.planResource.assign(resources.size(), -1);
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        if (!used[ri]) continue;
        const ResourceDesc& d = resources[ri];
        PlanResource r;
        r.desc = ri;
        r.name = d.name;
        r.kind = d.kind;
        r.imported = d.imported;
        r.exported = d.exported;
        r.persistent = d.persistent;
        r.transient = !d.imported && !d.exported && !d.persistent;
        if (d.kind == ResourceKind::Buffer) {
            r.bufferSize = resolvedBufferSize(d.buffer, c.options);
        } else {
            const Extent e = resolveExtent(d.texture, c.options);
            r.format = d.texture.format;
            r.width = e.width;
            r.height = e.height;
            r.cube = d.texture.cube;
            r.array = !d.texture.sceneLayers.empty();
            r.layers = resolvedLayers(d.texture);
            r.mips = d.texture.mips == 0 ? fullMipChain(e) : d.texture.mips;
        }
        c.planResource[ri] = static_cast<int32_t>(c.plan.resources.size());
        c.plan.resources.push_back(std::move(r));
    }

    for (uint32_t i = 0; i < c.plan.passes.size(); ++i) {
        PlanPass& p = c.plan.passes[i];
        const PassDesc& d = c.graph.passes[p.desc];
        for (uint32_t ai = 0; ai < d.accesses.size(); ++ai) {
            const auto ri = static_cast<uint32_t>(c.planResource[c.accessResource[p.desc][ai]]);
            PlanResource& r = c.plan.resources[ri];
            r.usageMask |= 1u << static_cast<uint32_t>(d.accesses[ai].usage);
            if (r.firstPass < 0) r.firstPass = static_cast<int32_t>(i);
            r.lastPass = static_cast<int32_t>(i);
            PlanAccess a;
            a.resource = ri;
            a.usage = d.accesses[ai].usage;
            a.load = d.accesses[ai].load;
            p.accesses.push_back(a);
        }
    }
    // Exported contents are read after the frame, so nothing may reuse their memory before its end.
    for (PlanResource& r : c.plan.resources)
        if (r.exported) r.lastPass = static_cast<int32_t>(c.plan.passes.size()) - 1;
}

// alias: group transients into heaps by memory class and place them, sharing memory across lifetimes.
void alias(Compiler& c) {
    auto& resources = c.plan.resources;
    const MemoryRequirementsFn& query = c.options.memoryRequirements;
    // A reconfiguration keeps the usages a resource had (options.previous): a pass switched off
    // must not make its resources new images of fewer usages, and more usages are harmless.
    if (const Plan* previous = c.options.previous)
        for (PlanResource& r : resources)
            if (const int32_t o = previous->findResource(r.name); o >= 0) {
                const PlanResource& was = previous->resources[static_cast<size_t>(o)];
                if (was.kind == r.kind && was.format == r.format && was.transient == r.transient)
                    r.usageMask |= was.usageMask;
            }
    for (PlanResource& r : resources)
        if (!r.imported) r.memory = query ? query(r) : estimateMemoryRequirements(r);

    std::vector<std::vector<uint32_t>> members;
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        PlanResource& r = resources[ri];
        if (!r.transient) continue;
        const bool buffers = r.kind == ResourceKind::Buffer;
        size_t h = 0;
        while (h < c.plan.heaps.size() &&
               (c.plan.heaps[h].memoryTypeBits != r.memory.memoryTypeBits ||
                c.plan.heaps[h].buffers != buffers))
            ++h;
        if (h == c.plan.heaps.size()) {
            c.plan.heaps.push_back({r.memory.memoryTypeBits, buffers, 0});
            members.emplace_back();
        }
        r.heap = static_cast<int32_t>(h);
        members[h].push_back(ri);
        c.plan.transientBytesUnaliased += alignUp(r.memory.size, r.memory.alignment);
    }

    for (size_t h = 0; h < members.size(); ++h) {
        std::vector<uint32_t>& list = members[h];
        uint64_t heapSize = 0;
        // The previous plan's heap of this memory class (options.previous).
        const Plan* previous = c.options.previous;
        const TransientHeap* previousHeap = nullptr;
        if (previous && h < previous->heaps.size() &&
            previous->heaps[h].memoryTypeBits == c.plan.heaps[h].memoryTypeBits &&
            previous->heaps[h].buffers == c.plan.heaps[h].buffers)
            previousHeap = &previous->heaps[h];
        if (c.options.alias) {
            // Largest first packs best; declaration order keeps equal sizes deterministic.
            std::stable_sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) {
                return resources[a].memory.size > resources[b].memory.size;
            });
            std::vector<uint32_t> placed, toPlace = list;
            // First the transients that can stay where the previous plan had them.
            if (previousHeap) {
                std::vector<uint32_t> rest;
                for (uint32_t ri : list) {
                    PlanResource& r = resources[ri];
                    const int32_t o = previous->findResource(r.name);
                    const PlanResource* was =
                        o >= 0 ? &previous->resources[static_cast<size_t>(o)] : nullptr;
                    bool kept = was && was->transient && was->heap == static_cast<int32_t>(h) &&
                                was->memory.size == r.memory.size &&
                                was->memory.alignment == r.memory.alignment &&
                                was->offset + r.memory.size <= previousHeap->size;
                    if (kept) {
                        r.offset = was->offset;
                        kept = std::none_of(placed.begin(), placed.end(), [&](uint32_t q) {
                            return lifetimesIntersect(r, resources[q]) &&
                                   rangesOverlap(r, resources[q]);
                        });
                    }
                    if (!kept) {
                        rest.push_back(ri);
                        continue;
                    }
                    placed.push_back(ri);
                    heapSize =
                        std::max(heapSize, r.offset + alignUp(r.memory.size, r.memory.alignment));
                }
                toPlace = std::move(rest);
            }
            for (uint32_t ri : toPlace) {
                PlanResource& r = resources[ri];
                std::vector<uint64_t> candidates{0};
                std::vector<uint32_t> live;
                for (uint32_t q : placed) {
                    if (!lifetimesIntersect(r, resources[q])) continue;
                    live.push_back(q);
                    candidates.push_back(alignUp(resources[q].offset + resources[q].memory.size,
                                                 r.memory.alignment));
                }
                std::sort(candidates.begin(), candidates.end());
                for (uint64_t offset : candidates) {
                    r.offset = offset;
                    if (std::none_of(live.begin(), live.end(),
                                     [&](uint32_t q) { return rangesOverlap(r, resources[q]); }))
                        break;
                }
                placed.push_back(ri);
                heapSize =
                    std::max(heapSize, r.offset + alignUp(r.memory.size, r.memory.alignment));
            }
            // A heap the new placement fits in is kept whole (its memory and what lies in it).
            if (previousHeap && heapSize <= previousHeap->size) heapSize = previousHeap->size;
        } else {
            // Largest alignment first, so every aligned size keeps the next offset aligned: no gaps.
            std::stable_sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) {
                return resources[a].memory.alignment > resources[b].memory.alignment;
            });
            for (uint32_t ri : list) {
                PlanResource& r = resources[ri];
                r.offset = alignUp(heapSize, r.memory.alignment);
                heapSize = r.offset + alignUp(r.memory.size, r.memory.alignment);
            }
        }
        c.plan.heaps[h].size = heapSize;
        c.plan.transientBytesAliased += heapSize;
    }

    // Who used each transient's memory before it: its first barrier must wait for them.
    c.aliasPreds.assign(resources.size(), {});
    c.aliasFrom.assign(resources.size(), -1);
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        const PlanResource& r = resources[ri];
        if (!r.transient) continue;
        for (uint32_t q : members[static_cast<size_t>(r.heap)]) {
            const PlanResource& o = resources[q];
            if (q == ri || o.lastPass >= r.firstPass || !rangesOverlap(r, o)) continue;
            c.aliasPreds[ri].push_back(q);
            const int32_t best = c.aliasFrom[ri];
            if (best < 0 || o.lastPass > resources[static_cast<size_t>(best)].lastPass ||
                (o.lastPass == resources[static_cast<size_t>(best)].lastPass &&
                 q < static_cast<uint32_t>(best)))
                c.aliasFrom[ri] = static_cast<int32_t>(q);
        }
    }
}

}  // namespace rg::compiler_steps
