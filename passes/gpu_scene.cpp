// GpuScene's creation and frame: the upload steps in order, the frame slots' buffers (camera,
// shadow views, lights), the camera each frame with its frustum and levels of detail, the
// content key and the scene's shader bindings.
#include "gpu_scene.h"

#include <atomic>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/hash.h"
#include "core/names.h"
#include "gpu_scene_detail.h"
#include "lighting/ltc.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

namespace {

struct CameraUniforms {
    glm::mat4 viewProj, view, proj, invViewProj;
    glm::vec4 position, viewport;
    glm::vec4 sceneMin, sceneMax;  // scene.glsl's Camera: the scene's bounds
    glm::mat4
        previousViewProj;  // the frame before's unjittered (reprojection); this frame's on the first
    glm::mat4 unjitteredViewProj;  // viewProj without the sub-pixel jitter (motion, culling)
    glm::vec4 jitter;  // xy: this frame's jitter, zw: the last frame's, in uv units (pixels / size)
    glm::vec4 temporal;  // x: 1 when the camera or a node moved since the last frame (0 on the
                         // first), y: frames since the first frame or the last camera cut, z: 1
                         // when the camera moved
};

// The Halton sequence's element `index` (1-based) in base `base`: the sub-pixel jitter's
// low-discrepancy points (2, 3), as TAA implementations take them (e.g. Karis 2014).
float halton(uint32_t index, uint32_t base) {
    float f = 1.0f, r = 0.0f;
    for (; index > 0; index /= base) {
        f /= static_cast<float>(base);
        r += f * static_cast<float>(index % base);
    }
    return r;
}

}  // namespace

GpuScene::~GpuScene() = default;

Result<void> GpuScene::setSetting(const std::string& name, const Value& value) {
    if (name == "area_light_model") {
        static const char* const models[] = {"frostbite", "ltc"};  // Lights.count.y
        for (uint32_t i = 0; i < 2; ++i)
            if (value.isString() && value.asString() == models[i]) {
                m_areaLightModel = i;
                return {};
            }
        return fail(ErrorCode::InvalidInput,
                    "scene setting 'area_light_model': expected \"frostbite\" or \"ltc\", got " +
                        (value.isString() ? "'" + value.asString() + "'" : value.typeName()));
    }
    if (name == "jitter" || name == "antialiasing") {
        if (name == "jitter" && value.isBool()) {
            m_jitterWanted = value.asBool();
            return {};
        }
        if (name == "antialiasing" && value.isString()) {
            m_temporalResolve = value.asString() == "taa";
            return {};
        }
        return fail(ErrorCode::InvalidInput,
                    "scene setting '" + name + "': expected " +
                        (name == "jitter" ? "a boolean" : "the antialiasing choice") + ", got " +
                        value.typeName());
    }
    return fail(ErrorCode::InvalidInput, "the scene has no setting '" + name +
                                             "' (it has: " + joinQuoted(settingNames()) + ")");
}

std::optional<bool> GpuScene::feature(const std::string& name) const {
    if (name == "lightmap") return hasLightmap();
    if (name == "motion") return moves();
    if (name == "local_shadows") return m_shadowViewCapacity > 0;
    if (name == "gpu_draws") return drawsGpuLists();
    if (name.starts_with("draws:")) {
        const std::string count = name.substr(6);
        if (count.empty() || count.size() > 9 ||
            !std::all_of(count.begin(), count.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return std::nullopt;
        return m_draws.size() >= std::stoul(count);
    }
    if (name.starts_with(kMaterialFeature)) {
        const std::string_view model = std::string_view(name).substr(kMaterialFeature.size());
        return std::any_of(m_draws.begin(), m_draws.end(), [&](const DrawItem& d) {
            return d.material < m_scene.materials.size() &&
                   m_scene.materials[d.material].model == model;
        });
    }
    return std::nullopt;
}

std::optional<uint32_t> GpuScene::layerExtent(const std::string& name) const {
    if (name == kShadowViewsExtent) return m_shadowViewCapacity;
    if (name == kShadowBatchesExtent) return static_cast<uint32_t>(m_shadowBatches.size());
    if (name == kCameraBatchesExtent) return m_cameraBatchCount;
    if (name == kDrawsExtent) return static_cast<uint32_t>(m_draws.size());
    if (name == kLightsExtent) return std::max(m_lightCount, 1u);
    if (name == kCameraRunsExtent)
        return std::max<uint32_t>(static_cast<uint32_t>(m_cameraRuns.size()), 1u);
    if (name == kShadowCastersExtent) {
        uint32_t casters = 0;
        for (const ShadowBatch& b : m_shadowBatches)
            casters += static_cast<uint32_t>(b.draws.size());
        return casters;
    }
    return std::nullopt;
}

Result<std::unique_ptr<GpuScene>> GpuScene::create(Context& ctx, Scene scene,
                                                   const GpuSceneOptions& options) {
    static std::atomic<uint64_t> ids{0};
    std::unique_ptr<GpuScene> s(new GpuScene());
    s->m_id = ++ids;
    s->m_ctx = &ctx;
    s->m_scene = std::move(scene);
    s->m_shadowViewCapacity = shadowViewCapacity(s->m_scene);
    if (s->m_scene.cameras.empty()) return fail(ErrorCode::InvalidInput, "the scene has no camera");
    if (s->m_scene.materials.empty()) s->m_scene.materials.push_back(Material{});
    const char* lodEnv = std::getenv("RG_LOD");
    s->m_levelsOfDetail = options.levelsOfDetail && !(lodEnv && std::string_view(lodEnv) == "0");
    // RG_INSTANCING=0: every camera draw on its own (to compare: the image is the same).
    const char* instancingEnv = std::getenv("RG_INSTANCING");
    s->m_instancing = !(instancingEnv && std::string_view(instancingEnv) == "0");
    // RG_TEXTURE_ARRAY_BYTES=N: texture arrays close at N bytes rather than 256 MiB (to compare:
    // the image is the same with every image an array of its own).
    if (const char* arrayEnv = std::getenv("RG_TEXTURE_ARRAY_BYTES"))
        s->m_textureArrayBytes = std::max<size_t>(std::strtoull(arrayEnv, nullptr, 10), 1);
    // A window of materials: as many as a uniform block of the device's range holds (64 KiB at
    // most, the std140 array's 416-byte elements).
    s->m_materialWindow = std::max<uint32_t>(
        std::min<uint32_t>(ctx.properties().limits.maxUniformBufferRange, 65536u) / 416u, 1u);
    // The images first: the texture sets take their arrays, the camera's runs the texture sets.
    if (auto r = s->uploadImages(ctx); !r) return std::unexpected(r.error());
    s->assignTextureSets();
    if (auto r = s->uploadGeometry(ctx); !r) return std::unexpected(r.error());
    if (auto r = s->createMaterials(ctx); !r) return std::unexpected(r.error());
    if (auto r = s->createFrameData(ctx, options); !r) return std::unexpected(r.error());
    return s;
}

Result<void> GpuScene::createFrameData(Context& ctx, const GpuSceneOptions& options) {
    if (auto r = createDecals(ctx); !r) return r;
    if (auto r = createProbes(ctx); !r) return r;
    auto table = convertLights(m_scene.lights, options.iesMode);
    if (!table) return std::unexpected(table.error());
    // With a baked lightmap, a light marked baked is in it, direct light included: the real-time
    // loop must not add it again.
    if (m_scene.bakedLightmap)
        for (size_t i = 0; i < m_scene.lights.size(); ++i)
            if (m_scene.lights[i].baked)
                table->lights[i].intensity =
                    glm::vec4(0.0f, 0.0f, 0.0f, table->lights[i].intensity.a);
    m_lightCount = static_cast<uint32_t>(table->lights.size());
    m_iesProfileCount = static_cast<uint32_t>(table->profiles.size());
    // scene.glsl's Lights block: a uvec4 header, then the scene's lights — at least as many bytes
    // as the LightsWindow uniform block sees of it.
    const VkDeviceSize lightBytes = std::max<VkDeviceSize>(
        16 + VkDeviceSize(m_lightCount) * sizeof(GpuLight), kLightsWindowBytes);
    const VkDeviceSize shadowViewBytes = this->shadowViewBytes();
    if (auto r =
            checkStorageRange(ctx, "its " + std::to_string(m_lightCount) + " lights", lightBytes);
        !r)
        return r;
    if (auto r = createLightTables(ctx, *table); !r) return r;
    // The same block as RGBA32F texels for the light loops (lib/scene.glsl's rgLight): on
    // lavapipe a texel fetch is one gather a field where a storage buffer's load is a loop over
    // the lanes. Where the device's texel buffers are too small for the scene's lights, none;
    // RG_LIGHT_TEXELS=0: none either (to compare: the image is the same).
    const char* texelsEnv = std::getenv("RG_LIGHT_TEXELS");
    VkFormatProperties texelFormat{};
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), VK_FORMAT_R32G32B32A32_SFLOAT,
                                        &texelFormat);
    const bool texels =
        !(texelsEnv && std::string_view(texelsEnv) == "0") &&
        (texelFormat.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT) != 0 &&
        lightBytes / 16 <= ctx.properties().limits.maxTexelBufferElements;
    // lib/light_tiles.glsl's GlobalLights: the lights that reach every pixel (its
    // rgReachesEverything: the sun, lights without a range), ascending — for every tile's loop.
    std::vector<uint32_t> global{0, 0, 0, 0};
    for (uint32_t i = 0; i < m_lightCount; ++i) {
        const GpuLight& l = table->lights[i];
        if (static_cast<int>(l.positionType.w + 0.5f) == static_cast<int>(GpuLightType::Sun) ||
            l.directionRange.w <= 0.0f)
            global.push_back(i);
    }
    global[0] = static_cast<uint32_t>(global.size() - 4);
    global.push_back(0);  // the runtime array is never empty
    auto globalBuffer = Buffer::create(ctx, "scene.global_lights", global.size() * sizeof(uint32_t),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!globalBuffer) return std::unexpected(globalBuffer.error());
    std::memcpy(globalBuffer->mapped(), global.data(), global.size() * sizeof(uint32_t));
    m_globalLights = std::move(*globalBuffer);
    for (uint32_t s = 0; s < ctx.framesInFlight(); ++s) {
        auto cam = Buffer::create(ctx, "scene.camera", sizeof(CameraUniforms),
                                  VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        if (!cam) return std::unexpected(cam.error());
        m_cameraBuffers.push_back(std::move(*cam));
        auto views = Buffer::create(ctx, "scene.shadow_views", shadowViewBytes,
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (!views) return std::unexpected(views.error());
        std::memset(views->mapped(), 0, shadowViewBytes);
        m_shadowViewBuffers.push_back(std::move(*views));
        auto lights = Buffer::create(
            ctx, "scene.lights", lightBytes,
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                (texels ? VkBufferUsageFlags(VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) : 0u),
            true);
        if (!lights) return std::unexpected(lights.error());
        auto* p = static_cast<uint8_t*>(lights->mapped());
        std::memset(p, 0, lightBytes);
        const uint32_t header[4] = {m_lightCount, m_areaLightModel, 0, 0};
        std::memcpy(p, header, sizeof header);
        if (m_lightCount)
            std::memcpy(p + 16, table->lights.data(), table->lights.size() * sizeof(GpuLight));
        if (texels) {
            VkBufferViewCreateInfo vi{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
            vi.buffer = lights->buffer();
            vi.format = VK_FORMAT_R32G32B32A32_SFLOAT;
            vi.range = VK_WHOLE_SIZE;
            VkBufferView view = VK_NULL_HANDLE;
            RG_VK_TRY(vkCreateBufferView(ctx.device(), &vi, nullptr, &view));
            m_lightTexelViews.emplace_back(ctx.device(), view);
            ctx.setName(VK_OBJECT_TYPE_BUFFER_VIEW, reinterpret_cast<uint64_t>(view),
                        "scene.light_texels");
        }
        m_lightBuffers.push_back(std::move(*lights));
        // SceneInstances: room for every draw four times a frame (the G-buffer, forward and
        // any other camera pass), one word each.
        const VkDeviceSize instanceBytes = (4 * std::max<VkDeviceSize>(m_draws.size(), 1)) * 4;
        auto instances = Buffer::create(ctx, "scene.instances", instanceBytes,
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (!instances) return std::unexpected(instances.error());
        std::memset(instances->mapped(), 0, instanceBytes);
        m_instanceBuffers.push_back(std::move(*instances));
    }
    m_instanceCursor.assign(ctx.framesInFlight(), 0);
    return {};
}

std::pair<uint32_t, uint32_t*> GpuScene::reserveInstances(uint32_t slot, uint32_t count,
                                                          bool always) const {
    if (!m_instancing && !always) return {0, nullptr};
    const Buffer& b = m_instanceBuffers[slot];
    const uint32_t first = m_instanceCursor[slot];
    if (first + uint64_t(count) > b.size() / 4) return {0, nullptr};
    m_instanceCursor[slot] = first + count;
    return {first, static_cast<uint32_t*>(b.mapped()) + first};
}

// scene.glsl's LightTables block: a uvec4 header (the IES profiles' width, height and count), the
// LTC table (two vec4 per entry), then every profile's texels (one float more, so that the runtime
// array is never empty). The same for every frame slot.
Result<void> GpuScene::createLightTables(Context& ctx, const GpuLightTable& table) {
    const size_t ltcBytes = size_t(ltc::kSize) * ltc::kSize * 32;
    const size_t texelCount = size_t(kIesWidth) * kIesHeight;
    const size_t bytes = 16 + ltcBytes + (m_iesProfileCount * texelCount + 1) * sizeof(float);
    auto buffer =
        Buffer::create(ctx, "scene.light_tables", bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buffer) return std::unexpected(buffer.error());
    auto* p = static_cast<uint8_t*>(buffer->mapped());
    std::memset(p, 0, bytes);
    const uint32_t header[4] = {kIesWidth, kIesHeight, m_iesProfileCount, 0};
    std::memcpy(p, header, sizeof header);
    float* ltcOut = reinterpret_cast<float*>(p + 16);
    for (const ltc::Entry& e : ltc::table()) {
        const float entry[8] = {e.inverse[0], e.inverse[1], e.inverse[2], e.inverse[3],
                                e.magnitude,  e.fresnel,    0.0f,         0.0f};
        std::memcpy(ltcOut, entry, sizeof entry);
        ltcOut += 8;
    }
    for (size_t i = 0; i < table.profiles.size(); ++i) {
        const IesTexture& t = table.profiles[i];
        RG_CHECK(t.texels.size() == texelCount)
            << "IES profile baked at " << t.width << " x " << t.height;
        std::memcpy(p + 16 + ltcBytes + i * texelCount * sizeof(float), t.texels.data(),
                    texelCount * sizeof(float));
    }
    m_lightTables = std::move(*buffer);
    return {};
}

// A storage buffer of `bytes` must fit the device's maxStorageBufferRange (128 MiB at least):
// a scene beyond it is refused naming what it holds and the limit, never bound past its end.
Result<void> GpuScene::checkStorageRange(Context& ctx, const std::string& what,
                                         VkDeviceSize bytes) const {
    const VkDeviceSize limit = ctx.properties().limits.maxStorageBufferRange;
    if (bytes <= limit) return {};
    return fail(ErrorCode::InvalidInput, "the scene's " + what + " take " + std::to_string(bytes) +
                                             " bytes of GPU buffer, over the device's "
                                             "maxStorageBufferRange of " +
                                             std::to_string(limit));
}

Result<void> GpuScene::selectCamera(const std::string& name) {
    for (size_t i = 0; i < m_scene.cameras.size(); ++i)
        if (m_scene.cameras[i].name == name) {
            m_camera = i;
            return {};
        }
    std::string names;
    for (const auto& c : m_scene.cameras) names += (names.empty() ? "'" : ", '") + c.name + "'";
    return fail(ErrorCode::NotFound,
                "the scene has no camera '" + name + "' (cameras: " + names + ")");
}

void GpuScene::updateFrame(uint32_t slot, uint32_t width, uint32_t height) {
    updateMoving(slot, !m_previousViewProj.has_value());
    m_frameCamera = camera().at(m_time);
    const Camera& c = m_frameCamera;
    const float aspect = static_cast<float>(width) / static_cast<float>(std::max(1u, height));
    const float fovy = c.focalLength > 0 ? 2.0f * std::atan(c.sensorHeight / (2.0f * c.focalLength))
                                         : c.verticalFov;
    CameraUniforms u{};
    u.view = glm::lookAt(c.position, c.target, c.up);
    if (c.orthographic) {
        const float h = 0.5f * c.orthoHeight, w = h * aspect;
        u.proj = glm::orthoRH_ZO(-w, w, -h, h, c.nearPlane, c.farPlane);
    } else {
        u.proj = glm::perspectiveRH_ZO(fovy, aspect, c.nearPlane, c.farPlane);
    }
    u.proj[1][1] *= -1.0f;  // Vulkan's y points down
    u.unjitteredViewProj = u.proj * u.view;
    // The sub-pixel jitter of a temporally resolved frame (TAA): Halton (2, 3) over 8 frames, ±½
    // pixel, moving every pass that rasterises or reconstructs positions by the same offset; the
    // unjittered matrix stays for motion, reprojection and culling. The first frame, which has no
    // history to resolve with, is not jittered: a one-frame render is the image itself.
    glm::vec2 jitter(0.0f);
    if (m_jitterWanted && m_temporalResolve && m_jitterFrame++ > 0) {
        const uint32_t index = 1 + (m_jitterFrame - 2) % 8;
        jitter = glm::vec2(halton(index, 2) - 0.5f, halton(index, 3) - 0.5f) /
                 glm::vec2(static_cast<float>(width), static_cast<float>(height));
        // An NDC offset of 2 × the uv offset: perspective clip x += o·w (w = −z_view), orthographic
        // clip x += o.
        const glm::vec2 ndc = 2.0f * jitter;
        if (c.orthographic)
            u.proj[3][0] += ndc.x, u.proj[3][1] += ndc.y;
        else
            u.proj[2][0] -= ndc.x, u.proj[2][1] -= ndc.y;
    }
    u.jitter = glm::vec4(jitter, m_previousJitter.value_or(jitter));
    m_previousJitter = jitter;
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.position = glm::vec4(c.position, 1.0f);
    u.viewport = glm::vec4(static_cast<float>(width), static_cast<float>(height),
                           1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height));
    // The bounds at load and wherever the moving nodes are now (the sun's cascades take their
    // depth range from them).
    u.sceneMin =
        glm::vec4(moves() ? glm::min(m_scene.boundsMin, m_movingMin) : m_scene.boundsMin, 1.0f);
    u.sceneMax =
        glm::vec4(moves() ? glm::max(m_scene.boundsMax, m_movingMax) : m_scene.boundsMax, 1.0f);
    u.previousViewProj = m_previousViewProj.value_or(u.unjitteredViewProj);
    // Pixels moved when the camera or a node did (the fullscreen kind's camera = "moved" passes:
    // TAA's reprojection).
    const bool cameraMoved = u.previousViewProj != u.unjitteredViewProj;
    u.temporal = glm::vec4(cameraMoved || m_nodesMoved ? 1.0f : 0.0f,
                           static_cast<float>(m_framesSinceCut++), cameraMoved ? 1.0f : 0.0f, 0.0f);
    m_previousViewProj = u.unjitteredViewProj;
    std::memcpy(m_cameraBuffers[slot].mapped(), &u, sizeof u);
    // The camera's culling and levels of detail per draw are found when a pass asks for them
    // (cullForCamera): the GPU-culled passes never do, and a 100 000-draw frame would spend most
    // of its scene update on them.
    m_viewCull = ViewCull{frustumPlanes(u.unjitteredViewProj),
                          c.position,
                          glm::normalize(c.target - c.position),
                          std::abs(u.proj[1][1]) * static_cast<float>(height) * 0.5f,
                          c.nearPlane,
                          c.orthographic};
    m_viewCullDone = false;
    updateShadowViews(slot, u.viewProj);
    m_instanceCursor[slot] = 0;
    std::memcpy(static_cast<uint8_t*>(m_lightBuffers[slot].mapped()) + 4, &m_areaLightModel,
                sizeof m_areaLightModel);
}

void GpuScene::cullForCamera() const {
    m_viewCullDone = true;
    const ViewCull& v = m_viewCull;
    // Per draw: whether its box meets the frustum, and its level of detail — a world length L
    // at view depth z spans L · |proj[1][1]| · height / (2z) pixels (orthographic: without the
    // z); each draw takes the coarsest level whose error spans at most a pixel at the nearest
    // depth of its box (the full one where the box reaches the near plane).
    const glm::vec3 absForward = glm::abs(v.forward);
    m_drawInView.resize(m_draws.size());
    m_drawLod.assign(m_draws.size(), 0);
    for (size_t d = 0; d < m_drawCull.size(); ++d) {
        const DrawCull& item = m_drawCull[d];
        m_drawInView[d] = boxMeetsFrustum(v.planes, item.lo, item.hi);
        if (item.lodCount < 2) continue;
        // The box's nearest depth: its centre's less the half extents along |forward| (the
        // smallest of the linear function over the eight corners).
        const glm::vec3 centre = 0.5f * (item.lo + item.hi), half = 0.5f * (item.hi - item.lo);
        const float nearest = glm::dot(centre - v.position, v.forward) - glm::dot(half, absForward);
        if (!v.orthographic && nearest <= v.nearPlane) continue;
        const float scale = v.orthographic ? v.pixelsPerMetre : v.pixelsPerMetre / nearest;
        uint8_t level = 0;
        for (uint32_t l = 1; l < item.lodCount; ++l)
            if (item.error[l - 1] * scale <= 1.0f) level = static_cast<uint8_t>(l);
        m_drawLod[d] = level;
    }
}

uint64_t GpuScene::contentHash(uint32_t slot) const {
    ContentHash h;
    h.u64(m_staticHash.value());
    for (const Buffer* b : {&m_cameraBuffers[slot], &m_lightBuffers[slot], &m_lightTables,
                            &m_globalLights, &m_shadowViewBuffers[slot], &m_decals, &m_probes})
        h.bytes(b->mapped(), b->size());
    return h.value();
}

VkBuffer GpuScene::bindingBuffer(std::string_view name, uint32_t slot) const {
    if (name == "Camera") return cameraBuffer(slot);
    if (name == "Lights" || name == "LightsWindow") return lightBuffer(slot);
    if (name == "LightTables") return m_lightTables.buffer();
    if (name == "GlobalLights") return m_globalLights.buffer();
    if (name == "ShadowViews") return shadowViewBuffer(slot);
    if (name == "Decals") return decalBuffer();
    if (name == "Probes") return probeBuffer();
    if (name == "SceneDraws") return drawBuffer(slot);
    if (name == "SceneTransforms") return ofSlot(m_transforms, slot).buffer();
    if (name == "SceneInstances") return m_instanceBuffers[slot].buffer();
    if (name == "SceneBvh") return bvhBuffer();
    if (name == "SceneEnvironmentCdf") return environmentCdfBuffer();
    return VK_NULL_HANDLE;
}

Result<VkBuffer> GpuScene::makeBindingBuffer(std::string_view name, uint32_t slot) const {
    if (name == "SceneBvh") return makeBvhBuffer();
    if (name == "SceneEnvironmentCdf") return makeEnvironmentCdfBuffer();
    if (VkBuffer buffer = bindingBuffer(name, slot); buffer != VK_NULL_HANDLE) return buffer;
    return fail(ErrorCode::NotFound,
                "the scene has no buffer binding '" + std::string(name) +
                    "', expected one of: 'Camera', 'Lights', 'LightsWindow', 'LightTables', "
                    "'GlobalLights', "
                    "'ShadowViews', 'Decals', 'Probes', 'SceneDraws', 'SceneTransforms', "
                    "'SceneInstances', 'SceneBvh', "
                    "'SceneEnvironmentCdf'");
}

}  // namespace rg::passes
