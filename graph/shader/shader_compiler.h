// Run-time GLSL -> SPIR-V compiler: glslang with #include, defines, error messages that name the
// GLSL file, line and pass, reflection from the SPIR-V, and a content-hashed SPIR-V cache (in
// memory and on disk). Vulkan-free; targets Vulkan 1.3 / SPIR-V 1.6, GLSL #version 460 when the
// source has no #version.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/result.h"
#include "shader/reflection.h"

namespace rg {

struct ShaderRequest {
    // The GLSL file: absolute, or relative to one of ShaderCompiler::Options::includeDirs (the
    // first root that has it wins). Ignored when `source` is not empty.
    std::string path;
    // In-memory GLSL (generated code) compiled instead of a file when not empty. `virtualName`
    // stands for the file in errors and gives the stage from its extension; its includes are
    // searched in the folder of virtualName when that is an absolute path, then includeDirs.
    std::string source;
    std::string virtualName;
    // Each pair becomes `#define NAME VALUE` before the first line (the source's line numbers are
    // unchanged). NAME must be an identifier; VALUE a single line (may be empty).
    std::vector<std::pair<std::string, std::string>> defines;
    std::string passName;              // for error messages: "pass 'NAME': ..."
    std::optional<ShaderStage> stage;  // default: from the extension (.vert, .frag, .comp)
    // The GLSL function compiled as the entry point; the SPIR-V entry point has the same name.
    std::string entry = "main";
};

struct ShaderModule {
    std::vector<uint32_t> spirv;
    ShaderReflection reflection;
    ShaderStage stage = ShaderStage::Compute;
    std::string entry = "main";  // SPIR-V entry point name (VkPipelineShaderStageCreateInfo::pName)
    // The source file and every file it includes (found by scanning #include lines, so a file
    // included under an #if that is off is listed too): absolute paths, source first, for hot
    // reload. A request from memory lists only its includes.
    std::vector<std::string> files;
    uint64_t hash = 0;       // cache key: sources, includes, defines, stage, entry, options
    bool fromCache = false;  // true when no glslang run was needed (memory or disk cache)
};

// Checks SPIR-V with the SPIRV-Tools validator for a Vulkan 1.3 environment; the error
// (InvalidInput) carries the validator's messages. For tests and tools.
Result<void> validateSpirv(std::span<const uint32_t> spirv);

// Threading: one ShaderCompiler is used by one thread at a time; separate instances may compile
// concurrently (also in separate processes sharing one cacheDir: cache files are written to a
// temporary name and renamed into place).
class ShaderCompiler {
public:
    struct Options {
        // Search roots, in order, for ShaderRequest::path and for #include. An #include is
        // first looked up in the including file's folder.
        std::vector<std::string> includeDirs;
        // Searched after includeDirs: the generated code of the pipeline being built (its
        // G-buffer layouts' headers), switched per pipeline with setGeneratedDir.
        std::string generatedDir;
        std::string cacheDir;    // "<cacheDir>/<16 hex digits>.spv"; "" disables the disk cache
        bool debugInfo = false;  // OpLine / OpSource with the GLSL text, for debuggers
    };

    struct Stats {
        uint32_t hits = 0;       // requests answered from the memory or disk cache
        uint32_t misses = 0;     // requests that ran glslang (including failed ones)
        double compileMs = 0.0;  // wall time spent in glslang, milliseconds
    };

    explicit ShaderCompiler(Options options);

    // Compiles (or finds in a cache) one shader stage. Failures: NotFound (the file or the
    // source root is missing), Io (unreadable file), InvalidInput (a GLSL error: one
    // `pass 'P': path:line: message` line per error; a bad define), Unsupported (reflection of a
    // resource kind rgraph does not bind).
    Result<ShaderModule> compile(const ShaderRequest& request);

    const Stats& stats() const { return m_stats; }
    void setGeneratedDir(std::string dir) { m_options.generatedDir = std::move(dir); }
    const Options& options() const { return m_options; }

private:
    Options m_options;
    Stats m_stats;
    std::unordered_map<uint64_t, ShaderModule> m_memory;  // by ShaderModule::hash
};

}  // namespace rg
