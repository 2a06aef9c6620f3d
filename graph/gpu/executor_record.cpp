// Executor: recording and submitting a frame — the frames-in-flight slots, the plan's barriers,
// one timestamp pair per pass — and gathering the timings of the frames that are done.
#include "executor.h"

#include <algorithm>

#include "core/check.h"
#include "executor_detail.h"

namespace rg::gpu {

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
        double ns =
            static_cast<double>(stamps[2 * i + 1] - stamps[2 * i]) * m_ctx.timestampPeriodNs();
        m_lastTimings.push_back(
            {slot.passNames[i], ns * 1e-6, i < slot.passCpuMs.size() ? slot.passCpuMs[i] : 0.0});
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
    m_lastSceneUpdateMs = msSince(t0);
    if (!m_onceDir.empty() && !m_floors && !hostCmd)
        if (auto r = onceCacheBeforeFrame(slotIndex); !r) return r;
    VkDevice dev = m_ctx.device();
    // Per pass its begin and end timestamps (queries 2i, 2i + 1), and one more written right after
    // the begin (2n + i) that is never read: it makes lavapipe take the begin time before the
    // pass's work. llvmpipe bins a timestamp into the scene being built and takes the time when
    // that scene is rasterised, at the next flush; lavapipe flushes before every timestamp not at
    // the top of the pipe. A compute pass's dispatch runs at once, between the two, so without the
    // extra flush its begin time was taken after its work and the work counted nowhere (a compute
    // pass doing 11 ms of fetches read 0.07 ms). Written on every device: one more query a pass
    // costs nothing measurable, and the timings then mean the same everywhere.
    const uint32_t passes = hostCmd ? 0u : static_cast<uint32_t>(m_built->plan.passes.size());
    const uint32_t queries = 3 * passes;
    if (queries > slot.queryCapacity || !slot.queries) {
        VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = std::max(queries, 3u);
        VkQueryPool pool = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateQueryPool(dev, &qi, nullptr, &pool));
        slot.queries = OwnedQueryPool(dev, pool);
        slot.queryCapacity = qi.queryCount;
    }
    slot.queryCount = 2 * passes;  // the ones collect() reads
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
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    if (auto r = recordHostCopies(cmd, /*imports=*/true); !r) return r;

    const uint64_t number = m_frameNumberBase + m_frameIndex;
    FrameInfo info{number, static_cast<double>(number) / 60.0, slotIndex, m_persistentEpoch};
    for (size_t i = 0; i < m_built->plan.passes.size(); ++i) {
        const PlanPass& pass = m_built->plan.passes[i];
        m_ctx.beginLabel(cmd, pass.name);
        recordBarriers(cmd, pass.barriers);
        if (queries) {
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries.get(),
                                 static_cast<uint32_t>(2 * i));
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries.get(),
                                 static_cast<uint32_t>(2 * passes + i));
        }
        RecordContext rc{m_ctx,          cmd,           pass, m_built->graph.passes[pass.desc],
                         m_built->table, m_built->plan, info, m_scene};
        const auto recordStart = Clock::now();
        m_built->instances[i]->record(rc);
        slot.passCpuMs.push_back(msSince(recordStart));
        if (queries)
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries.get(),
                                 static_cast<uint32_t>(2 * i + 1));
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
    if (m_onceToSave) return onceCacheAfterFrame(fence);
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

}  // namespace rg::gpu
