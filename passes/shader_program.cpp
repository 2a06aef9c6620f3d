#include "shader_program.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include "core/check.h"
#include "gpu_scene.h"

namespace rg::passes {

using namespace rg::gpu;

std::string passPrefix(const PassDesc& desc) {
    return (desc.origin.empty() ? "" : desc.origin + ": ") + "pass '" + desc.name + "': ";
}

VkShaderStageFlags toVkStageFlags(uint32_t mask) {
    VkShaderStageFlags f = 0;
    if (mask & stageBit(ShaderStage::Vertex)) f |= VK_SHADER_STAGE_VERTEX_BIT;
    if (mask & stageBit(ShaderStage::Fragment)) f |= VK_SHADER_STAGE_FRAGMENT_BIT;
    if (mask & stageBit(ShaderStage::Compute)) f |= VK_SHADER_STAGE_COMPUTE_BIT;
    return f;
}

namespace {

// The most lights that reach every pixel the standard light loop unrolls (RG_SCENE_GLOBAL_LIGHTS);
// a scene with more keeps one loop over the whole list.
constexpr uint32_t kMaxUnrolledGlobalLights = 4;

VkDescriptorType toVkDescriptor(DescriptorType t) {
    switch (t) {
        case DescriptorType::CombinedImageSampler:
            return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        case DescriptorType::SampledImage:
            return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        case DescriptorType::Sampler:
            return VK_DESCRIPTOR_TYPE_SAMPLER;
        case DescriptorType::StorageImage:
            return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        case DescriptorType::UniformBuffer:
            return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        case DescriptorType::StorageBuffer:
            return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        case DescriptorType::UniformTexelBuffer:
            return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

// The scene's bindings (passes/gpu_scene.h bindingBuffer, and its environment), by block name
// and type: bound whatever the pass declares.
bool isSceneBinding(const ReflectedBinding& b) {
    static const std::pair<const char*, DescriptorType> kScene[] = {
        {"Camera", DescriptorType::UniformBuffer},
        {"Lights", DescriptorType::StorageBuffer},
        {"LightsWindow", DescriptorType::UniformBuffer},
        {"LightTables", DescriptorType::StorageBuffer},
        {"GlobalLights", DescriptorType::StorageBuffer},
        {"Decals", DescriptorType::StorageBuffer},
        {"ShadowViews", DescriptorType::StorageBuffer},
        {"SceneDraws", DescriptorType::StorageBuffer},
        {"SceneTransforms", DescriptorType::StorageBuffer},
        {"SceneInstances", DescriptorType::StorageBuffer},
        {"SceneBvh", DescriptorType::StorageBuffer},
        {"Probes", DescriptorType::UniformBuffer},
        {"SceneEnvironmentCdf", DescriptorType::StorageBuffer},
        {"SceneEnvironment", DescriptorType::CombinedImageSampler},
        {"SceneLightmap", DescriptorType::CombinedImageSampler},
        {"SceneLightTexels", DescriptorType::UniformTexelBuffer}};
    return std::any_of(std::begin(kScene), std::end(kScene),
                       [&](const auto& e) { return b.name == e.first && b.type == e.second; });
}

bool isParamsBlock(const ReflectedBinding& b) {
    return b.type == DescriptorType::UniformBuffer && b.name == "Params";
}

// Which usages may stand behind a descriptor type.
bool usageFits(DescriptorType t, Usage u) {
    switch (t) {
        case DescriptorType::CombinedImageSampler:
        case DescriptorType::SampledImage:
            return u == Usage::Sampled;
        case DescriptorType::StorageImage:
        case DescriptorType::StorageBuffer:
            return u == Usage::StorageRead || u == Usage::StorageWrite ||
                   u == Usage::StorageReadWrite;
        case DescriptorType::UniformBuffer:
            return u == Usage::UniformRead;
        case DescriptorType::Sampler:
        case DescriptorType::UniformTexelBuffer:  // the scene's lights only
            return false;
    }
    return false;
}

std::string glslName(std::string s) {
    std::replace(s.begin(), s.end(), '.', '_');
    return s;
}

Result<OwnedSampler> makeSampler(VkDevice dev, VkFilter filter) {
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = filter;
    si.mipmapMode =
        filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler s = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateSampler(dev, &si, nullptr, &s));
    return OwnedSampler(dev, s);
}

}  // namespace

Result<void> ShaderProgram::build(PassSetup& setup, std::vector<ShaderRequest> stages,
                                  std::map<uint32_t, VkDescriptorSetLayout> externalSets,
                                  uint32_t mipVariants) {
    m_external = std::move(externalSets);
    m_variants = std::max(1u, mipVariants);
    const PassDesc& desc = setup.desc;
    // Defines from params.defines = { NAME = value, ... } (numbers, booleans or strings).
    std::vector<std::pair<std::string, std::string>> defines;
    for (const auto& [name, v] : desc.params["defines"].asTable()) {
        std::string value;
        if (v.isBool())
            value = v.asBool() ? "1" : "0";
        else if (v.isNumber()) {
            double d = v.asNumber();
            value = d == static_cast<double>(static_cast<long long>(d))
                        ? std::to_string(static_cast<long long>(d))
                        : std::to_string(d);
        } else if (v.isString())
            value = v.asString();
        else
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + "params.defines." + name +
                            ": expected a number, boolean or string, got " + v.typeName());
        defines.emplace_back(name, value);
    }
    // The light types of the scene (lib/scene.glsl RG_SCENE_LIGHT_TYPES): the light loop keeps
    // only their branches. A new scene is a new build, so the shaders follow it.
    // RG_SCENE_IES: whether any light has an IES profile (without, no profile lookup at all).
    // Likewise RG_SCENE_SHADOWED_LIGHTS when a local light casts shadows (lib/shadows.glsl: the
    // light loop looks its shadow up only then, with a blocker search only for lights with a size).
    if (setup.scene) {
        uint32_t types = 0;
        int shadowed = 0;  // 1: only punctual lights cast shadows; 2: a light with a size does
        bool ies = false;
        // The lights that reach every pixel (the sun, lights without a range: light_culling.comp's
        // global list, in scene order) with their types, when there are a few: the standard light
        // loop unrolls them, each read at a constant index and evaluated with only its type's
        // branch, then loops over the tile's lights with only the types of ranged lights
        // (RG_SCENE_TILE_LIGHT_TYPES). On lavapipe a load at a constant index is one load where a
        // per-pixel index is one per pixel (materials/standard_shading.glsl).
        //
        // A scene of at most that many lights whose ranged lights are all large (a range of at
        // least a quarter of the scene's diagonal: they reach much of any view) unrolls its ranged
        // lights too and compiles no tile loop (RG_SCENE_TILE_LIGHT_TYPES 0): the window ends each
        // at its range exactly, so a pixel beyond it adds 0 as the tile's list would have left it
        // out, and a light read at a constant index everywhere cost less than the same light
        // through the tiles' lists over most of the screen (the default scene's lamp: ~4.5 against
        // ~12.6 ms of lighting_standard at 1280×720 on lavapipe).
        std::string globalIndices, globalTypes;
        uint32_t globalCount = 0, tileTypes = 0;
        const auto& lights = sceneOf(setup)->scene().lights;
        const float diagonal =
            glm::length(sceneOf(setup)->scene().boundsMax - sceneOf(setup)->scene().boundsMin);
        const bool unrollAll = lights.size() <= kMaxUnrolledGlobalLights &&
                               std::all_of(lights.begin(), lights.end(), [&](const Light& l) {
                                   return l.type == LightType::Directional || !(l.range > 0.0f) ||
                                          l.range >= 0.25f * diagonal;
                               });
        for (size_t i = 0; i < lights.size(); ++i) {
            const Light& l = lights[i];
            const uint32_t type = static_cast<uint32_t>(l.type);
            types |= 1u << type;
            ies = ies || !l.ies.empty();
            if (l.castShadows)
                shadowed = std::max(
                    shadowed, l.type == LightType::Point || l.type == LightType::Spot ? 1 : 2);
            if (unrollAll || l.type == LightType::Directional || !(l.range > 0.0f)) {
                globalIndices += (globalCount ? "," : "") + std::to_string(i) + "u";
                globalTypes += (globalCount ? "," : "") + std::to_string(type) + "u";
                ++globalCount;
            } else {
                tileTypes |= 1u << type;
            }
        }
        defines.emplace_back("RG_SCENE_LIGHT_TYPES", std::to_string(types));
        if (globalCount >= 1 && globalCount <= kMaxUnrolledGlobalLights) {
            defines.emplace_back("RG_SCENE_GLOBAL_LIGHTS", std::to_string(globalCount));
            defines.emplace_back("RG_SCENE_GLOBAL_LIGHT_INDICES", globalIndices);
            defines.emplace_back("RG_SCENE_GLOBAL_LIGHT_TYPE_LIST", globalTypes);
            defines.emplace_back("RG_SCENE_TILE_LIGHT_TYPES", std::to_string(tileTypes));
        }
        defines.emplace_back("RG_SCENE_IES", ies ? "1" : "0");
        // RG_LIGHT_TEXELS: the light loops read the lights through a texel buffer of the same
        // memory (lib/scene.glsl rgLight) where the device's texel buffers hold them.
        if (sceneOf(setup)->lightTexelView(0) != VK_NULL_HANDLE)
            defines.emplace_back("RG_LIGHT_TEXELS", "1");
        // RG_SCENE_PROBES: how many local light probes the scene has (lib/ibl.glsl's composition
        // loops that many times at most: none compiles no loop at all).
        defines.emplace_back(
            "RG_SCENE_PROBES",
            std::to_string(std::min(sceneOf(setup)->scene().probes.size(), kMaxProbes)));
        // RG_SCENE_PROBE_SHAPES: which shapes its probes have (1 sphere, 2 box, 3 both): a scene of
        // one shape compiles only that shape's influence and parallax (lib/probes.glsl).
        int probeShapes = 0;
        for (const Probe& probe : sceneOf(setup)->scene().probes) probeShapes |= probe.box ? 2 : 1;
        if (probeShapes) defines.emplace_back("RG_SCENE_PROBE_SHAPES", std::to_string(probeShapes));
        if (shadowed) defines.emplace_back("RG_SCENE_SHADOWED_LIGHTS", std::to_string(shadowed));
        // RG_SCENE_LIGHTMAP: the scene has a baked SG lightmap (lib/lightmap.glsl): the G-buffer
        // pass adds its radiosity, the distant probe's diffuse light is left out (the lightmap holds it).
        if (const Lightmap* lm = sceneOf(setup)->scene().bakedLightmap.get()) {
            auto number = [](double v) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%.9g", v);
                return std::string(buf);
            };
            defines.emplace_back("RG_SCENE_LIGHTMAP", "1");
            defines.emplace_back("RG_LIGHTMAP_LOBES", std::to_string(lm->axes.size()));
            defines.emplace_back("RG_LIGHTMAP_SHARPNESS", number(lm->sharpness));
            std::string unit = "float[](";
            for (size_t k = 0; k < lm->unit.size(); ++k)
                unit += (k ? ", " : "") + number(lm->unit[k]);
            defines.emplace_back("RG_LIGHTMAP_UNIT", unit + ")");
        }
    }

    for (auto& req : stages) {
        req.passName = desc.name;
        req.defines.insert(req.defines.end(), defines.begin(), defines.end());
        // A fragment shader may read its 2×2 quad's other pixels by a swap
        // (gpu::Context::fragmentQuadOps).
        if (req.stage == ShaderStage::Fragment && setup.gpu.fragmentQuadOps())
            req.defines.emplace_back("RG_QUAD_OPS", "1");
        auto mod = setup.shaders.compile(req);
        if (!mod) {
            Error e = mod.error();
            if (!desc.origin.empty()) e.message = desc.origin + ": " + e.message;
            return std::unexpected(e);
        }
        // Floor mode (PassSetup::floor): the same outputs or work-group size, no work.
        if (setup.floor && (mod->reflection.stageMask &
                            (stageBit(ShaderStage::Fragment) | stageBit(ShaderStage::Compute)))) {
            const ShaderReflection& r = mod->reflection;
            ShaderRequest floor;
            floor.passName = desc.name;
            std::ostringstream src;
            src << "#version 460\n// rgraph bench --floors: '" << desc.name << "' doing nothing\n";
            if (r.stageMask & stageBit(ShaderStage::Compute)) {
                src << "layout(local_size_x = " << r.localSize[0]
                    << ", local_size_y = " << r.localSize[1]
                    << ", local_size_z = " << r.localSize[2] << ") in;\nvoid main() {}\n";
                floor.virtualName = "floor.comp";
                floor.stage = ShaderStage::Compute;
            } else {
                std::ostringstream body;
                for (uint32_t loc : r.colorOutputs) {
                    const bool integer = std::find(r.integerOutputs.begin(), r.integerOutputs.end(),
                                                   loc) != r.integerOutputs.end();
                    src << "layout(location = " << loc << ") out " << (integer ? "uvec4" : "vec4")
                        << " o" << loc << ";\n";
                    body << "    o" << loc << " = " << (integer ? "uvec4(0u)" : "vec4(0.0)")
                         << ";\n";
                }
                src << "void main() {\n" << body.str() << "}\n";
                floor.virtualName = "floor.frag";
                floor.stage = ShaderStage::Fragment;
            }
            floor.source = src.str();
            mod = setup.shaders.compile(floor);
            if (!mod) return std::unexpected(mod.error());
        }
        for (const auto& f : mod->files)
            if (std::find(m_files.begin(), m_files.end(), f) == m_files.end()) m_files.push_back(f);
        if (m_modules.empty())
            m_reflection = mod->reflection;
        else {
            auto merged = mergeReflections(m_reflection, mod->reflection, desc.name);
            if (!merged) return std::unexpected(merged.error());
            m_reflection = *merged;
        }
        m_modules.push_back(std::move(*mod));
    }

    VkDevice dev = setup.gpu.device();
    for (const auto& mod : m_modules) {
        VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        ci.codeSize = mod.spirv.size() * sizeof(uint32_t);
        ci.pCode = mod.spirv.data();
        VkShaderModule sm = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateShaderModule(dev, &ci, nullptr, &sm));
        m_vkModules.emplace_back(dev, sm);
    }
    for (size_t i = 0; i < m_modules.size(); ++i) {
        VkPipelineShaderStageCreateInfo si{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        si.stage = static_cast<VkShaderStageFlagBits>(toVkStageFlags(stageBit(m_modules[i].stage)));
        si.module = m_vkModules[i].get();
        si.pName = m_modules[i].entry.c_str();
        m_stageInfos.push_back(si);
    }
    if (auto r = createLayouts(setup); !r) return r;
    return writeDescriptors(setup);
}

Result<void> ShaderProgram::createLayouts(PassSetup& setup) {
    VkDevice dev = setup.gpu.device();
    uint32_t setCount = 0;
    for (const auto& b : m_reflection.bindings) setCount = std::max(setCount, b.set + 1);
    for (const auto& [set, _] : m_external) setCount = std::max(setCount, set + 1);
    std::vector<VkDescriptorSetLayout> raw;
    for (uint32_t s = 0; s < setCount; ++s) {
        if (auto ext = m_external.find(s); ext != m_external.end()) {
            m_setLayouts.emplace_back();
            raw.push_back(ext->second);
            continue;
        }
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        for (const auto& b : m_reflection.bindings) {
            if (b.set != s) continue;
            VkDescriptorSetLayoutBinding lb{};
            lb.binding = b.binding;
            lb.descriptorType = toVkDescriptor(b.type);
            lb.descriptorCount = std::max(1u, b.count);
            lb.stageFlags = toVkStageFlags(b.stageMask);
            bindings.push_back(lb);
        }
        VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        li.bindingCount = static_cast<uint32_t>(bindings.size());
        li.pBindings = bindings.data();
        VkDescriptorSetLayout layout = VK_NULL_HANDLE;
        RG_VK_TRY(vkCreateDescriptorSetLayout(dev, &li, nullptr, &layout));
        m_setLayouts.emplace_back(dev, layout);
        raw.push_back(layout);
    }
    VkPushConstantRange range{};
    for (const auto& m : m_modules) m_pushStages |= toVkStageFlags(stageBit(m.stage));
    range.stageFlags = m_pushStages;
    range.size = m_reflection.pushConstantSize;
    VkPipelineLayoutCreateInfo pi{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pi.setLayoutCount = static_cast<uint32_t>(raw.size());
    pi.pSetLayouts = raw.data();
    pi.pushConstantRangeCount = range.size ? 1 : 0;
    pi.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreatePipelineLayout(dev, &pi, nullptr, &layout));
    m_layout = OwnedPipelineLayout(dev, layout);
    return {};
}

Result<void> ShaderProgram::writeDescriptors(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    VkDevice dev = setup.gpu.device();
    const uint32_t slots =
        setup.gpu.framesInFlight() * m_variants;  // descriptor sets per set index
    if (m_setLayouts.empty()) return {};

    auto lin = makeSampler(dev, VK_FILTER_LINEAR);
    if (!lin) return std::unexpected(lin.error());
    m_linear = std::move(*lin);
    auto near = makeSampler(dev, VK_FILTER_NEAREST);
    if (!near) return std::unexpected(near.error());
    m_nearest = std::move(*near);

    std::map<VkDescriptorType, uint32_t> counts;
    for (const auto& b : m_reflection.bindings)
        if (!m_external.count(b.set))
            counts[toVkDescriptor(b.type)] += std::max(1u, b.count) * slots;
    if (counts.empty()) counts[VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER] = 1;  // a pool needs one size
    std::vector<VkDescriptorPoolSize> sizes;
    for (auto [t, n] : counts) sizes.push_back({t, n});
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = static_cast<uint32_t>(m_setLayouts.size()) * slots;
    pi.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pi.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateDescriptorPool(dev, &pi, nullptr, &pool));
    m_pool = OwnedDescriptorPool(dev, pool);

    for (const auto& b : m_reflection.bindings)
        if (isParamsBlock(b)) m_params = &b;
    if (m_params) {
        for (uint32_t s = 0; s < setup.gpu.framesInFlight(); ++s) {
            auto buf =
                Buffer::create(setup.gpu, desc.name + ".Params", std::max(16u, m_params->blockSize),
                               VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
            if (!buf) return std::unexpected(buf.error());
            m_paramBuffers.push_back(std::move(*buf));
        }
    }

    // Resolve every binding to a resource of this pass before writing anything.
    struct Bound {
        const ReflectedBinding* binding;
        const PhysicalResource* resource;
        Usage usage;
        bool previousMip =
            false;  // `<image>_previous`: the mip before the one a per-mip variant writes
        bool stencil = false;  // the stencil aspect (as = "stencil")
    };
    std::vector<Bound> bound;
    const Value& bindMap = desc.params["bind"];
    std::vector<const ReflectedBinding*> sceneBindings;
    for (const auto& b : m_reflection.bindings) {
        // A texel buffer is bound only for the scene's lights, in any set (another set's would
        // be missing from the layouts the scene provides).
        if (b.type == DescriptorType::UniformTexelBuffer && !isSceneBinding(b))
            return fail(ErrorCode::Unsupported,
                        passPrefix(desc) + "texel buffer '" + b.name +
                            "' is not supported (use a storage buffer; a samplerBuffer is read "
                            "only from the scene's lights, SceneLightTexels)");
        if (isParamsBlock(b) || m_external.count(b.set)) continue;
        // The scene's camera, lights and the rest, bound whatever the pass declares.
        if (isSceneBinding(b)) {
            if (!setup.scene)
                return fail(ErrorCode::InvalidInput,
                            passPrefix(desc) + "shader binding '" + b.name +
                                "' is the scene's, but no scene is loaded (give --scene)");
            if (b.type == DescriptorType::UniformTexelBuffer &&
                sceneOf(setup)->lightTexelView(0) == VK_NULL_HANDLE)
                return fail(ErrorCode::Unsupported,
                            passPrefix(desc) + "shader binding '" + b.name +
                                "': the device's texel buffers cannot hold the scene's lights "
                                "(read them with rgLight, lib/scene.glsl)");
            if (b.type != DescriptorType::CombinedImageSampler &&
                b.type != DescriptorType::UniformTexelBuffer) {
                if (auto buffer = sceneOf(setup)->makeBindingBuffer(b.name, 0); !buffer)
                    return fail(ErrorCode::Device, passPrefix(desc) +
                                                       "could not make the scene's '" + b.name +
                                                       "' buffer: " + buffer.error().message);
            }
            // A pass that traces the scene's triangles every frame (the reference mode) starts its
            // rays on the G-buffer's surfaces: those must be the traced ones, the full meshes.
            if (b.name == "SceneBvh" && desc.params["cadence"].asString() != "once")
                sceneOf(setup)->drawFullMeshes();
            sceneBindings.push_back(&b);
            continue;
        }
        // A sampler named `<image>_previous` for an image the pass writes as storage: in
        // per-mip variant m, mip m − 1 of it (a mip chain built from itself, e.g. a depth pyramid).
        // `bind` may name the image for `<name>` (e.g. bind = { target = "env_source" }).
        if (b.type == DescriptorType::CombinedImageSampler && b.name.size() > 9 &&
            b.name.ends_with("_previous")) {
            const std::string base = b.name.substr(0, b.name.size() - 9);
            const std::string named = bindMap[base].isString() ? bindMap[base].asString() : "";
            const Access* chain = nullptr;
            for (const auto& a : desc.accesses)
                if ((named.empty() ? glslName(a.resource) == base : a.resource == named) &&
                    (a.usage == Usage::StorageWrite || a.usage == Usage::StorageReadWrite))
                    chain = &a;
            if (chain) {
                bound.push_back({&b, setup.resources.find(chain->resource), chain->usage, true});
                continue;
            }
        }
        std::string want = bindMap[b.name].isString() ? bindMap[b.name].asString() : "";
        const Access* access = nullptr;
        for (const auto& a : desc.accesses) {
            // A stencil read (as = "stencil") binds `<resource>_stencil` only.
            const bool named = a.stencil      ? glslName(a.resource) + "_stencil" == b.name
                               : want.empty() ? glslName(a.resource) == b.name
                                              : a.resource == want;
            if (named && (!access || usageFits(b.type, a.usage))) access = &a;
        }
        std::string where = "shader binding '" + b.name + "' (set " + std::to_string(b.set) +
                            ", binding " + std::to_string(b.binding) + ", " + toString(b.type) +
                            ")";
        if (!access)
            return fail(
                ErrorCode::InvalidInput,
                passPrefix(desc) + where + " matches no resource the pass reads or writes" +
                    (b.name.ends_with("_stencil")
                         ? "; a stencil is read with { \"" + b.name.substr(0, b.name.size() - 8) +
                               "\", as = \"stencil\" } in reads"
                     : want.empty() ? "; list it in reads/writes or map it with bind = { " +
                                          b.name + " = \"resource\" }"
                                    : " (params.bind names '" + want + "')"));
        if (!usageFits(b.type, access->usage))
            return fail(ErrorCode::InvalidInput,
                        passPrefix(desc) + where + " is bound to '" + access->resource +
                            "', which the pass declares as " + usageName(access->usage));
        const PhysicalResource* phys = setup.resources.find(access->resource);
        RG_CHECK(phys) << "resource '" << access->resource
                       << "' of a kept pass has no physical resource";
        bool wantImage =
            b.type != DescriptorType::UniformBuffer && b.type != DescriptorType::StorageBuffer;
        if (wantImage != (phys->image != nullptr))
            return fail(ErrorCode::InvalidInput, passPrefix(desc) + where + " is bound to '" +
                                                     access->resource + "', which is a " +
                                                     (phys->image ? "texture" : "buffer"));
        bound.push_back({&b, phys, access->usage, false, access->stencil});
    }

    m_sets.resize(slots);
    for (uint32_t s = 0; s < slots; ++s) {
        m_sets[s].assign(m_setLayouts.size(), VK_NULL_HANDLE);
        for (size_t set = 0; set < m_setLayouts.size(); ++set) {
            if (!m_setLayouts[set]) continue;  // external
            VkDescriptorSetLayout layout = m_setLayouts[set].get();
            VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
            ai.descriptorPool = m_pool.get();
            ai.descriptorSetCount = 1;
            ai.pSetLayouts = &layout;
            RG_VK_TRY(vkAllocateDescriptorSets(dev, &ai, &m_sets[s][set]));
        }

        std::vector<VkWriteDescriptorSet> writes;
        std::vector<VkDescriptorImageInfo> images;
        std::vector<VkDescriptorBufferInfo> buffers;
        images.reserve(bound.size() + sceneBindings.size());
        buffers.reserve(bound.size() + sceneBindings.size() + 1);
        std::vector<VkBufferView> texelViews;
        texelViews.reserve(sceneBindings.size());
        for (const auto& bd : bound) {
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = m_sets[s][bd.binding->set];
            w.dstBinding = bd.binding->binding;
            w.descriptorCount = 1;
            w.descriptorType = toVkDescriptor(bd.binding->type);
            if (bd.resource->image) {
                const gpu::Image& img = *bd.resource->image;
                const FormatInfo& fi = formatInfo(img.desc().format);
                bool storage = bd.binding->type == DescriptorType::StorageImage;
                bool nearest =
                    fi.integer || fi.depth || desc.params["filter"].asString() == "nearest";
                // A depth buffer the pass also attaches read-only is sampled in that layout.
                const bool depthAttached =
                    std::any_of(desc.accesses.begin(), desc.accesses.end(), [&](const Access& a) {
                        return a.usage == Usage::DepthStencilRead &&
                               setup.resources.find(a.resource) == bd.resource;
                    });
                const uint32_t mip = std::min(s % m_variants, img.desc().mips - 1);
                images.push_back({nearest ? m_nearest.get() : m_linear.get(),
                                  bd.previousMip ? img.mipView(mip > 0 ? mip - 1 : 0)
                                  : storage      ? img.mipView(mip)
                                  : bd.stencil   ? img.stencilView()
                                                 : img.view(),
                                  storage || bd.previousMip ? VK_IMAGE_LAYOUT_GENERAL
                                  : depthAttached ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                  : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
                w.pImageInfo = &images.back();
            } else {
                buffers.push_back({bd.resource->buffer->buffer(), 0, VK_WHOLE_SIZE});
                w.pBufferInfo = &buffers.back();
            }
            writes.push_back(w);
        }
        for (const ReflectedBinding* b : sceneBindings) {
            if (b->type ==
                DescriptorType::CombinedImageSampler) {  // SceneEnvironment, SceneLightmap
                if (b->name == "SceneLightmap")
                    images.push_back({m_linear.get(), sceneOf(setup)->lightmapView(),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
                else
                    images.push_back({sceneOf(setup)->environmentSampler(),
                                      sceneOf(setup)->environmentView(),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
                VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                w.dstSet = m_sets[s][b->set];
                w.dstBinding = b->binding;
                w.descriptorCount = 1;
                w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
                w.pImageInfo = &images.back();
                writes.push_back(w);
                continue;
            }
            if (b->type == DescriptorType::UniformTexelBuffer) {  // SceneLightTexels
                VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                w.dstSet = m_sets[s][b->set];
                w.dstBinding = b->binding;
                w.descriptorCount = 1;
                w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
                texelViews.push_back(sceneOf(setup)->lightTexelView(s / m_variants));
                w.pTexelBufferView = &texelViews.back();
                writes.push_back(w);
                continue;
            }
            buffers.push_back({sceneOf(setup)->bindingBuffer(b->name, s / m_variants), 0,
                               GpuScene::bindingRange(b->name)});
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = m_sets[s][b->set];
            w.dstBinding = b->binding;
            w.descriptorCount = 1;
            w.descriptorType = toVkDescriptor(b->type);
            w.pBufferInfo = &buffers.back();
            writes.push_back(w);
        }
        if (m_params) {
            buffers.push_back({m_paramBuffers[s / m_variants].buffer(), 0, VK_WHOLE_SIZE});
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = m_sets[s][m_params->set];
            w.dstBinding = m_params->binding;
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w.pBufferInfo = &buffers.back();
            writes.push_back(w);
        }
        vkUpdateDescriptorSets(dev, static_cast<uint32_t>(writes.size()), writes.data(), 0,
                               nullptr);
    }
    return {};
}

namespace {

// Writes a number or a list of numbers as floats into [offset, offset+size).
void putFloats(std::vector<uint8_t>& bytes, uint32_t offset, uint32_t size, const Value& v) {
    std::vector<float> f;
    if (v.isNumber())
        f.push_back(static_cast<float>(v.asNumber()));
    else if (v.isBool())
        f.push_back(v.asBool() ? 1.0f : 0.0f);
    else
        for (const auto& e : v.asList()) f.push_back(static_cast<float>(e.asNumber()));
    size_t n = std::min<size_t>(f.size(), size / sizeof(float));
    if (n > 0 && offset + n * sizeof(float) <= bytes.size())
        std::memcpy(bytes.data() + offset, f.data(), n * sizeof(float));
}

}  // namespace

void ShaderProgram::writeUniforms(const Value& uniforms, uint32_t slot) {
    std::vector<uint8_t> bytes(m_params->blockSize, 0);
    for (const auto& m : m_params->members) putFloats(bytes, m.offset, m.size, uniforms[m.name]);
    std::memcpy(m_paramBuffers[slot].mapped(), bytes.data(), bytes.size());
}

void ShaderProgram::bind(RecordContext& rc, VkPipelineBindPoint point, uint32_t mipVariant) {
    const uint32_t slot = rc.frame.slot;
    if (m_params && mipVariant == 0) writeUniforms(rc.desc.params["uniforms"], slot);
    const uint32_t index = slot * m_variants + std::min(mipVariant, m_variants - 1);
    if (!m_sets.empty())
        for (size_t set = 0; set < m_sets[index].size(); ++set)
            if (m_sets[index][set] != VK_NULL_HANDLE)
                vkCmdBindDescriptorSets(rc.cmd, point, m_layout.get(), static_cast<uint32_t>(set),
                                        1, &m_sets[index][set], 0, nullptr);
    if (m_reflection.pushConstantSize) {
        std::vector<uint8_t> bytes(m_reflection.pushConstantSize, 0);
        const Value& constants = rc.desc.params["constants"];
        for (const auto& m : m_reflection.pushConstants) {
            if (m.name == "rg_outputSize")
                putFloats(bytes, m.offset, m.size,
                          Value(Value::List{Value(static_cast<double>(rc.plan.outputWidth)),
                                            Value(static_cast<double>(rc.plan.outputHeight))}));
            else if (m.name == "rg_time")
                putFloats(bytes, m.offset, m.size, Value(rc.frame.timeSeconds));
            else if (m.name == "rg_frame")
                putFloats(bytes, m.offset, m.size, Value(static_cast<double>(rc.frame.index)));
            else if (m.name == "rg_mip")
                putFloats(bytes, m.offset, m.size, Value(static_cast<double>(mipVariant)));
            else if (m.name == "rg_mipCount")
                putFloats(bytes, m.offset, m.size, Value(static_cast<double>(m_variants)));
            else
                putFloats(bytes, m.offset, m.size, constants[m.name]);
        }
        vkCmdPushConstants(rc.cmd, m_layout.get(), m_pushStages, 0,
                           static_cast<uint32_t>(bytes.size()), bytes.data());
    }
}

}  // namespace rg::passes
