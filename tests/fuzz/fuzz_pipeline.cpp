// Fuzz target: a Lua pipeline script through the whole front end without a GPU, as `rgraph graph`
// runs it: the sandboxed Lua host (instruction and memory limits), the declarations into a
// PipelineDesc, the material system's generated GLSL, and the graph compiler.
#include "runtime/session.h"
#include "core/compiler.h"
#include "fuzz_common.h"
#include "lua/lua_host.h"
#include "lua/pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const rg::LuaHostOptions options = [] {
        setenv("RG_ROOT", RG_SOURCE_ROOT, 0);  // the project's scripts/ for require
        rg::LuaHostOptions o = rg::luaHostOptionsWithoutDevice();
        o.instructions = 2'000'000;  // a fuzzer's time goes to breadth, not to long loops
        o.memoryBytes = 64u << 20;
        return o;
    }();
    const std::string path = rg::fuzz::writeInput(data, size, "fuzz_pipeline.lua");
    rg::LuaHost host(options);
    auto pipeline = host.load(path);
    if (!pipeline) return 0;
    (void)rg::generatePipelineGlsl(*pipeline);
    rg::CompileOptions compile;
    compile.outputWidth = 64;
    compile.outputHeight = 32;
    (void)rg::compile(pipeline->graph, compile);
    return 0;
}
