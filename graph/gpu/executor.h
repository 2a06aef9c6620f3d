// Executor: turns a compiled Plan into GPU work. build() compiles the graph against the
// device's memory requirements, places transient resources in shared heaps, creates the
// exported/imported ones with their own memory, and prepares one PassInstance per kept pass.
// frame() records the plan (dynamic rendering, synchronization2 barriers, one timestamp pair
// per pass, debug labels) into the next frame-in-flight slot and submits it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/compiler.h"
#include "image/image.h"
#include "pass_kind.h"

namespace rg::gpu {

struct PassTiming {
    std::string name;
    double gpuMs = 0.0;
    double cpuMs = 0.0;  // recording its commands (the pass instance's record())
};

struct BuildStats {
    double compileMs = 0.0;    // graph compile()
    double resourcesMs = 0.0;  // physical resources
    double prepareMs = 0.0;    // pass instances (shaders, pipelines)
};

// What an incremental build reused and what it made anew.
struct BuildReport {
    std::vector<std::string> passesPrepared;  // new pass instances (pipelines, descriptor sets)
    std::vector<std::string> passesReused;
    uint32_t resourcesCreated = 0;
    uint32_t resourcesReused = 0;
    std::string summary() const;
};

// An image of the host application's (a swapchain image, its own target), in `layout` before a
// frame and left in it after: rgraph copies it into an imported texture at the frame's start, or
// an exported texture into it at the frame's end (a blit: formats may differ, sizes must match).
struct HostImage {
    VkImage image = VK_NULL_HANDLE;
    uint32_t width = 0, height = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

class Executor {
public:
    Executor(Context& ctx, ShaderCompiler& shaders, const PassRegistry& kinds);
    ~Executor();
    Executor(const Executor&) = delete;
    Executor& operator=(const Executor&) = delete;

    // Fills each PassDesc::type from its kind and rejects unknown kinds (with a suggestion).
    Result<void> resolveKinds(GraphDesc& graph) const;
    // Compiles and builds. Resources and pass instances of the previous build that did not
    // change are reused; the rest of it is retired through the deletion queue. On failure the
    // previous build stays in place, untouched.
    Result<void> build(const GraphDesc& graph, const CompileOptions& options);
    const BuildReport& lastBuildReport() const { return m_lastReport; }
    uint32_t buildCount() const { return m_buildCount; }
    // Zeros every persistent resource (a new pipeline starts without history).
    Result<void> resetPersistent();
    // New `uniforms` of each pass (parameter changes): nothing is rebuilt or re-recorded.
    void updateUniforms(const GraphDesc& graph);

    // The scene passes draw and bind (camera, lights, materials); the next build prepares every
    // pass anew unless it is the scene (SceneBinding::id) the running build was prepared against.
    // A texture with `scene_layers = NAME` gets the layers the scene's extent NAME says.
    // `perFrame` runs before each frame is recorded, with its frame-in-flight slot.
    void setScene(const SceneBinding* scene, std::function<void(uint32_t slot)> perFrame);
    // Floor mode for the builds that follow (PassSetup::floor): every pass is prepared again.
    void setFloors(bool on);
    const SceneBinding* scene() const { return m_scene; }
    uint64_t sceneId() const { return m_scene ? m_scene->id() : 0; }  // 0 without a scene

    // Contents for an imported texture (uploaded now, then kept in ShaderReadOnly layout).
    Result<void> setImport(const std::string& name, const rg::Image& data);

    // The host's images: copied into `name` (an imported texture) at every frame's start, or
    // `name` (any texture of the plan) copied into them at its end. An empty image removes it.
    void setHostImport(const std::string& name, const HostImage& image);
    void setHostExport(const std::string& name, const HostImage& image);

    // Records and submits one frame on rgraph's queue. With `hostCmd`, records it into the
    // host's command buffer instead (no timestamps); the host submits it and must have waited
    // for the frame before the one it records next (the frames-in-flight slots are reused).
    Result<void> frame(VkCommandBuffer hostCmd = VK_NULL_HANDLE);
    Result<void> finish();  // waits for every submitted frame and gathers their timings

    // Reads one layer and mip (default: mip 0 / layer 0) of an exported texture after finish().
    // `stencil`: a depth/stencil texture's stencil values (one channel, 0..255).
    Result<rg::Image> readback(const std::string& resource, uint32_t layer = 0, uint32_t mip = 0,
                               bool stencil = false);
    Result<std::vector<uint8_t>> readbackBuffer(const std::string& resource);
    // What a readback pass copied in the last finished frame.
    Result<rg::Image> passResult(const std::string& pass);

    // The disk cache of once-per-build outputs (off until set; never in floor mode or for frames
    // the host records). Before a frame in which passes with cadence = "once" are due, their
    // outputs are restored from `dir`/once/KEY.bin when it exists — the passes then skip, as if
    // they had recorded — else they record and their outputs are written there once the frame is
    // done. KEY hashes what those outputs are a function of: the device and driver, the passes
    // (kind, parameters, accesses, shader sources with their includes), the resources'
    // descriptions, imported contents and the scene's SceneBinding::contentHash(slot), so a
    // change to any of them makes a new entry. A once pass that reads anything else (an output of
    // a per-frame pass, a host image) is never cached, nor is what reads its outputs. The newest
    // kOnceCacheEntries entries are kept.
    void setOnceCache(std::string dir);
    struct OnceCacheStats {
        uint32_t restoredPasses = 0, savedPasses = 0;  // in the last frame that had any due
        double restoreMs = 0.0, saveMs = 0.0;
        std::string file;  // the entry they were restored from or saved to
    };
    const OnceCacheStats& onceCacheStats() const { return m_onceStats; }
    static constexpr size_t kOnceCacheEntries = 8;

    const Plan& plan() const;
    const GraphDesc& graph() const;
    const BuildStats& buildStats() const { return m_buildStats; }
    const std::vector<PassTiming>& lastTimings() const { return m_lastTimings; }
    double lastRecordMs() const { return m_lastRecordMs; }
    // Of it, the scene's per-frame update (setScene's perFrame: the camera, moving nodes, shadow
    // views; the camera's culling and levels run when a pass first asks, in its recording).
    double lastSceneUpdateMs() const { return m_lastSceneUpdateMs; }
    uint64_t framesSubmitted() const { return m_frameIndex; }
    // The frame number shaders see (rg_frame, rg_time = number / 60 s) is `first` + the frames
    // submitted: a range of a sequence (rgraph render --frames A..B) numbers its frames as the
    // whole run would.
    void setFrameNumberBase(uint64_t first) { m_frameNumberBase = first; }
    std::vector<std::string> files() const;  // shader files of every pass

private:
    struct FrameSlot {
        OwnedCommandPool pool;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        OwnedFence fence;
        OwnedQueryPool queries;
        uint32_t queryCapacity = 0;  // the pool's size
        uint32_t queryCount = 0;     // the pass timestamps collect() reads
        bool pending = false;        // submitted, timings not yet read
        std::vector<std::string> passNames;
        std::vector<double> passCpuMs;
    };
    struct Built;  // physical resources + pass instances of one plan

    Result<void> createSlots();
    Result<void> collect(FrameSlot& slot);
    void recordBarriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers);
    Result<void> clearPersistent(size_t index);  // zeros, and a new persistent epoch
    Result<void> clearContents(size_t index);    // zeros only (an emptied history)
    Result<void> prepareInParallel(Built& built, const Plan& plan,
                                   const std::vector<size_t>& passes);
    Result<const PhysicalResource*> exportedResource(const std::string& name);
    struct OnceSet {
        std::vector<size_t> passes, resources;  // plan indices
        uint64_t bytes = 0;                     // the resources' contents, back to back
        uint64_t key = 0;
    };
    OnceSet cacheableOncePasses(uint32_t slot) const;
    Result<void> onceCacheBeforeFrame(uint32_t slot);
    Result<void> onceCacheAfterFrame(VkFence fence);
    void recordOnceCopies(VkCommandBuffer cmd, const OnceSet& set, VkBuffer staging, bool restore);

    Context& m_ctx;
    ShaderCompiler& m_shaders;
    const PassRegistry& m_kinds;
    std::unique_ptr<Built> m_built;
    std::vector<FrameSlot> m_slots;
    std::map<std::string, rg::Image> m_importData;
    std::map<std::string, HostImage> m_hostImports, m_hostExports;
    Result<void> recordHostCopies(VkCommandBuffer cmd, bool imports);
    uint64_t m_frameIndex = 0;
    uint64_t m_frameNumberBase = 0;  // setFrameNumberBase
    uint64_t m_persistentEpoch = 0;  // FrameInfo::persistentEpoch
    const SceneBinding* m_scene = nullptr;
    std::function<void(uint32_t)> m_perFrame;
    bool m_forceRebuild = false;
    bool m_floors = false;
    BuildStats m_buildStats;
    BuildReport m_lastReport;
    uint32_t m_buildCount = 0;
    std::vector<PassTiming> m_lastTimings;
    double m_lastRecordMs = 0.0;
    double m_lastSceneUpdateMs = 0.0;
    std::string m_onceDir;
    std::optional<OnceSet> m_onceToSave;  // recorded this frame: written after it
    OnceCacheStats m_onceStats;
};

}  // namespace rg::gpu
