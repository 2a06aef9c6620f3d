#include "session.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "passes/passes.h"

namespace fs = std::filesystem;

namespace rg {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

LuaHostOptions hostOptions(std::vector<PassKindSchema> kinds) {
    LuaHostOptions o;
    o.projectRoot = projectRoot();
    o.searchDirs = {projectRoot() + "/scripts", projectRoot() + "/materials"};
    o.kinds = std::move(kinds);
    return o;
}
}  // namespace

LuaHostOptions luaHostOptions(const Runtime& runtime) { return hostOptions(runtime.kinds().schemas()); }

LuaHostOptions luaHostOptionsWithoutDevice() {
    gpu::PassRegistry registry;
    passes::registerBuiltinPassKinds(registry);
    return hostOptions(registry.schemas());
}

Session::Session(Runtime& runtime, SessionOptions options) : m_runtime(runtime), m_options(std::move(options)) {}
Session::~Session() = default;

void Session::note(const std::string& line) {
    m_log.push_back(line);
    if (m_options.verbose) std::fprintf(stderr, "rgraph: %s\n", line.c_str());
}

// The pipeline's graph with parameters as uniforms, captures exported, and shader paths that
// exist next to the pipeline script made absolute (shaders/ and the root are searched anyway).
GraphDesc Session::buildableGraph(const PipelineDesc& p) const {
    GraphDesc g = graphWithParams(p);
    for (auto& r : g.resources)
        for (const auto& c : m_options.captures)
            if (r.name == c) r.exported = true;
    const fs::path dir = fs::absolute(p.file).parent_path();
    for (auto& pass : g.passes) {
        const Value& s = pass.params["shader"];
        std::error_code ec;
        if (s.isString() && !s.asString().empty() && fs::path(s.asString()).is_relative() &&
            fs::is_regular_file(dir / s.asString(), ec))
            pass.params.table()["shader"] = Value((dir / s.asString()).string());
    }
    return g;
}

Result<void> Session::load(const std::string& file) {
    auto t0 = Clock::now();
    auto host = std::make_unique<LuaHost>(luaHostOptions(m_runtime));
    auto pipeline = host->load(file);
    if (!pipeline) return std::unexpected(pipeline.error());
    for (const auto& c : m_options.captures)
        if (!pipeline->graph.findResource(c))
            return fail(ErrorCode::NotFound, "--capture: the pipeline has no resource named '" + c + "'");
    // The executor keeps its previous build when this one fails.
    if (auto r = m_runtime.executor().build(buildableGraph(*pipeline), m_options.compile); !r) return r;
    m_host = std::move(host);
    m_pipeline = std::move(*pipeline);
    m_rebuilds = 0;
    m_loadMs = msSince(t0);
    note("loaded " + file + ": " + std::to_string(m_runtime.executor().plan().passes.size()) + " passes (" +
         m_runtime.executor().lastBuildReport().summary() + ")");
    return {};
}

Result<void> Session::frame() {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    auto t0 = Clock::now();
    auto changes = m_host->frame({m_frame, static_cast<double>(m_frame) / 60.0}, m_pipeline);
    m_callbackMs = msSince(t0);
    if (!changes) return std::unexpected(changes.error());
    if (!changes->empty()) {
        PipelineDesc next = m_pipeline;
        applyFrameChanges(next, *changes);
        GraphDesc graph = buildableGraph(next);
        if (changes->structural()) {
            if (auto r = m_runtime.executor().build(graph, m_options.compile); !r) return r;
            ++m_rebuilds;
            std::string what;
            for (const auto& [pass, on] : changes->enabled) what += (what.empty() ? "" : ", ") + std::string(on ? "enabled '" : "disabled '") + pass + "'";
            for (const auto& [pass, shader] : changes->shaders) what += (what.empty() ? "" : ", ") + ("'" + pass + "' uses " + shader);
            note("frame " + std::to_string(m_frame) + ": " + what + "; " + m_runtime.executor().lastBuildReport().summary());
        } else {
            m_runtime.executor().updateUniforms(graph);
        }
        m_pipeline = std::move(next);
    }
    if (auto r = m_runtime.executor().frame(); !r) return r;
    ++m_frame;
    return {};
}

std::vector<std::string> Session::files() const {
    std::vector<std::string> out = m_pipeline.files;
    for (const auto& f : m_runtime.executor().files()) out.push_back(f);
    return out;
}

}  // namespace rg
