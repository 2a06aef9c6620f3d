// Session: a pipeline script running on the executor. load() is transactional — a script that
// fails to load or compile leaves the previous pipeline running and returns the error. Each frame
// calls the script's rg.frame(ctx) once and applies what it changed (parameters: uniforms only;
// enabling/disabling a pass or swapping its shader: an incremental rebuild) before rendering; the
// first frame after a load has its callback run by load(), whose build already holds what it
// changed, so frame() then applies only overrides set since.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bake/lightmap.h"
#include "lua/lua_host.h"
#include "passes/gpu_scene.h"
#include "runtime.h"

namespace rg {

struct SessionOptions {
    CompileOptions compile;
    // The scene (.lua, .gltf, .glb) the pipeline's `scene` passes draw; "" = the default scene
    // (scripts/scenes/default.lua) when the pipeline has a scene pass.
    std::string scene;
    // A scene made in memory (the library's Renderer::setScene): drawn instead of `scene`.
    std::shared_ptr<const Scene> sceneData;
    std::string camera;                            // a camera of the scene by name; "" = its first
    std::map<std::string, std::string> sceneArgs;  // a Lua scene's `scene.args` (--scene-arg)
    // --environment: "" = the scene's own (a glTF scene with no light and no environment gets the
    // sky); "sky", "none", or an equirectangular .hdr/.exr file (graph/scene/environment.h).
    std::string environment;
    // --environment-sun: "" = the scene's own mode; "auto", "light", "remove" or "keep" (scene.h
    // Environment::sun) for an "hdr" environment.
    std::string environmentSun;
    // --variant: a glTF scene's KHR_materials_variants variant by name ("" = its defaults).
    std::string variant;
    // A debug view instead of the pipeline's display image: a view of the pipeline's scripts
    // (rg.view) or of scripts/views.lua (normals, stencil, lights, shadow:LIGHT, sgN, ...),
    // drawn into `debug_view` after the pipeline's passes.
    std::string view;
    std::vector<std::string> captures;  // resources to export for readback
    bool verbose = false;               // print what each rebuild reused
    // Print what the scene's loaders skipped or changed (Scene::warnings: an extension ignored,
    // a texture without a source) even when not verbose; the command line does, the library
    // leaves them to Renderer's log.
    bool warnings = false;
    bool levelsOfDetail =
        true;  // the primitives' coarser levels where they stay within a pixel (GpuSceneOptions)
    // The folder whose once/ holds the outputs of passes with cadence = "once", restored from there
    // and saved there (gpu::Executor::setOnceCache); "" (the default: tests, bench) records them.
    std::string onceCache;
    // Bakes a scene.lightmap missing from the lightmap cache (rg_baker's bake::bakeLightmap, which
    // the command line and the golden runner link); null: such a scene is an error naming the command.
    bake::BakeFunction bakeLightmap = nullptr;
    // Parameter values set when a script loads (after the scene's camera settings), checked like
    // ctx.params: the golden tests' `params` and determinism profile.
    std::map<std::string, Value> params;
    // Values for parameters a pipeline may not declare, set where it does (checked the same): a
    // test harness's profile, e.g. taa_jitter = false for images compared pixel by pixel.
    std::map<std::string, Value> paramsIfDeclared;
    // Called every frame after the script's rg.frame with the pipeline as rg.frame left it; its
    // changes are applied on top (the golden tests' frame callbacks).
    std::function<Result<FrameChanges>(const FrameContext&, const PipelineDesc&)> frameHook;
    // The number the first frame renders as (ctx.frame; ctx.time = frame / 60 s): a range of a
    // scripted sequence (rgraph render --frames A..B) starts where the whole run would be.
    uint64_t firstFrame = 0;
};

class Session {
public:
    Session(Runtime& runtime, SessionOptions options);
    ~Session();

    Result<void> load(const std::string& pipelineFile);
    // One frame: rg.frame's changes, then recorded and submitted — or, with `hostCmd`, recorded
    // into the host's command buffer for the host to submit (Executor::frame).
    Result<void> frame(VkCommandBuffer hostCmd = VK_NULL_HANDLE);
    // Parameter values and pass switches that hold over the script's rg.frame (applied after it
    // each frame, as SessionOptions::frameHook's are): `rgraph serve`'s controls, the library's
    // setParameter/setPassEnabled. Applied at once, through the same path as rg.frame's changes:
    // an unknown parameter or pass, a wrong type, a value out of range, or a change the graph
    // cannot be built with (a pass a kept pass needs switched off, a switch whose shader does not
    // compile) is an error, and nothing changes — the running plan keeps rendering.
    Result<void> setOverride(const std::string& param, const Value& value);
    // A camera cut before the next frame (as rg.frame's ctx.cut()): every history — the graph's
    // persistent resources (TAA's, SSR's, the exposure) — and the camera's last frame start afresh.
    void cut() { m_cutRequested = true; }
    // Places the scene's dynamic node `name` at `world` from the next frame
    // (passes::GpuScene::setNodeTransform); an error without a scene.
    Result<void> setNodeTransform(const std::string& name, const glm::mat4& world);
    Result<void> setPassOverride(const std::string& pass, bool enabled);
    const FrameChanges& overrides() const { return m_overrides; }
    // Overrides carried over from another session (the library's reload for a new scene or size),
    // before load(): the load applies those its pipeline still has and accepts, and notes each
    // one it drops.
    void carryOverrides(const FrameChanges& overrides);
    // Exports one more resource for readback (or decodes one more G-buffer channel): reloads the
    // pipeline with it when one is loaded. A name the pipeline has neither as a resource nor as a
    // channel is an error, and nothing changes.
    Result<void> addCapture(const std::string& name);
    const std::vector<std::string>& captures() const { return m_options.captures; }

    const PipelineDesc& pipeline() const { return m_pipeline; }
    uint64_t framesRendered() const { return m_frame; }
    uint32_t rebuilds() const { return m_rebuilds; }  // structural rebuilds since the last load
    uint64_t loads() const { return m_loads; }        // successful loads so far
    double lastFrameCallbackMs() const { return m_callbackMs; }
    double lastLoadMs() const { return m_loadMs; }
    const std::vector<std::string>& log() const { return m_log; }
    const Scene* scene() const;
    const passes::GpuScene* gpuScene() const { return m_scene.get(); }
    // Reading, building and uploading the scene at the last load (file to GPU), ms; 0 without one.
    double lastSceneLoadMs() const { return m_sceneLoadMs; }
    // A capture that names a G-buffer channel ("gbuffer.smoothness" or "<layout>.<channel>"):
    // the layout that holds it. Its targets are exported; `render` decodes the channel.
    // `--capture gbuffer.X` / `LAYOUT.X`: decoded per pixel with its material's layout, the
    // material named by the pixel's stencil (`stencil`; `byId` gives each identity's layout and channel —
    // gbuffer.X maps a standard name through the material's `channels`); pixels whose material
    // has no such channel are NaN.
    struct ChannelCapture {
        std::string name;
        LayoutDesc layout;
        std::string channel;
        std::map<uint32_t, std::pair<LayoutDesc, std::string>> byId;  // by identity
        std::string stencil;  // the depth whose stencil holds the identities, or ""
    };
    const std::vector<ChannelCapture>& channelCaptures() const { return m_channels; }
    // A channel capture read back and decoded, after a frame: see ChannelCapture.
    Result<Image> channelImage(const ChannelCapture& capture) const;
    // The image `render` shows: the view's when a view is set, else the pipeline's display.
    std::string displayResource() const {
        return m_options.view.empty() ? m_pipeline.output : "debug_view";
    }
    // Scripts and shaders the running pipeline was built from (what `watch` polls).
    std::vector<std::string> files() const;
    bool loaded() const { return m_host != nullptr; }

private:
    // The graph the executor builds: parameters in, shader paths resolved (with
    // keepMissingShaders, a pass whose shader file went missing keeps the path it was built
    // from), captures exported.
    Result<GraphDesc> buildableGraph(const PipelineDesc& p, bool keepMissingShaders);
    // The frame context of frame m_frame (ctx in rg.frame), with what the scene holds (`facts`,
    // counted once per load), and what the script's rg.frame, the frame hook and the overrides
    // change for it in `pipeline`.
    FrameContext frameContext(const std::optional<FrameContext::SceneFacts>& facts) const;
    // One rule for pass switches: the overrides (the library, the live page) win, then the
    // explicit switches of rg.frame and the frame hook — kept in `switches` until switched again,
    // so a script switches a pass once — then the automatic ones (auto_enabled), only for passes
    // neither has set. `switches` gets this frame's explicit switches (the caller keeps it when
    // the changes are applied).
    Result<FrameChanges> frameChanges(LuaHost& host, const FrameContext& ctx,
                                      const PipelineDesc& pipeline, const FrameChanges& overrides,
                                      std::map<std::string, bool>& switches);
    Result<std::unique_ptr<passes::GpuScene>> loadScene(PipelineDesc& pipeline);
    // `changes` on top of the running pipeline: updated uniforms, or a rebuild of the passes they
    // touch. A build that fails leaves the pipeline and the executor's plan as they were.
    Result<void> apply(const FrameChanges& changes);
    void note(const std::string& line);
    void warn(const std::string& line);  // note(), printed also when options.warnings

    Runtime& m_runtime;
    SessionOptions m_options;
    std::unique_ptr<LuaHost> m_host;
    std::unique_ptr<passes::GpuScene> m_scene;
    // What m_scene holds for the pipeline (ctx.scene): fixed while the two stay loaded.
    std::optional<FrameContext::SceneFacts> m_sceneFacts;
    std::string m_sceneFile;
    double m_sceneLoadMs = 0;
    std::string m_sceneKey;  // the scene's files (contents) and arguments at the last load
    std::function<void(uint32_t)> m_sceneUpdate;  // writes the scene's camera for a frame slot
    PipelineDesc m_pipeline;
    uint64_t m_frame = 0;
    bool m_cutRequested = false;  // cut()
    // The frame whose rg.frame the last load already ran (its changes are in m_pipeline).
    std::optional<uint64_t> m_framePrepared;
    uint32_t m_rebuilds = 0;
    uint64_t m_loads = 0;
    double m_callbackMs = 0.0;
    double m_loadMs = 0.0;
    std::vector<std::string> m_log;
    std::vector<ChannelCapture> m_channels;
    FrameChanges m_overrides;
    std::map<std::string, bool>
        m_switches;  // rg.frame's explicit pass switches, kept (frameChanges)
    // Each pass's shader as last resolved to a file ("origin\npass\nname" -> path): what a pass
    // keeps while the file is missing (buildableGraph).
    std::map<std::string, std::string> m_shaderPaths;
};

// Writes gbuffer_<layout>.glsl (pack/unpack, generated) for every layout of the pipeline into
// generatedShaderDir(), which shaders reach with #include "gbuffer_<layout>.glsl".
// Returns the folder it wrote them to: a folder of generatedShaderDir() named by their content, so
// two pipelines that declare a layout of the same name differently never overwrite each other.
// useLayoutHeaders points the runtime's shader compiler at it (and has the next build prepare
// every pass when it changed).
Result<std::string> writeLayoutHeaders(const PipelineDesc& pipeline);
void useLayoutHeaders(Runtime& runtime, const std::string& dir);

// The pipeline's HDR output as absolute luminance (cd/m²): read back and divided by the
// pre-exposure it was rendered with (rg.output's `hdr` and `exposure`; colour channels only), with
// the exposure state beside it (RgExposureState, shaders/lib/exposure_state.h: EV100, exposure,
// pre-exposure).
struct AbsoluteHdr {
    Image image;
    float ev100 = 0.0f, exposure = 0.0f, preExposure = 1.0f;
};
Result<AbsoluteHdr> readAbsoluteHdr(gpu::Executor& executor, const PipelineDesc& pipeline);

// Options for a LuaHost that sees the project's scripts/ and materials/ and the runtime's kinds.
LuaHostOptions luaHostOptions(const Runtime& runtime);
// Same, without a GPU: the built-in kinds' schemas.
LuaHostOptions luaHostOptionsWithoutDevice();

}  // namespace rg
