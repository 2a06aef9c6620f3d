#include "runtime.h"

#include <cstdlib>
#include <filesystem>

#include "passes/passes.h"

namespace rg {

namespace fs = std::filesystem;

std::string projectRoot() {
    if (const char* r = std::getenv("RG_ROOT"); r && *r) return r;
    return RG_SOURCE_ROOT;
}

std::string cacheDir() {
    if (const char* c = std::getenv("RG_CACHE_DIR"); c && *c) return c;
    return RG_DEFAULT_CACHE_DIR;
}

std::string generatedShaderDir() { return cacheDir() + "/generated"; }

void prepareEnvironment() {
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
