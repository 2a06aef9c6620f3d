// Shader reflection: what a SPIR-V module binds (descriptors, push constants, work-group size,
// colour outputs), read from the SPIR-V itself with SPIRV-Cross so a layout is never written
// twice. Plain data, Vulkan-free: the GPU layer turns a ShaderReflection into VkDescriptorSetLayouts
// and a VkPipelineLayout.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"

namespace rg {

enum class ShaderStage : uint8_t { Vertex, Fragment, Compute };

// One bit per ShaderStage, as used by ReflectedBinding::stageMask and ShaderReflection::stageMask.
constexpr uint32_t stageBit(ShaderStage s) { return 1u << static_cast<uint32_t>(s); }

// "vertex", "fragment", "compute".
const char* toString(ShaderStage s);

// ".vert" -> Vertex, ".frag" -> Fragment, ".comp" -> Compute (the last extension of the path, or
// the one before ".hlsl": "x.frag.hlsl" is an HLSL fragment shader); nullopt for anything else.
std::optional<ShaderStage> stageFromPath(std::string_view path);

enum class DescriptorType : uint8_t {
    CombinedImageSampler,  // sampler2D, samplerCube, ...
    SampledImage,          // texture2D
    Sampler,               // sampler
    StorageImage,          // image2D
    UniformBuffer,         // uniform Block { ... }
    StorageBuffer,         // buffer Block { ... }
    UniformTexelBuffer,  // samplerBuffer (bound for the scene's lights only: passes/shader_program.cpp)
};

// "combined_image_sampler", "sampled_image", "sampler", "storage_image", "uniform_buffer",
// "storage_buffer", "uniform_texel_buffer".
const char* toString(DescriptorType t);

// A top-level member of a block (UBO, SSBO or push constants), offsets and sizes in bytes as
// laid out in the SPIR-V (std140 / std430 / explicit offset). An unsized trailing array has
// size 0.
struct BlockMember {
    std::string name;
    uint32_t offset = 0;
    uint32_t size = 0;

    bool operator==(const BlockMember&) const = default;
};

struct ReflectedBinding {
    uint32_t set = 0;
    uint32_t binding = 0;
    uint32_t count = 1;  // array size (product of all dimensions); 0 for an unsized array
    DescriptorType type = DescriptorType::UniformBuffer;
    // The variable's name; for blocks the block's type name ("Params" in
    // `uniform Params { ... } params;`), which is what both stages of a pipeline share.
    std::string name;
    uint32_t stageMask = 0;  // stageBit() of every stage that declares it
    // readonly / writeonly qualifiers of storage images and buffers. Every other type is
    // read-only by nature: nonWritable = true, nonReadable = false.
    bool nonWritable = false;
    bool nonReadable = false;
    uint32_t blockSize = 0;            // UBO/SSBO declared size in bytes (unsized array as 0)
    std::vector<BlockMember> members;  // UBO/SSBO top-level members, in declaration order
    std::string imageFormat;           // storage image format qualifier ("rgba16f"), "" if none

    bool operator==(const ReflectedBinding&) const = default;
};

struct ShaderReflection {
    uint32_t stageMask = 0;                      // stages this reflection covers
    std::vector<ReflectedBinding> bindings;      // sorted by (set, binding)
    uint32_t pushConstantSize = 0;               // bytes; 0 when there is no push-constant block
    std::vector<BlockMember> pushConstants;      // push-constant block members
    std::array<uint32_t, 3> localSize{0, 0, 0};  // compute work-group size; 0s for other stages
    std::vector<uint32_t> colorOutputs;          // fragment output locations, ascending
    std::vector<uint32_t> integerOutputs;  // those of them with an integer type (uvec4, ivec4)
    bool discards =
        false;  // a stage can discard (OpKill, OpTerminateInvocation, OpDemoteToHelperInvocation)

    bool operator==(const ShaderReflection&) const = default;

    // The binding at (set, binding), or nullptr.
    const ReflectedBinding* find(uint32_t set, uint32_t binding) const;
    // The binding with this name, or nullptr.
    const ReflectedBinding* find(std::string_view name) const;
};

// Reflects a SPIR-V module with exactly one entry point. Fails (InvalidInput) when the words are
// not SPIR-V, and (Unsupported) for resource kinds rgraph has no DescriptorType for (texel
// buffers, subpass inputs, acceleration structures), naming the variable.
Result<ShaderReflection> reflectSpirv(std::span<const uint32_t> spirv);

// Merges the reflections of the stages of one pipeline (e.g. vertex + fragment) into one layout
// description: bindings at the same set/binding become one with both stage bits, push-constant
// blocks are united. Fails (InvalidInput) when two stages put different descriptor types or
// array sizes at the same set/binding; the message names both variables and stages, prefixed
// with "pass 'NAME': " when passName is not empty.
Result<ShaderReflection> mergeReflections(const ShaderReflection& a, const ShaderReflection& b,
                                          std::string_view passName = {});

}  // namespace rg
