#include "executor.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <thread>

#include <unistd.h>

#include "core/check.h"
#include "core/hash.h"
#include "core/names.h"
#include "gpu/compile_scope.h"
#include "shader/shader_compiler.h"

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
    // What its passes were prepared against: a build against another scene or other generated
    // headers prepares every pass again.
    uint64_t sceneId = 0;
    std::string generatedDir;
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
// is prepared again even when its declaration did not change (hot reload). A file that is not
// there (deleted, or mid-save) gives no stamp: there is nothing to prepare the pass from again,
// and the pass as it was keeps running.
std::optional<std::string> sourceStamp(const PassInstance& instance) {
    std::string stamp;
    for (const auto& f : instance.files()) {
        std::error_code ec;
        auto t = std::filesystem::last_write_time(f, ec);
        if (ec) return std::nullopt;
        auto size = std::filesystem::file_size(f, ec);
        stamp += f + "@" + std::to_string(t.time_since_epoch().count()) + ":" + std::to_string(size) + ";";
    }
    return stamp;
}
bool sourcesChanged(const PassInstance& instance, const std::string& before) {
    auto now = sourceStamp(instance);
    return now && *now != before;
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
    // pipelines built for its materials — as do new layout headers (their shaders include them);
    // memory and resources do not depend on either, so their contents (persistent history)
    // carry over. The scene and the headers the running build has (a load that failed and gave
    // them back) re-prepare nothing.
    const Built* old = m_built.get();
    const std::string& generatedDir = m_shaders.options().generatedDir;
    const bool samePassInputs = old && old->sceneId == m_sceneId && old->generatedDir == generatedDir;
    const Built* oldPasses = m_forceRebuild || !samePassInputs ? nullptr : old;
    auto built = std::make_unique<Built>();
    built->plan = std::move(*plan);
    built->sceneId = m_sceneId;
    built->generatedDir = generatedDir;
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
    // descriptor sets; the others are prepared on several threads (prepareInParallel).
    auto t2 = Clock::now();
    const size_t passCount = planPtr->passes.size();
    built->instances.resize(passCount);
    built->sourceStamps.resize(passCount);
    std::vector<size_t> toPrepare;
    std::vector<char> prepared(passCount, 0);
    for (size_t p = 0; p < passCount; ++p) {
        const PlanPass& pass = planPtr->passes[p];
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
                    !sourcesChanged(*instance, old->sourceStamps[static_cast<size_t>(o)])) {
                    built->instances[p] = instance;
                    built->sourceStamps[p] = old->sourceStamps[static_cast<size_t>(o)];
                    continue;
                }
            }
        }
        toPrepare.push_back(p);
        prepared[p] = 1;
    }
    if (auto r = prepareInParallel(*built, *planPtr, toPrepare); !r) return std::unexpected(r.error());
    for (size_t p = 0; p < passCount; ++p)
        (prepared[p] ? report.passesPrepared : report.passesReused).push_back(planPtr->passes[p].name);
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

// Prepares the listed passes of `built` (indices into plan.passes), in order of their indices as
// far as anything but the pipeline compiles goes: each worker prepares one pass at a time under
// one lock and gives it up inside vkCreate*Pipelines (gpu/compile_scope.h), so the driver's
// compiles overlap — on lavapipe most of the set-up time (2 threads: the default pipeline's
// ~500 ms → ~300 ms). RG_PREPARE_THREADS=N sets the thread count (1: serial). The first failing
// pass in plan order gives the error, whichever thread met it first.
Result<void> Executor::prepareInParallel(Built& built, const Plan& plan, const std::vector<size_t>& passes) {
    std::vector<std::optional<Error>> errors(passes.size());
    auto prepareOne = [&](size_t k) {
        const size_t p = passes[k];
        const PlanPass& pass = plan.passes[p];
        const PassDesc& desc = built.graph.passes[pass.desc];
        auto instance = std::shared_ptr<PassInstance>(m_kinds.find(desc.kind)->create());
        PassSetup setup{m_ctx, m_shaders, plan, pass, desc, built.table, m_scene, m_floors};
        // An exception must not leave a worker thread (that would end the process): it becomes
        // the pass's error, as a failed prepare's.
        Result<void> prepared;
        try {
            prepared = instance->prepare(setup);
        } catch (const std::exception& e) {
            prepared = fail(ErrorCode::Device, "pass '" + pass.name + "': set-up failed: " + e.what());
        }
        if (!prepared) {
            errors[k] = prepared.error();
            return;
        }
        built.sourceStamps[p] = sourceStamp(*instance).value_or(std::string());
        built.instances[p] = std::move(instance);
    };
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    if (const char* env = std::getenv("RG_PREPARE_THREADS"); env && std::atoi(env) > 0) threads = static_cast<unsigned>(std::atoi(env));
    threads = static_cast<unsigned>(std::min<size_t>({threads, 8, passes.size()}));
    if (threads <= 1) {
        for (size_t k = 0; k < passes.size() && !(k > 0 && errors[k - 1]); ++k) prepareOne(k);
    } else {
        std::mutex lock;
        size_t next = 0;
        bool failed = false;
        auto worker = [&] {
            std::unique_lock<std::mutex> held(lock);
            t_prepareLock = &held;
            while (next < passes.size() && !failed) {
                const size_t k = next++;
                prepareOne(k);
                if (errors[k]) failed = true;
            }
            t_prepareLock = nullptr;
        };
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
    }
    for (auto& e : errors)
        if (e) return std::unexpected(*e);
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
            memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
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

void Executor::setScene(const passes::GpuScene* scene, uint64_t sceneId, std::function<void(uint32_t)> perFrame, uint32_t shadowViews) {
    m_scene = scene;
    m_sceneId = scene ? sceneId : 0;
    m_sceneShadowViews = shadowViews;
    m_perFrame = std::move(perFrame);
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
    if (!m_onceDir.empty() && !m_floors && !hostCmd)
        if (auto r = onceCacheBeforeFrame(slotIndex); !r) return r;
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
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
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
    if (m_onceToSave) return onceCacheAfterFrame(fence);
    return {};
}

// ---- The disk cache of once-per-build outputs (setOnceCache) -------------------------------

void Executor::setOnceCache(std::string dir, std::function<uint64_t(uint32_t)> sceneKey) {
    m_onceDir = std::move(dir);
    m_onceSceneKey = std::move(sceneKey);
}

namespace {

void hashValue(ContentHash& h, const Value& v) {
    if (v.isBool()) {
        h.u64(1);
        h.u64(v.asBool());
    } else if (v.isNumber()) {
        h.u64(2);
        h.u64(std::bit_cast<uint64_t>(v.asNumber()));
    } else if (v.isString()) {
        h.u64(3);
        h.str(v.asString());
    } else if (v.isList()) {
        h.u64(4 + (v.asList().size() << 8));
        for (const Value& e : v.asList()) hashValue(h, e);
    } else if (v.isTable()) {
        h.u64(5 + (v.asTable().size() << 8));
        for (const auto& [k, e] : v.asTable()) {
            h.str(k);
            hashValue(h, e);
        }
    } else {
        h.u64(0);
    }
}

void hashFile(ContentHash& h, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    h.str(path);
    h.str(text);
}

// Bytes of a resource as the cache stores it: every mip of every layer, tightly packed (the depth
// aspect of a depth format), or the whole buffer.
uint64_t cachedBytes(const PlanResource& r) {
    if (r.kind == ResourceKind::Buffer) return r.bufferSize;
    uint64_t bytes = 0;
    for (uint32_t m = 0; m < r.mips; ++m)
        bytes += uint64_t(std::max(1u, r.width >> m)) * std::max(1u, r.height >> m) * r.layers * copyTexelBytes(r.format);
    return bytes;
}

std::vector<VkBufferImageCopy> cachedRegions(const PlanResource& r, VkDeviceSize offset) {
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t m = 0; m < r.mips; ++m) {
        VkBufferImageCopy c{};
        c.bufferOffset = offset;
        c.imageSubresource = {aspectOf(r.format) & ~VkImageAspectFlags(VK_IMAGE_ASPECT_STENCIL_BIT), m, 0, r.layers};
        c.imageExtent = {std::max(1u, r.width >> m), std::max(1u, r.height >> m), 1};
        regions.push_back(c);
        offset += VkDeviceSize(c.imageExtent.width) * c.imageExtent.height * r.layers * copyTexelBytes(r.format);
    }
    return regions;
}

constexpr char kOnceMagic[8] = {'R', 'G', 'O', 'N', 'C', 'E', '0', '1'};

}  // namespace

// The once passes due now whose outputs are a function of what the key covers: start from every
// due once pass and drop, until none is dropped, each that touches a resource written by a pass
// outside the set (a per-frame pass, a once pass not due), a transient, a host image or a stencil
// format. Its resources: everything the set writes.
Executor::OnceSet Executor::cacheableOncePasses(uint32_t slot) const {
    OnceSet set;
    const Plan& plan = m_built->plan;
    const size_t n = plan.passes.size();
    std::vector<char> in(n, 0);
    for (size_t p = 0; p < n; ++p) in[p] = m_built->instances[p]->dueOnce(m_persistentEpoch);
    if (std::find(in.begin(), in.end(), 1) == in.end()) return set;  // every frame but the first after a build
    std::vector<std::vector<size_t>> writers(plan.resources.size());
    for (size_t p = 0; p < n; ++p)
        for (const PlanAccess& a : plan.passes[p].accesses)
            if (usageWrites(a.usage)) writers[a.resource].push_back(p);
    for (bool changed = true; changed;) {
        changed = false;
        for (size_t p = 0; p < n; ++p) {
            if (!in[p]) continue;
            for (const PlanAccess& a : plan.passes[p].accesses) {
                const PlanResource& r = plan.resources[a.resource];
                bool ok = (r.persistent || r.imported) && !m_hostImports.count(r.name) && !formatInfo(r.format).stencil;
                for (size_t w : writers[a.resource]) ok = ok && in[w];
                if (!ok) {
                    in[p] = 0;
                    changed = true;
                    break;
                }
            }
        }
    }
    std::vector<char> written(plan.resources.size(), 0), touched(plan.resources.size(), 0);
    for (size_t p = 0; p < n; ++p) {
        if (!in[p]) continue;
        set.passes.push_back(p);
        for (const PlanAccess& a : plan.passes[p].accesses) {
            touched[a.resource] = 1;
            if (usageWrites(a.usage)) written[a.resource] = 1;
        }
    }
    if (set.passes.empty()) return set;
    ContentHash h;
    h.str("rgraph once-per-build outputs, format 1");
    std::error_code ec;  // this build of the code: a pass kind's C++ may change what it writes
    h.u64(std::filesystem::file_size("/proc/self/exe", ec));
    h.u64(static_cast<uint64_t>(std::filesystem::last_write_time("/proc/self/exe", ec).time_since_epoch().count()));
    const VkPhysicalDeviceProperties& props = m_ctx.properties();
    h.u64((uint64_t(props.vendorID) << 32) | props.deviceID);
    h.u64(props.driverVersion);
    h.str(props.deviceName);
    h.str(m_ctx.deviceInfo().driver);
    for (size_t p : set.passes) {
        const PlanPass& pass = plan.passes[p];
        const PassDesc& desc = m_built->graph.passes[pass.desc];
        h.str(pass.name);
        h.str(desc.kind);
        hashValue(h, desc.params);
        for (const Access& a : desc.accesses) {
            h.str(a.resource);
            h.u64((uint64_t(a.usage) << 1) | uint64_t(a.load));
        }
        for (const std::string& f : m_built->instances[p]->files()) hashFile(h, f);
    }
    for (size_t i = 0; i < plan.resources.size(); ++i) {
        if (!touched[i]) continue;
        const PlanResource& r = plan.resources[i];
        h.str(r.name);
        for (uint64_t v : {uint64_t(r.kind), uint64_t(r.format), uint64_t(r.width), uint64_t(r.height), uint64_t(r.layers),
                           uint64_t(r.mips), uint64_t(r.cube), uint64_t(r.array), r.bufferSize, uint64_t(r.persistent)})
            h.u64(v);
        if (auto d = m_importData.find(r.name); r.imported && d != m_importData.end()) {
            h.u64(d->second.width);
            h.u64(d->second.height);
            h.u64(d->second.channels);
            h.bytes(d->second.pixels.data(), d->second.pixels.size() * sizeof(float));
        }
        if (written[i]) {
            set.resources.push_back(i);
            set.bytes += cachedBytes(r);
        }
    }
    h.u64(m_scene && m_onceSceneKey ? m_onceSceneKey(slot) : 0);
    set.key = h.value();
    return set;
}

namespace {

std::string onceCachePath(const std::string& dir, uint64_t key) {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(key));
    return (std::filesystem::path(dir) / "once" / name).string();
}

}  // namespace

// Records the copies between the set's resources and `staging` (their bytes back to back, as
// cachedBytes and cachedRegions lay them out), in either direction; the images go from and back to
// ShaderReadOnly, where every frame leaves a persistent texture.
void Executor::recordOnceCopies(VkCommandBuffer cmd, const OnceSet& set, VkBuffer staging, bool restore) {
    const Plan& plan = m_built->plan;
    const VkImageLayout transfer = restore ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const VkAccessFlags2 transferAccess = restore ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_TRANSFER_READ_BIT;
    if (!restore)
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkDeviceSize offset = 0;
    for (size_t i : set.resources) {
        const PlanResource& r = plan.resources[i];
        if (r.kind == ResourceKind::Buffer) {
            VkBuffer buffer = m_built->buffers[i]->buffer();
            VkBufferCopy c{restore ? offset : 0, restore ? 0 : offset, r.bufferSize};
            vkCmdCopyBuffer(cmd, restore ? staging : buffer, restore ? buffer : staging, 1, &c);
        } else {
            VkImage image = m_built->images[i]->image();
            const VkImageAspectFlags aspect = aspectOf(r.format);
            imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, transferAccess, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, transfer);
            const auto regions = cachedRegions(r, offset);
            if (restore) vkCmdCopyBufferToImage(cmd, staging, image, transfer, static_cast<uint32_t>(regions.size()), regions.data());
            else vkCmdCopyImageToBuffer(cmd, image, transfer, staging, static_cast<uint32_t>(regions.size()), regions.data());
            imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, restore ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT, transfer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
        offset += cachedBytes(r);
    }
    if (restore)
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    else
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

// Restores the due once passes' outputs when the cache has them (they then skip), else marks them
// to be saved after the frame. A missing, short or mismatched file is a miss, never an error.
Result<void> Executor::onceCacheBeforeFrame(uint32_t slot) {
    m_onceToSave.reset();
    OnceSet set = cacheableOncePasses(slot);
    if (set.passes.empty()) return {};
    m_onceStats = {};
    const auto t0 = Clock::now();
    const Plan& plan = m_built->plan;
    const std::string path = onceCachePath(m_onceDir, set.key);
    m_onceStats.file = path;
    std::ifstream in(path, std::ios::binary);
    bool hit = false;
    std::optional<Buffer> staging;
    if (in) {
        char magic[8] = {};
        uint64_t key = 0, count = 0;
        in.read(magic, 8);
        in.read(reinterpret_cast<char*>(&key), 8);
        in.read(reinterpret_cast<char*>(&count), 8);
        hit = in && std::equal(magic, magic + 8, kOnceMagic) && key == set.key && count == set.resources.size();
        if (hit) {
            auto buf = Buffer::create(m_ctx, "once_cache.upload", std::max<uint64_t>(set.bytes, 4), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
            if (!buf) return std::unexpected(buf.error());
            staging = std::move(*buf);
            auto* dst = static_cast<char*>(staging->mapped());
            for (size_t i : set.resources) {
                uint64_t bytes = 0;
                in.read(reinterpret_cast<char*>(&bytes), 8);
                if (!in || bytes != cachedBytes(plan.resources[i])) {
                    hit = false;
                    break;
                }
                in.read(dst, static_cast<std::streamsize>(bytes));
                dst += bytes;
            }
            hit = hit && in;
        }
    }
    if (!hit) {
        m_onceToSave = std::move(set);
        return {};
    }
    auto uploaded = m_ctx.submitNow([&](VkCommandBuffer cmd) { recordOnceCopies(cmd, set, staging->buffer(), /*restore=*/true); });
    if (!uploaded) return uploaded;
    for (size_t p : set.passes) m_built->instances[p]->restoredOnce(m_persistentEpoch);
    std::error_code ec;  // the entry's time orders the cache's eviction: this one is in use
    std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now(), ec);
    m_onceStats.restoredPasses = static_cast<uint32_t>(set.passes.size());
    m_onceStats.restoreMs = msSince(t0);
    return {};
}

// Once the frame that recorded them is done: the set's outputs read back and written to the cache
// (a temporary file renamed into place, so a reader never sees half an entry), then the oldest
// entries beyond kOnceCacheEntries removed. A cache that cannot be written is skipped with a
// warning: the frame was rendered.
Result<void> Executor::onceCacheAfterFrame(VkFence fence) {
    OnceSet set = std::move(*m_onceToSave);
    m_onceToSave.reset();
    RG_VK_TRY(vkWaitForFences(m_ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    const auto t0 = Clock::now();
    const Plan& plan = m_built->plan;
    auto staging = Buffer::create(m_ctx, "once_cache.readback", std::max<uint64_t>(set.bytes, 4), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto copied = m_ctx.submitNow([&](VkCommandBuffer cmd) { recordOnceCopies(cmd, set, staging->buffer(), /*restore=*/false); });
    if (!copied) return copied;
    const std::filesystem::path path = onceCachePath(m_onceDir, set.key);
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    const std::filesystem::path temp = path.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        const uint64_t count = set.resources.size();
        out.write(kOnceMagic, 8);
        out.write(reinterpret_cast<const char*>(&set.key), 8);
        out.write(reinterpret_cast<const char*>(&count), 8);
        const auto* src = static_cast<const char*>(staging->mapped());
        for (size_t i : set.resources) {
            const uint64_t bytes = cachedBytes(plan.resources[i]);
            out.write(reinterpret_cast<const char*>(&bytes), 8);
            out.write(src, static_cast<std::streamsize>(bytes));
            src += bytes;
        }
        if (!out) {
            std::fprintf(stderr, "rgraph: warning: could not write the once-per-build cache entry %s\n", temp.c_str());
            std::filesystem::remove(temp, ec);
            return {};
        }
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        return {};
    }
    std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> entries;
    for (const auto& e : std::filesystem::directory_iterator(path.parent_path(), ec))
        if (e.path().extension() == ".bin") entries.emplace_back(e.last_write_time(ec), e.path());
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t k = kOnceCacheEntries; k < entries.size(); ++k) std::filesystem::remove(entries[k].second, ec);
    m_onceStats.savedPasses = static_cast<uint32_t>(set.passes.size());
    m_onceStats.saveMs = msSince(t0);
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

Result<rg::Image> Executor::readback(const std::string& name, uint32_t layer, uint32_t mip) {
    auto found = exportedResource(name);
    if (!found) return std::unexpected(found.error());
    const PhysicalResource* phys = *found;
    if (!phys->image) return fail(ErrorCode::InvalidInput, "resource '" + name + "' is a buffer: use readbackBuffer");
    const PlanResource& r = *phys->plan;
    if (layer >= std::max(r.layers, 1u) || mip >= std::max(r.mips, 1u))
        return fail(ErrorCode::InvalidInput, "resource '" + name + "': no layer " + std::to_string(layer) + " / mip " + std::to_string(mip) +
                                                 " (it has " + std::to_string(r.layers) + " and " + std::to_string(r.mips) + ")");
    const uint32_t width = std::max(r.width >> mip, 1u), height = std::max(r.height >> mip, 1u);
    const uint32_t texelBytes = copyTexelBytes(r.format);
    const size_t texels = size_t(width) * height;
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
        region.imageSubresource = {copyAspect, mip, layer, 1};
        region.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host->buffer(), 1, &region);
        imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     toVkLayout(last == Layout::Undefined ? Layout::General : last));
    });
    if (!sub) return std::unexpected(sub.error());
    rg::Image out;
    out.width = width;
    out.height = height;
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
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
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
