// ShaderProgram: the shader side of a pass kind. Compiles the stages with the ShaderCompiler,
// builds descriptor-set layouts and the pipeline layout from SPIR-V reflection (never written by
// hand), and binds each reflected binding to a resource of the pass:
//  - a binding named like a resource the pass reads or writes ('.' in resource names reads as
//    '_' in GLSL), or mapped explicitly with params.bind = { glslName = "resource" };
//  - a uniform block named `Params` is filled every frame from params.uniforms by member name
//    (numbers and lists of numbers, as floats), so changing a parameter re-records nothing;
//  - push constants: built-in members `rg_outputSize` (vec2, texels), `rg_time` (float, seconds),
//    `rg_frame` (float), `rg_mip` and `rg_mipCount` (floats: the mip a per-mip variant writes, of how many) and any member named
//    in params.constants (floats).
// Per-mip variants (the compute kind's per_mip): variant v binds every storage image at mip v
// (clamped to its chain) instead of mip 0, so one pass writes a whole mip chain, a dispatch each.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gpu/pass_kind.h"
#include "shader/shader_compiler.h"

namespace rg::passes {

class ShaderProgram {
public:
    // `stages`: requests whose passName/defines are filled in from the pass here.
    // `externalSets`: set index -> layout someone else binds (scene draws bind materials in set 1).
    Result<void> build(gpu::PassSetup& setup, std::vector<ShaderRequest> stages,
                       std::map<uint32_t, VkDescriptorSetLayout> externalSets = {},
                       uint32_t mipVariants = 1);

    VkPipelineLayout layout() const { return m_layout.get(); }
    const std::vector<VkPipelineShaderStageCreateInfo>& stageInfos() const { return m_stageInfos; }
    const ShaderReflection& reflection() const { return m_reflection; }
    std::vector<std::string> files() const { return m_files; }

    // Writes this frame's uniforms and push constants and binds the descriptor sets.
    void bind(gpu::RecordContext& rc, VkPipelineBindPoint point, uint32_t mipVariant = 0);

private:
    Result<void> createLayouts(gpu::PassSetup& setup);
    Result<void> writeDescriptors(gpu::PassSetup& setup);
    void writeUniforms(const Value& uniforms, uint32_t slot);

    std::vector<ShaderModule> m_modules;
    std::vector<gpu::OwnedShaderModule> m_vkModules;
    std::vector<VkPipelineShaderStageCreateInfo> m_stageInfos;
    ShaderReflection m_reflection;
    std::vector<std::string> m_files;
    std::vector<gpu::OwnedDescriptorSetLayout> m_setLayouts;  // null where a set is external
    std::map<uint32_t, VkDescriptorSetLayout> m_external;
    uint32_t m_ownedSets = 0;  // sets [0, m_ownedSets) bound by bind(), external ones skipped
    gpu::OwnedPipelineLayout m_layout;
    gpu::OwnedDescriptorPool m_pool;
    uint32_t m_variants = 1;                           // per-mip descriptor variants
    std::vector<std::vector<VkDescriptorSet>> m_sets;  // [frame slot × m_variants + variant][set]
    gpu::OwnedSampler m_linear, m_nearest;
    const ReflectedBinding* m_params = nullptr;  // the `Params` uniform block, if any
    std::vector<gpu::Buffer> m_paramBuffers;     // one per frame slot
    VkShaderStageFlags m_pushStages = 0;
};

// Helpers shared by the pass kinds.
std::string passPrefix(const PassDesc& desc);  // "deferred.lua:12: pass 'x': " or "pass 'x': "
VkShaderStageFlags toVkStageFlags(uint32_t stageMask);

}  // namespace rg::passes
