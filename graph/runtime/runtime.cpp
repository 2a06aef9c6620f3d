#include "runtime.h"

#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>

#include "passes/passes.h"
#include "scene/mesh_lod.h"
#include "scene/scene.h"

namespace rg {

namespace fs = std::filesystem;

namespace {
std::string& rootOverride() {
    static std::string dir;
    return dir;
}
std::string& cacheOverride() {
    static std::string dir;
    return dir;
}
// <prefix>/share/rgraph when this code runs from <prefix>/bin or <prefix>/lib (an installed copy).
std::string installedRoot() {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&installedRoot), &info) || !info.dli_fname) return {};
    std::error_code ec;
    const fs::path self = fs::canonical(fs::path(info.dli_fname), ec);
    if (ec) return {};
    // bin/, lib/ or lib/<multiarch>/ below the prefix.
    for (fs::path dir = self.parent_path(); dir.has_parent_path() && dir != dir.parent_path();
         dir = dir.parent_path()) {
        const fs::path share = dir.parent_path() / "share" / "rgraph";
        if (fs::is_directory(share / "scripts", ec)) return share.string();
        if (dir.filename() != "lib" && dir.parent_path().filename() != "lib") break;
    }
    return {};
}
}  // namespace

void setProjectRoot(std::string dir) { rootOverride() = std::move(dir); }
void setCacheDir(std::string dir) { cacheOverride() = std::move(dir); }

std::string projectRoot() {
    if (const char* r = std::getenv("RG_ROOT"); r && *r) return r;
    if (!rootOverride().empty()) return rootOverride();
    static const std::string installed = installedRoot();
    return installed.empty() ? std::string(RG_SOURCE_ROOT) : installed;
}

std::string cacheDir() {
    if (const char* c = std::getenv("RG_CACHE_DIR"); c && *c) return c;
    if (!cacheOverride().empty()) return cacheOverride();
    static const std::string installed = installedRoot();
    if (installed.empty()) return RG_DEFAULT_CACHE_DIR;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/rgraph";
    if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/rgraph";
    return (fs::temp_directory_path() / "rgraph-cache").string();
}

std::string generatedShaderDir() { return cacheDir() + "/generated"; }

void prepareEnvironment() {
    setGltfDecodeCacheDir(cacheDir() + "/decoded");  // Draco-compressed glTF geometry, decoded
    setMeshLodCacheDir(cacheDir() + "/lods");        // meshoptimizer's levels of detail, by content
    std::string mesa = cacheDir() + "/mesa";
    std::error_code ec;
    fs::create_directories(mesa, ec);
    setenv("MESA_SHADER_CACHE_DIR", mesa.c_str(), /*overwrite=*/0);
}

Result<std::unique_ptr<Runtime>> Runtime::create(const RuntimeOptions& options) {
    prepareEnvironment();
    auto rt = std::make_unique<Runtime>();
    gpu::ContextOptions co;
    co.deviceIndex = options.device;
    co.validation = options.validation;
    co.framesInFlight = options.framesInFlight;
    co.pipelineCachePath = cacheDir() + "/pipelines.bin";
    co.external = options.external;
    auto ctx = gpu::Context::create(co);
    if (!ctx) return std::unexpected(ctx.error());
    rt->m_context = std::move(*ctx);

    ShaderCompiler::Options so;
    const std::string root = projectRoot();
    so.includeDirs = {root + "/shaders", root};
    so.generatedDir = generatedShaderDir();  // each pipeline's own folder below it: setGeneratedDir
    so.cacheDir = cacheDir() + "/spirv";
    std::error_code ec;
    fs::create_directories(so.cacheDir, ec);
    rt->m_shaders = std::make_unique<ShaderCompiler>(so);
    passes::registerBuiltinPassKinds(rt->m_kinds);
    rt->m_executor = std::make_unique<gpu::Executor>(*rt->m_context, *rt->m_shaders, rt->m_kinds);
    return rt;
}

Result<GraphDesc> builtinGraph(const std::string& name) {
    if (name != "test")
        return fail(ErrorCode::NotFound, "no built-in graph named '" + name + "' (known: 'test')");
    GraphDesc g;
    ResourceDesc pattern;
    pattern.name = "pattern";
    pattern.texture.format = Format::RGBA16F;
    ResourceDesc output;
    output.name = "output";
    output.texture.format = Format::RGBA16F;
    output.exported = true;
    g.resources = {pattern, output};

    PassDesc gen;
    gen.name = "pattern";
    gen.kind = "compute";
    gen.type = PassType::Compute;
    gen.accesses = {{"pattern", Usage::StorageWrite}};
    gen.params = Value(Value::Table{{"shader", Value("test/pattern.comp")}});

    PassDesc transform;
    transform.name = "transform";
    transform.kind = "fullscreen";
    transform.accesses = {{"pattern", Usage::Sampled}, {"output", Usage::ColorAttachment}};
    transform.params = Value(Value::Table{
        {"shader", Value("test/transform.frag")},
        {"uniforms", Value(Value::Table{{"scale", Value(1.0)}})},
    });
    g.passes = {gen, transform};
    return g;
}

}  // namespace rg
