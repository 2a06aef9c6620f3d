// The command line's exit codes, error reports, argument reader and the pipeline a command works on.
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

#include "lua/lua_host.h"
#include "cli.h"

namespace rg::cli {

int exitCodeOf(const Error& e) {
    switch (e.code) {
        case ErrorCode::InvalidInput:
        case ErrorCode::NotFound:
        case ErrorCode::Unsupported:
            return kUsage;
        default:
            return kFailed;
    }
}

int report(const Error& e) {
    std::fprintf(stderr, "rgraph: error: %s\n", e.describe().c_str());
    return exitCodeOf(e);
}

int usageError(const std::string& msg, const char* command) {
    std::fprintf(stderr, "rgraph %s: %s (see 'rgraph %s --help')\n", command, msg.c_str(), command);
    return kUsage;
}

Args Args::parse(int argc, char** argv, int first, const std::vector<std::string>& known) {
    static const std::vector<std::string> flags = {"verbose", "floors", "rebake", "no-cache",
                                                   "ibl",     "family"};  // options without a value
    Args a;
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            a.help = true;
            continue;
        }
        if (arg.rfind("--", 0) != 0) {
            a.values[""].push_back(arg);
            continue;
        }
        std::string name = arg.substr(2), value;
        if (std::find(flags.begin(), flags.end(), name) != flags.end() &&
            std::find(known.begin(), known.end(), name) != known.end()) {
            a.values[name].push_back("1");
            continue;
        }
        const auto eq = name.find('=');
        if (eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            a.error = "unknown option --" + name;
            return a;
        }
        if (eq == std::string::npos) {
            if (i + 1 >= argc) {
                a.error = "option --" + name + " needs a value";
                return a;
            }
            value = argv[++i];
        }
        a.values[name].push_back(value);
    }
    return a;
}

std::optional<int> parseCommand(int argc, char** argv, const char* command,
                                const std::vector<std::string>& options, const char* help,
                                Args& args) {
    args = Args::parse(argc, argv, 2, options);
    if (args.help) {
        std::fputs(help, stdout);
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, command);
    return std::nullopt;
}

bool parseSize(const std::string& s, uint32_t& w, uint32_t& h) {
    unsigned a = 0, b = 0;
    char x = 0;
    if (std::sscanf(s.c_str(), "%u%c%u", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a == 0 ||
        b == 0 || a > 16384 || b > 16384)
        return false;
    w = a;
    h = b;
    return true;
}

bool parseShard(const std::string& s, uint32_t& shard, uint32_t& shards) {
    const auto slash = s.find('/');
    if (slash == std::string::npos) return false;
    uint32_t k = 0, n = 0;
    if (!parseCount(s.substr(0, slash), k) || !parseCount(s.substr(slash + 1), n) || k > n ||
        n > 65536)
        return false;
    shard = k - 1;
    shards = n;
    return true;
}

bool parseCount(const std::string& s, uint32_t& n, bool allowZero) {
    char* end = nullptr;
    unsigned long v = std::strtoul(s.c_str(), &end, 10);
    if (s.empty() || s[0] == '-' || *end || (v == 0 && !allowZero) || v > 1000000) return false;
    n = static_cast<uint32_t>(v);
    return true;
}

std::string defaultPipeline() { return projectRoot() + "/scripts/pipelines/deferred.lua"; }
std::string pipelineArg(const Args& args) { return args.get("pipeline", defaultPipeline()); }
bool isBuiltin(const std::string& p) { return p.rfind("builtin:", 0) == 0; }

// The graph a command works on, without a GPU: a pipeline script or builtin:NAME.
Result<GraphDesc> loadGraph(const Args& args) {
    std::string pipeline = pipelineArg(args);
    if (isBuiltin(pipeline)) return builtinGraph(pipeline.substr(8));
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(pipeline);
    if (!p) return std::unexpected(p.error());
    return graphWithParams(*p);
}

}  // namespace rg::cli
