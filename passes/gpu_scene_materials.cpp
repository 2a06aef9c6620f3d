// GpuScene's images and materials: the scene's textures with their mip chains and samplers, the
// default textures, the environment and the baked lightmap as images, every material's parameters
// in uniform buffers (one a window, and windows of many), and a descriptor set per texture set
// (set 1 of scene draws, shaders/lib/material.glsl).
#include "gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "core/hash.h"
#include "lighting/sg.h"
#include "scene/environment.h"

namespace rg::passes {

using namespace rg::gpu;

namespace {

// RgMaterialData (shaders/lib/material.glsl): vec4s only, the same in std140 and std430.
struct MaterialUniforms {
    glm::vec4 baseColorOpacity, emissive, factors, factors2, diffuseColor, f0;
    glm::vec4 uvTransform[16];  // 5 standard maps, kMaterialTextureSlots own ones, one spare
    glm::vec4 custom[4];
};
static_assert(sizeof(MaterialUniforms) == 416);
// The standard maps and the model's own: bindings 1 .. kMaterialTextures of set 1 (0: a
// material's parameters, kMaterialTextures + 1: a window of materials').
constexpr uint32_t kMaterialTextures = 5 + kMaterialTextureSlots;
static_assert(2 * kMaterialTextures <= 16);
static_assert(kMaterialTextures + 1 == 9, "lib/material.glsl's MaterialWindow binding");

// A material's texture references slot by slot: the five standard maps, then its model's own in
// slot order; a slot without one: no texture.
std::vector<const TextureRef*> slotRefs(const Material& m) {
    static const TextureRef none;
    std::vector<const TextureRef*> refs = m.textureRefs();
    refs.resize(kMaterialTextures, &none);
    return refs;
}

VkFilter toVk(Filter f) { return f == Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }
VkSamplerAddressMode toVk(Wrap w) {
    switch (w) {
        case Wrap::ClampToEdge:
            return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case Wrap::MirroredRepeat:
            return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        default:
            return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

Result<OwnedSampler> makeSampler(VkDevice dev, const SamplerDesc& d) {
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = toVk(d.magFilter);
    si.minFilter = toVk(d.minFilter);
    si.mipmapMode = d.mipmapMode == MipmapMode::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST
                                                        : VK_SAMPLER_MIPMAP_MODE_LINEAR;
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
Result<void> copyToImage(Context& ctx, VkImage image, const Buffer& staging,
                         const std::vector<VkBufferImageCopy>& regions) {
    return ctx.submitNow([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               static_cast<uint32_t>(regions.size()), regions.data());
        imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

// Uploads RGBA8 layers, each its levels (values already in the image's encoding; every layer's
// level m the same size), as one 2-D array image (an array view even with one layer) ready for
// sampling.
Result<gpu::Image> uploadRgba8(Context& ctx, const std::string& name, bool srgb,
                               const std::vector<std::vector<const rg::Image*>>& layers) {
    const std::vector<const rg::Image*>& first = layers.front();
    ImageDesc d;
    d.name = name;
    d.format = srgb ? Format::RGBA8Srgb : Format::RGBA8Unorm;
    d.width = first[0]->width;
    d.height = first[0]->height;
    d.mips = static_cast<uint32_t>(first.size());
    d.layers = static_cast<uint32_t>(layers.size());
    d.array = true;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    size_t bytes = 0;
    for (const auto& levels : layers)
        for (const auto* l : levels) bytes += size_t(l->width) * l->height * 4;
    auto staging =
        Buffer::create(ctx, name + ".staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<uint8_t*>(staging->mapped());
    std::vector<VkBufferImageCopy> regions;
    size_t offset = 0;
    for (uint32_t layer = 0; layer < layers.size(); ++layer)
        for (uint32_t m = 0; m < layers[layer].size(); ++m) {
            const rg::Image& l = *layers[layer][m];
            for (size_t i = 0; i < size_t(l.width) * l.height; ++i)
                for (uint32_t c = 0; c < 4; ++c) {
                    float v = c < l.channels ? l.pixels[i * l.channels + c] : 1.0f;
                    dst[offset + i * 4 + c] =
                        static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
                }
            VkBufferImageCopy r{};
            r.bufferOffset = offset;
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, layer, 1};
            r.imageExtent = {l.width, l.height, 1};
            regions.push_back(r);
            offset += size_t(l.width) * l.height * 4;
        }
    if (auto sub = copyToImage(ctx, img->image(), *staging, regions); !sub)
        return std::unexpected(sub.error());
    return img;
}

Result<gpu::Image> solidTexture(Context& ctx, const std::string& name, glm::vec4 value) {
    rg::Image pixel(1, 1, 4);
    for (int c = 0; c < 4; ++c) pixel.pixels[static_cast<size_t>(c)] = value[c];
    return uploadRgba8(ctx, name, false, {{&pixel}});
}

// Half-float bits of a value half precision holds exactly (0, ±2^-14..65504 with 10 mantissa bits).
uint16_t exactHalfBits(float f) {
    uint32_t x = 0;
    std::memcpy(&x, &f, sizeof x);
    const auto sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
    if ((x & 0x7fffffffu) == 0) return sign;
    const auto exponent = static_cast<int>((x >> 23) & 0xffu) - 127 + 15;
    RG_CHECK(exponent > 0 && exponent < 31 && (x & 0x1fffu) == 0)
        << f << " is not exact in half precision";
    return static_cast<uint16_t>(sign | (exponent << 10) | ((x >> 13) & 0x3ffu));
}

// A 1x1 RGBA16F texture: values 8 bits cannot hold exactly. The default normal map is one —
// (0.5, 0.5, 1) in RGBA8 reads back as 128/255 and tilts every unmapped normal by 0.3°.
Result<gpu::Image> solidHalfTexture(Context& ctx, const std::string& name, glm::vec4 value) {
    const uint16_t texel[4] = {exactHalfBits(value.x), exactHalfBits(value.y),
                               exactHalfBits(value.z), exactHalfBits(value.w)};
    ImageDesc d;
    d.name = name;
    d.format = Format::RGBA16F;
    d.width = d.height = 1;
    d.array = true;  // as the scene's textures (lib/material.glsl's sampler2DArray)
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto img = gpu::Image::create(ctx, d);
    if (!img) return std::unexpected(img.error());
    auto staging = Buffer::create(ctx, name + ".staging", sizeof texel,
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    std::memcpy(staging->mapped(), texel, sizeof texel);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {1, 1, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub)
        return std::unexpected(sub.error());
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
    auto staging =
        Buffer::create(ctx, name + ".staging", texels * 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<float*>(staging->mapped());
    for (size_t i = 0; i < texels; ++i)
        for (uint32_t c = 0; c < 4; ++c)
            dst[i * 4 + c] =
                c < src.channels ? src.pixels[i * src.channels + c] : (c == 3 ? 1.0f : 0.0f);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {src.width, src.height, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub)
        return std::unexpected(sub.error());
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
    auto staging = Buffer::create(ctx, "scene.lightmap.staging", texels * d.layers * 8,
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto* dst = static_cast<uint16_t*>(staging->mapped());
    std::vector<float> flat;  // I_k((0, 0, 1)) of the unit lobes
    if (lm)
        for (const glm::vec3& axis : lm->axes)
            flat.push_back(
                lighting::irradiance({axis, lm->sharpness, glm::vec3(1.0f)}, glm::vec3(0, 0, 1)).x);
    for (uint32_t layer = 0; layer < d.layers; ++layer)
        for (size_t i = 0; i < texels; ++i) {
            glm::vec3 a(0.0f);
            if (lm && layer < lm->lobes.size() && i < lm->lobes[layer].size())
                a = lm->lobes[layer][i];
            else if (lm && layer == lm->lobes.size())
                for (size_t k = 0; k < lm->lobes.size(); ++k) a += flat[k] * lm->lobes[k][i];
            for (int c = 0; c < 4; ++c)
                dst[(size_t(layer) * texels + i) * 4 + size_t(c)] = glm::packHalf1x16(
                    c < 3 ? std::clamp(std::isfinite(a[c]) ? a[c] : 0.0f, 0.0f, 65504.0f) : 1.0f);
        }
    hash.u64(d.width);
    hash.u64(d.height);
    hash.bytes(dst, texels * d.layers * 8);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, d.layers};
    r.imageExtent = {d.width, d.height, 1};
    if (auto sub = copyToImage(ctx, img->image(), *staging, {r}); !sub)
        return std::unexpected(sub.error());
    return img;
}

}  // namespace

Result<void> GpuScene::uploadImages(Context& ctx) {
    // The scene's images as layers of 2-D array images, one array per shape — size, mip count and
    // encoding — of at most maxImageArrayLayers and 256 MiB (m_textureArrayBytes: an array is
    // staged whole, and one image of it must stay far below any device's maxResourceSize, 2 GiB
    // at least): a material's textures are (array, layer), so materials whose textures differ
    // only in layer share a texture set and a draw call (lavapipe has no descriptor indexing for
    // one array of every texture).
    const uint32_t maxLayers = std::max(ctx.properties().limits.maxImageArrayLayers, 1u);
    struct Array {
        std::string name;
        bool srgb = false;
        size_t bytes = 0;                                   // its layers' RGBA8 texels
        std::vector<std::vector<const rg::Image*>> layers;  // each its levels
    };
    std::vector<Array> arrays;
    std::map<std::tuple<uint32_t, uint32_t, size_t, bool>, uint32_t> open;  // shape → array
    m_imageLayer.clear();
    for (const SceneImage& si : m_scene.images) {
        std::vector<const rg::Image*> levels;
        for (uint32_t m = 0; m < std::max(1u, si.mipLevels); ++m) {
            if (m > 0 && m - 1 >= si.mips.size()) break;
            levels.push_back(&si.level(m));
        }
        if (levels.empty() || levels[0]->width == 0)
            return fail(ErrorCode::InvalidInput, "scene image '" + si.name + "' has no pixels");
        m_staticHash.u64(si.srgb);
        size_t layerBytes = 0;
        for (const rg::Image* level : levels) {
            m_staticHash.u64(level->width);
            m_staticHash.u64(level->height);
            m_staticHash.u64(level->channels);
            m_staticHash.bytes(level->pixels.data(), level->pixels.size() * sizeof(float));
            layerBytes += size_t(level->width) * level->height * 4;
        }
        const auto shape = std::tuple(levels[0]->width, levels[0]->height, levels.size(), si.srgb);
        auto at = open.find(shape);
        if (at == open.end() || arrays[at->second].layers.size() >= maxLayers ||
            (arrays[at->second].bytes > 0 &&
             arrays[at->second].bytes + layerBytes > m_textureArrayBytes)) {
            at = open.insert_or_assign(shape, static_cast<uint32_t>(arrays.size())).first;
            arrays.push_back({"scene.textures" + std::to_string(arrays.size()) + "." +
                                  std::to_string(levels[0]->width) + "x" +
                                  std::to_string(levels[0]->height) + (si.srgb ? ".srgb" : ""),
                              si.srgb,
                              0,
                              {}});
        }
        Array& array = arrays[at->second];
        array.bytes += layerBytes;
        m_imageLayer.push_back({at->second, static_cast<uint32_t>(array.layers.size())});
        array.layers.push_back(std::move(levels));
    }
    for (const Array& array : arrays) {
        auto img = uploadRgba8(ctx, array.name, array.srgb, array.layers);
        if (!img) return std::unexpected(img.error());
        m_textureArrays.push_back(std::move(*img));
    }
    auto white = solidTexture(ctx, "scene.white", glm::vec4(1.0f));
    if (!white) return std::unexpected(white.error());
    m_white = std::move(*white);
    auto flat = solidHalfTexture(ctx, "scene.flat_normal", glm::vec4(0.5f, 0.5f, 1.0f, 1.0f));
    if (!flat) return std::unexpected(flat.error());
    m_flatNormal = std::move(*flat);
    for (const SamplerDesc& d : m_scene.samplers) {
        for (auto v : {uint64_t(d.magFilter), uint64_t(d.minFilter), uint64_t(d.mipmapMode),
                       uint64_t(d.wrapS), uint64_t(d.wrapT)})
            m_staticHash.u64(v);
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
    auto env =
        m_scene.environment ? environmentImage(m_scene) : Result<rg::Image>(std::move(black));
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

void GpuScene::assignTextureSets() {
    std::map<std::vector<std::pair<int32_t, int32_t>>, uint32_t> setOf;
    m_materialTextureSet.clear();
    m_textureSetSlots.clear();
    for (const Material& m : m_scene.materials) {
        std::vector<std::pair<int32_t, int32_t>> slots;
        for (const TextureRef* ref : slotRefs(m)) {
            const bool sampler =
                ref->sampler >= 0 && size_t(ref->sampler) < m_scene.samplers.size();
            // The image's array (its layer is the material's parameter); a slot the material
            // names a texture for but whose image is missing keeps its own key (−2): the
            // material's shader variant still samples it (the default's texels).
            const auto image = imageLayer(*ref);
            slots.emplace_back(
                image ? static_cast<int32_t>(image->first) : (ref->valid() ? -2 : -1),
                sampler ? ref->sampler : -1);
        }
        auto [at, added] = setOf.emplace(slots, static_cast<uint32_t>(m_textureSetSlots.size()));
        if (added) m_textureSetSlots.push_back(std::move(slots));
        m_materialTextureSet.push_back(at->second);
    }
}

Result<void> GpuScene::createMaterials(Context& ctx) {
    VkDevice dev = ctx.device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    bindings.push_back({0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1,
                        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    for (uint32_t b = 1; b <= kMaterialTextures; ++b)
        bindings.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                            VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    bindings.push_back({kMaterialTextures + 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1,
                        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = static_cast<uint32_t>(bindings.size());
    li.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateDescriptorSetLayout(dev, &li, nullptr, &layout));
    m_materialLayout = OwnedDescriptorSetLayout(dev, layout);

    // Every material's parameters, in material order: a draw reads its own by index
    // (lib/material.glsl), so draws of many materials go in one call.
    std::vector<MaterialUniforms> uniforms(m_scene.materials.size());
    for (size_t i = 0; i < m_scene.materials.size(); ++i) {
        const Material& m = m_scene.materials[i];
        MaterialUniforms& u = uniforms[i];
        u.baseColorOpacity = glm::vec4(m.baseColor, m.opacity);
        // w: 1 for emission relative to the exposure, its EC folded into the colour (the shaders
        // multiply by 2^(EV100 − 3): lib/exposure.glsl's rgEmissiveScale).
        u.emissive = m.emissiveEv ? glm::vec4(m.emissive * std::exp2(m.emissiveEc), 1.0f)
                                  : glm::vec4(m.emissive, 0.0f);
        u.factors = glm::vec4(m.smoothness, m.metalMask, m.reflectance, m.ao);
        u.factors2 = glm::vec4(m.normalScale, m.occlusionStrength, m.alphaCutoff,
                               static_cast<float>(m.alphaMode));
        u.diffuseColor = glm::vec4(m.diffuseColor, m.model == "two_colour" ? 1.0f : 0.0f);
        u.f0 = glm::vec4(m.f0, 0.0f);
        const std::vector<const TextureRef*> refs = slotRefs(m);
        for (uint32_t t = 0; t < kMaterialTextures; ++t) {
            const glm::mat3& x = refs[t]->transform;  // column-major: x[col][row]
            u.uvTransform[2 * t] =
                glm::vec4(x[0][0], x[1][0], x[2][0], static_cast<float>(refs[t]->texCoord));
            // w of the second row: the image's layer in its array (uploadImages).
            const auto image = imageLayer(*refs[t]);
            u.uvTransform[2 * t + 1] = glm::vec4(x[0][1], x[1][1], x[2][1],
                                                 image ? static_cast<float>(image->second) : 0.0f);
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
    }
    // The parameters twice, in uniform buffers (on lavapipe a storage buffer's loads in a fragment
    // shader skip its helper invocations, whose texture derivatives then went wrong: sparkles along
    // triangle edges): one material a window at the device's offset alignment, for the CPU's
    // draws (bound at the material: its loads uniform over the draw); and runs of
    // materialWindow() materials (a uniform block's range), each window at the alignment, for the
    // GPU's draws (bound at the run's window, read at the instance's index within it).
    const auto align =
        std::max<VkDeviceSize>(ctx.properties().limits.minUniformBufferOffsetAlignment, 1);
    auto aligned = [&](VkDeviceSize b) { return (b + align - 1) / align * align; };
    m_materialStride = static_cast<uint32_t>(aligned(sizeof(MaterialUniforms)));
    m_windowStride =
        static_cast<uint32_t>(aligned(VkDeviceSize(m_materialWindow) * sizeof(MaterialUniforms)));
    const size_t windows = (uniforms.size() + m_materialWindow - 1) / m_materialWindow;
    auto one =
        Buffer::create(ctx, "scene.materials", VkDeviceSize(m_materialStride) * uniforms.size(),
                       VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    if (!one) return std::unexpected(one.error());
    auto runs =
        Buffer::create(ctx, "scene.material_windows", VkDeviceSize(m_windowStride) * windows,
                       VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    if (!runs) return std::unexpected(runs.error());
    std::memset(runs->mapped(), 0, VkDeviceSize(m_windowStride) * windows);
    for (size_t i = 0; i < uniforms.size(); ++i) {
        std::memcpy(static_cast<uint8_t*>(one->mapped()) + i * m_materialStride, &uniforms[i],
                    sizeof(MaterialUniforms));
        std::memcpy(static_cast<uint8_t*>(runs->mapped()) +
                        (i / m_materialWindow) * m_windowStride +
                        (i % m_materialWindow) * sizeof(MaterialUniforms),
                    &uniforms[i], sizeof(MaterialUniforms));
    }
    m_materialBuffer = std::move(*one);
    m_materialWindows = std::move(*runs);

    // One descriptor set per texture set: a material, its textures, a window of materials.
    const auto count = static_cast<uint32_t>(m_textureSetSlots.size());
    VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 2 * count},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, count * kMaterialTextures}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = count;
    pi.poolSizeCount = 2;
    pi.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateDescriptorPool(dev, &pi, nullptr, &pool));
    m_pool = OwnedDescriptorPool(dev, pool);
    std::vector<VkDescriptorSetLayout> layouts(count, layout);
    m_textureSets.resize(count);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = count;
    ai.pSetLayouts = layouts.data();
    RG_VK_TRY(vkAllocateDescriptorSets(dev, &ai, m_textureSets.data()));

    for (uint32_t i = 0; i < count; ++i) {
        VkDescriptorBufferInfo one{m_materialBuffer.buffer(), 0, sizeof(MaterialUniforms)};
        VkDescriptorBufferInfo window{m_materialWindows.buffer(), 0,
                                      VkDeviceSize(m_materialWindow) * sizeof(MaterialUniforms)};
        VkDescriptorImageInfo ii[kMaterialTextures];
        VkWriteDescriptorSet writes[kMaterialTextures + 2];
        writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[0].dstSet = m_textureSets[i];
        writes[0].dstBinding = 0;
        writes[0].descriptorCount = 1;
        writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        writes[0].pBufferInfo = &one;
        writes[kMaterialTextures + 1] = writes[0];
        writes[kMaterialTextures + 1].dstBinding = kMaterialTextures + 1;
        writes[kMaterialTextures + 1].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        writes[kMaterialTextures + 1].pBufferInfo = &window;
        for (uint32_t t = 0; t < kMaterialTextures; ++t) {
            const auto [image, sampler] = m_textureSetSlots[i][t];
            VkImageView view = image >= 0 ? m_textureArrays[static_cast<size_t>(image)].view()
                                          : (t == 2 ? m_flatNormal.view() : m_white.view());
            VkSampler s = sampler >= 0 ? m_samplers[static_cast<size_t>(sampler)].get()
                                       : m_defaultSampler.get();
            ii[t] = {s, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            writes[t + 1] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[t + 1].dstSet = m_textureSets[i];
            writes[t + 1].dstBinding = static_cast<uint32_t>(t + 1);
            writes[t + 1].descriptorCount = 1;
            writes[t + 1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[t + 1].pImageInfo = &ii[t];
        }
        vkUpdateDescriptorSets(dev, kMaterialTextures + 2, writes, 0, nullptr);
    }
    return {};
}

void GpuScene::bindMaterial(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t material) const {
    bindTextureSet(cmd, layout, m_materialTextureSet[material], material);
}

void GpuScene::bindTextureSet(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t set,
                              uint32_t material) const {
    VkDescriptorSet ds = m_textureSets[set];
    // Binding 0's, then binding 9's (dynamic offsets go in binding order).
    const uint32_t offsets[2] = {material * m_materialStride,
                                 material / m_materialWindow * m_windowStride};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &ds, 2, offsets);
}

}  // namespace rg::passes
