// Executor: construction, and the build — the graph compiled against the device, its physical
// resources placed and created, a pass instance prepared for each kept pass (reused if unchanged).
#include "executor.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "core/names.h"
#include "executor_detail.h"
#include "gpu/compile_scope.h"
#include "shader/shader_compiler.h"

namespace rg::gpu {

namespace {

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

bool sameHeap(const TransientHeap& a, const TransientHeap& b) {
    return a.size == b.size && a.memoryTypeBits == b.memoryTypeBits && a.buffers == b.buffers;
}

// Same physical shape: a resource built for `a` serves `b`.
bool sameShape(const PlanResource& a, const PlanResource& b) {
    return a.kind == b.kind && a.format == b.format && a.width == b.width && a.height == b.height &&
           a.layers == b.layers && a.mips == b.mips && a.cube == b.cube && a.array == b.array &&
           a.bufferSize == b.bufferSize && a.usageMask == b.usageMask &&
           a.transient == b.transient && a.imported == b.imported && a.persistent == b.persistent;
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
        stamp += f + "@" + std::to_string(t.time_since_epoch().count()) + ":" +
                 std::to_string(size) + ";";
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
        if (a[i].resource != b[i].resource || a[i].usage != b[i].usage || a[i].load != b[i].load)
            return false;
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
    s += ", reused " + std::to_string(passesReused.size()) +
         "; resources: " + std::to_string(resourcesCreated) + " created, " +
         std::to_string(resourcesReused) + " reused";
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

Result<void> Executor::build(const GraphDesc& graphIn, const CompileOptions& optionsIn) {
    if (m_slots.empty())
        if (auto r = createSlots(); !r) return r;
    GraphDesc graph = graphIn;
    if (auto r = resolveKinds(graph); !r) return r;
    // Resources the scene sizes: a buffer's scene_count = NAME gives count_bytes more per item of
    // the scene's extent NAME (none without a scene); a texture's scene_layers = NAME the layers
    // the extent says, at most those declared — e.g. a shadow-view array gets the views its
    // shadowed local lights can use; an extent of 0 gets one 1×1 layer, not the declared capacity
    // (24 MiB at 1024² × 6 in d32f). A name the scene lacks is an error naming the resource.
    auto extentOf = [&](const ResourceDesc& r, const std::string& field,
                        const std::string& name) -> Result<uint32_t> {
        if (!m_scene) return 0u;
        if (const std::optional<uint32_t> extent = m_scene->layerExtent(name)) return *extent;
        std::string names;
        for (const auto& n : m_scene->extentNames())
            names += (names.empty() ? "'" : ", '") + n + "'";
        return fail(ErrorCode::InvalidInput, (r.origin.empty() ? "" : r.origin + ": ") +
                                                 "resource '" + r.name + "': " + field + " = '" +
                                                 name + "': the scene has no such extent (it has " +
                                                 names + ")");
    };
    for (ResourceDesc& r : graph.resources) {
        if (r.kind != ResourceKind::Buffer || r.buffer.sceneCount.empty()) continue;
        auto extent = extentOf(r, "scene_count", r.buffer.sceneCount);
        if (!extent) return std::unexpected(extent.error());
        r.buffer.size += uint64_t(*extent) * r.buffer.countBytes;
        r.buffer.sceneCount.clear();
    }
    if (m_scene)
        for (ResourceDesc& r : graph.resources) {
            if (r.kind != ResourceKind::Texture || r.texture.sceneLayers.empty()) continue;
            auto extent = extentOf(r, "scene_layers", r.texture.sceneLayers);
            if (!extent) return std::unexpected(extent.error());
            r.texture.layers = std::clamp(*extent, 1u, r.texture.layers);
            if (*extent == 0) {
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
        if (r.kind == ResourceKind::Texture)
            req = Image::requirements(ctx, imageDescOf(r));
        else
            req = Buffer::requirements(ctx, r.bufferSize, bufferUsageOf(r.usageMask));
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
    const bool samePassInputs =
        old && old->sceneId == sceneId() && old->generatedDir == generatedDir;
    const Built* oldPasses = m_forceRebuild || !samePassInputs ? nullptr : old;
    auto built = std::make_unique<Built>();
    built->plan = std::move(*plan);
    built->sceneId = sceneId();
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
        auto mem = m_ctx.allocator().allocateHeap(std::max<uint64_t>(heap.size, 1),
                                                  heap.memoryTypeBits, type);
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
            auto img = r.heap >= 0 ? Image::createPlaced(
                                         m_ctx, d, built->heaps[static_cast<size_t>(r.heap)]->get(),
                                         r.offset)
                                   : Image::create(m_ctx, d);
            if (!img) return std::unexpected(img.error());
            built->images[i] = std::make_shared<Image>(std::move(*img));
        } else {
            VkBufferUsageFlags usage = bufferUsageOf(r.usageMask);
            auto buf = r.heap >= 0 ? Buffer::createPlaced(
                                         m_ctx, r.name, r.bufferSize, usage,
                                         built->heaps[static_cast<size_t>(r.heap)]->get(), r.offset)
                                   : Buffer::create(m_ctx, r.name, r.bufferSize, usage, false);
            if (!buf) return std::unexpected(buf.error());
            built->buffers[i] = std::make_shared<Buffer>(std::move(*buf));
        }
    }
    for (size_t i = 0; i < planPtr->resources.size(); ++i)
        built->table.set(planPtr->resources[i].name,
                         PhysicalResource{&planPtr->resources[i], built->images[i].get(),
                                          built->buffers[i].get()});
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
                bool resourcesKept =
                    std::all_of(pass.accesses.begin(), pass.accesses.end(),
                                [&](const PlanAccess& a) { return resourceReused[a.resource]; });
                const auto& instance = old->instances[static_cast<size_t>(o)];
                if (od.kind == desc.kind && sameAccesses(od.accesses, desc.accesses) &&
                    resourcesKept && withoutUniforms(od.params) == withoutUniforms(desc.params) &&
                    od.materials == desc.materials &&
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
    if (auto r = prepareInParallel(*built, *planPtr, toPrepare); !r)
        return std::unexpected(r.error());
    for (size_t p = 0; p < passCount; ++p)
        (prepared[p] ? report.passesPrepared : report.passesReused)
            .push_back(planPtr->passes[p].name);
    m_buildStats.prepareMs = msSince(t2);

    // A history (rg.resource's `history`) whose source is now written otherwise than last frame
    // starts empty: a pass writing the source was prepared anew (its shader reloaded, its
    // parameters or inputs changed, a new scene) or the set of passes writing it changed (one
    // switched on or off). A resized source resizes its history, which a new resource clears.
    auto writersOf = [](const Plan& plan, const std::string& resource) {
        std::vector<std::string> names;
        const int32_t r = plan.findResource(resource);
        if (r < 0) return names;
        for (const PlanPass& pass : plan.passes)
            if (std::any_of(pass.accesses.begin(), pass.accesses.end(), [&](const PlanAccess& a) {
                    return a.resource == static_cast<uint32_t>(r) && usageWrites(a.usage);
                }))
                names.push_back(pass.name);
        return names;
    };
    std::vector<bool> historyStale(planPtr->resources.size(), false);
    for (size_t i = 0; i < planPtr->resources.size(); ++i) {
        const std::string& source = built->graph.resources[planPtr->resources[i].desc].historyOf;
        if (source.empty() || !resourceReused[i]) continue;
        const auto writers = writersOf(*planPtr, source);
        historyStale[i] = !old || writers != writersOf(old->plan, source);
        for (size_t p = 0; p < passCount && !historyStale[i]; ++p)
            historyStale[i] = prepared[p] && std::find(writers.begin(), writers.end(),
                                                       planPtr->passes[p].name) != writers.end();
    }

    // Upload imported contents into resources that are new.
    for (size_t i = 0; i < planPtr->resources.size(); ++i) {
        const PlanResource& r = planPtr->resources[i];
        if (!r.imported || resourceReused[i] || m_hostImports.count(r.name))
            continue;  // the host's image comes in each frame
        if (!m_importData.count(r.name))
            return fail(
                ErrorCode::InvalidInput,
                "imported resource '" + r.name + "' has no contents (nothing was uploaded for it)");
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
        if (historyStale[i])  // the once passes' outputs stand: no new epoch
            if (auto u = clearContents(i); !u) return u;
    }
    return {};
}

// Prepares the listed passes of `built` (indices into plan.passes), in order of their indices as
// far as anything but the pipeline compiles goes: each worker prepares one pass at a time under
// one lock and gives it up inside vkCreate*Pipelines (gpu/compile_scope.h), so the driver's
// compiles overlap — on lavapipe most of the set-up time (2 threads: the default pipeline's
// ~500 ms → ~300 ms). RG_PREPARE_THREADS=N sets the thread count (1: serial). The first failing
// pass in plan order gives the error, whichever thread met it first.
Result<void> Executor::prepareInParallel(Built& built, const Plan& plan,
                                         const std::vector<size_t>& passes) {
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
            prepared =
                fail(ErrorCode::Device, "pass '" + pass.name + "': set-up failed: " + e.what());
        }
        if (!prepared) {
            errors[k] = prepared.error();
            return;
        }
        built.sourceStamps[p] = sourceStamp(*instance).value_or(std::string());
        built.instances[p] = std::move(instance);
    };
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    if (const char* env = std::getenv("RG_PREPARE_THREADS"); env && std::atoi(env) > 0)
        threads = static_cast<unsigned>(std::atoi(env));
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

// A new persistent resource starts as zeros, in the state every frame expects it in; the
// passes due once per persistent epoch (cadence "once") run again.
Result<void> Executor::clearPersistent(size_t index) {
    ++m_persistentEpoch;
    return clearContents(index);
}

Result<void> Executor::clearContents(size_t index) {
    const PlanResource& r = m_built->plan.resources[index];
    Image* image = m_built->images[index].get();
    Buffer* buffer = m_built->buffers[index].get();
    return m_ctx.submitNow([&](VkCommandBuffer cmd) {
        if (buffer) {
            vkCmdFillBuffer(cmd, buffer->buffer(), 0, VK_WHOLE_SIZE, 0);
            memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
            return;
        }
        VkImageAspectFlags aspect = aspectOf(r.format);
        imageBarrier(cmd, image->image(), aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkImageSubresourceRange range{aspect, 0, VK_REMAINING_MIP_LEVELS, 0,
                                      VK_REMAINING_ARRAY_LAYERS};
        if (isDepthStencil(r.format)) {
            VkClearDepthStencilValue zero{0.0f, 0};
            vkCmdClearDepthStencilImage(cmd, image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                        &zero, 1, &range);
        } else {
            VkClearColorValue zero{};
            vkCmdClearColorImage(cmd, image->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero,
                                 1, &range);
        }
        imageBarrier(cmd, image->image(), aspect, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

void Executor::setScene(const SceneBinding* scene, std::function<void(uint32_t)> perFrame) {
    m_scene = scene;
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

const Plan& Executor::plan() const {
    static const Plan kEmpty;
    return m_built ? m_built->plan : kEmpty;
}

const GraphDesc& Executor::graph() const {
    static const GraphDesc kEmpty;
    return m_built ? m_built->graph : kEmpty;
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
