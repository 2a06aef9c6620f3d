#include "shader/reflection.h"

#include <spirv_cross/spirv_cross_c.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <tuple>

namespace rg {

namespace {

constexpr uint32_t kSpirvMagic = 0x07230203u;

struct ContextDeleter {
    void operator()(spvc_context_s* c) const { spvc_context_destroy(c); }
};
using ContextPtr = std::unique_ptr<spvc_context_s, ContextDeleter>;

// The GLSL layout qualifier of a storage image format; "" for Unknown.
const char* imageFormatName(SpvImageFormat f) {
    switch (f) {
        case SpvImageFormatRgba32f:
            return "rgba32f";
        case SpvImageFormatRgba16f:
            return "rgba16f";
        case SpvImageFormatR32f:
            return "r32f";
        case SpvImageFormatRgba8:
            return "rgba8";
        case SpvImageFormatRgba8Snorm:
            return "rgba8_snorm";
        case SpvImageFormatRg32f:
            return "rg32f";
        case SpvImageFormatRg16f:
            return "rg16f";
        case SpvImageFormatR11fG11fB10f:
            return "r11f_g11f_b10f";
        case SpvImageFormatR16f:
            return "r16f";
        case SpvImageFormatRgba16:
            return "rgba16";
        case SpvImageFormatRgb10A2:
            return "rgb10_a2";
        case SpvImageFormatRg16:
            return "rg16";
        case SpvImageFormatRg8:
            return "rg8";
        case SpvImageFormatR16:
            return "r16";
        case SpvImageFormatR8:
            return "r8";
        case SpvImageFormatRgba16Snorm:
            return "rgba16_snorm";
        case SpvImageFormatRg16Snorm:
            return "rg16_snorm";
        case SpvImageFormatRg8Snorm:
            return "rg8_snorm";
        case SpvImageFormatR16Snorm:
            return "r16_snorm";
        case SpvImageFormatR8Snorm:
            return "r8_snorm";
        case SpvImageFormatRgba32i:
            return "rgba32i";
        case SpvImageFormatRgba16i:
            return "rgba16i";
        case SpvImageFormatRgba8i:
            return "rgba8i";
        case SpvImageFormatR32i:
            return "r32i";
        case SpvImageFormatRg32i:
            return "rg32i";
        case SpvImageFormatRg16i:
            return "rg16i";
        case SpvImageFormatRg8i:
            return "rg8i";
        case SpvImageFormatR16i:
            return "r16i";
        case SpvImageFormatR8i:
            return "r8i";
        case SpvImageFormatRgba32ui:
            return "rgba32ui";
        case SpvImageFormatRgba16ui:
            return "rgba16ui";
        case SpvImageFormatRgba8ui:
            return "rgba8ui";
        case SpvImageFormatR32ui:
            return "r32ui";
        case SpvImageFormatRgb10a2ui:
            return "rgb10_a2ui";
        case SpvImageFormatRg32ui:
            return "rg32ui";
        case SpvImageFormatRg16ui:
            return "rg16ui";
        case SpvImageFormatRg8ui:
            return "rg8ui";
        case SpvImageFormatR16ui:
            return "r16ui";
        case SpvImageFormatR8ui:
            return "r8ui";
        case SpvImageFormatR64ui:
            return "r64ui";
        case SpvImageFormatR64i:
            return "r64i";
        default:
            return "";
    }
}

// "vertex", "vertex+fragment", ...
std::string stageNames(uint32_t mask) {
    std::string s;
    for (ShaderStage st : {ShaderStage::Vertex, ShaderStage::Fragment, ShaderStage::Compute}) {
        if (!(mask & stageBit(st))) continue;
        if (!s.empty()) s += '+';
        s += toString(st);
    }
    return s.empty() ? std::string("no") : s;
}

std::string passPrefix(std::string_view passName) {
    return passName.empty() ? std::string() : "pass '" + std::string(passName) + "': ";
}

// Reads one SPIR-V module through SPIRV-Cross's reflection-only backend.
class Reflector {
public:
    Reflector(spvc_context ctx, spvc_compiler compiler) : m_ctx(ctx), m_compiler(compiler) {}

    Result<ShaderReflection> run() {
        const spvc_entry_point* entries = nullptr;
        size_t entryCount = 0;
        if (spvc_compiler_get_entry_points(m_compiler, &entries, &entryCount) != SPVC_SUCCESS ||
            entryCount != 1)
            return fail(ErrorCode::InvalidInput, "SPIR-V module has " + std::to_string(entryCount) +
                                                     " entry points, expected exactly one");
        ShaderStage stage;
        switch (entries[0].execution_model) {
            case SpvExecutionModelVertex:
                stage = ShaderStage::Vertex;
                break;
            case SpvExecutionModelFragment:
                stage = ShaderStage::Fragment;
                break;
            case SpvExecutionModelGLCompute:
                stage = ShaderStage::Compute;
                break;
            default:
                return fail(ErrorCode::Unsupported,
                            "SPIR-V entry point '" + std::string(entries[0].name) +
                                "' is not a vertex, fragment or compute shader");
        }
        m_out.stageMask = stageBit(stage);

        spvc_resources resources = nullptr;
        if (spvc_compiler_create_shader_resources(m_compiler, &resources) != SPVC_SUCCESS)
            return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());

        struct Kind {
            spvc_resource_type type;
            std::optional<DescriptorType> descriptor;  // nullopt: no DescriptorType for it
            const char* what;
        };
        const Kind kinds[] = {
            {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, DescriptorType::UniformBuffer, "uniform buffer"},
            {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, DescriptorType::StorageBuffer, "storage buffer"},
            {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, DescriptorType::CombinedImageSampler, "sampler"},
            {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, DescriptorType::SampledImage, "texture"},
            {SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS, DescriptorType::Sampler, "sampler"},
            {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, DescriptorType::StorageImage, "image"},
            {SPVC_RESOURCE_TYPE_SUBPASS_INPUT, std::nullopt, "subpass input"},
            {SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE, std::nullopt, "acceleration structure"},
            {SPVC_RESOURCE_TYPE_ATOMIC_COUNTER, std::nullopt, "atomic counter"},
        };
        for (const Kind& kind : kinds) {
            const spvc_reflected_resource* list = nullptr;
            size_t count = 0;
            if (spvc_resources_get_resource_list_for_type(resources, kind.type, &list, &count) !=
                SPVC_SUCCESS)
                return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());
            for (size_t i = 0; i < count; ++i) {
                if (!kind.descriptor)
                    return fail(ErrorCode::Unsupported,
                                std::string(kind.what) + " '" + list[i].name +
                                    "' is not supported (rgraph binds images, samplers and "
                                    "uniform/storage buffers)");
                auto b = binding(list[i], *kind.descriptor);
                if (!b) return std::unexpected(b.error());
                if (auto added = addBinding(m_out.bindings, std::move(*b), {}); !added)
                    return std::unexpected(added.error());
            }
        }

        if (auto pc = pushConstants(resources); !pc) return std::unexpected(pc.error());
        if (stage == ShaderStage::Compute) workGroupSize();
        if (stage == ShaderStage::Fragment)
            if (auto out = colorOutputs(resources); !out) return std::unexpected(out.error());

        std::sort(m_out.bindings.begin(), m_out.bindings.end(), [](const auto& x, const auto& y) {
            return std::tie(x.set, x.binding) < std::tie(y.set, y.binding);
        });
        return std::move(m_out);
    }

    // Adds b to list, or merges it into the entry already at its set/binding.
    static Result<void> addBinding(std::vector<ReflectedBinding>& list, ReflectedBinding b,
                                   std::string_view passName) {
        auto it = std::find_if(list.begin(), list.end(), [&](const ReflectedBinding& e) {
            return e.set == b.set && e.binding == b.binding;
        });
        if (it == list.end()) {
            list.push_back(std::move(b));
            return {};
        }
        ReflectedBinding& e = *it;
        const std::string where = passPrefix(passName) + "set " + std::to_string(b.set) +
                                  " binding " + std::to_string(b.binding) + " is ";
        const auto describe = [](const ReflectedBinding& r) {
            std::string s = "'" + r.name + "' (" + toString(r.type);
            if (r.count != 1) s += "[" + std::to_string(r.count) + "]";
            return s + ") in the " + stageNames(r.stageMask) + " stage";
        };
        if (e.type != b.type || e.count != b.count)
            return fail(ErrorCode::InvalidInput,
                        where + describe(e) + " but " + describe(b) +
                            ": one set/binding must "
                            "have one descriptor type and array size in all stages of a pipeline");
        if (!e.imageFormat.empty() && !b.imageFormat.empty() && e.imageFormat != b.imageFormat)
            return fail(ErrorCode::InvalidInput,
                        where + "'" + e.name + "' (" + e.imageFormat + ") in the " +
                            stageNames(e.stageMask) + " stage but '" + b.name + "' (" +
                            b.imageFormat + ") in the " + stageNames(b.stageMask) +
                            " stage: the storage image formats differ");
        e.stageMask |= b.stageMask;
        // The pipeline needs write access if any stage writes, read access if any stage reads.
        e.nonWritable = e.nonWritable && b.nonWritable;
        e.nonReadable = e.nonReadable && b.nonReadable;
        if (b.blockSize > e.blockSize) {
            e.blockSize = b.blockSize;
            e.members = std::move(b.members);
        }
        if (e.imageFormat.empty()) e.imageFormat = std::move(b.imageFormat);
        return {};
    }

private:
    std::string lastError() const {
        const char* s = spvc_context_get_last_error_string(m_ctx);
        return s && *s ? s : "unknown SPIRV-Cross error";
    }

    spvc_type type(spvc_type_id id) const { return spvc_compiler_get_type_handle(m_compiler, id); }

    // Product of all array dimensions of a variable's type; 0 for a runtime-sized array.
    uint32_t arraySize(spvc_type_id typeId) const {
        spvc_type t = type(typeId);
        uint32_t n = 1;
        for (unsigned d = 0; d < spvc_type_get_num_array_dimensions(t); ++d) {
            SpvId dim = spvc_type_get_array_dimension(t, d);
            uint32_t size = dim;
            if (!spvc_type_array_dimension_is_literal(t, d)) {
                // Sized by a specialization constant: its default value.
                spvc_constant c = spvc_compiler_get_constant_handle(m_compiler, dim);
                size = c ? spvc_constant_get_scalar_u32(c, 0, 0) : 1;
            }
            n *= size;
        }
        return n;
    }

    bool hasDecoration(SpvId id, SpvDecoration d) const {
        return spvc_compiler_has_decoration(m_compiler, id, d) != SPVC_FALSE;
    }

    // Declared size and top-level members of a struct type.
    Result<std::vector<BlockMember>> members(spvc_type_id structId, uint32_t& size) const {
        spvc_type t = type(structId);
        size_t declared = 0;
        if (spvc_compiler_get_declared_struct_size(m_compiler, t, &declared) != SPVC_SUCCESS)
            return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());
        size = static_cast<uint32_t>(declared);
        std::vector<BlockMember> out;
        const unsigned n = spvc_type_get_num_member_types(t);
        for (unsigned i = 0; i < n; ++i) {
            BlockMember m;
            const char* name = spvc_compiler_get_member_name(m_compiler, structId, i);
            m.name = name ? name : "";
            unsigned offset = 0;
            size_t memberSize = 0;
            if (spvc_compiler_type_struct_member_offset(m_compiler, t, i, &offset) !=
                    SPVC_SUCCESS ||
                spvc_compiler_get_declared_struct_member_size(m_compiler, t, i, &memberSize) !=
                    SPVC_SUCCESS)
                return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());
            m.offset = offset;
            m.size = static_cast<uint32_t>(memberSize);
            out.push_back(std::move(m));
        }
        return out;
    }

    Result<ReflectedBinding> binding(const spvc_reflected_resource& r, DescriptorType dt) const {
        ReflectedBinding b;
        b.set = spvc_compiler_get_decoration(m_compiler, r.id, SpvDecorationDescriptorSet);
        b.binding = spvc_compiler_get_decoration(m_compiler, r.id, SpvDecorationBinding);
        b.count = arraySize(r.type_id);
        b.type = dt;
        b.name = r.name ? r.name : "";
        b.stageMask = m_out.stageMask;
        b.nonWritable = true;
        b.nonReadable = false;

        spvc_type base = type(r.base_type_id);
        // A samplerBuffer is a uniform texel buffer (a sampled image of dimension Buffer: SPIRV-Cross
        // lists it with the separate images).
        if ((dt == DescriptorType::CombinedImageSampler || dt == DescriptorType::SampledImage) &&
            spvc_type_get_image_dimension(base) == SpvDimBuffer)
            b.type = dt = DescriptorType::UniformTexelBuffer;
        switch (dt) {
            case DescriptorType::UniformBuffer:
            case DescriptorType::StorageBuffer: {
                auto m = members(r.base_type_id, b.blockSize);
                if (!m) return std::unexpected(m.error());
                b.members = std::move(*m);
                if (dt == DescriptorType::StorageBuffer) {
                    // readonly/writeonly on a buffer block decorate every member; SPIRV-Cross
                    // reports the decorations common to the variable and all its members.
                    const SpvDecoration* decos = nullptr;
                    size_t n = 0;
                    spvc_compiler_get_buffer_block_decorations(m_compiler, r.id, &decos, &n);
                    b.nonWritable =
                        std::find(decos, decos + n, SpvDecorationNonWritable) != decos + n;
                    b.nonReadable =
                        std::find(decos, decos + n, SpvDecorationNonReadable) != decos + n;
                }
                break;
            }
            case DescriptorType::CombinedImageSampler:
            case DescriptorType::SampledImage:
            case DescriptorType::StorageImage:
                if (spvc_type_get_image_dimension(base) == SpvDimBuffer)
                    return fail(ErrorCode::Unsupported,
                                "texel buffer '" + b.name +
                                    "' is not supported (use a storage buffer; a samplerBuffer "
                                    "is read only from the scene's lights)");
                if (dt == DescriptorType::StorageImage) {
                    b.nonWritable = hasDecoration(r.id, SpvDecorationNonWritable);
                    b.nonReadable = hasDecoration(r.id, SpvDecorationNonReadable);
                    b.imageFormat = imageFormatName(spvc_type_get_image_storage_format(base));
                }
                break;
            case DescriptorType::Sampler:
            case DescriptorType::UniformTexelBuffer:
                break;
        }
        return b;
    }

    Result<void> pushConstants(spvc_resources resources) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        if (spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT,
                                                      &list, &count) != SPVC_SUCCESS)
            return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());
        for (size_t i = 0; i < count; ++i) {  // GLSL allows one block per stage
            uint32_t size = 0;
            auto m = members(list[i].base_type_id, size);
            if (!m) return std::unexpected(m.error());
            m_out.pushConstantSize = std::max(m_out.pushConstantSize, size);
            for (auto& member : *m) m_out.pushConstants.push_back(std::move(member));
        }
        return {};
    }

    void workGroupSize() {
        for (unsigned i = 0; i < 3; ++i)
            m_out.localSize[i] = spvc_compiler_get_execution_mode_argument_by_index(
                m_compiler, SpvExecutionModeLocalSize, i);
        // local_size_x_id = N: the size is a specialization constant; report its default.
        spvc_specialization_constant xyz[3];
        spvc_compiler_get_work_group_size_specialization_constants(m_compiler, &xyz[0], &xyz[1],
                                                                   &xyz[2]);
        for (unsigned i = 0; i < 3; ++i) {
            if (xyz[i].id == 0) continue;
            if (spvc_constant c = spvc_compiler_get_constant_handle(m_compiler, xyz[i].id))
                m_out.localSize[i] = spvc_constant_get_scalar_u32(c, 0, 0);
        }
    }

    Result<void> colorOutputs(spvc_resources resources) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        if (spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_STAGE_OUTPUT,
                                                      &list, &count) != SPVC_SUCCESS)
            return fail(ErrorCode::InvalidInput, "SPIR-V reflection failed: " + lastError());
        for (size_t i = 0; i < count; ++i) {
            if (!hasDecoration(list[i].id, SpvDecorationLocation)) continue;
            const uint32_t loc =
                spvc_compiler_get_decoration(m_compiler, list[i].id, SpvDecorationLocation);
            // An output array occupies consecutive locations.
            const uint32_t n = std::max(arraySize(list[i].type_id), 1u);
            for (uint32_t k = 0; k < n; ++k) m_out.colorOutputs.push_back(loc + k);
            const spvc_basetype base = spvc_type_get_basetype(
                spvc_compiler_get_type_handle(m_compiler, list[i].base_type_id));
            if (base == SPVC_BASETYPE_INT32 || base == SPVC_BASETYPE_UINT32)
                for (uint32_t k = 0; k < n; ++k) m_out.integerOutputs.push_back(loc + k);
        }
        std::sort(m_out.colorOutputs.begin(), m_out.colorOutputs.end());
        m_out.colorOutputs.erase(std::unique(m_out.colorOutputs.begin(), m_out.colorOutputs.end()),
                                 m_out.colorOutputs.end());
        return {};
    }

    spvc_context m_ctx;
    spvc_compiler m_compiler;
    ShaderReflection m_out;
};

}  // namespace

const char* toString(ShaderStage s) {
    switch (s) {
        case ShaderStage::Vertex:
            return "vertex";
        case ShaderStage::Fragment:
            return "fragment";
        case ShaderStage::Compute:
            return "compute";
    }
    return "unknown";
}

std::optional<ShaderStage> stageFromPath(std::string_view path) {
    const auto dot = path.find_last_of('.');
    const auto slash = path.find_last_of('/');
    if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash))
        return std::nullopt;
    const std::string_view ext = path.substr(dot);
    // HLSL: the stage's extension before .hlsl (fxaa.frag.hlsl).
    if (ext == ".hlsl") return stageFromPath(path.substr(0, dot));
    if (ext == ".vert") return ShaderStage::Vertex;
    if (ext == ".frag") return ShaderStage::Fragment;
    if (ext == ".comp") return ShaderStage::Compute;
    return std::nullopt;
}

const char* toString(DescriptorType t) {
    switch (t) {
        case DescriptorType::CombinedImageSampler:
            return "combined_image_sampler";
        case DescriptorType::SampledImage:
            return "sampled_image";
        case DescriptorType::Sampler:
            return "sampler";
        case DescriptorType::StorageImage:
            return "storage_image";
        case DescriptorType::UniformBuffer:
            return "uniform_buffer";
        case DescriptorType::StorageBuffer:
            return "storage_buffer";
        case DescriptorType::UniformTexelBuffer:
            return "uniform_texel_buffer";
    }
    return "unknown";
}

const ReflectedBinding* ShaderReflection::find(uint32_t set, uint32_t binding) const {
    for (const auto& b : bindings)
        if (b.set == set && b.binding == binding) return &b;
    return nullptr;
}

const ReflectedBinding* ShaderReflection::find(std::string_view name) const {
    for (const auto& b : bindings)
        if (b.name == name) return &b;
    return nullptr;
}

Result<ShaderReflection> reflectSpirv(std::span<const uint32_t> spirv) {
    if (spirv.size() < 5 || spirv[0] != kSpirvMagic) {
        char magic[16] = "none";
        if (!spirv.empty()) std::snprintf(magic, sizeof magic, "0x%08x", spirv[0]);
        return fail(ErrorCode::InvalidInput, "not a SPIR-V module (" +
                                                 std::to_string(spirv.size()) + " words, magic " +
                                                 magic + ", expected 0x07230203)");
    }
    spvc_context raw = nullptr;
    if (spvc_context_create(&raw) != SPVC_SUCCESS)
        return fail(ErrorCode::InvalidInput, "SPIRV-Cross: cannot create a context");
    ContextPtr ctx(raw);
    spvc_parsed_ir ir = nullptr;
    spvc_compiler compiler = nullptr;
    if (spvc_context_parse_spirv(raw, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(raw, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &compiler) != SPVC_SUCCESS) {
        const char* why = spvc_context_get_last_error_string(raw);
        return fail(ErrorCode::InvalidInput,
                    std::string("cannot parse SPIR-V: ") + (why && *why ? why : "unknown error"));
    }
    auto out = Reflector(raw, compiler).run();
    if (!out) return out;
    // Whether the module can discard a fragment: a pass drawn over every pixel may then leave
    // some as they were, so its targets' previous (cleared) contents still count.
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (op == 252 || op == 4416 || op == 5380)
            out->discards = true;  // OpKill, OpTerminateInvocation, OpDemoteToHelperInvocation
        if (words == 0) break;
        i += words;
    }
    return out;
}

Result<ShaderReflection> mergeReflections(const ShaderReflection& a, const ShaderReflection& b,
                                          std::string_view passName) {
    ShaderReflection out = a;
    out.stageMask |= b.stageMask;
    for (const auto& binding : b.bindings)
        if (auto r = Reflector::addBinding(out.bindings, binding, passName); !r)
            return std::unexpected(r.error());
    std::sort(out.bindings.begin(), out.bindings.end(), [](const auto& x, const auto& y) {
        return std::tie(x.set, x.binding) < std::tie(y.set, y.binding);
    });

    // One push-constant range covers every stage's block; members are united by offset/name.
    out.pushConstantSize = std::max(a.pushConstantSize, b.pushConstantSize);
    for (const auto& m : b.pushConstants)
        if (std::find(out.pushConstants.begin(), out.pushConstants.end(), m) ==
            out.pushConstants.end())
            out.pushConstants.push_back(m);
    std::stable_sort(out.pushConstants.begin(), out.pushConstants.end(),
                     [](const auto& x, const auto& y) { return x.offset < y.offset; });

    for (size_t i = 0; i < 3; ++i) out.localSize[i] = std::max(a.localSize[i], b.localSize[i]);
    for (uint32_t loc : b.colorOutputs) out.colorOutputs.push_back(loc);
    std::sort(out.colorOutputs.begin(), out.colorOutputs.end());
    out.colorOutputs.erase(std::unique(out.colorOutputs.begin(), out.colorOutputs.end()),
                           out.colorOutputs.end());
    for (uint32_t loc : b.integerOutputs) out.integerOutputs.push_back(loc);
    std::sort(out.integerOutputs.begin(), out.integerOutputs.end());
    out.integerOutputs.erase(std::unique(out.integerOutputs.begin(), out.integerOutputs.end()),
                             out.integerOutputs.end());
    out.discards = a.discards || b.discards;
    return out;
}

}  // namespace rg
