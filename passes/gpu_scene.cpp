#include "gpu_scene.h"

#include <atomic>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "core/hash.h"
#include "core/light_units.h"
#include "lighting/area_lights.h"
#include "lighting/ltc.h"
#include "lighting/punctual.h"
#include "lighting/sg.h"
#include "scene/bvh.h"
#include "scene/environment.h"

namespace rg::passes {

using namespace rg::gpu;

namespace {

// std140 layout of MaterialData (shaders/lib/material.glsl).
struct MaterialUniforms {
    glm::vec4 baseColorOpacity, emissive, factors, factors2, diffuseColor, f0;
    glm::vec4 uvTransform[10];
    glm::vec4 custom[4];
};
static_assert(sizeof(MaterialUniforms) == 320);

struct CameraUniforms {
    glm::mat4 viewProj, view, proj, invViewProj;
    glm::vec4 position, viewport;
    glm::vec4 sceneMin, sceneMax;  // scene.glsl's Camera: the scene's bounds
    glm::mat4 previousViewProj;    // the frame before's (reprojection); this frame's on the first
};

VkFilter toVk(Filter f) { return f == Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }
VkSamplerAddressMode toVk(Wrap w) {
    switch (w) {
    case Wrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case Wrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

Result<OwnedSampler> makeSampler(VkDevice dev, const SamplerDesc& d) {
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = toVk(d.magFilter);
    si.minFilter = toVk(d.minFilter);
    si.mipmapMode = d.mipmapMode == MipmapMode::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = toVk(d.wrapS);
    si.addressModeV = toVk(d.wrapT);
    si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler s = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateSampler(dev, &si, nullptr, &s));
    return OwnedSampler(dev, s);
}

// Copies staged texels into `image` (all of it in TRANSFER_DST, from UNDEFINED) and leaves it
// ready for sampling.
Result<void> copyToImage(Context& ctx, VkImage image, const Buffer& staging, const std::vector<VkBufferImageCopy>& regions) {
    return ctx.submitNow([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               static_cast<uint32_t>(regions.size()), regions.data());
        imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

// Uploads RGBA8 levels (values already in the image's encoding) and leaves the image ready for sampling.
Result<gpu::Image> uploadRgba8(Context& ctx, const std::string& name, bool srgb, const std::vector<const rg::Image*>& levels) {
    ImageDesc d;
    d.name = name;
    d.format = srgb ? Format::RGBA8Srgb : Format::RGBA8Unorm;
    d.width = levels[0]->width;
    d.height = levels[0]->height;
    d.mips = static_cast<uint32_t>(levels.size());
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    size_t bytes = 0;
    for (const auto* l : levels) bytes += size_t(l->width) * l->height * 4;
    auto staging = Buffer::create(ctx, name + ".staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<uint8_t*>(staging->mapped());
    std::vector<VkBufferImageCopy> regions;
    size_t offset = 0;
    for (uint32_t m = 0; m < levels.size(); ++m) {
        const rg::Image& l = *levels[m];
        for (size_t i = 0; i < size_t(l.width) * l.height; ++i)
            for (uint32_t c = 0; c < 4; ++c) {
                float v = c < l.channels ? l.pixels[i * l.channels + c] : 1.0f;
                dst[offset + i * 4 + c] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
            }
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
        r.imageExtent = {l.width, l.height, 1};
        regions.push_back(r);
        offset += size_t(l.width) * l.height * 4;
    }
    if (auto sub = copyToImage(ctx, img->image(), *staging, regions); !sub) return std::unexpected(sub.error());
    return img;
}

Result<gpu::Image> solidTexture(Context& ctx, const std::string& name, glm::vec4 value) {
    rg::Image pixel(1, 1, 4);
    for (int c = 0; c < 4; ++c) pixel.pixels[static_cast<size_t>(c)] = value[c];
    return uploadRgba8(ctx, name, false, {&pixel});
}

// Half-float bits of a value half precision holds exactly (0, ±2^-14..65504 with 10 mantissa bits).
uint16_t exactHalfBits(float f) {
    uint32_t x = 0;
    std::memcpy(&x, &f, sizeof x);
    const auto sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
    if ((x & 0x7fffffffu) == 0) return sign;
    const auto exponent = static_cast<int>((x >> 23) & 0xffu) - 127 + 15;
    RG_CHECK(exponent > 0 && exponent < 31 && (x & 0x1fffu) == 0) << f << " is not exact in half precision";
    return static_cast<uint16_t>(sign | (exponent << 10) | ((x >> 13) & 0x3ffu));
}

// A 1x1 RGBA16F texture: values 8 bits cannot hold exactly. The default normal map is one —
// (0.5, 0.5, 1) in RGBA8 reads back as 128/255 and tilts every unmapped normal by 0.3°.
Result<gpu::Image> solidHalfTexture(Context& ctx, const std::string& name, glm::vec4 value) {
    const uint16_t texel[4] = {exactHalfBits(value.x), exactHalfBits(value.y), exactHalfBits(value.z), exactHalfBits(value.w)};
    ImageDesc d;
    d.name = name;
    d.format = Format::RGBA16F;
    d.width = d.height = 1;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    auto staging = Buffer::create(ctx, name + ".staging", sizeof texel, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    std::memcpy(staging->mapped(), texel, sizeof texel);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {1, 1, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub) return std::unexpected(sub.error());
    return img;
}

// Uploads a float image (1..4 channels; missing colour channels 0, alpha 1) as RGBA32F.
Result<gpu::Image> uploadRgba32f(Context& ctx, const std::string& name, const rg::Image& src) {
    ImageDesc d;
    d.name = name;
    d.format = Format::RGBA32F;
    d.width = src.width;
    d.height = src.height;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    const size_t texels = size_t(src.width) * src.height;
    auto staging = Buffer::create(ctx, name + ".staging", texels * 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<float*>(staging->mapped());
    for (size_t i = 0; i < texels; ++i)
        for (uint32_t c = 0; c < 4; ++c) dst[i * 4 + c] = c < src.channels ? src.pixels[i * src.channels + c] : (c == 3 ? 1.0f : 0.0f);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {src.width, src.height, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub) return std::unexpected(sub.error());
    return img;
}

// The baked lightmap's lobes as the layers of an RGBA16F array (amplitudes beyond half precision's
// range clamped to 65504), then one more layer: the irradiance at the surface normal itself,
// Σ_k A_k I_k(0, 0, 1), which a surface without a normal map reads instead of evaluating every
// lobe (the sum is linear in the amplitudes, so filtering it is filtering them); none: a 1×1×2
// black array, so the view stays an array.
Result<gpu::Image> uploadLightmap(Context& ctx, const Lightmap* lm, ContentHash& hash) {
    ImageDesc d;
    d.name = "scene.lightmap";
    d.format = Format::RGBA16F;
    d.width = lm ? std::max(lm->width, 1u) : 1;
    d.height = lm ? std::max(lm->height, 1u) : 1;
    d.layers = lm ? static_cast<uint32_t>(lm->lobes.size()) + 1 : 2;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    const size_t texels = size_t(d.width) * d.height;
    auto staging = Buffer::create(ctx, "scene.lightmap.staging", texels * d.layers * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<uint16_t*>(staging->mapped());
    std::vector<float> flat;  // I_k((0, 0, 1)) of the unit lobes
    if (lm)
        for (const glm::vec3& axis : lm->axes) flat.push_back(lighting::irradiance({axis, lm->sharpness, glm::vec3(1.0f)}, glm::vec3(0, 0, 1)).x);
    for (uint32_t layer = 0; layer < d.layers; ++layer)
        for (size_t i = 0; i < texels; ++i) {
            glm::vec3 a(0.0f);
            if (lm && layer < lm->lobes.size() && i < lm->lobes[layer].size()) a = lm->lobes[layer][i];
            else if (lm && layer == lm->lobes.size())
                for (size_t k = 0; k < lm->lobes.size(); ++k) a += flat[k] * lm->lobes[k][i];
            for (int c = 0; c < 4; ++c)
                dst[(size_t(layer) * texels + i) * 4 + size_t(c)] =
                    glm::packHalf1x16(c < 3 ? std::clamp(std::isfinite(a[c]) ? a[c] : 0.0f, 0.0f, 65504.0f) : 1.0f);
        }
    hash.u64(d.width);
    hash.u64(d.height);
    hash.bytes(dst, texels * d.layers * 8);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, d.layers};
    r.imageExtent = {d.width, d.height, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub) return std::unexpected(sub.error());
    return img;
}

}  // namespace

GpuScene::~GpuScene() = default;

Result<std::unique_ptr<GpuScene>> GpuScene::create(Context& ctx, Scene scene, const GpuSceneOptions& options) {
    static std::atomic<uint64_t> ids{0};
    std::unique_ptr<GpuScene> s(new GpuScene());
    s->m_id = ++ids;
    s->m_ctx = &ctx;
    s->m_scene = std::move(scene);
    if (s->m_scene.cameras.empty()) return fail(ErrorCode::InvalidInput, "the scene has no camera");
    if (s->m_scene.materials.empty()) s->m_scene.materials.push_back(Material{});
    const char* lodEnv = std::getenv("RG_LOD");
    s->m_levelsOfDetail = options.levelsOfDetail && !(lodEnv && std::string_view(lodEnv) == "0");
    if (auto r = s->uploadGeometry(ctx); !r) return std::unexpected(r.error());
    if (auto r = s->uploadImages(ctx); !r) return std::unexpected(r.error());
    if (auto r = s->createMaterials(ctx); !r) return std::unexpected(r.error());
    if (auto r = s->createFrameData(ctx, options); !r) return std::unexpected(r.error());
    return s;
}

namespace {

// The world-space box around vertices under `world`.
std::pair<glm::vec3, glm::vec3> worldBox(const std::vector<Vertex>& vertices, const glm::mat4& world) {
    if (vertices.empty()) return {glm::vec3(world[3]), glm::vec3(world[3])};
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vertex& v : vertices) {
        const glm::vec3 p = glm::vec3(world * glm::vec4(v.position, 1.0f));
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return {lo, hi};
}

// The six planes (a, b, c, d: inside where a x + b y + c z + d >= 0) of a clip-space frustum
// with depth 0..1 (Gribb & Hartmann), normalised.
std::array<glm::vec4, 6> frustumPlanes(const glm::mat4& m) {
    const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]), r1(m[0][1], m[1][1], m[2][1], m[3][1]),
        r2(m[0][2], m[1][2], m[2][2], m[3][2]), r3(m[0][3], m[1][3], m[2][3], m[3][3]);
    std::array<glm::vec4, 6> p = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
    for (auto& q : p) q /= std::max(glm::length(glm::vec3(q)), 1e-20f);
    return p;
}

bool sphereMeetsFrustum(const std::array<glm::vec4, 6>& planes, glm::vec3 centre, float radius) {
    for (const auto& q : planes)
        if (glm::dot(glm::vec3(q), centre) + q.w < -radius) return false;
    return true;
}

// False when the box lies wholly outside one of the planes (its corner furthest along the
// plane's normal is behind it); conservative near the frustum's edges.
bool boxMeetsFrustum(const std::array<glm::vec4, 6>& planes, glm::vec3 lo, glm::vec3 hi) {
    for (const auto& q : planes) {
        const glm::vec3 corner(q.x >= 0 ? hi.x : lo.x, q.y >= 0 ? hi.y : lo.y, q.z >= 0 ? hi.z : lo.z);
        if (glm::dot(glm::vec3(q), corner) + q.w < 0.0f) return false;
    }
    return true;
}

// The size of the ShadowViews block: a uvec4 header, the views, then an ivec4 per light.
constexpr size_t kShadowViewBytes = 16 + size_t(kMaxShadowViews) * sizeof(GpuShadowView) + size_t(kMaxLights) * 16;

}  // namespace

Result<void> GpuScene::uploadGeometry(Context& ctx) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    struct Range {
        uint32_t firstIndex, indexCount;
        int32_t vertexOffset;
        uint32_t material;
        std::vector<DrawLod> lods;  // the coarser index lists after the full one, errors in the primitive's space
    };
    std::vector<std::vector<Range>> meshRanges;
    for (const Mesh& mesh : m_scene.meshes) {
        std::vector<Range> ranges;
        for (const Primitive& p : mesh.primitives) {
            ranges.push_back({static_cast<uint32_t>(indices.size()), static_cast<uint32_t>(p.indices.size()),
                              static_cast<int32_t>(vertices.size()), std::min<uint32_t>(p.material, static_cast<uint32_t>(m_scene.materials.size() - 1)),
                              {}});
            vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
            indices.insert(indices.end(), p.indices.begin(), p.indices.end());
            for (size_t l = 0; l < p.lods.size() && l + 1 < kMaxDrawLods; ++l) {
                ranges.back().lods.push_back({static_cast<uint32_t>(indices.size()), static_cast<uint32_t>(p.lods[l].indices.size()), p.lods[l].error});
                indices.insert(indices.end(), p.lods[l].indices.begin(), p.lods[l].indices.end());
            }
        }
        meshRanges.push_back(std::move(ranges));
    }
    for (const Node& node : m_scene.nodes) {
        if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= meshRanges.size()) continue;
        const glm::mat4 normal = glm::mat4(glm::transpose(glm::inverse(glm::mat3(node.world))));
        const auto& ranges = meshRanges[static_cast<size_t>(node.mesh)];
        for (size_t k = 0; k < ranges.size(); ++k)
            if (ranges[k].indexCount) {
                const auto [lo, hi] = worldBox(m_scene.meshes[static_cast<size_t>(node.mesh)].primitives[k].vertices, node.world);
                DrawItem& item = m_draws.emplace_back(DrawItem{ranges[k].firstIndex, ranges[k].indexCount, ranges[k].vertexOffset,
                                                               ranges[k].material, node.world, normal, lo, hi, node.lightmapRect});
                item.lods[0] = {item.firstIndex, item.indexCount, 0.0f};
                item.castsShadows = node.castShadows && m_scene.materials[item.material].alphaMode != AlphaMode::Blend;
                // An error in the primitive's space, in the world: times the node's largest axis scale.
                const float scale = std::max({glm::length(glm::vec3(node.world[0])), glm::length(glm::vec3(node.world[1])),
                                              glm::length(glm::vec3(node.world[2]))});
                if (m_levelsOfDetail)
                    for (const DrawLod& lod : ranges[k].lods) item.lods[item.lodCount++] = {lod.firstIndex, lod.indexCount, lod.error * scale};
            }
    }
    // SceneDraws: a uvec4 header (draw count), then per draw (boxMin, firstIndex), (boxMax,
    // indexCount), (vertexOffset, material, casts shadows, level-of-detail count), then the levels'
    // first indices, index counts and errors (lib/scene.glsl RgDraw) — 96 bytes.
    {
        constexpr size_t kWords = 6;
        std::vector<glm::vec4> words(1 + kWords * std::max<size_t>(m_draws.size(), 1), glm::vec4(0.0f));
        words[0] = glm::vec4(std::bit_cast<float>(static_cast<uint32_t>(m_draws.size())), 0.0f, 0.0f, 0.0f);
        for (size_t d = 0; d < m_draws.size(); ++d) {
            const DrawItem& item = m_draws[d];
            glm::vec4* w = &words[1 + kWords * d];
            w[0] = glm::vec4(item.boundsMin, std::bit_cast<float>(item.firstIndex));
            w[1] = glm::vec4(item.boundsMax, std::bit_cast<float>(item.indexCount));
            w[2] = glm::vec4(std::bit_cast<float>(item.vertexOffset), std::bit_cast<float>(item.material),
                             std::bit_cast<float>(item.castsShadows ? 1u : 0u), std::bit_cast<float>(item.lodCount));
            for (uint32_t l = 0; l < kMaxDrawLods; ++l) {
                w[3][static_cast<int>(l)] = std::bit_cast<float>(item.lods[l].firstIndex);
                w[4][static_cast<int>(l)] = std::bit_cast<float>(item.lods[l].indexCount);
                w[5][static_cast<int>(l)] = item.lods[l].error;
            }
        }
        auto buf = Buffer::create(ctx, "scene.draws", words.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (!buf) return std::unexpected(buf.error());
        std::memcpy(buf->mapped(), words.data(), words.size() * sizeof(glm::vec4));
        m_staticHash.bytes(words.data(), words.size() * sizeof(glm::vec4));
        for (const DrawItem& item : m_draws) m_staticHash.bytes(&item.world, sizeof item.world);
        m_drawBuffer = std::move(*buf);
    }
    if (vertices.empty()) {  // keep valid (empty) buffers for an empty scene
        vertices.resize(1);
        indices.resize(3, 0);
    }
    auto upload = [&](Buffer& target, const void* data, size_t bytes, VkBufferUsageFlags usage, const char* name) -> Result<void> {
        auto staging = Buffer::create(ctx, std::string(name) + ".staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
        if (!staging) return std::unexpected(staging.error());
        std::memcpy(staging->mapped(), data, bytes);
        auto buf = Buffer::create(ctx, name, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
        if (!buf) return std::unexpected(buf.error());
        target = std::move(*buf);
        VkBuffer src = staging->buffer(), dst = target.buffer();
        return ctx.submitNow([&](VkCommandBuffer cmd) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(cmd, src, dst, 1, &region);
            memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT);
        });
    };
    m_staticHash.bytes(vertices.data(), vertices.size() * sizeof(Vertex));
    m_staticHash.bytes(indices.data(), indices.size() * sizeof(uint32_t));
    if (auto r = upload(m_vertices, vertices.data(), vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "scene.vertices"); !r) return r;
    return upload(m_indices, indices.data(), indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "scene.indices");
}

Result<void> GpuScene::uploadImages(Context& ctx) {
    for (const SceneImage& si : m_scene.images) {
        std::vector<const rg::Image*> levels;
        for (uint32_t m = 0; m < std::max(1u, si.mipLevels); ++m) {
            if (m > 0 && m - 1 >= si.mips.size()) break;
            levels.push_back(&si.level(m));
        }
        if (levels.empty() || levels[0]->width == 0)
            return fail(ErrorCode::InvalidInput, "scene image '" + si.name + "' has no pixels");
        m_staticHash.u64(si.srgb);
        for (const rg::Image* level : levels) {
            m_staticHash.u64(level->width);
            m_staticHash.u64(level->height);
            m_staticHash.u64(level->channels);
            m_staticHash.bytes(level->pixels.data(), level->pixels.size() * sizeof(float));
        }
        auto img = uploadRgba8(ctx, "scene." + si.name, si.srgb, levels);
        if (!img) return std::unexpected(img.error());
        m_images.push_back(std::move(*img));
    }
    auto white = solidTexture(ctx, "scene.white", glm::vec4(1.0f));
    if (!white) return std::unexpected(white.error());
    m_white = std::move(*white);
    auto flat = solidHalfTexture(ctx, "scene.flat_normal", glm::vec4(0.5f, 0.5f, 1.0f, 1.0f));
    if (!flat) return std::unexpected(flat.error());
    m_flatNormal = std::move(*flat);
    for (const SamplerDesc& d : m_scene.samplers) {
        for (auto v : {uint64_t(d.magFilter), uint64_t(d.minFilter), uint64_t(d.mipmapMode), uint64_t(d.wrapS), uint64_t(d.wrapT)}) m_staticHash.u64(v);
        auto s = makeSampler(ctx.device(), d);
        if (!s) return std::unexpected(s.error());
        m_samplers.push_back(std::move(*s));
    }
    auto def = makeSampler(ctx.device(), SamplerDesc{});
    if (!def) return std::unexpected(def.error());
    m_defaultSampler = std::move(*def);
    // The environment (graph/scene/environment.h): equirectangular nits, black without one. Its
    // sampler wraps around the vertical seam and clamps at the poles.
    rg::Image black(1, 1, 4);
    auto env = m_scene.environment ? environmentImage(m_scene) : Result<rg::Image>(std::move(black));
    if (!env) return std::unexpected(env.error());
    m_staticHash.u64(env->width);
    m_staticHash.u64(env->height);
    m_staticHash.bytes(env->pixels.data(), env->pixels.size() * sizeof(float));
    m_environmentCdf = environmentCdf(*env);
    auto envImage = uploadRgba32f(ctx, "scene.environment", *env);
    if (!envImage) return std::unexpected(envImage.error());
    m_environment = std::move(*envImage);
    SamplerDesc envSampler;
    envSampler.wrapS = Wrap::Repeat;
    envSampler.wrapT = Wrap::ClampToEdge;
    auto es = makeSampler(ctx.device(), envSampler);
    if (!es) return std::unexpected(es.error());
    m_environmentSampler = std::move(*es);
    auto lightmap = uploadLightmap(ctx, m_scene.bakedLightmap.get(), m_staticHash);
    if (!lightmap) return std::unexpected(lightmap.error());
    m_lightmap = std::move(*lightmap);
    return {};
}

Result<void> GpuScene::createMaterials(Context& ctx) {
    VkDevice dev = ctx.device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    bindings.push_back({0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    for (uint32_t b = 1; b <= 5; ++b)
        bindings.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = static_cast<uint32_t>(bindings.size());
    li.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateDescriptorSetLayout(dev, &li, nullptr, &layout));
    m_materialLayout = OwnedDescriptorSetLayout(dev, layout);

    const auto count = static_cast<uint32_t>(m_scene.materials.size());
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, count},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, count * 5}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = count;
    pi.poolSizeCount = 2;
    pi.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateDescriptorPool(dev, &pi, nullptr, &pool));
    m_pool = OwnedDescriptorPool(dev, pool);
    std::vector<VkDescriptorSetLayout> layouts(count, layout);
    m_materialSets.resize(count);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = count;
    ai.pSetLayouts = layouts.data();
    RG_VK_TRY(vkAllocateDescriptorSets(dev, &ai, m_materialSets.data()));

    for (uint32_t i = 0; i < count; ++i) {
        const Material& m = m_scene.materials[i];
        MaterialUniforms u{};
        u.baseColorOpacity = glm::vec4(m.baseColor, m.opacity);
        u.emissive = glm::vec4(m.emissive, 0.0f);
        u.factors = glm::vec4(m.smoothness, m.metalMask, m.reflectance, m.ao);
        u.factors2 = glm::vec4(m.normalScale, m.occlusionStrength, m.alphaCutoff, static_cast<float>(m.alphaMode));
        u.diffuseColor = glm::vec4(m.diffuseColor, m.model == "two_colour" ? 1.0f : 0.0f);
        u.f0 = glm::vec4(m.f0, 0.0f);
        const TextureRef* refs[5] = {&m.baseColorTex, &m.metallicRoughnessTex, &m.normalTex, &m.occlusionTex, &m.emissiveTex};
        for (int t = 0; t < 5; ++t) {
            const glm::mat3& x = refs[t]->transform;  // column-major: x[col][row]
            u.uvTransform[2 * t] = glm::vec4(x[0][0], x[1][0], x[2][0], static_cast<float>(refs[t]->texCoord));
            u.uvTransform[2 * t + 1] = glm::vec4(x[0][1], x[1][1], x[2][1], 0.0f);
        }
        // Game-team parameters: the material's extra numbers, in key order.
        size_t slot = 0;
        for (const auto& [key, value] : m.extra.asTable()) {
            if (!value.isNumber() || slot >= 16) continue;
            u.custom[slot / 4][static_cast<int>(slot % 4)] = static_cast<float>(value.asNumber());
            ++slot;
        }
        m_staticHash.bytes(&u, sizeof u);
        for (const TextureRef* ref : refs) {
            m_staticHash.u64(static_cast<uint64_t>(static_cast<int64_t>(ref->image)));
            m_staticHash.u64(static_cast<uint64_t>(static_cast<int64_t>(ref->sampler)));
        }
        auto buf = Buffer::create(ctx, "material." + m.name, sizeof u, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        if (!buf) return std::unexpected(buf.error());
        std::memcpy(buf->mapped(), &u, sizeof u);
        m_materialBuffers.push_back(std::move(*buf));

        VkDescriptorBufferInfo bi{m_materialBuffers.back().buffer(), 0, VK_WHOLE_SIZE};
        VkDescriptorImageInfo ii[5];
        VkWriteDescriptorSet writes[6];
        writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[0].dstSet = m_materialSets[i];
        writes[0].dstBinding = 0;
        writes[0].descriptorCount = 1;
        writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        writes[0].pBufferInfo = &bi;
        for (int t = 0; t < 5; ++t) {
            const TextureRef& ref = *refs[t];
            const bool has = ref.image >= 0 && static_cast<size_t>(ref.image) < m_images.size();
            VkImageView view = has ? m_images[static_cast<size_t>(ref.image)].view() : (t == 2 ? m_flatNormal.view() : m_white.view());
            VkSampler sampler = ref.sampler >= 0 && static_cast<size_t>(ref.sampler) < m_samplers.size()
                                    ? m_samplers[static_cast<size_t>(ref.sampler)].get()
                                    : m_defaultSampler.get();
            ii[t] = {sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            writes[t + 1] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[t + 1].dstSet = m_materialSets[i];
            writes[t + 1].dstBinding = static_cast<uint32_t>(t + 1);
            writes[t + 1].descriptorCount = 1;
            writes[t + 1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[t + 1].pImageInfo = &ii[t];
        }
        vkUpdateDescriptorSets(dev, 6, writes, 0, nullptr);
    }
    return {};
}

namespace {

std::string lightLabel(const Light& l) { return "light '" + l.name + "' (" + lightTypeName(l.type) + ")"; }

// A unit vector perpendicular to `n`: `hint` made perpendicular, or any when they are parallel.
glm::vec3 perpendicularTo(glm::vec3 n, glm::vec3 hint) {
    glm::vec3 p = hint - glm::dot(hint, n) * n;
    if (glm::length(p) < 1e-4f) p = glm::cross(n, std::abs(n.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    return glm::normalize(p);
}

}  // namespace

Result<GpuLightTable> convertLights(const std::vector<Light>& lights, IesMode iesMode) {
    GpuLightTable table;
    if (lights.size() > kMaxLights)
        return fail(ErrorCode::InvalidInput, "the scene has " + std::to_string(lights.size()) + " lights; the GPU light list holds at most " +
                                                 std::to_string(kMaxLights));
    for (const Light& l : lights) {
        const std::string label = lightLabel(l);
        const bool punctual = l.type == LightType::Point || l.type == LightType::Spot;
        const bool sun = l.type == LightType::Directional;
        // seed 000 tbl:8: the units each type takes (as the scene loaders check; a Scene built
        // in C++ may not have been).
        const std::vector<std::string> units = punctual ? std::vector<std::string>{"lm", "cd"}
                                               : sun    ? std::vector<std::string>{"lux"}
                                                        : std::vector<std::string>{"lm", "nits", "ev100"};
        if (std::find(units.begin(), units.end(), l.unit) == units.end()) {
            std::string list;
            for (const auto& u : units) list += (list.empty() ? "'" : ", '") + u + "'";
            return fail(ErrorCode::InvalidInput, label + ": unit '" + l.unit + "' is not one of " + list + " (seed 000 tbl:8)");
        }
        if (!std::isfinite(l.intensity) || (l.unit != "ev100" && l.intensity < 0.0f))
            return fail(ErrorCode::InvalidInput, label + ": intensity must be a finite number, not negative (" + l.unit + ")");
        if (!l.ies.empty() && !punctual)
            return fail(ErrorCode::InvalidInput, label + ": an IES profile applies to point and spot lights only");
        const glm::vec3 direction = glm::length(l.direction) > 0.0f ? glm::normalize(l.direction) : glm::vec3(0, -1, 0);

        glm::vec3 color = l.color;
        if (l.temperatureK > 0) {
            if (!lights::colorTemperatureInRange(l.temperatureK, l.daylight))
                return fail(ErrorCode::InvalidInput, label + ": temperature " + std::to_string(l.temperatureK) + " K is outside the " +
                                                         (l.daylight ? "daylight locus's 4000-25000 K" : "black body's 1667-25000 K") +
                                                         " that colour temperature converts");
            auto rgb = lights::colorTemperatureToRgb(l.temperatureK, l.daylight);
            color *= glm::vec3(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2]));
        }
        GpuLight g{};
        const float invSqrRange = l.range > 0 ? 1.0f / (l.range * l.range) : 0.0f;
        g.positionType = glm::vec4(l.position, 0.0f);
        g.directionRange = glm::vec4(direction, invSqrRange);
        g.intensity.a = -1.0f;
        GpuLightType type = GpuLightType::Point;
        double value = l.intensity;  // cd, lux or cd/m² once converted
        switch (l.type) {
        case LightType::Point:
        case LightType::Spot: {
            type = l.type == LightType::Point ? GpuLightType::Point : GpuLightType::Spot;
            // tbl:9; spots by eq:17 (Φ / π), or eq:16's exact cone when the light asks for it.
            if (l.unit == "lm")
                value = l.type == LightType::Point ? lights::pointIntensityFromLumens(l.intensity)
                                                   : lights::spotIntensityFromLumens(l.intensity, l.outerAngle, l.exactCone);
            // lst:4: the cone as a scale and offset of cos θ; a point light has none (0, 1).
            lighting::AngleScaleOffset cone;
            if (l.type == LightType::Spot) cone = lighting::spotAngleScaleOffset(l.innerAngle, l.outerAngle);
            g.params = glm::vec4(cone.scale, cone.offset, 0.0f, 0.0f);
            if (!l.ies.empty()) {
                auto it = std::find(table.profilePaths.begin(), table.profilePaths.end(), l.ies);
                if (it == table.profilePaths.end()) {
                    if (table.profiles.size() >= kMaxIesProfiles)
                        return fail(ErrorCode::InvalidInput, label + ": the scene uses more than " + std::to_string(kMaxIesProfiles) +
                                                                 " different IES profiles");
                    auto profile = loadIes(l.ies);
                    if (!profile) return fail(profile.error().code, label + ": " + profile.error().message, profile.error().reasons);
                    if (profile->maxCandela <= 0.0f)
                        return fail(ErrorCode::InvalidInput, label + ": the IES profile '" + l.ies + "' sends no light (its largest candela value is 0)");
                    table.profiles.push_back(bakeIes(*profile, kIesWidth, kIesHeight));
                    table.profilePaths.push_back(l.ies);
                    it = table.profilePaths.end() - 1;
                }
                const auto index = static_cast<size_t>(it - table.profilePaths.begin());
                g.intensity.a = static_cast<float>(index);
                // eq:27: I is either the profile's maximum candela or the user's intensity (mask).
                if (!l.iesMode.empty() && l.iesMode != "mask" && l.iesMode != "intensity")
                    return fail(ErrorCode::InvalidInput, label + ": ies_mode '" + l.iesMode + "' is not 'mask' or 'intensity'");
                const bool profileIntensity = l.iesMode.empty() ? iesMode == IesMode::Intensity : l.iesMode == "intensity";
                if (profileIntensity) value = table.profiles[index].maxCandela;
                // lst:5's light space: z the nadir (the light's direction), x horizontal 0°.
                g.axis = glm::vec4(perpendicularTo(direction, l.up), 0.0f);
            }
            break;
        }
        case LightType::Directional: {
            type = GpuLightType::Sun;  // lux; lst:6 takes the disk's sin and cos
            g.params = glm::vec4(0.0f, 0.0f, std::sin(l.sunAngularRadius), std::cos(l.sunAngularRadius));
            break;
        }
        case LightType::Sphere:
        case LightType::Disk:
        case LightType::Rect:
        case LightType::Tube: {
            lighting::AreaLightShape shape;
            if (l.type == LightType::Rect) {
                if (!(l.width > 0.0f && l.height > 0.0f))
                    return fail(ErrorCode::InvalidInput, label + ": width and height must be positive metres, got " +
                                                             std::to_string(l.width) + " x " + std::to_string(l.height));
                if (glm::length(glm::cross(l.up, direction)) < 1e-6f)
                    return fail(ErrorCode::InvalidInput, label + ": up is parallel to the direction (or zero); the rect needs a height axis");
                shape = {lighting::AreaShape::Rectangle, 0.0, 0.0, l.width, l.height};
                type = GpuLightType::Rect;
                g.params = glm::vec4(0.0f, 0.0f, 0.0f, l.width);
                g.axis = glm::vec4(perpendicularTo(direction, l.up), l.height);
            } else {
                if (!(l.radius > 0.0f)) return fail(ErrorCode::InvalidInput, label + ": radius must be positive metres, got " + std::to_string(l.radius));
                if (l.type == LightType::Tube && !(l.length > 0.0f))
                    return fail(ErrorCode::InvalidInput, label + ": length must be positive metres, got " + std::to_string(l.length));
                shape.shape = l.type == LightType::Sphere ? lighting::AreaShape::Sphere
                              : l.type == LightType::Disk ? lighting::AreaShape::Disk
                                                          : lighting::AreaShape::Tube;
                shape.radius = l.radius;
                shape.length = l.length;
                type = l.type == LightType::Sphere ? GpuLightType::Sphere : l.type == LightType::Disk ? GpuLightType::Disk : GpuLightType::Tube;
                // A disk's cone (lst:9): the spot's scale and offset, and in axis.w how far behind
                // the disk its virtual apex lies (r / tan θ_outer); without one, scale 0, offset 1.
                lighting::AngleScaleOffset cone;
                if (l.type == LightType::Disk && l.cone) {
                    cone = lighting::spotAngleScaleOffset(l.innerAngle, l.outerAngle);
                    g.axis = glm::vec4(0.0f, 0.0f, 0.0f, l.radius / std::tan(std::clamp(l.outerAngle, 1e-3f, 1.5707f)));
                }
                g.params = glm::vec4(cone.scale, cone.offset, l.radius, l.type == LightType::Tube ? l.length : 0.0f);
            }
            const lighting::AreaUnit unit = l.unit == "lm"     ? lighting::AreaUnit::Lumens
                                            : l.unit == "nits" ? lighting::AreaUnit::Nits
                                                               : lighting::AreaUnit::Ev100;
            value = lighting::areaLightLuminance(shape, l.intensity, unit);  // tbl:12, eq:12: cd/m²
            break;
        }
        }
        g.positionType.w = static_cast<float>(type);
        const glm::vec3 rgb = color * static_cast<float>(value);
        g.intensity = glm::vec4(rgb, g.intensity.a);
        if (!std::isfinite(rgb.r) || !std::isfinite(rgb.g) || !std::isfinite(rgb.b))
            return fail(ErrorCode::InvalidInput, label + ": intensity " + std::to_string(l.intensity) + " " + l.unit + " is not a finite value on the GPU");
        table.lights.push_back(g);
    }
    return table;
}

// std430 RgDecal (shaders/lib/scene.glsl).
struct GpuDecal {
    glm::mat4 worldToBox;
    glm::vec4 baseColorOpacity;  // rgb, opacity
    glm::vec4 params;            // smoothness, metalMask, reflectance, 0
    glm::vec4 flags;             // has base colour, smoothness, metal mask, reflectance (0/1)
    glm::vec4 axis;              // xyz: the box's +Y axis in world space (normal target); w: blend normal
};

Result<void> GpuScene::createDecals(Context& ctx) {
    std::vector<GpuDecal> decals;
    for (const Decal& d : m_scene.decals) {
        GpuDecal g{};
        g.worldToBox = glm::inverse(d.world);
        g.baseColorOpacity = glm::vec4(d.baseColor, d.opacity);
        g.params = glm::vec4(d.smoothness, d.metalMask, d.reflectance, 0.0f);
        g.flags = glm::vec4(d.hasBaseColor, d.hasSmoothness, d.hasMetalMask, d.hasReflectance);
        g.axis = glm::vec4(glm::normalize(glm::vec3(d.world[1])), d.normal ? 1.0f : 0.0f);
        decals.push_back(g);
    }
    auto buf = Buffer::create(ctx, "scene.decals", 16 + std::max<size_t>(1, decals.size()) * sizeof(GpuDecal),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    m_decals = std::move(*buf);
    auto* p = static_cast<uint8_t*>(m_decals.mapped());
    uint32_t header[4] = {static_cast<uint32_t>(decals.size()), 0, 0, 0};
    std::memcpy(p, header, 16);
    if (!decals.empty()) std::memcpy(p + 16, decals.data(), decals.size() * sizeof(GpuDecal));
    return {};
}

// std430 RgProbe (shaders/lib/probes.glsl).
struct GpuProbe {
    glm::vec4 positionShape;  // xyz: capture point and proxy centre; w: 0 sphere, 1 box
    glm::vec4 extentFade;     // xyz: box half extents (a sphere: its radius in x); w: fade (m)
    glm::vec4 axes[3];        // box: its local axes in world space (rows of world → local)
    glm::vec4 influence;      // xyz: the influence box's half extents (a sphere: its radius in x)
};

Result<void> GpuScene::createProbes(Context& ctx) {
    // §4.9.5: the composition takes local probes "from small to large" until the reflection is
    // complete; a scene's priority goes before size.
    const auto& probes = m_scene.probes;
    // Size: the volume it reflects in (its influence).
    auto volume = [](const Probe& p) {
        const glm::vec3 h = p.influenceHalfExtents();
        return p.box ? 8.0f * h.x * h.y * h.z : 4.18879f * h.x * h.x * h.x;
    };
    m_probeOrder.resize(probes.size());
    for (size_t i = 0; i < probes.size(); ++i) m_probeOrder[i] = i;
    std::stable_sort(m_probeOrder.begin(), m_probeOrder.end(), [&](size_t a, size_t b) {
        if (probes[a].priority != probes[b].priority) return probes[a].priority > probes[b].priority;
        return volume(probes[a]) < volume(probes[b]);
    });
    std::vector<GpuProbe> out;
    for (size_t i : m_probeOrder) {
        const Probe& p = probes[i];
        GpuProbe g{};
        g.positionShape = glm::vec4(p.position, p.box ? 1.0f : 0.0f);
        g.extentFade = glm::vec4(p.box ? 0.5f * p.size : glm::vec3(p.radius), p.fade);
        for (int a = 0; a < 3; ++a) g.axes[a] = glm::vec4(glm::normalize(p.rotation[a]), 0.0f);
        g.influence = glm::vec4(p.influenceHalfExtents(), 0.0f);
        out.push_back(g);
    }
    auto buf = Buffer::create(ctx, "scene.probes", 16 + kMaxProbes * sizeof(GpuProbe), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    m_probes = std::move(*buf);
    auto* bytes = static_cast<uint8_t*>(m_probes.mapped());
    std::memset(bytes, 0, 16 + kMaxProbes * sizeof(GpuProbe));
    const uint32_t header[4] = {static_cast<uint32_t>(out.size()), 0, 0, 0};
    std::memcpy(bytes, header, 16);
    if (!out.empty()) std::memcpy(bytes + 16, out.data(), out.size() * sizeof(GpuProbe));
    return {};
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
            if (m_scene.lights[i].baked) table->lights[i].intensity = glm::vec4(0.0f, 0.0f, 0.0f, table->lights[i].intensity.a);
    m_lightCount = static_cast<uint32_t>(table->lights.size());
    m_iesProfileCount = static_cast<uint32_t>(table->profiles.size());
    // scene.glsl's Lights block: a uvec4 header, RG_MAX_LIGHTS lights, the LTC table (two vec4 per
    // entry), then every profile's texels (one float more, so the runtime array is never empty).
    const size_t ltcBytes = size_t(ltc::kSize) * ltc::kSize * 32;
    const size_t ltcOffset = 16 + size_t(kMaxLights) * sizeof(GpuLight);
    const size_t lightBytes = ltcOffset + ltcBytes;
    const size_t texelCount = size_t(kIesWidth) * kIesHeight;
    const size_t bytes = lightBytes + (m_iesProfileCount * texelCount + 1) * sizeof(float);
    for (uint32_t s = 0; s < ctx.framesInFlight(); ++s) {
        auto cam = Buffer::create(ctx, "scene.camera", sizeof(CameraUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        if (!cam) return std::unexpected(cam.error());
        m_cameraBuffers.push_back(std::move(*cam));
        auto views = Buffer::create(ctx, "scene.shadow_views", kShadowViewBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (!views) return std::unexpected(views.error());
        std::memset(views->mapped(), 0, kShadowViewBytes);
        m_shadowViewBuffers.push_back(std::move(*views));
        auto lights = Buffer::create(ctx, "scene.lights", bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        if (!lights) return std::unexpected(lights.error());
        auto* p = static_cast<uint8_t*>(lights->mapped());
        std::memset(p, 0, bytes);
        const uint32_t header[4] = {m_lightCount, m_areaLightModel, kIesWidth, kIesHeight};
        std::memcpy(p, header, sizeof header);
        if (m_lightCount) std::memcpy(p + 16, table->lights.data(), table->lights.size() * sizeof(GpuLight));
        float* ltcOut = reinterpret_cast<float*>(p + ltcOffset);
        for (const ltc::Entry& e : ltc::table()) {
            const float entry[8] = {e.inverse[0], e.inverse[1], e.inverse[2], e.inverse[3], e.magnitude, e.fresnel, 0.0f, 0.0f};
            std::memcpy(ltcOut, entry, sizeof entry);
            ltcOut += 8;
        }
        for (size_t i = 0; i < table->profiles.size(); ++i) {
            const IesTexture& t = table->profiles[i];
            RG_CHECK(t.texels.size() == texelCount) << "IES profile baked at " << t.width << " x " << t.height;
            std::memcpy(p + lightBytes + i * texelCount * sizeof(float), t.texels.data(), texelCount * sizeof(float));
        }
        m_lightBuffers.push_back(std::move(*lights));
    }
    return {};
}

Result<void> GpuScene::selectCamera(const std::string& name) {
    for (size_t i = 0; i < m_scene.cameras.size(); ++i)
        if (m_scene.cameras[i].name == name) {
            m_camera = i;
            return {};
        }
    std::string names;
    for (const auto& c : m_scene.cameras) names += (names.empty() ? "'" : ", '") + c.name + "'";
    return fail(ErrorCode::NotFound, "the scene has no camera '" + name + "' (cameras: " + names + ")");
}

void GpuScene::updateFrame(uint32_t slot, uint32_t width, uint32_t height) {
    const Camera& c = camera();
    const float aspect = static_cast<float>(width) / static_cast<float>(std::max(1u, height));
    const float fovy = c.focalLength > 0 ? 2.0f * std::atan(c.sensorHeight / (2.0f * c.focalLength)) : c.verticalFov;
    CameraUniforms u{};
    u.view = glm::lookAt(c.position, c.target, c.up);
    if (c.orthographic) {
        const float h = 0.5f * c.orthoHeight, w = h * aspect;
        u.proj = glm::orthoRH_ZO(-w, w, -h, h, c.nearPlane, c.farPlane);
    } else {
        u.proj = glm::perspectiveRH_ZO(fovy, aspect, c.nearPlane, c.farPlane);
    }
    u.proj[1][1] *= -1.0f;  // Vulkan's y points down
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.position = glm::vec4(c.position, 1.0f);
    u.viewport = glm::vec4(static_cast<float>(width), static_cast<float>(height), 1.0f / static_cast<float>(width),
                           1.0f / static_cast<float>(height));
    u.sceneMin = glm::vec4(m_scene.boundsMin, 1.0f);
    u.sceneMax = glm::vec4(m_scene.boundsMax, 1.0f);
    u.previousViewProj = m_previousViewProj.value_or(u.viewProj);
    m_previousViewProj = u.viewProj;
    std::memcpy(m_cameraBuffers[slot].mapped(), &u, sizeof u);
    const auto planes = frustumPlanes(u.viewProj);
    m_drawInView.resize(m_draws.size());
    for (size_t d = 0; d < m_draws.size(); ++d) m_drawInView[d] = boxMeetsFrustum(planes, m_draws[d].boundsMin, m_draws[d].boundsMax);
    // Levels of detail: a world length L at view depth z spans L · |proj[1][1]| · height / (2z)
    // pixels (orthographic: without the z); each draw takes the coarsest level whose error spans at
    // most a pixel at the nearest depth of its box (the full one where the box reaches the
    // near plane).
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const float pixelsPerMetre = std::abs(u.proj[1][1]) * static_cast<float>(height) * 0.5f;
    m_drawLod.assign(m_draws.size(), 0);
    for (size_t d = 0; d < m_draws.size(); ++d) {
        const DrawItem& item = m_draws[d];
        if (item.lodCount < 2) continue;
        float nearest = std::numeric_limits<float>::max();
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 corner((k & 1) ? item.boundsMax.x : item.boundsMin.x, (k & 2) ? item.boundsMax.y : item.boundsMin.y,
                                   (k & 4) ? item.boundsMax.z : item.boundsMin.z);
            nearest = std::min(nearest, glm::dot(corner - c.position, forward));
        }
        if (!c.orthographic && nearest <= c.nearPlane) continue;
        const float scale = c.orthographic ? pixelsPerMetre : pixelsPerMetre / nearest;
        uint8_t level = 0;
        for (uint32_t l = 1; l < item.lodCount; ++l)
            if (item.lods[l].error * scale <= 1.0f) level = static_cast<uint8_t>(l);
        m_drawLod[d] = level;
    }
    updateShadowViews(slot, u.viewProj);
    std::memcpy(static_cast<uint8_t*>(m_lightBuffers[slot].mapped()) + 4, &m_areaLightModel, sizeof m_areaLightModel);
}

uint64_t GpuScene::contentHash(uint32_t slot) const {
    ContentHash h;
    h.u64(m_staticHash.value());
    for (const Buffer* b : {&m_cameraBuffers[slot], &m_lightBuffers[slot], &m_shadowViewBuffers[slot], &m_decals, &m_probes})
        h.bytes(b->mapped(), b->size());
    return h.value();
}

VkBuffer GpuScene::bvhBuffer() const {
    if (m_bvh.buffer() != VK_NULL_HANDLE) return m_bvh.buffer();
    std::vector<glm::vec3> corners;
    // The draws' triangles, from the scene's meshes under each node's transform.
    for (const Node& node : m_scene.nodes) {
        if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= m_scene.meshes.size()) continue;
        for (const Primitive& p : m_scene.meshes[static_cast<size_t>(node.mesh)].primitives) {
            const uint32_t material = std::min<uint32_t>(p.material, static_cast<uint32_t>(m_scene.materials.size() - 1));
            if (m_scene.materials[material].alphaMode == AlphaMode::Blend) continue;
            for (size_t i = 0; i + 2 < p.indices.size(); i += 3)
                for (int k = 0; k < 3; ++k) {
                    const uint32_t v = p.indices[i + k];
                    corners.push_back(v < p.vertices.size() ? glm::vec3(node.world * glm::vec4(p.vertices[v].position, 1.0f)) : glm::vec3(0.0f));
                }
        }
    }
    const FlatBvh bvh = buildBvh(corners);
    const glm::uvec4 header(bvh.nodeCount, bvh.triangleCount, bvh.depth, 0u);
    const size_t bytes = sizeof header + std::max<size_t>(bvh.data.size(), 1) * sizeof(glm::vec4);
    auto buf = Buffer::create(*m_ctx, "scene.bvh", bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return VK_NULL_HANDLE;  // ShaderProgram reports it
    auto* p = static_cast<uint8_t*>(buf->mapped());
    std::memset(p, 0, bytes);
    std::memcpy(p, &header, sizeof header);
    if (!bvh.data.empty()) std::memcpy(p + sizeof header, bvh.data.data(), bvh.data.size() * sizeof(glm::vec4));
    m_bvh = std::move(*buf);
    return m_bvh.buffer();
}

VkBuffer GpuScene::environmentCdfBuffer() const {
    if (m_environmentCdfBuffer.buffer() != VK_NULL_HANDLE) return m_environmentCdfBuffer.buffer();
    const glm::uvec4 header(m_environmentCdf.width, m_environmentCdf.height, 0u, 0u);
    const size_t bytes = sizeof header + m_environmentCdf.data.size() * sizeof(float);
    auto buf = Buffer::create(*m_ctx, "scene.environment_cdf", bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return VK_NULL_HANDLE;  // ShaderProgram reports it
    auto* p = static_cast<uint8_t*>(buf->mapped());
    std::memcpy(p, &header, sizeof header);
    std::memcpy(p + sizeof header, m_environmentCdf.data.data(), m_environmentCdf.data.size() * sizeof(float));
    m_environmentCdfBuffer = std::move(*buf);
    return m_environmentCdfBuffer.buffer();
}

VkBuffer GpuScene::bindingBuffer(std::string_view name, uint32_t slot) const {
    if (name == "Camera") return cameraBuffer(slot);
    if (name == "Lights" || name == "LightsWindow") return lightBuffer(slot);
    if (name == "ShadowViews") return shadowViewBuffer(slot);
    if (name == "Decals") return decalBuffer();
    if (name == "Probes") return probeBuffer();
    if (name == "SceneDraws") return drawBuffer();
    if (name == "SceneBvh") return bvhBuffer();
    if (name == "SceneEnvironmentCdf") return environmentCdfBuffer();
    return VK_NULL_HANDLE;
}

uint32_t shadowViewsNeeded(const Light& l) {
    if (!l.castShadows || l.type == LightType::Directional) return 0;
    return l.type == LightType::Spot && l.outerAngle <= glm::radians(60.0f) ? 1 : 6;
}

uint32_t shadowViewCapacity(const Scene& scene) {
    uint32_t views = 0;
    for (size_t i = 0; i < scene.lights.size() && i < kMaxLights; ++i) {
        const uint32_t count = shadowViewsNeeded(scene.lights[i]);
        if (views + count <= kMaxShadowViews) views += count;
    }
    return views;
}

std::pair<uint32_t, uint32_t> GpuScene::shadowViewsOf(size_t light) const {
    if (light >= m_lightViews.size() || m_lightViews[light].y == 0) return {0, 0};
    return {static_cast<uint32_t>(m_lightViews[light].x), static_cast<uint32_t>(m_lightViews[light].y)};
}

void GpuScene::updateShadowViews(uint32_t slot, const glm::mat4& cameraViewProj) {
    m_shadowViewDraws.clear();
    m_lightViews.assign(kMaxLights, glm::ivec4(-1, 0, 0, 0));
    std::vector<GpuShadowView> views;
    const auto camera = frustumPlanes(cameraViewProj);
    // A light without a range reaches as far as the scene goes.
    const float sceneSize = glm::length(m_scene.boundsMax - m_scene.boundsMin);
    const float nearPlane = 0.05f;
    for (size_t i = 0; i < m_scene.lights.size() && i < kMaxLights; ++i) {
        const Light& l = m_scene.lights[i];
        const uint32_t count = shadowViewsNeeded(l);
        if (count == 0) continue;
        const float far = l.range > 0.0f ? l.range : std::max(sceneSize, 1.0f) * 2.0f;
        if (!sphereMeetsFrustum(camera, l.position, far)) continue;  // its light does not reach the view
        const bool single = count == 1;
        if (views.size() + count > kMaxShadowViews) continue;
        // A cube's faces see a little past 90° so that filter taps near a face's edge stay on
        // its map (16 texels of a 1024 map); a spot's view covers its outer cone.
        const float tanHalf = single ? std::tan(std::min(l.outerAngle + glm::radians(2.0f), glm::radians(75.0f))) : 1.0f / (1.0f - 32.0f / 1024.0f);
        const glm::mat4 proj = glm::perspectiveRH_ZO(2.0f * std::atan(tanHalf), 1.0f, nearPlane, far);
        static const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        m_lightViews[i] = glm::ivec4(static_cast<int>(views.size()), static_cast<int>(count), 0, 0);
        const float radius = std::max({l.radius, 0.5f * std::max(l.width, l.height), 0.5f * l.length});
        for (uint32_t f = 0; f < count; ++f) {
            const glm::vec3 axis = single ? l.direction : axes[f];
            const glm::vec3 up = single ? (std::abs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)) : ups[f];
            GpuShadowView v;
            v.viewProj = proj * glm::lookAt(l.position, l.position + axis, up);
            v.position = glm::vec4(l.position, nearPlane);
            v.params = glm::vec4(far, tanHalf, radius, static_cast<float>(i));
            views.push_back(v);
            // The casters this view sees.
            const auto planes = frustumPlanes(v.viewProj);
            std::vector<size_t> draws;
            for (size_t d = 0; d < m_draws.size(); ++d)
                if (m_draws[d].castsShadows && boxMeetsFrustum(planes, m_draws[d].boundsMin, m_draws[d].boundsMax))
                    draws.push_back(d);
            m_shadowViewDraws.push_back(std::move(draws));
        }
    }
    auto* p = static_cast<uint8_t*>(m_shadowViewBuffers[slot].mapped());
    const glm::uvec4 header(static_cast<uint32_t>(views.size()), 0, 0, 0);
    std::memcpy(p, &header, sizeof header);
    if (!views.empty()) std::memcpy(p + 16, views.data(), views.size() * sizeof(GpuShadowView));
    std::memcpy(p + 16 + size_t(kMaxShadowViews) * sizeof(GpuShadowView), m_lightViews.data(), m_lightViews.size() * sizeof(glm::ivec4));
}

}  // namespace rg::passes
