// `rgraph graph`: the compiled plan of a pipeline as DOT, JSON or text, without a GPU.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "layout/layout.h"
#include "lua/lua_host.h"
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph graph [--pipeline FILE.lua|builtin:NAME] [--format dot|json|materials] [--size "
    "WxH] [--capture RESOURCE]...\n\n"
    "Compiles the pipeline (no GPU needed; memory sizes are estimated) and prints the plan:\n"
    "passes in order, culled passes and why, resources with lifetimes and memory offsets,\n"
    "barriers. Without a scene every resource and pass is planned, those declared only_when\n"
    "included (what a scene and the parameters leave out shows when rendering with --verbose).\n"
    "Default format: dot. '--format materials' prints the material system instead:\n"
    "each material's id, layout, lighting path and stencil value, how they were assigned,\n"
    "and how many ids and stencil classes are left.\n";

}  // namespace

int cmdGraph(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(argc, argv, "graph", {"pipeline", "format", "size", "capture"},
                                 kHelp, args))
        return *done;
    std::string format = args.get("format", "dot");
    if (format != "dot" && format != "json" && format != "materials")
        return usageError("--format must be 'dot', 'json' or 'materials'", "graph");
    if (format == "materials") {
        const std::string pipeline = pipelineArg(args);
        if (isBuiltin(pipeline))
            return usageError("--format materials: built-in graphs declare no materials", "graph");
        LuaHost host(luaHostOptionsWithoutDevice());
        auto p = host.load(pipeline);
        if (!p) return report(p.error());
        std::printf("%s", describeMaterialSystem(*p).c_str());
        return kOk;
    }
    CompileOptions opts;
    if (args.has("size") && !parseSize(args.get("size"), opts.outputWidth, opts.outputHeight))
        return usageError(
            "--size must be WIDTHxHEIGHT with each side in 1..16384, e.g. 1280x720; got '" +
                args.get("size") + "'",
            "graph");
    auto graph = loadGraph(args);
    if (!graph) return report(graph.error());
    for (const auto& c : args.all("capture")) {
        auto it = std::find_if(graph->resources.begin(), graph->resources.end(),
                               [&](auto& r) { return r.name == c; });
        if (it == graph->resources.end())
            return report(Error(ErrorCode::NotFound, "--capture: no resource named '" + c + "'"));
        it->exported = true;
    }
    auto plan = compile(*graph, opts);
    if (!plan) return report(plan.error());
    std::printf("%s\n", format == "dot" ? plan->toDot().c_str() : plan->toJson().c_str());
    return kOk;
}

}  // namespace rg::cli
