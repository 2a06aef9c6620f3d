// The Lua 5.4 host: runs pipeline scripts in a sandbox and turns their declarations into a
// validated PipelineDesc; calls the script's rg.frame(ctx) before each frame.
//
// Sandbox: no io, no os except os.clock/os.time/os.date, no load/loadfile/dofile, no
// package.loadlib; `require` loads text chunks only from the pipeline's folder, scripts/ and
// materials/. A run is stopped past `instructions` VM instructions or `memoryBytes` of Lua
// memory, with an error that says so. Every error carries `file:line` and a traceback.
// C++ exceptions never cross lua_error. Threading: one thread per LuaHost.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "core/kind_schema.h"
#include "declarations.h"
#include "pipeline.h"

namespace rg {

struct LuaHostOptions {
    std::string projectRoot;              // chunk names are relative to it
    std::vector<std::string> searchDirs;  // for require, after the pipeline's own folder
    std::vector<PassKindSchema> kinds;    // what `kind = ...` may name
    uint64_t instructions = 100'000'000;  // per call into the script
    size_t memoryBytes = 256u << 20;
    // Scene scripts: `scene.args`, NAME = VALUE from the command line (--scene-arg); a value
    // that reads as a number is a number, else a string.
    std::map<std::string, std::string> sceneArgs;
};

struct FrameContext {
    uint64_t frame = 0;
    double time = 0.0;  // seconds
    // What the scene holds (ctx.scene in Lua; absent when the pipeline draws no scene).
    struct SceneFacts {
        uint32_t draws = 0, lights = 0, decals = 0;
        uint32_t suns = 0;     // directional lights (shadow cascades follow the first)
        uint32_t probes = 0;   // local light probes
        uint32_t blended = 0;  // draws of blended materials (the forward pass's)
        uint32_t lines = 0;    // draws of points and lines (a lines pass's)
        // Draws per stencil class (ctx.scene.classes.NAME): a pass that works on one class's
        // pixels only has nothing to do without them (scripts/lighting.lua's lighting.per_class).
        std::map<std::string, uint32_t> classes;
    };
    std::optional<SceneFacts> scene;
    uint32_t width = 0,
             height = 0;  // the output's size in pixels (ctx.width, ctx.height; 0: not known)
};

// What a debug view's function may ask of the scene (rg.view's v.scene).
struct ViewFacts {
    struct Light {
        std::string name;
        bool shadow = false;  // casts shadows
    };
    std::vector<Light> lights;              // in the scene's order: the GPU light list's index
    std::optional<uint32_t> lightmapLobes;  // the baked lightmap's SG lobes; none: no lightmap
};

// What rg.frame(ctx) changed. Parameters are applied without recompiling; enabling,
// disabling or swapping a shader is structural (the plan is recompiled incrementally).
// `enabled` are explicit switches (ctx.pass(p).enabled = v; the runtime keeps them until switched
// again), `automatic` what a module judges from the scene each frame (ctx.pass(p).auto_enabled:
// the default loop's passes without work), which the runtime applies only to passes no explicit
// switch has set (Session::frameChanges).
struct FrameChanges {
    std::map<std::string, Value> params;
    std::map<std::string, bool> enabled;         // pass -> enabled
    std::map<std::string, bool> automatic;       // pass -> enabled, unless switched explicitly
    std::map<std::string, std::string> shaders;  // pass -> shader path
    // ctx.cut(): a camera cut before this frame — every history (the graph's persistent resources:
    // TAA's, SSR's, the exposure) and the camera's last frame start afresh.
    bool cut = false;
    bool structural() const { return !enabled.empty() || !shaders.empty(); }
    bool empty() const { return params.empty() && automatic.empty() && !structural(); }
};

class LuaHost {
public:
    explicit LuaHost(LuaHostOptions options);
    ~LuaHost();
    LuaHost(const LuaHost&) = delete;
    LuaHost& operator=(const LuaHost&) = delete;

    // Runs the script in a fresh Lua state and validates what it declared.
    Result<PipelineDesc> load(const std::string& file);
    // Runs the script in a fresh Lua state and returns what it declared, unvalidated (scene
    // scripts: graph/scene turns scene.* declarations into a Scene). `files` gets every script
    // it loaded.
    Result<std::vector<Declaration>> loadDeclarations(const std::string& file,
                                                      std::vector<std::string>* files = nullptr);
    bool hasFrameCallback() const;
    // Calls rg.frame(ctx); `current` supplies parameter values and pass states to read.
    Result<FrameChanges> frame(const FrameContext& ctx, const PipelineDesc& current);

    // The debug view `view` added to `loaded`, the pipeline load() returned: the function of the
    // view registered with rg.view under that name (or whose pattern matches it) declares its
    // passes and resources after the pipeline's, then everything is validated again. Views
    // come from the scripts the pipeline loaded and, when none of them has `view`, from
    // scripts/views.lua (the standard views). `scene`: what the scene holds (nullptr: none).
    // An unknown view, or one the pipeline or scene cannot show, is an error saying why.
    Result<PipelineDesc> addView(const std::string& view, const PipelineDesc& loaded,
                                 const ViewFacts* scene);

    struct Impl;  // the Lua state and what the script declared (lua_host_impl.h)

private:
    std::unique_ptr<Impl> m;
};

// Applies changes to a pipeline in place (parameters validated already).
void applyFrameChanges(PipelineDesc& pipeline, const FrameChanges& changes);

// The GraphDesc to build: the pipeline's graph with every parameter merged into each pass's
// `uniforms` (a pass's own uniforms win), and the output exported.
// Also resolves stencil = { class = "name" } to the class's ref and mask, and gives each
// `scene` pass its materials (PassDesc::materials, see sceneMaterials), and the parameters a
// pass names in `switches` into its defines.
GraphDesc graphWithParams(const PipelineDesc& pipeline);

// Whether some pass compiles `param` into its shaders (switches = { param = "DEFINE" }) or an
// only_when names it (it chooses resources and passes): a change to it rebuilds the graph's
// changed passes rather than updating uniforms.
bool isSwitch(const PipelineDesc& pipeline, const std::string& param);

// Makes absolute the passes' relative shader paths that name a file next to the pipeline script
// (shaders/ and the project root are searched by the shader compiler anyway).
void resolveShaderPaths(GraphDesc& graph, const std::string& pipelineFile,
                        const std::string& projectRoot = "");

// The pipeline materials a scene pass draws (params.materials / params.paths; default all that
// have a surface), typed: `custom` lists the numeric material params in key order, the order of
// MaterialData.custom.
std::vector<PassMaterial> sceneMaterials(const PipelineDesc& pipeline, const Value& passParams);

}  // namespace rg
