// The scene on the GPU: one vertex and one index buffer for every primitive, the images with
// their mip chains as layers of arrays by shape, every material's parameters in uniform buffers
// and a descriptor set per set of texture arrays materials share (set 1 of scene draws, see
// shaders/lib/material.glsl), and per frame slot the camera uniforms and the light list
// (shaders/lib/scene.glsl's Lights block: the lights converted once here — cd, lux or cd/m², see
// convertLights — followed by their baked IES profiles).
// Defined in gpu_scene.cpp (creation, the frame, bindings), gpu_scene_geometry.cpp,
// gpu_scene_materials.cpp (images, materials), gpu_scene_lights.cpp (convertLights, shadow views)
// and gpu_scene_probes.cpp (decals, probes, the environment's distribution).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/hash.h"
#include "gpu/context.h"
#include "gpu/pass_kind.h"
#include "gpu/resources.h"
#include "lighting/ies.h"
#include "lighting/light_table.h"
#include "scene/environment.h"
#include "scene/scene.h"

namespace rg::passes {

// The light table (graph/lighting/light_table.h) by the names this room uses.
using lighting::convertLights;
using lighting::GpuLight;
using lighting::GpuLightTable;
using lighting::GpuLightType;
using lighting::IesMode;
using lighting::kIesHeight;
using lighting::kIesWidth;
using lighting::kMaxIesProfiles;
using lighting::kMaxLights;

// One level of detail of a draw: its index range and how far its surface lies from the full one
// (world metres).
struct DrawLod {
    uint32_t firstIndex = 0, indexCount = 0;
    float error = 0.0f;
};
inline constexpr uint32_t kMaxDrawLods = 4;  // the full range and up to three coarser ones
// The vec4 words of a draw's record in SceneDraws (lib/scene.glsl RgDraw).
inline constexpr size_t kDrawWords = 8;

struct DrawItem {
    uint32_t firstIndex = 0;  // the full index range (lods[0])
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t material = 0;  // index into Scene::materials
    glm::mat4 world{1.0f};
    glm::mat4 normalMatrix{1.0f};
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world-space box around its vertices
    glm::vec4 lightmapRect{0.0f};                // its node's Node::lightmapRect
    // Levels of detail, finest first: lods[0] is the full range (error 0), then the primitive's
    // coarser index lists (Primitive::lods) with their error scaled by the node's largest axis.
    std::array<DrawLod, kMaxDrawLods> lods{};
    uint32_t lodCount = 1;
    // Drawn into the shadow maps: an opaque material's draw whose node casts shadows (Node::castShadows).
    bool castsShadows = true;
};

// A node's points or lines (Mesh::points, Mesh::lines): their index range — single vertices or
// pairs — in the scene's buffers, drawn by the `scene` kind's lines mode (scene_pass_lines.cpp).
struct LineDrawItem {
    uint32_t firstIndex = 0, indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t material = 0;  // index into Scene::materials
    glm::mat4 world{1.0f};
    bool points = false;  // a point list, else a segment list
};

// The shadow views of the scene's local lights (lib/shadows.glsl's ShadowViews block): how many
// views a frame can have, and one view as the GPU reads it.
inline constexpr uint32_t kMaxShadowViews = RG_MAX_SHADOW_VIEWS;  // shaders/lib/limits.h
struct GpuShadowView {
    glm::mat4 viewProj;  // world → the view's clip space (perspective, depth 0..1)
    glm::vec4 position;  // xyz: the light's position; w: the near plane (m)
    glm::vec4
        params;  // x: the far plane (m); y: tan of half the field of view; z: the light's radius (m); w: light index
};
// The views a local light with castShadows gets when its range reaches the view: one for a spot of
// outer angle ≤ 60°, six (a cube) otherwise; 0 for a light without shadows or the sun.
uint32_t shadowViewsNeeded(const Light& light);
// The most views a frame of the scene can have (its shadowed local lights' views in light order,
// as updateFrame places them, up to kMaxShadowViews): what a `scene_layers = "shadow_views"`
// resource is given (Executor::build).
uint32_t shadowViewCapacity(const Scene& scene);

// The lights the `LightsWindow` uniform block holds (lib/lighting.glsl RG_LIGHTS_WINDOW): the head
// of each Lights buffer again, its 16-byte header and 204 lights — within the 16 KiB
// maxUniformBufferRange every Vulkan device has.
inline constexpr uint32_t kLightsWindow = 204;
inline constexpr VkDeviceSize kLightsWindowBytes =
    16 + VkDeviceSize(kLightsWindow) * sizeof(GpuLight);
static_assert(kLightsWindowBytes <= 16384,
              "the lights' uniform window must fit the smallest maxUniformBufferRange");

struct GpuSceneOptions {
    IesMode iesMode = IesMode::Mask;
    // Draw the primitives' coarser levels of detail where their error stays within a pixel
    // or texel (false: always the full meshes; the environment's RG_LOD=0 sets it false too).
    bool levelsOfDetail = true;
};

// The scene on the GPU, as the executor and the pass kinds see it (gpu::SceneBinding): its one
// named extent is "shadow_views" (shadowViewCapacity).
class GpuScene final : public gpu::SceneBinding {
public:
    static Result<std::unique_ptr<GpuScene>> create(gpu::Context& ctx, Scene scene,
                                                    const GpuSceneOptions& options = {});
    ~GpuScene() override;
    // A number no other scene of the process has had: what the executor tells scenes apart by
    // (an address can be a freed scene's).
    uint64_t id() const override { return m_id; }
    std::optional<uint32_t> layerExtent(const std::string& name) const override;
    std::vector<std::string> extentNames() const override {
        return {kShadowViewsExtent,   kShadowCastersExtent, kShadowBatchesExtent,
                kCameraBatchesExtent, kDrawsExtent,         kCameraRunsExtent,
                kLightsExtent};
    }
    // Its features: "lightmap", a baked lightmap (scene.lightmap, from the cache or baked), and
    // "material:MODEL", whether a draw's material is of that pipeline material (any name: false
    // for one the scene does not draw) — what render_loop.lua's `opaque` copy exists for.
    std::optional<bool> feature(const std::string& name) const override;
    // and "motion", whether a node moves (Node::dynamic): render_loop.lua's motion target; and
    // "draws:N", whether it has at least N draws (scripts/culling.lua: the GPU-culled G-buffer);
    // "local_shadows", whether a local light casts shadows (scripts/shadows.lua's culling of
    // their casters); "gpu_draws", whether its passes can draw from instance lists the GPU
    // wrote (the device starts indirect draws at an instance, and instancing is on: not
    // RG_INSTANCING=0).
    std::vector<std::string> featureNames() const override {
        return {"lightmap", "material:MODEL", "motion", "draws:N", "local_shadows", "gpu_draws"};
    }
    static constexpr const char* kShadowViewsExtent = "shadow_views";
    // The draws that cast shadows, and their batches: casters sharing a mesh (vertex offset,
    // index range) and cull mode, which a culling pass draws as one instanced draw per level of
    // detail (shaders/shadows/cascade_cull.comp; buffers sized with scene_count).
    static constexpr const char* kShadowCastersExtent = "shadow_casters";
    static constexpr const char* kShadowBatchesExtent = "shadow_batches";
    // Shadow batch b: its draws (ascending), and the cull mode they share.
    struct ShadowBatch {
        std::vector<uint32_t> draws;
        bool doubleSided = false;
    };
    const std::vector<ShadowBatch>& shadowBatches() const { return m_shadowBatches; }
    // The camera's batches (cameraBatchKey's, without the level), the draws, and the runs: what
    // the GPU culling of the G-buffer's draws sizes its buffers by
    // (shaders/passes/camera_cull.comp: a command per batch and level, an instance slot per draw
    // and level, a count per run).
    static constexpr const char* kCameraBatchesExtent = "camera_batches";
    static constexpr const char* kDrawsExtent = "draws";
    static constexpr const char* kCameraRunsExtent = "camera_runs";
    // The scene's lights (at least 1): what the light culling's per-light buffers are sized by
    // (scripts/lighting.lua's light_spheres).
    static constexpr const char* kLightsExtent = "lights";
    // A camera run: the batches whose materials draw with one pipeline and one binding — the same
    // pipeline material, alpha mode (so the same shader variant, with the texture set), cull
    // mode, texture set (textureSet) and window of materials (materialWindow) — consecutive, so
    // that their indirect commands (kMaxDrawLods a batch) are one range the G-buffer draws with
    // one vkCmdDrawIndexedIndirectCount: the draws are grouped by pipeline and textures, not by
    // material (each draw's parameters come from the run's window of them, its textures' layers
    // among them). Ordered by that key.
    struct CameraRun {
        uint32_t firstCommand = 0, commands = 0;
        uint32_t textureSet = 0;
        uint32_t firstMaterial = 0;  // its materials' window: this one's (materialWindow)
        bool doubleSided = false;
    };
    const std::vector<CameraRun>& cameraRuns() const { return m_cameraRuns; }
    // Draw d's camera run.
    uint32_t cameraRun(size_t d) const { return m_drawRun[d]; }

    const Scene& scene() const { return m_scene; }
    const std::vector<DrawItem>& draws() const { return m_draws; }
    // The points and lines every node with such a mesh draws, in node order.
    const std::vector<LineDrawItem>& lineDraws() const { return m_lineDraws; }
    // Whether draw d's world box meets the camera's frustum this frame (the camera updateFrame
    // wrote; found for every draw at the first call of a frame): the camera's scene passes skip
    // the draws it does not.
    bool drawInView(size_t d) const {
        if (!m_viewCullDone) cullForCamera();
        return d >= m_drawInView.size() || m_drawInView[d] != 0;
    }
    // The level of detail the camera's scene passes draw draw d with this frame (as drawInView):
    // the coarsest whose error, at the nearest depth of the draw's box, projects to at most a pixel.
    const DrawLod& viewLod(size_t d) const {
        if (!m_viewCullDone) cullForCamera();
        return m_draws[d].lods[d < m_drawLod.size() && !m_fullMeshes ? m_drawLod[d] : 0];
    }
    // From now on the camera's passes draw the full meshes (a pass traces the scene's triangles
    // every frame from the G-buffer's surfaces: they must be the same). The sun's cascades may
    // stay coarser: a caster inside its receiver shadows nothing the full one would not.
    // SceneDraws' header says so too (its y: 1), for the levels the GPU picks (lib/culling.glsl).
    void drawFullMeshes() const;
    // Draw d's camera batch at the level of detail viewLod gives: draws with the same key share a
    // mesh range and material (one instanced draw, passes/scene_pass.cpp), keys below
    // cameraBatchKeys().
    uint32_t cameraBatchKey(size_t d) const {
        if (!m_viewCullDone) cullForCamera();
        return m_cameraBatch[d] * kMaxDrawLods +
               (d < m_drawLod.size() && !m_fullMeshes ? m_drawLod[d] : 0);
    }
    size_t cameraBatchKeys() const { return m_cameraBatchCount * size_t(kMaxDrawLods); }
    VkBuffer vertexBuffer() const { return m_vertices.buffer(); }
    VkBuffer indexBuffer() const { return m_indices.buffer(); }
    VkDescriptorSetLayout materialSetLayout() const { return m_materialLayout.get(); }
    // The texture sets: materials with the same texture array (the images of one shape, each a
    // layer: the layer is the material's parameter) and sampler in every texture slot share one
    // (a scene of untextured materials has one), and its descriptor set — set 1 of scene draws:
    // its textures, a material's parameters (binding 0, at a dynamic offset) and a window of
    // materialWindow() materials' (binding 9, read by index; a dynamic offset too).
    uint32_t textureSet(uint32_t material) const { return m_materialTextureSet[material]; }
    uint32_t textureSetCount() const { return static_cast<uint32_t>(m_textureSets.size()); }
    // Binds set 1 for a draw of `material` alone (its textures, its parameters' window).
    void bindMaterial(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t material) const;
    // Binds texture set `set` with the window of materials holding `material` (a camera run's).
    void bindTextureSet(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t set,
                        uint32_t material) const;
    // How many materials one window of the GPU's draws holds (lib/material.glsl
    // RG_MATERIAL_WINDOW): as many as a uniform block of the device's maxUniformBufferRange holds
    // (at most 64 KiB). A camera run's materials are in one window; an instance's index is its
    // material's within it (SceneTransforms).
    uint32_t materialWindow() const { return m_materialWindow; }

    // The camera the frame renders with (the scene's first, or `name`).
    const Camera& camera() const { return m_scene.cameras.at(m_camera); }
    Result<void> selectCamera(const std::string& name);
    // Writes frame slot `slot`'s camera for an output of width x height: the camera at the frame's
    // time (setTime) along its path (Camera::path).
    void updateFrame(uint32_t slot, uint32_t width, uint32_t height);
    // The time of the frames updateFrame writes next (seconds; a session's ctx.time).
    void setTime(double seconds) { m_time = seconds; }
    // A camera cut: the next frame has no last frame (no motion, the jitter sequence and the
    // frame count of Camera.temporal.y anew).
    void cut() {
        m_previousViewProj.reset();
        m_previousJitter.reset();
        m_jitterFrame = 0;
        m_framesSinceCut = 0;
    }
    // The camera of the frame updateFrame wrote last: camera() at that frame's time along its path.
    const Camera& frameCamera() const { return m_frameCamera; }
    // A key of everything the scene gives the GPU as frame slot `slot` holds it now: geometry,
    // images and samplers, materials, the environment and lightmap (hashed as uploaded), and the
    // slot's camera, lights, shadow views, decals and probes — what the disk cache of
    // once-per-build outputs (Executor::setOnceCache) keys a scene by.
    uint64_t contentHash(uint32_t slot) const override;
    VkBuffer cameraBuffer(uint32_t slot) const { return m_cameraBuffers[slot].buffer(); }
    VkBuffer lightBuffer(uint32_t slot) const { return m_lightBuffers[slot].buffer(); }
    // Frame slot `slot`'s Lights block as a texel buffer of RGBA32F texels (SceneLightTexels,
    // lib/scene.glsl's rgLight), or VK_NULL_HANDLE where the device's texel buffers cannot hold
    // the scene's lights: then the light loops read the block itself.
    VkBufferView lightTexelView(uint32_t slot) const {
        return m_lightTexelViews.empty() ? VK_NULL_HANDLE : m_lightTexelViews[slot].get();
    }
    // Which area-light model the light loop evaluates (lib/scene.glsl's Lights.count.y): 0 Frostbite's
    // (seed 002 §4.7), 1 linearly transformed cosines (lib/ltc.glsl). Written into each frame slot's
    // Lights block by updateFrame; a session sets it from the pipeline's `area_lights` parameter.
    // A setting of the scene's GPU data that a pipeline parameter drives (rg.param's `scene`):
    // "area_light_model" = "frostbite" or "ltc" (0 or 1: the light block's count.y, which
    // lib/lighting.glsl's loop reads). An unknown setting or value is an error naming what is.
    Result<void> setSetting(const std::string& name, const Value& value);
    // "jitter" (boolean) and "antialiasing" ("taa" jitters; the pipeline's `taa_jitter` and
    // `antialiasing` parameters): the camera's sub-pixel jitter (updateFrame) is on when both are.
    static std::vector<std::string> settingNames() {
        return {"area_light_model", "jitter", "antialiasing"};
    }
    // Frame slot `slot`'s shadow views (ShadowViews): for every local light with castShadows
    // whose range reaches the camera's view, one perspective view (a spot of outer angle ≤ 60°)
    // or six (a cube), in light order, up to kMaxShadowViews; then per light its first view and
    // count. Written by updateFrame; the draws each view sees found when asked (shadowViewDraws).
    VkBuffer shadowViewBuffer(uint32_t slot) const { return m_shadowViewBuffers[slot].buffer(); }
    uint32_t shadowViewCount() const { return static_cast<uint32_t>(m_shadowViewPlanes.size()); }
    // The draws whose world boxes meet view v's frustum (this frame).
    // Found on the first call of a frame (a pass that draws every view's casters directly; one
    // whose culling pass chose them on the GPU, shaders/shadows/local_cull.comp, never asks).
    const std::vector<size_t>& shadowViewDraws(uint32_t v) const;
    // How many frames' casters the CPU walked so (shadowViewDraws): none while the GPU culls them.
    uint64_t shadowViewWalks() const { return m_shadowViewWalks; }
    // The opaque triangles in world space as a ray-cast hierarchy (graph/scene/bvh.h) for
    // shaders that bind `SceneBvh` (lib/bvh.glsl: the reference mode's shadow rays): a uvec4
    // header (nodes, triangles, depth), then FlatBvh::data. Built on first use.
    VkBuffer bvhBuffer() const;
    // The draws as shaders see them (`SceneDraws`, lib/scene.glsl RgDraw): each draw's world box,
    // index range and vertex offset, and whether it casts shadows (opaque): what a culling pass
    // needs to write indirect draw commands (shaders/shadows/cascade_cull.comp).
    // Frame slot `slot`'s: a scene whose nodes move writes their boxes there each frame.
    VkBuffer drawBuffer(uint32_t slot) const { return ofSlot(m_drawBuffers, slot).buffer(); }
    // Nodes that move (Node::dynamic: a path, or placed by setNodeTransform): updateFrame places
    // them at the frame's time, their draws' transforms, boxes and levels of detail with them,
    // and keeps each draw's last world matrix in SceneTransforms for the motion the camera's
    // passes write (scene.vert with RG_MOTION).
    bool moves() const { return !m_moving.empty(); }
    bool drawMoves(size_t d) const { return d < m_drawMoves.size() && m_drawMoves[d] != 0; }
    // Places dynamic node `name` at `world` from the next frame (its path, if it has one, no
    // longer applies). An error for a node the scene lacks or one declared static.
    Result<void> setNodeTransform(const std::string& name, const glm::mat4& world);
    // Instanced camera draws (scene.vert): `SceneTransforms` holds per draw its world matrix, the
    // normal matrix's three columns, the lightmap rect and the last frame's world matrix
    // (kTransformWords vec4; per frame slot when nodes move); `SceneInstances`, per frame
    // slot, lists draw indices that a run of draws sharing a mesh, level of detail and material
    // is drawn from as one instanced draw (firstInstance = the run's first entry, so
    // gl_InstanceIndex indexes the list). reserveInstances hands out `count` entries of slot
    // `slot`'s list for this frame — their first index and where to write them — or a null
    // pointer when the list is full or RG_INSTANCING=0 (the caller then draws one at a time);
    // updateFrame empties it.
    // A draw that moves always takes the list (`always`): only there does scene.vert find its
    // last frame's transform.
    std::pair<uint32_t, uint32_t*> reserveInstances(uint32_t slot, uint32_t count,
                                                    bool always = false) const;
    static constexpr uint32_t kTransformWords = RG_TRANSFORM_WORDS;  // shaders/lib/limits.h
    // Whether draws that share a mesh are drawn instanced (RG_INSTANCING=0: one at a time, the
    // camera's and the sun's shadows' alike).
    bool instancing() const { return m_instancing; }
    // Whether its passes can draw from instance lists the GPU wrote: instancing on and the device
    // starts indirect draws at an instance (feature "gpu_draws").
    bool drawsGpuLists() const {
        return m_instancing && m_ctx && m_ctx->drawIndirectFirstInstance();
    }
    // How many entries of slot `slot`'s list the frame recorded there handed out.
    uint32_t instancesUsed(uint32_t slot) const { return m_instanceCursor[slot]; }
    // The buffer behind scene binding `name` (a shader block of that name: Camera, Lights,
    // LightsWindow, LightTables and GlobalLights, SceneTransforms, SceneInstances, ShadowViews — frame slot `slot`'s — Decals, Probes, SceneDraws, SceneBvh, SceneEnvironmentCdf), VK_NULL_HANDLE for
    // another name or a buffer that could not be made.
    VkBuffer bindingBuffer(std::string_view name, uint32_t slot) const;
    // The same, or why there is none: the failure of the Vulkan call behind a buffer built on
    // first use (SceneBvh, SceneEnvironmentCdf; the error names the call and its VkResult), or
    // NotFound for a name that is not a scene binding.
    Result<VkBuffer> makeBindingBuffer(std::string_view name, uint32_t slot) const;
    // How much of it the binding sees: kLightsWindowBytes for LightsWindow (the Lights buffer's
    // head, as a uniform block), the whole buffer otherwise.
    static VkDeviceSize bindingRange(std::string_view name) {
        return name == "LightsWindow" ? kLightsWindowBytes : VK_WHOLE_SIZE;
    }
    // The first of light `light`'s shadow views this frame and how many (0: none).
    std::pair<uint32_t, uint32_t> shadowViewsOf(size_t light) const;
    // The decals (shaders/lib/scene.glsl's Decals block): a count, then one RgDecal each.
    VkBuffer decalBuffer() const { return m_decals.buffer(); }
    // The local light probes (shaders/lib/probes.glsl's Probes block): a count, then one RgProbe
    // each in the order the composition visits them (priority, then the smaller first); probe k
    // is captured into cubes k of the capture target (layers 6k .. 6k + 5).
    VkBuffer probeBuffer() const { return m_probes.buffer(); }
    // The scene's probes in that order (indices into scene().probes).
    const std::vector<size_t>& probeOrder() const { return m_probeOrder; }
    // The environment as an equirectangular RGBA32F image of luminance (nits) in world orientation
    // (graph/scene/environment.h's mapping; 1x1 black without one), with its sampler: what a
    // shader's `SceneEnvironment` sampler2D is bound to.
    VkImageView environmentView() const { return m_environment.view(); }
    // The environment's importance-sampling distribution (graph/scene/environment.h
    // EnvironmentCdf: a uvec4 header (columns, rows, 0, 0), then its data) for shaders that bind
    // `SceneEnvironmentCdf` (the reference mode's environment samples). Built on first use.
    VkBuffer environmentCdfBuffer() const;
    VkSampler environmentSampler() const { return m_environmentSampler.get(); }
    // The baked SG lightmap (Scene::bakedLightmap) as an RGBA16F 2D array, one layer per lobe (rgb:
    // the lobe's amplitude, nits), with a linear, clamping sampler: what a shader's `SceneLightmap`
    // sampler2DArray is bound to (lib/lightmap.glsl); 1×1×2 black without one. Lights marked baked
    // are uploaded dark when the scene has one (the lightmap holds their light).
    bool hasLightmap() const { return m_scene.bakedLightmap != nullptr; }
    VkImageView lightmapView() const { return m_lightmap.view(); }
    uint32_t lightCount() const { return m_lightCount; }
    // GPU memory the scene holds (bytes, as the device reports each image's requirements):
    // geometry (vertices, indices, the draw list, the BVH once built), textures (the materials'
    // images with their mips, the defaults), and the environment and lightmap images.
    struct Memory {
        uint64_t geometry = 0, textures = 0, environment = 0, lightmap = 0;
    };
    Memory memory() const;
    uint32_t iesProfileCount() const { return m_iesProfileCount; }

private:
    uint64_t m_id = 0;
    uint32_t m_shadowViewCapacity = 0;  // layerExtent("shadow_views")
    GpuScene() = default;
    Result<void> uploadGeometry(gpu::Context& ctx);
    Result<void> uploadImages(gpu::Context& ctx);
    // Each material's texture set (textureSet), from the scene and the images' arrays.
    void assignTextureSets();
    // The (array, layer) of the image `ref` names, if the scene has it (uploadImages).
    std::optional<std::pair<uint32_t, uint32_t>> imageLayer(const TextureRef& ref) const {
        if (ref.image < 0 || size_t(ref.image) >= m_imageLayer.size()) return std::nullopt;
        return m_imageLayer[size_t(ref.image)];
    }
    Result<void> createMaterials(gpu::Context& ctx);
    Result<void> createFrameData(gpu::Context& ctx, const GpuSceneOptions& options);
    Result<void> createLightTables(gpu::Context& ctx, const GpuLightTable& table);
    Result<void> checkStorageRange(gpu::Context& ctx, const std::string& what,
                                   VkDeviceSize bytes) const;
    // The ShadowViews block's size: its header, kMaxShadowViews views and an ivec4 per light.
    VkDeviceSize shadowViewBytes() const;

    Scene m_scene;
    gpu::Context* m_ctx = nullptr;
    std::vector<DrawItem> m_draws;
    std::vector<LineDrawItem> m_lineDraws;
    gpu::Buffer m_vertices, m_indices;
    // The scene's images as layers of 2-D arrays, one per shape (uploadImages); per scene image its
    // (array, layer).
    std::vector<gpu::Image> m_textureArrays;
    std::vector<std::pair<uint32_t, uint32_t>> m_imageLayer;
    size_t m_textureArrayBytes = size_t(256) << 20;  // an array's most (RG_TEXTURE_ARRAY_BYTES)
    gpu::Image m_white, m_flatNormal;                // defaults for missing textures
    gpu::Image m_environment;
    EnvironmentCdf
        m_environmentCdf;  // of the uploaded image (a 1x1 black one without an environment)
    mutable gpu::Buffer m_environmentCdfBuffer;  // environmentCdfBuffer(), once built
    gpu::OwnedSampler m_environmentSampler;
    gpu::Image m_lightmap;
    std::vector<gpu::OwnedSampler> m_samplers;
    gpu::OwnedSampler m_defaultSampler;
    gpu::OwnedDescriptorSetLayout m_materialLayout;
    gpu::OwnedDescriptorPool m_pool;
    // Every material's RgMaterialData (lib/material.glsl), in uniform buffers: one a window of
    // m_materialStride bytes, and m_materialWindow a window of m_windowStride bytes.
    gpu::Buffer m_materialBuffer, m_materialWindows;
    uint32_t m_materialStride = 0, m_windowStride = 0, m_materialWindow = 1;
    // Per material its texture set; per set its slots' (texture array, sampler) indices (array −1:
    // the slot's default; sampler −1: the default sampler), and its descriptor set.
    std::vector<uint32_t> m_materialTextureSet;
    std::vector<std::vector<std::pair<int32_t, int32_t>>> m_textureSetSlots;
    std::vector<VkDescriptorSet> m_textureSets;
    std::vector<gpu::Buffer> m_cameraBuffers, m_lightBuffers, m_shadowViewBuffers;
    std::vector<gpu::OwnedBufferView> m_lightTexelViews;  // lightTexelView, per slot (or none)
    // SceneTransforms (kTransformWords vec4 per draw) and SceneDraws: one, or one per frame slot
    // when nodes move.
    std::vector<gpu::Buffer> m_transforms, m_drawBuffers;
    // Frame slot `slot`'s of such a list (its only one while nothing moves).
    static const gpu::Buffer& ofSlot(const std::vector<gpu::Buffer>& list, uint32_t slot) {
        return list[list.size() > 1 ? slot : 0];
    }
    // Draw d's record of SceneTransforms at `out`: `world` (its world matrix now), its normal
    // matrix and lightmap rect, and `previous`, the last frame's world matrix.
    void writeTransform(glm::vec4* out, size_t d, const glm::mat4& previous) const;
    Result<void> perSlot(gpu::Context& ctx, const char* name, const std::vector<glm::vec4>& words,
                         std::vector<gpu::Buffer>& out) const;
    // The nodes that move (gpu_scene_motion.cpp): their draws and line draws, each draw's box in
    // its mesh's space, and where setNodeTransform placed the node.
    struct Moving {
        size_t node = 0;
        uint32_t firstDraw = 0, drawCount = 0, firstLine = 0, lineCount = 0;
        std::vector<std::pair<glm::vec3, glm::vec3>> boxes;
        std::vector<std::array<float, kMaxDrawLods - 1>> lodErrors;  // per draw, mesh space
        std::optional<glm::mat4> placed;
    };
    std::vector<Moving> m_moving;
    std::vector<uint8_t> m_drawMoves;                // per draw: 1 when its node moves
    glm::vec3 m_movingMin{0.0f}, m_movingMax{0.0f};  // the moving draws' boxes this frame
    bool m_nodesMoved =
        false;  // a node's transform differs from the last frame's (Camera.temporal.x)
    // Records node `node`'s draws from firstDraw and line draws from firstLine (uploadGeometry).
    void addMoving(size_t node, uint32_t firstDraw, uint32_t firstLine);
    // Places the moving nodes for this frame and writes slot `slot`'s records of their draws;
    // `fresh` (the first frame, a cut): the last frame's transforms are this frame's.
    void updateMoving(uint32_t slot, bool fresh);
    std::vector<ShadowBatch> m_shadowBatches;  // the casters by mesh and cull mode
    std::vector<uint32_t> m_cameraBatch;       // per draw: its mesh range and material's batch
    std::vector<CameraRun> m_cameraRuns;       // cameraRuns
    std::vector<uint32_t> m_drawRun;           // per draw: its camera run
    // Per draw what the camera's culling and level choice read (cullForCamera), packed (40 bytes rather than a
    // DrawItem's ~250: the 100 000-node city's update was bound by the memory it walked).
    struct DrawCull {
        glm::vec3 lo{0.0f};
        uint32_t lodCount = 1;
        glm::vec3 hi{0.0f};
        std::array<float, kMaxDrawLods - 1> error{};  // levels 1.. (world metres)
    };
    std::vector<DrawCull> m_drawCull;
    uint32_t m_cameraBatchCount = 0;
    std::vector<gpu::Buffer> m_instanceBuffers;  // SceneInstances, per slot
    // Entries of each slot's SceneInstances handed out this frame: scratch of the recording, which
    // runs on a const scene.
    mutable std::vector<uint32_t> m_instanceCursor;
    bool m_instancing = true;    // RG_INSTANCING=0: none
    gpu::Buffer m_lightTables;   // LightTables: the LTC table and IES profiles, for every slot
    gpu::Buffer m_globalLights;  // GlobalLights: the lights that reach every pixel
    std::vector<std::array<glm::vec4, 6>> m_shadowViewPlanes;    // per view of this frame
    mutable std::vector<std::vector<size_t>> m_shadowViewDraws;  // shadowViewDraws, once found
    mutable uint64_t m_shadowViewWalks = 0;
    mutable gpu::Buffer m_bvh;                          // bvhBuffer(), once built
    Result<VkBuffer> makeBvhBuffer() const;             // bvhBuffer(), or why it failed
    Result<VkBuffer> makeEnvironmentCdfBuffer() const;  // environmentCdfBuffer(), or why it failed
    ContentHash m_staticHash;  // what was uploaded at creation (contentHash)
    // The camera of the frame updateFrame wrote last, as the per-draw culling and level choice
    // read it; cullForCamera runs them for it once, when a pass first asks (drawInView, viewLod).
    struct ViewCull {
        std::array<glm::vec4, 6> planes{};
        glm::vec3 position{0.0f}, forward{0.0f, 0.0f, -1.0f};
        float pixelsPerMetre = 1.0f;  // |proj[1][1]| · height / 2
        float nearPlane = 0.0f;
        bool orthographic = false;
    };
    ViewCull m_viewCull;
    mutable bool m_viewCullDone = true;
    void cullForCamera() const;
    mutable std::vector<char> m_drawInView;  // per draw: its box meets the camera's frustum
    mutable std::vector<uint8_t> m_drawLod;  // per draw: the level of detail viewLod gives
    bool m_levelsOfDetail = true;            // GpuSceneOptions::levelsOfDetail
    mutable bool m_fullMeshes = false;       // drawFullMeshes()
    std::vector<glm::ivec4>
        m_lightViews;  // per light of the scene: first view (−1: none), count — as uploaded
    void updateShadowViews(uint32_t slot, const glm::mat4& cameraViewProj);
    gpu::Buffer m_decals;
    Result<void> createDecals(gpu::Context& ctx);
    gpu::Buffer m_probes;
    std::vector<size_t> m_probeOrder;
    Result<void> createProbes(gpu::Context& ctx);
    uint32_t m_lightCount = 0;
    uint32_t m_iesProfileCount = 0;
    uint32_t m_areaLightModel = 0;
    bool m_jitterWanted = false, m_temporalResolve = false;  // setSetting "jitter", "antialiasing"
    uint32_t m_jitterFrame = 0;                              // the Halton sequence's position
    uint32_t m_framesSinceCut = 0;                           // Camera.temporal.y, from a cut
    double m_time = 0.0;                                     // setTime
    Camera m_frameCamera;                                    // frameCamera
    std::optional<glm::vec2> m_previousJitter;
    size_t m_camera = 0;
    std::optional<glm::mat4>
        m_previousViewProj;  // the last frame's camera (Camera.previousViewProj)
};

// The scene a pass of this room draws: the executor's scene binding, which is a GpuScene.
inline const GpuScene* sceneOf(const gpu::SceneBinding* scene) {
    return static_cast<const GpuScene*>(scene);
}
inline const GpuScene* sceneOf(const gpu::PassSetup& setup) { return sceneOf(setup.scene); }
inline const GpuScene* sceneOf(const gpu::RecordContext& ctx) { return sceneOf(ctx.scene); }

}  // namespace rg::passes
