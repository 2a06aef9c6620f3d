// The contract between the executor and pass kinds (implemented in passes/). A pass kind is
// generic; a pipeline gives it shaders and bindings through PassDesc::params. Each kept pass of
// a plan gets its own PassInstance: prepare() once per plan build (pipelines, descriptor sets),
// record() once per frame.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/graph.h"
#include "core/kind_schema.h"
#include "core/plan.h"
#include "image/image.h"
#include "resources.h"
#include "scene_binding.h"

namespace rg {
class ShaderCompiler;
}

namespace rg::gpu {

// The physical resource behind a plan resource. Exactly one of image / buffer is set.
struct PhysicalResource {
    const PlanResource* plan = nullptr;
    Image* image = nullptr;
    Buffer* buffer = nullptr;
};

class ResourceTable {
public:
    const PhysicalResource* find(const std::string& name) const {
        auto it = m_byName.find(name);
        return it == m_byName.end() ? nullptr : &it->second;
    }
    void set(const std::string& name, PhysicalResource r) { m_byName[name] = r; }
    void clear() { m_byName.clear(); }

private:
    std::map<std::string, PhysicalResource> m_byName;
};

struct PassSetup {
    Context& gpu;
    ShaderCompiler& shaders;
    const Plan& plan;
    const PlanPass& pass;
    const PassDesc& desc;
    const ResourceTable& resources;
    const SceneBinding* scene = nullptr;  // the loaded scene, if any
    // Floor mode (rgraph bench --floors): every shader program replaces its fragment shader by one
    // that writes zeros to the same outputs, and its compute shader by an empty one of the same
    // work-group size — the pass's cost with the same targets, geometry and dispatches.
    bool floor = false;
};

struct FrameInfo {
    uint64_t index = 0;      // frames rendered since the plan was built
    double timeSeconds = 0;  // fixed step in tests: index / 60
    uint32_t slot = 0;       // frame-in-flight slot
    // Counts the times persistent resources were cleared (new resources, a reset of history):
    // a pass that fills a persistent resource once (the compute kind's cadence = "once") fills it
    // again when this changes.
    uint64_t persistentEpoch = 0;
};

struct RecordContext {
    Context& gpu;
    VkCommandBuffer cmd;
    const PlanPass& pass;
    const PassDesc& desc;
    const ResourceTable& resources;
    const Plan& plan;
    FrameInfo frame;
    const SceneBinding* scene = nullptr;  // the loaded scene, if any
};

class PassInstance {
public:
    virtual ~PassInstance() = default;
    // Errors name the pass and the parameter ("pass 'tonemap': params.shader: ...").
    virtual Result<void> prepare(PassSetup& setup) = 0;
    virtual void record(RecordContext& ctx) = 0;
    // Files this pass was built from (shaders and their includes), for hot reload.
    virtual std::vector<std::string> files() const { return {}; }
    // A pass that records once per build (cadence = "once") and has yet to for this persistent
    // epoch; restoredOnce tells it that the executor restored its outputs from the disk cache
    // instead (Executor::setOnceCache), so it does not record until the next epoch or build.
    virtual bool dueOnce(uint64_t /*epoch*/) const { return false; }
    virtual void restoredOnce(uint64_t /*epoch*/) {}
    // Data a pass copied to the host in the last finished frame (the readback kind).
    virtual std::optional<rg::Image> hostResult() const { return std::nullopt; }
};

struct PassKindInfo {
    PassKindSchema schema;  // name, type, parameters: what scripts may declare
    std::function<std::unique_ptr<PassInstance>()> create;
};

class PassRegistry {
public:
    void add(PassKindInfo info) { m_kinds[info.schema.name] = std::move(info); }
    const PassKindInfo* find(const std::string& name) const {
        auto it = m_kinds.find(name);
        return it == m_kinds.end() ? nullptr : &it->second;
    }
    std::vector<PassKindSchema> schemas() const {
        std::vector<PassKindSchema> out;
        for (const auto& [n, k] : m_kinds) out.push_back(k.schema);
        return out;
    }
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& [n, _] : m_kinds) out.push_back(n);
        return out;
    }

private:
    std::map<std::string, PassKindInfo> m_kinds;
};

}  // namespace rg::gpu
