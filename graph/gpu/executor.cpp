#include "executor.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "core/check.h"
#include "core/names.h"

namespace rg::gpu {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

ImageDesc imageDescOf(const PlanResource& r) {
    ImageDesc d;
    d.name = r.name;
    d.format = r.format;
    d.width = r.width;
    d.height = r.height;
    d.layers = r.layers;
    d.mips = r.mips;
    d.cube = r.cube;
    d.array = r.array;
    d.usage = imageUsageOf(r.usageMask, r.format);
    if (r.imported) d.usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    return d;
}

}  // namespace

// Physical resources and pass instances of one plan. Shared pointers, so an incremental rebuild
// can reuse what did not change while the old build stays intact until the new one succeeds.
struct Executor::Built {
    Plan plan;  // owned here so pass instances and the table may point into it
    GraphDesc graph;
    std::vector<std::shared_ptr<OwnedMemory>> heaps;
    std::vector<std::shared_ptr<Image>> images;    // by plan resource index
    std::vector<std::shared_ptr<Buffer>> buffers;  // by plan resource index
    ResourceTable table;
    std::vector<std::shared_ptr<PassInstance>> instances;  // by plan pass index
    std::vector<std::string> sourceStamps;  // by plan pass index: its files' times and sizes when prepared
};

namespace {

bool sameHeap(const TransientHeap& a, const TransientHeap& b) {
    return a.size == b.size && a.memoryTypeBits == b.memoryTypeBits && a.buffers == b.buffers;
}

// Same physical shape: a resource built for `a` serves `b`.
bool sameShape(const PlanResource& a, const PlanResource& b) {
    return a.kind == b.kind && a.format == b.format && a.width == b.width && a.height == b.height &&
           a.layers == b.layers && a.mips == b.mips && a.cube == b.cube && a.array == b.array && a.bufferSize == b.bufferSize &&
           a.usageMask == b.usageMask && a.transient == b.transient && a.imported == b.imported &&
           a.persistent == b.persistent;
}

Value withoutUniforms(const Value& params) {
    Value v = params;
    if (v.isTable()) v.table().erase("uniforms");
    return v;
}

// Modification times and sizes of a pass's shader files: a pass whose sources changed on disk
// is prepared again even when its declaration did not change (hot reload).
std::string sourceStamp(const PassInstance& instance) {
    std::string stamp;
    for (const auto& f : instance.files()) {
        std::error_code ec;
        auto t = std::filesystem::last_write_time(f, ec);
        auto size = std::filesystem::file_size(f, ec);
        stamp += f + "@" + std::to_string(t.time_since_epoch().count()) + ":" + std::to_string(size) + ";";
    }
    return stamp;
}

bool sameAccesses(const std::vector<Access>& a, const std::vector<Access>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].resource != b[i].resource || a[i].usage != b[i].usage || a[i].load != b[i].load) return false;
    return true;
}

}  // namespace

std::string BuildReport::summary() const {
    std::string s = "rebuilt " + std::to_string(passesPrepared.size()) + " pass(es)";
    if (!passesPrepared.empty()) {
        s += " (";
        for (size_t i = 0; i < passesPrepared.size(); ++i) s += (i ? ", " : "") + passesPrepared[i];
        s += ")";
    }
    s += ", reused " + std::to_string(passesReused.size()) + "; resources: " + std::to_string(resourcesCreated) +
         " created, " + std::to_string(resourcesReused) + " reused";
    return s;
}

Executor::Executor(Context& ctx, ShaderCompiler& shaders, const PassRegistry& kinds)
    : m_ctx(ctx), m_shaders(shaders), m_kinds(kinds) {}

Executor::~Executor() {
    vkDeviceWaitIdle(m_ctx.device());
    m_built.reset();
    m_slots.clear();
    (void)m_ctx.waitIdle();
}

Result<void> Executor::resolveKinds(GraphDesc& graph) const {
    for (auto& p : graph.passes) {
        const PassKindInfo* kind = m_kinds.find(p.kind);
        if (!kind) {
            std::string msg = (p.origin.empty() ? "" : p.origin + ": ") + "pass '" + p.name +
                              "': unknown kind '" + p.kind + "'";
            if (const std::string best = closestName(p.kind, m_kinds.names(), 3); !best.empty())
                msg += " (did you mean '" + best + "'?)";
            std::string all;
            for (const auto& n : m_kinds.names()) all += (all.empty() ? "" : ", ") + n;
            return fail(ErrorCode::InvalidInput, msg + "; known kinds: " + all);
        }
        p.type = kind->schema.type;
    }
    return {};
}

Result<void> Executor::createSlots() {
    VkDevice dev = m_ctx.device();
    for (uint32_t i = 0; i < m_ctx.framesInFlight(); ++i) {
        FrameSlot s;
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        pi.queueFamilyIndex = m_ctx.queueFamily();
        VkCommandPool pool = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateCommandPool(dev, &pi, nullptr, &pool));
        s.pool = OwnedCommandPool(dev, pool);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        RG_VK_TRY(vkAllocateCommandBuffers(dev, &ai, &s.cmd));
        VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        VkFence fence = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateFence(dev, &fi, nullptr, &fence));
        s.fence = OwnedFence(dev, fence);
        m_slots.push_back(std::move(s));
    }
    return {};
}

Result<void> Executor::build(const GraphDesc& graphIn, const CompileOptions& optionsIn) {
    if (m_slots.empty())
        if (auto r = createSlots(); !r) return r;
    GraphDesc graph = graphIn;
    if (auto r = resolveKinds(graph); !r) return r;
    // Resources the scene sizes: a shadow-view array gets the layers the scene's shadowed local
    // lights can use (at most those declared); a scene without any gets one 1×1 layer, not the
    // declared capacity (24 MiB at 1024² × 6 in d32f).
    if (m_scene)
        for (ResourceDesc& r : graph.resources) {
            if (r.kind != ResourceKind::Texture || r.texture.sceneLayers != "shadow_views") continue;
            r.texture.layers = std::clamp(m_sceneShadowViews, 1u, r.texture.layers);
            if (m_sceneShadowViews == 0) {
                r.texture.sizeMode = SizeMode::Absolute;
                r.texture.width = r.texture.height = 1;
                r.texture.mips = 1;
            }
        }

    auto t0 = Clock::now();
    CompileOptions options = optionsIn;
    Context& ctx = m_ctx;
    options.memoryRequirements = [&ctx](const PlanResource& r) {
        VkMemoryRequirements req;
        if (r.kind == ResourceKind::Texture) req = Image::requirements(ctx, imageDescOf(r));
        else req = Buffer::requirements(ctx, r.bufferSize, bufferUsageOf(r.usageMask));
        return MemoryRequirements{req.size, req.alignment, req.memoryTypeBits};
    };
    // A rebuild keeps the previous build's memory placement where it can (a toggled pass moves
    // no other resource), so the passes over unchanged resources are reused, not prepared again.
    if (m_built && !options.previous) options.previous = &m_built->plan;
    auto plan = compile(graph, options);
    if (!plan) return std::unexpected(plan.error());
    m_buildStats.compileMs = msSince(t0);

    // Physical resources: reuse the previous build's where nothing about them changed.
    auto t1 = Clock::now();
    BuildReport report;
    // A new scene (setScene) re-prepares every pass — passes hold the scene's buffers and
    // pipelines built for its materials — but memory and resources do not depend on the scene,
    // so their contents (persistent history) carry over.
    const Built* old = m_built.get();
    const Built* oldPasses = m_forceRebuild ? nullptr : old;
    auto built = std::make_unique<Built>();
    built->plan = std::move(*plan);
    built->graph = std::move(graph);
    const Plan* planPtr = &built->plan;
    std::vector<bool> heapReused(planPtr->heaps.size(), false);
    for (size_t h = 0; h < planPtr->heaps.size(); ++h) {
        const auto& heap = planPtr->heaps[h];
        if (old && h < old->plan.heaps.size() && sameHeap(old->plan.heaps[h], heap)) {
            built->heaps.push_back(old->heaps[h]);
            heapReused[h] = true;
            continue;
        }
        uint32_t type = 0;
        auto mem = m_ctx.allocator().allocateHeap(std::max<uint64_t>(heap.size, 1), heap.memoryTypeBits, type);
        if (!mem) return std::unexpected(mem.error());
        built->heaps.push_back(std::make_shared<OwnedMemory>(std::move(*mem)));
    }
    built->images.resize(planPtr->resources.size());
    built->buffers.resize(planPtr->resources.size());
    std::vector<bool> resourceReused(planPtr->resources.size(), false);
    for (size_t i = 0; i < planPtr->resources.size(); ++i) {
        const PlanResource& r = planPtr->resources[i];
        if (old) {
            int32_t o = old->plan.findResource(r.name);
            if (o >= 0) {
                const PlanResource& orr = old->plan.resources[static_cast<size_t>(o)];
                bool placementKept = r.heap < 0 ? orr.heap < 0
                                                : (orr.heap == r.heap && orr.offset == r.offset &&
                                                   heapReused[static_cast<size_t>(r.heap)]);
                if (sameShape(orr, r) && placementKept) {
                    built->images[i] = old->images[static_cast<size_t>(o)];
                    built->buffers[i] = old->buffers[static_cast<size_t>(o)];
                    resourceReused[i] = true;
                    ++report.resourcesReused;
                    continue;
                }
            }
        }
        ++report.resourcesCreated;
        if (r.kind == ResourceKind::Texture) {
            ImageDesc d = imageDescOf(r);
            auto img = r.heap >= 0 ? Image::createPlaced(m_ctx, d, built->heaps[static_cast<size_t>(r.heap)]->get(), r.offset)
                                   : Image::create(m_ctx, d);
            if (!img) return std::unexpected(img.error());
            built->images[i] = std::make_shared<Image>(std::move(*img));
        } else {
            VkBufferUsageFlags usage = bufferUsageOf(r.usageMask);
            auto buf = r.heap >= 0 ? Buffer::createPlaced(m_ctx, r.name, r.bufferSize, usage,
                                                          built->heaps[static_cast<size_t>(r.heap)]->get(), r.offset)
                                   : Buffer::create(m_ctx, r.name, r.bufferSize, usage, false);
            if (!buf) return std::unexpected(buf.error());
            built->buffers[i] = std::make_shared<Buffer>(std::move(*buf));
        }
    }
    for (size_t i = 0; i < planPtr->resources.size(); ++i)
        built->table.set(planPtr->resources[i].name,
                         PhysicalResource{&planPtr->resources[i], built->images[i].get(), built->buffers[i].get()});
    m_buildStats.resourcesMs = msSince(t1);

    // Pass instances: an unchanged pass over unchanged resources keeps its pipeline and
    // descriptor sets.
    auto t2 = Clock::now();
    for (const auto& pass : planPtr->passes) {
        const PassDesc& desc = built->graph.passes[pass.desc];
        if (oldPasses) {
            int32_t o = old->plan.findPass(pass.name);
            if (o >= 0) {
                const PlanPass& op = old->plan.passes[static_cast<size_t>(o)];
                const PassDesc& od = old->graph.passes[op.desc];
                bool resourcesKept = std::all_of(pass.accesses.begin(), pass.accesses.end(),
                                                 [&](const PlanAccess& a) { return resourceReused[a.resource]; });
                const auto& instance = old->instances[static_cast<size_t>(o)];
                if (od.kind == desc.kind && sameAccesses(od.accesses, desc.accesses) && resourcesKept &&
                    withoutUniforms(od.params) == withoutUniforms(desc.params) &&
                    sourceStamp(*instance) == old->sourceStamps[static_cast<size_t>(o)]) {
                    built->instances.push_back(instance);
                    built->sourceStamps.push_back(old->sourceStamps[static_cast<size_t>(o)]);
                    report.passesReused.push_back(pass.name);
                    continue;
                }
            }
        }
        auto instance = std::shared_ptr<PassInstance>(m_kinds.find(desc.kind)->create());
        PassSetup setup{m_ctx, m_shaders, *planPtr, pass, desc, built->table, m_scene, m_floors};
        if (auto r = instance->prepare(setup); !r) return std::unexpected(r.error());
        built->sourceStamps.push_back(sourceStamp(*instance));
        built->instances.push_back(std::move(instance));
        report.passesPrepared.push_back(pass.name);
    }
    m_buildStats.prepareMs = msSince(t2);

    // Upload imported contents into resources that are new.
    for (size_t i = 0; i < planPtr->resources.size(); ++i) {
        const PlanResource& r = planPtr->resources[i];
        if (!r.imported || resourceReused[i] || m_hostImports.count(r.name)) continue;  // the host's image comes in each frame
        if (!m_importData.count(r.name))
            return fail(ErrorCode::InvalidInput, "imported resource '" + r.name + "' has no contents (nothing was uploaded for it)");
    }

    // Swap in; the old build may still be used by frames in flight.
    if (m_built) {
        std::shared_ptr<Built> retired(std::move(m_built));
        m_ctx.deferDestroy([retired]() mutable { retired.reset(); });
    }
    m_built = std::move(built);
    m_forceRebuild = false;
    m_lastReport = report;
    ++m_buildCount;
    for (size_t i = 0; i < m_built->plan.resources.size(); ++i) {
        const PlanResource& r = m_built->plan.resources[i];
        if (r.imported && !resourceReused[i] && !m_hostImports.count(r.name))
            if (auto u = setImport(r.name, m_importData[r.name]); !u) return u;
        if (r.persistent && !resourceReused[i])
            if (auto u = clearPersistent(i); !u) return u;
    }
    return {};
}

// A new persistent resource starts as zeros, in the state every frame expects it in.
Result<void> Executor::clearPersistent(size_t index) {
    ++m_persistentEpoch;
    const PlanResource& r = m_built->plan.resources[index];
    Image* image = m_built->images[index].get();
    Buffer* buffer = m_built->buffers[index].get();
    return m_ctx.submitNow([&](VkCommandBuffer cmd) {
        if (buffer) {
            vkCmdFillBuffer(cmd, buffer->buffer(), 0, VK_WHOLE_SIZE, 0);
            VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
            mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
            mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
            mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
            mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.memoryBarrierCount = 1;
            dep.pMemoryBarriers = &mb;
            vkCmdPipelineBarrier2(cmd, &dep);
            return;
        }
        VkImageAspectFlags aspect = aspectOf(r.format);
        imageBarrier(cmd, image->image(), aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkImageSubresourceRange range{aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
        if (isDepthStencil(r.format)) {
            VkClearDepthStencilValue zero{0.0f, 0};
            vkCmdClearDepthStencilImage(cmd, image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        } else {
            VkClearColorValue zero{};
            vkCmdClearColorImage(cmd, image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        }
        imageBarrier(cmd, image->image(), aspect, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

void Executor::setScene(const passes::GpuScene* scene, std::function<void(uint32_t)> perFrame, uint32_t shadowViews) {
    m_scene = scene;
    m_sceneShadowViews = shadowViews;
    m_perFrame = std::move(perFrame);
    m_forceRebuild = true;
}

void Executor::setFloors(bool on) {
    if (on != m_floors) m_forceRebuild = true;
    m_floors = on;
}

Result<void> Executor::resetPersistent() {
    if (!m_built) return {};
    if (auto r = finish(); !r) return r;
    for (size_t i = 0; i < m_built->plan.resources.size(); ++i)
        if (m_built->plan.resources[i].persistent)
            if (auto r = clearPersistent(i); !r) return r;
    return {};
}

void Executor::updateUniforms(const GraphDesc& graph) {
    if (!m_built) return;
    for (auto& pass : m_built->graph.passes) {
        const PassDesc* p = graph.findPass(pass.name);
        if (p && pass.params.isTable()) pass.params.table()["uniforms"] = p->params["uniforms"];
    }
}

Result<void> Executor::setImport(const std::string& name, const rg::Image& data) {
    m_importData[name] = data;
    if (!m_built) return {};
    const PhysicalResource* phys = m_built->table.find(name);
    if (!phys) return {};  // not used by the current plan
    if (!phys->image)
        return fail(ErrorCode::Unsupported, "imported resource '" + name + "': only textures can be uploaded");
    const PlanResource& r = *phys->plan;
    if (data.width != r.width || data.height != r.height)
        return fail(ErrorCode::InvalidInput,
                    "imported resource '" + name + "' is " + std::to_string(r.width) + "x" +
                        std::to_string(r.height) + " but the data is " + std::to_string(data.width) +
                        "x" + std::to_string(data.height));
    const uint32_t comps = formatInfo(r.format).components;
    const size_t texels = size_t(r.width) * r.height;
    std::vector<float> src(texels * comps, 0.0f);
    for (size_t i = 0; i < texels; ++i)
        for (uint32_t c = 0; c < comps; ++c)
            src[i * comps + c] = c < data.channels ? data.pixels[i * data.channels + c] : (c == 3 ? 1.0f : 0.0f);
    const size_t bytes = texels * formatInfo(r.format).bytesPerTexel;
    auto staging = Buffer::create(m_ctx, name + ".staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    if (!encodeTexels(r.format, src.data(), texels, staging->mapped()))
        return fail(ErrorCode::Unsupported, "imported resource '" + name + "': cannot upload format '" +
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
        vkCmdCopyBufferToImage(cmd, staging->buffer(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, mips);
    });
}

void Executor::recordBarriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers) {
    if (barriers.empty()) return;
    std::vector<VkImageMemoryBarrier2> images;
    std::vector<VkBufferMemoryBarrier2> buffers;
    for (const Barrier& b : barriers) {
        const PlanResource& r = m_built->plan.resources[b.resource];
        if (r.kind == ResourceKind::Texture) {
            VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            ib.srcStageMask = toVkStages(b.srcStages);
            ib.srcAccessMask = toVkAccess(b.srcAccess);
            ib.dstStageMask = toVkStages(b.dstStages);
            ib.dstAccessMask = toVkAccess(b.dstAccess);
            ib.oldLayout = toVkLayout(b.oldLayout);
            ib.newLayout = toVkLayout(b.newLayout);
            ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            ib.image = m_built->images[b.resource]->image();
            ib.subresourceRange = {aspectOf(r.format), 0, VK_REMAINING_MIP_LEVELS, 0,
                                   VK_REMAINING_ARRAY_LAYERS};
            images.push_back(ib);
        } else {
            VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            bb.srcStageMask = toVkStages(b.srcStages);
            bb.srcAccessMask = toVkAccess(b.srcAccess);
            bb.dstStageMask = toVkStages(b.dstStages);
            bb.dstAccessMask = toVkAccess(b.dstAccess);
            bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            bb.buffer = m_built->buffers[b.resource]->buffer();
            bb.size = VK_WHOLE_SIZE;
            buffers.push_back(bb);
        }
    }
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
    dep.pImageMemoryBarriers = images.data();
    dep.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
    dep.pBufferMemoryBarriers = buffers.data();
    vkCmdPipelineBarrier2(cmd, &dep);
}

Result<void> Executor::collect(FrameSlot& slot) {
    if (!slot.pending) return {};
    VkFence fence = slot.fence.get();
    RG_VK_TRY(vkWaitForFences(m_ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    slot.pending = false;
    if (slot.queryCount == 0) return {};
    std::vector<uint64_t> stamps(slot.queryCount);
    RG_VK_TRY(vkGetQueryPoolResults(m_ctx.device(), slot.queries.get(), 0, slot.queryCount,
                                    stamps.size() * sizeof(uint64_t), stamps.data(),
                                    sizeof(uint64_t), VK_QUERY_RESULT_64_BIT));
    m_lastTimings.clear();
    for (size_t i = 0; i < slot.passNames.size(); ++i) {
        double ns = static_cast<double>(stamps[2 * i + 1] - stamps[2 * i]) * m_ctx.timestampPeriodNs();
        m_lastTimings.push_back({slot.passNames[i], ns * 1e-6, i < slot.passCpuMs.size() ? slot.passCpuMs[i] : 0.0});
    }
    return {};
}

Result<void> Executor::frame(VkCommandBuffer hostCmd) {
    RG_CHECK(m_built) << "Executor::frame() before build()";
    const uint32_t slotIndex = static_cast<uint32_t>(m_frameIndex % m_slots.size());
    FrameSlot& slot = m_slots[slotIndex];
    if (auto r = collect(slot); !r) return r;
    m_ctx.collectGarbage(slotIndex);
    m_ctx.setCurrentSlot(slotIndex);

    auto t0 = Clock::now();
    if (m_perFrame) m_perFrame(slotIndex);
    VkDevice dev = m_ctx.device();
    const uint32_t queries = hostCmd ? 0u : static_cast<uint32_t>(m_built->plan.passes.size() * 2);
    if (queries > slot.queryCount || !slot.queries) {
        VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = std::max(queries, 2u);
        VkQueryPool pool = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateQueryPool(dev, &qi, nullptr, &pool));
        slot.queries = OwnedQueryPool(dev, pool);
    }
    slot.queryCount = queries;
    slot.passNames.clear();
    slot.passCpuMs.clear();

    VkCommandBuffer cmd = hostCmd ? hostCmd : slot.cmd;
    if (!hostCmd) {
        RG_VK_TRY(vkResetCommandPool(dev, slot.pool.get(), 0));
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        RG_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
    }
    if (queries) vkCmdResetQueryPool(cmd, slot.queries.get(), 0, queries);

    // Frames in flight share the plan's resources: the previous frame must be done with
    // them before this one starts overwriting (its first barriers come from UNDEFINED).
    VkMemoryBarrier2 frameBarrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    frameBarrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    frameBarrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    frameBarrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    frameBarrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &frameBarrier;
    vkCmdPipelineBarrier2(cmd, &dep);
    if (auto r = recordHostCopies(cmd, /*imports=*/true); !r) return r;

    FrameInfo info{m_frameIndex, static_cast<double>(m_frameIndex) / 60.0, slotIndex, m_persistentEpoch};
    for (size_t i = 0; i < m_built->plan.passes.size(); ++i) {
        const PlanPass& pass = m_built->plan.passes[i];
        m_ctx.beginLabel(cmd, pass.name);
        recordBarriers(cmd, pass.barriers);
        if (queries)
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries.get(), static_cast<uint32_t>(2 * i));
        RecordContext rc{m_ctx, cmd, pass, m_built->graph.passes[pass.desc], m_built->table, m_built->plan, info, m_scene};
        const auto recordStart = Clock::now();
        m_built->instances[i]->record(rc);
        slot.passCpuMs.push_back(msSince(recordStart));
        if (queries)
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries.get(), static_cast<uint32_t>(2 * i + 1));
        m_ctx.endLabel(cmd);
        slot.passNames.push_back(pass.name);
    }
    recordBarriers(cmd, m_built->plan.finalBarriers);
    if (auto r = recordHostCopies(cmd, /*imports=*/false); !r) return r;
    m_lastRecordMs = msSince(t0);
    if (hostCmd) {  // the host submits
        ++m_frameIndex;
        return {};
    }
    RG_VK_TRY(vkEndCommandBuffer(cmd));

    VkFence fence = slot.fence.get();
    RG_VK_TRY(vkResetFences(dev, 1, &fence));
    VkCommandBufferSubmitInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    ci.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &ci;
    RG_VK_TRY(vkQueueSubmit2(m_ctx.queue(), 1, &submit, fence));
    slot.pending = true;
    ++m_frameIndex;
    return {};
}

void Executor::setHostImport(const std::string& name, const HostImage& image) {
    if (image.image) m_hostImports[name] = image;
    else m_hostImports.erase(name);
}
void Executor::setHostExport(const std::string& name, const HostImage& image) {
    if (image.image) m_hostExports[name] = image;
    else m_hostExports.erase(name);
}

// The host's images in or out: a blit each (nearest, equal sizes: a copy with format conversion),
// the host image from and back to its own layout; an import overwrites the imported texture and
// leaves it ShaderReadOnly (where every frame expects it), an export reads a texture from its
// final layout and puts it back there.
Result<void> Executor::recordHostCopies(VkCommandBuffer cmd, bool imports) {
    for (const auto& [name, host] : imports ? m_hostImports : m_hostExports) {
        const PhysicalResource* phys = m_built->table.find(name);
        const std::string what = std::string(imports ? "host image imported as '" : "host image exported from '") + name + "'";
        if (!phys || !phys->image) return fail(ErrorCode::InvalidInput, what + ": the plan has no texture of that name");
        const PlanResource& r = *phys->plan;
        if (imports && !r.imported) return fail(ErrorCode::InvalidInput, what + ": declare it imported (rg.resource { import = true })");
        if (!imports && !r.exported && !r.persistent && !r.imported)
            return fail(ErrorCode::InvalidInput, what + ": it is transient (its memory is reused within the frame): export it (capture it, or Renderer::keep)");
        if (host.width != r.width || host.height != r.height)
            return fail(ErrorCode::InvalidInput, what + ": the host image is " + std::to_string(host.width) + "x" + std::to_string(host.height) +
                                                     ", the texture " + std::to_string(r.width) + "x" + std::to_string(r.height));
        const VkImageAspectFlags aspect = aspectOf(r.format);
        VkImage graph = phys->image->image();
        const VkImageLayout graphBefore = imports ? VK_IMAGE_LAYOUT_UNDEFINED : toVkLayout(r.finalLayout);
        const VkImageLayout graphAfter = imports ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : toVkLayout(r.finalLayout);
        VkImage src = imports ? host.image : graph, dst = imports ? graph : host.image;
        const VkImageLayout srcLayout = imports ? host.layout : graphBefore, dstLayout = imports ? graphBefore : host.layout;
        constexpr auto all = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        constexpr auto rw = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        imageBarrier(cmd, src, aspect, all, rw, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, srcLayout,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        imageBarrier(cmd, dst, aspect, all, rw, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     imports ? VK_IMAGE_LAYOUT_UNDEFINED : dstLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkImageBlit blit{};
        blit.srcSubresource = {aspect, 0, 0, 1};
        blit.dstSubresource = {aspect, 0, 0, 1};
        blit.srcOffsets[1] = blit.dstOffsets[1] = {static_cast<int32_t>(r.width), static_cast<int32_t>(r.height), 1};
        vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        imageBarrier(cmd, src, aspect, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, all, rw, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     imports ? host.layout : graphAfter);
        imageBarrier(cmd, dst, aspect, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, all, rw, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     imports ? graphAfter : host.layout);
    }
    return {};
}

Result<void> Executor::finish() {
    // Oldest first, so the timings kept are those of the newest frame.
    for (uint64_t k = 0; k < m_slots.size(); ++k) {
        uint64_t idx = (m_frameIndex + k) % m_slots.size();
        if (auto r = collect(m_slots[idx]); !r) return r;
    }
    return m_ctx.waitIdle();
}

Result<const PhysicalResource*> Executor::exportedResource(const std::string& name) {
    if (!m_built) return fail(ErrorCode::InvalidInput, "readback before the graph was built");
    const PhysicalResource* phys = m_built->table.find(name);
    if (!phys) {
        if (m_built->graph.findResource(name))
            return fail(ErrorCode::InvalidInput, "resource '" + name + "' is not used by any kept pass");
        return fail(ErrorCode::NotFound, "no resource named '" + name + "'");
    }
    if (!phys->plan->exported && !phys->plan->imported && !phys->plan->persistent)
        return fail(ErrorCode::InvalidInput, "resource '" + name +
                                                 "' is transient: capture (export) it to read it back");
    if (auto r = finish(); !r) return std::unexpected(r.error());
    return phys;
}

Result<rg::Image> Executor::readback(const std::string& name) {
    auto found = exportedResource(name);
    if (!found) return std::unexpected(found.error());
    const PhysicalResource* phys = *found;
    if (!phys->image) return fail(ErrorCode::InvalidInput, "resource '" + name + "' is a buffer: use readbackBuffer");
    const PlanResource& r = *phys->plan;
    const uint32_t texelBytes = copyTexelBytes(r.format);
    const size_t texels = size_t(r.width) * r.height;
    auto host = Buffer::create(m_ctx, name + ".readback", texels * texelBytes,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!host) return std::unexpected(host.error());
    VkImage image = phys->image->image();
    VkImageAspectFlags aspect = aspectOf(r.format);
    VkImageAspectFlags copyAspect = formatInfo(r.format).depth ? static_cast<VkImageAspectFlags>(VK_IMAGE_ASPECT_DEPTH_BIT) : aspect;
    Layout last = r.imported && r.finalLayout == Layout::Undefined ? Layout::ShaderReadOnly : r.finalLayout;
    auto sub = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image, aspect, toVkStages(r.finalStages) | VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     toVkAccess(r.finalAccess), VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT, toVkLayout(last),
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {copyAspect, 0, 0, 1};
        region.imageExtent = {r.width, r.height, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host->buffer(), 1, &region);
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     toVkLayout(last == Layout::Undefined ? Layout::General : last));
    });
    if (!sub) return std::unexpected(sub.error());
    rg::Image out;
    out.width = r.width;
    out.height = r.height;
    out.channels = isDepthStencil(r.format) ? 1 : formatInfo(r.format).components;
    out.pixels.resize(texels * out.channels);
    decodeTexels(r.format, host->mapped(), texels, out.pixels.data());
    return out;
}

Result<std::vector<uint8_t>> Executor::readbackBuffer(const std::string& name) {
    auto found = exportedResource(name);
    if (!found) return std::unexpected(found.error());
    const PhysicalResource* phys = *found;
    if (!phys->buffer) return fail(ErrorCode::InvalidInput, "resource '" + name + "' is a texture: use readback");
    const uint64_t size = phys->buffer->size();
    auto host = Buffer::create(m_ctx, name + ".readback", size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!host) return std::unexpected(host.error());
    VkBuffer src = phys->buffer->buffer();
    auto sub = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        mb.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        mb.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &mb;
        vkCmdPipelineBarrier2(cmd, &dep);
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, src, host->buffer(), 1, &region);
    });
    if (!sub) return std::unexpected(sub.error());
    std::vector<uint8_t> out(size);
    std::memcpy(out.data(), host->mapped(), size);
    return out;
}

const Plan& Executor::plan() const {
    static const Plan kEmpty;
    return m_built ? m_built->plan : kEmpty;
}

const GraphDesc& Executor::graph() const {
    static const GraphDesc kEmpty;
    return m_built ? m_built->graph : kEmpty;
}

Result<rg::Image> Executor::passResult(const std::string& pass) {
    if (auto r = finish(); !r) return std::unexpected(r.error());
    int32_t index = m_built ? m_built->plan.findPass(pass) : -1;
    if (index < 0) return fail(ErrorCode::NotFound, "no kept pass named '" + pass + "'");
    auto result = m_built->instances[static_cast<size_t>(index)]->hostResult();
    if (!result) return fail(ErrorCode::InvalidInput, "pass '" + pass + "' has no host result (not a readback pass, or no frame ran)");
    return *result;
}

std::vector<std::string> Executor::files() const {
    std::vector<std::string> out;
    if (!m_built) return out;
    for (const auto& inst : m_built->instances)
        for (auto& f : inst->files())
            if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    return out;
}

}  // namespace rg::gpu
