// Runtime: what the command line and the GPU tests share — where the project's folders are,
// the caches, the Vulkan context, the shader compiler, the pass kinds and an executor.
//
// Folders: the project root is RG_ROOT when set, else the source tree the binary was built
// from. Caches live in RG_CACHE_DIR (default: <build>/cache): SPIR-V in spirv/, Mesa's shader
// cache in mesa/ (MESA_SHADER_CACHE_DIR is set there unless the caller already set it).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "gpu/executor.h"
#include "shader/shader_compiler.h"

namespace rg {

// The folder with scripts/, materials/ and shaders/: RG_ROOT when set, else setProjectRoot's,
// else <prefix>/share/rgraph beside an installed binary or library, else the source tree.
std::string projectRoot();
// Caches: RG_CACHE_DIR when set, else setCacheDir's, else the build tree's cache/ (an installed
// copy: $XDG_CACHE_HOME/rgraph or ~/.cache/rgraph).
std::string cacheDir();
void setProjectRoot(std::string dir);
void setCacheDir(std::string dir);
// Generated GLSL (G-buffer pack/unpack of each layout): <cacheDir>/generated, on the include path.
std::string generatedShaderDir();
// Sets MESA_SHADER_CACHE_DIR (unless set) before any Vulkan call.
void prepareEnvironment();

struct RuntimeOptions {
    std::optional<uint32_t> device;
    std::optional<bool> validation;
    uint32_t framesInFlight = 2;
    std::optional<gpu::ExternalDevice> external;  // the host's device (the library's HostDevice)
};

class Runtime {
public:
    static Result<std::unique_ptr<Runtime>> create(const RuntimeOptions& options = {});

    gpu::Context& gpu() { return *m_context; }
    ShaderCompiler& shaders() { return *m_shaders; }
    const gpu::PassRegistry& kinds() const { return m_kinds; }
    gpu::Executor& executor() { return *m_executor; }

private:
    std::unique_ptr<gpu::Context> m_context;
    std::unique_ptr<ShaderCompiler> m_shaders;
    gpu::PassRegistry m_kinds;
    std::unique_ptr<gpu::Executor> m_executor;
};

// Built-in graphs, usable before any pipeline script: "test" = compute pattern -> fullscreen
// transform -> `output` (RGBA16F), sized relative to the output.
Result<GraphDesc> builtinGraph(const std::string& name);

}  // namespace rg
