#include "session.h"
#include "session_detail.h"
#include "core/hash.h"
#include "core/read_whole.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

#include <unistd.h>

#include "bake/lightmap.h"
#include "core/names.h"
#include "passes/passes.h"
#include "scene/environment.h"
#include "shaders/lib/exposure_state.h"
#include "core/temp_path.h"

namespace fs = std::filesystem;

namespace rg {

using namespace detail;

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

LuaHostOptions hostOptions(std::vector<PassKindSchema> kinds) {
    LuaHostOptions o;
    o.projectRoot = projectRoot();
    o.searchDirs = {projectRoot() + "/scripts", projectRoot() + "/materials"};
    o.kinds = std::move(kinds);
    return o;
}
}  // namespace

Result<AbsoluteHdr> readAbsoluteHdr(gpu::Executor& executor, const PipelineDesc& pipeline) {
    auto hdr = executor.readback(pipeline.hdr);
    if (!hdr) return std::unexpected(hdr.error());
    auto state = executor.readbackBuffer(pipeline.exposure);
    if (!state) return std::unexpected(state.error());
    RgExposureState s{};
    std::memcpy(&s, state->data(), std::min<size_t>(sizeof s, state->size()));
    AbsoluteHdr out;
    out.ev100 = s.ev100;
    out.exposure = s.exposure;
    out.preExposure = s.preExposure > 0 ? s.preExposure : 1.0f;
    out.image = std::move(*hdr);
    for (size_t i = 0; i < out.image.pixels.size(); ++i)
        if (i % out.image.channels < 3) out.image.pixels[i] /= out.preExposure;
    return out;
}

LuaHostOptions luaHostOptions(const Runtime& runtime) {
    return hostOptions(runtime.kinds().schemas());
}

LuaHostOptions luaHostOptionsWithoutDevice() {
    gpu::PassRegistry registry;
    passes::registerBuiltinPassKinds(registry);
    return hostOptions(registry.schemas());
}

Session::Session(Runtime& runtime, SessionOptions options)
    : m_runtime(runtime), m_options(std::move(options)), m_frame(m_options.firstFrame) {
    // (A fresh runtime's executor: its frame numbers then match the script's ctx.frame.)
    if (m_frame) m_runtime.executor().setFrameNumberBase(m_frame);
}
Session::~Session() {
    // The executor must not keep drawing (or calling back into) a scene that goes away with us,
    // and the frames still in flight draw with its buffers: they finish first.
    // (Also when another session's scene has replaced ours: frames recorded before that drew ours.)
    if (m_scene) {
        if (auto r = m_runtime.executor().finish(); !r)
            std::fprintf(stderr, "rgraph: %s\n", r.error().describe().c_str());
        if (m_runtime.executor().scene() == m_scene.get())
            m_runtime.executor().setScene(nullptr, {});
    }
}

void Session::note(const std::string& line) {
    m_log.push_back(line);
    if (m_options.verbose) std::fprintf(stderr, "rgraph: %s\n", line.c_str());
}

void Session::warn(const std::string& line) {
    m_log.push_back(line);
    if (m_options.verbose || m_options.warnings) std::fprintf(stderr, "rgraph: %s\n", line.c_str());
}

// The pipeline's graph with parameters as uniforms, captures exported, and shader paths that
// exist next to the pipeline script made absolute (shaders/ and the root are searched anyway).
Result<GraphDesc> Session::buildableGraph(const PipelineDesc& p, bool keepMissingShaders) {
    GraphDesc g = graphWithParams(p);
    // Resources declared `only_when` (render_loop.lua's lightmap_specular: while the scene has a
    // baked lightmap and the parameter is on) leave the graph with every access to them when the
    // condition fails, so they cost no attachment traffic (~10 ms of a 1280×720 G-buffer on
    // lavapipe), and the passes that accessed them lose the condition's defines (the reflection
    // then takes the distant probe).
    const gpu::SceneBinding* bound = m_runtime.executor().scene();
    // Whether a resource's or pass's condition holds (`what`: "resource 'NAME'", for errors).
    auto holds = [&](const ResourceDesc::Condition& c, const std::string& origin,
                     const std::string& what) -> Result<bool> {
        const std::string prefix =
            (origin.empty() ? "" : origin + ": ") + what + ": only_when.scene = '";
        bool keep = true;
        for (const std::string& feature : c.sceneFeatures) {
            // "material:NAME" names a material of the pipeline (a misspelt one would drop the
            // resource in every scene, in silence).
            if (feature.starts_with(gpu::SceneBinding::kMaterialFeature)) {
                const std::string model =
                    feature.substr(gpu::SceneBinding::kMaterialFeature.size());
                std::vector<std::string> names;
                for (const MaterialDesc& m : p.materials) names.push_back(m.name);
                if (std::find(names.begin(), names.end(), model) == names.end())
                    return fail(ErrorCode::InvalidInput,
                                prefix + feature + "': the pipeline declares no material '" +
                                    model + "' (it has " + joinQuoted(names) + ")");
            }
            if (!bound) {
                keep = false;  // no scene: no feature
                continue;
            }
            const std::optional<bool> has = bound->feature(feature);
            if (!has)
                return fail(ErrorCode::InvalidInput,
                            prefix + feature + "': the scene has no such feature (it has " +
                                joinQuoted(bound->featureNames()) + ")");
            keep = keep && *has;
        }
        for (const std::string& name : c.params) {
            const ParamDesc* on = p.findParam(name);
            keep = keep && on && on->value.isBool() && on->value.asBool();
        }
        return keep;
    };
    std::vector<std::pair<std::string, std::vector<std::string>>> dropped;  // name, defines
    for (const ResourceDesc& r : g.resources) {
        if (!r.onlyWhen) continue;
        auto keep = holds(*r.onlyWhen, r.origin, "resource '" + r.name + "'");
        if (!keep) return std::unexpected(keep.error());
        if (!*keep) dropped.emplace_back(r.name, r.onlyWhen->defines);
    }
    for (PassDesc& pass : g.passes) {
        if (!pass.onlyWhen) continue;
        auto keep = holds(*pass.onlyWhen, pass.origin, "pass '" + pass.name + "'");
        if (!keep) return std::unexpected(keep.error());
        if (!*keep) pass.enabled = false;
    }
    // A pass that wrote only dropped resources (render_loop.lua's copy of the opaque frame and its
    // mips) has nothing left to do: it leaves with them.
    auto writes = [](const PassDesc& pass) {
        return std::any_of(pass.accesses.begin(), pass.accesses.end(),
                           [](const Access& a) { return usageWrites(a.usage); });
    };
    std::vector<bool> wrote(g.passes.size());
    for (size_t i = 0; i < g.passes.size(); ++i) wrote[i] = writes(g.passes[i]);
    for (const auto& [target, defines] : dropped) {
        std::erase_if(g.resources, [&](const ResourceDesc& r) { return r.name == target; });
        for (auto& pass : g.passes) {
            const size_t before = pass.accesses.size();
            std::erase_if(pass.accesses, [&](const Access& a) { return a.resource == target; });
            if (pass.accesses.size() != before && pass.params.isTable() &&
                pass.params["defines"].isTable()) {
                Value::Table table = pass.params["defines"].asTable();
                for (const auto& d : defines) table.erase(d);
                pass.params.table()["defines"] = Value(table);
            }
        }
    }
    if (!dropped.empty())
        for (size_t i = 0; i < g.passes.size(); ++i)
            if (wrote[i] && !writes(g.passes[i])) g.passes[i].enabled = false;
    // load = "pass": the targets that pass drew first are loaded while it runs, cleared otherwise
    // (the G-buffer after its first phase: scripts/culling.lua).
    for (PassDesc& pass : g.passes)
        for (Access& a : pass.accesses)
            if (!a.loadAfter.empty()) {
                const PassDesc* first = g.findPass(a.loadAfter);
                a.load = first && first->enabled;
            }
    for (auto& r : g.resources) {
        if (!m_options.view.empty() && r.name == "debug_view") r.exported = true;
        for (const auto& c : m_options.captures)
            if (r.name == c) r.exported = true;
        for (const auto& ch : m_channels) {
            for (const auto& t : ch.layout.targets)
                if (r.name == t.name) r.exported = true;
            for (const auto& [_, lc] : ch.byId)
                for (const auto& t : lc.first.targets)
                    if (r.name == t.name) r.exported = true;
            if (r.name == ch.stencil) r.exported = true;
        }
    }
    std::vector<std::string> declared;  // each pass's shader as the script names it
    for (const auto& pass : g.passes)
        declared.push_back(pass.params["shader"].isString() ? pass.params["shader"].asString()
                                                            : "");
    resolveShaderPaths(g, p.file, projectRoot());
    // keepMissingShaders: a shader file that went away since a pass was built with it (deleted,
    // or mid-save) keeps the path it had, so that the executor keeps the pass as it runs and
    // rebuilding others (a switch, a parameter) goes on; a load compiles it anew and reports it
    // missing.
    for (size_t i = 0; i < g.passes.size(); ++i) {
        PassDesc& pass = g.passes[i];
        if (declared[i].empty() || fs::path(declared[i]).is_absolute()) continue;
        const std::string key = pass.origin + "\n" + pass.name + "\n" + declared[i];
        const std::string now = pass.params["shader"].asString();
        if (fs::path(now).is_absolute())
            m_shaderPaths[key] = now;
        else if (auto it = m_shaderPaths.find(key); keepMissingShaders && it != m_shaderPaths.end())
            pass.params.table()["shader"] = Value(it->second);
    }
    return g;
}

Result<std::string> writeLayoutHeaders(const PipelineDesc& pipeline) {
    std::vector<std::pair<std::string, std::string>> headers;  // file name, text
    ContentHash hash;  // over every header: the folder's name
    for (const auto& layout : pipeline.layouts) {
        auto info = analyzeLayout(layout);
        if (!info) return std::unexpected(info.error());
        const std::string glsl = "// Generated by rgraph from layout '" + layout.name +
                                 "'. Do not edit: change the layout in Lua.\n" +
                                 generateGlsl(*info);
        headers.emplace_back("gbuffer_" + layout.name + ".glsl", glsl);
        for (const std::string* part : {&headers.back().first, &headers.back().second})
            hash.str(*part);
    }
    // Every material's pixels decoded by materialId (decals, debug views, the reference).
    auto dispatch = generatePipelineGlsl(pipeline);
    if (!dispatch) return std::unexpected(dispatch.error());
    headers.emplace_back("gbuffer_pipeline.glsl", *dispatch);
    hash.str(*dispatch);
    // Each lighting path's deferred pass (lighting.path_pass).
    for (auto& [fileName, glsl] : generateLightingShaders(pipeline)) {
        hash.str(fileName);
        hash.str(glsl);
        headers.emplace_back(std::move(fileName), std::move(glsl));
    }
    const fs::path dir = fs::path(generatedShaderDir()) / hash.hex();
    std::error_code ec;
    fs::create_directories(dir, ec);
    for (const auto& [fileName, glsl] : headers) {
        const fs::path file = dir / fileName;
        // Rewrite only when it changed, so file times (and hot reload) stay quiet.
        std::ifstream in(file);
        std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (old == glsl) continue;
        const fs::path tmp = tempPathBeside(file.string());
        std::ofstream(tmp) << glsl;
        fs::rename(tmp, file, ec);
        if (ec) return fail(ErrorCode::Io, "cannot write '" + file.string() + "': " + ec.message());
    }
    return dir.string();
}

void useLayoutHeaders(Runtime& runtime, const std::string& dir) {
    // The executor's next build prepares every pass again when the folder is not the one its
    // running build was prepared with.
    runtime.shaders().setGeneratedDir(dir);
}

namespace {

// What the scene holds for the pipeline (ctx.scene): its counts, and its draws per stencil class
// of the pipeline's materials. Fixed while the two stay loaded, so counted once per load (over
// the draws: a frame of a 100 000-node scene would spend a millisecond on it).
FrameContext::SceneFacts sceneFacts(const passes::GpuScene& scene, const PipelineDesc& pipeline) {
    const Scene& s = scene.scene();
    FrameContext::SceneFacts facts;
    facts.draws = static_cast<uint32_t>(scene.draws().size());
    facts.lights = scene.lightCount();
    facts.decals = static_cast<uint32_t>(s.decals.size());
    facts.suns =
        static_cast<uint32_t>(std::count_if(s.lights.begin(), s.lights.end(), [](const Light& l) {
            return l.type == LightType::Directional;
        }));
    facts.probes = static_cast<uint32_t>(s.probes.size());
    facts.lines = static_cast<uint32_t>(scene.lineDraws().size());
    std::map<std::string, std::string> classOf;  // material name -> its stencil class
    for (const auto& m : pipeline.materials)
        if (!m.stencil.empty()) classOf[m.name] = m.stencil;
    for (const auto& d : scene.draws()) {
        const Material& m = s.materials[d.material];
        facts.blended += m.alphaMode == AlphaMode::Blend;
        if (auto it = classOf.find(m.model); it != classOf.end()) ++facts.classes[it->second];
    }
    return facts;
}

// What a frame's changes do to the graph, for the log: "disabled 'decals', 'sky' uses X.frag".
std::string describeStructural(const FrameChanges& changes) {
    std::string what;
    for (const auto& [pass, on] : changes.enabled)
        what +=
            (what.empty() ? "" : ", ") + std::string(on ? "enabled '" : "disabled '") + pass + "'";
    for (const auto& [pass, shader] : changes.shaders)
        what += (what.empty() ? "" : ", ") + ("'" + pass + "' uses " + shader);
    return what;
}

}  // namespace

Result<void> Session::load(const std::string& file) {
    auto t0 = Clock::now();
    // Everything the new pipeline needs is read and checked first; the runtime the running plan
    // uses (its scene, its layout headers, its captures) is touched only after that, by a
    // rollback that puts each back unless the new plan is built.
    auto host = std::make_unique<LuaHost>(luaHostOptions(m_runtime));
    auto pipeline = host->load(file);
    if (!pipeline) return std::unexpected(pipeline.error());
    auto headers = writeLayoutHeaders(*pipeline);
    if (!headers) return std::unexpected(headers.error());
    std::unique_ptr<passes::GpuScene> scene;
    double sceneMs = 0;
    if (hasScenePass(*pipeline)) {
        auto s0 = Clock::now();
        auto loaded = loadScene(*pipeline);
        if (!loaded) return std::unexpected(loaded.error());
        scene = std::move(*loaded);
        sceneMs = std::chrono::duration<double, std::milli>(Clock::now() - s0).count();
    } else if (!m_options.scene.empty()) {
        return fail(ErrorCode::InvalidInput,
                    "--scene: pipeline '" + file + "' has no scene pass to draw it");
    }
    if (!m_options.view.empty()) {
        // The view's passes (rg.view; scripts/views.lua) join the pipeline's.
        const ViewFacts facts = scene ? viewFactsOf(scene->scene()) : ViewFacts{};
        auto viewed = host->addView(m_options.view, *pipeline, scene ? &facts : nullptr);
        if (!viewed) return std::unexpected(viewed.error());
        *pipeline = std::move(*viewed);
    }
    // Parameters after the view: the pipeline a view returns is declared anew, with the
    // parameters' defaults (a view of the AO ignored --set ao_radius before).
    // paramsIfDeclared join where the pipeline declares them and params do not set them.
    std::map<std::string, Value> values = m_options.params;
    for (const auto& [name, value] : m_options.paramsIfDeclared)
        if (pipeline->findParam(name)) values.emplace(name, value);
    for (const auto& [name, value] : values) {
        auto checked = checkedParam(*pipeline, name, value);
        if (!checked) return std::unexpected(checked.error());
        pipeline->findParam(name)->value = *checked;
    }
    if (scene)
        if (auto r = applySceneSettings(*scene, *pipeline); !r) return r;
    auto channels = channelCapturesOf(*pipeline, m_options.captures);
    if (!channels) return std::unexpected(channels.error());

    // From here the runtime is pointed at the new pipeline; until commit, leaving this function
    // points it back at the previous one, which keeps rendering.
    struct Rollback {
        Session& s;
        std::string headers = s.m_runtime.shaders().options().generatedDir;
        const gpu::SceneBinding* scene = s.m_runtime.executor().scene();
        std::function<void(uint32_t)> hook = s.m_sceneUpdate;
        std::vector<ChannelCapture> channels = s.m_channels;
        bool sceneChanged = false, committed = false;
        ~Rollback() {
            if (committed) return;
            useLayoutHeaders(s.m_runtime, headers);
            s.m_sceneUpdate = hook;
            s.m_channels = channels;
            if (sceneChanged) s.m_runtime.executor().setScene(scene, hook);
        }
    } rollback{*this};
    useLayoutHeaders(m_runtime, *headers);
    m_channels = std::move(*channels);
    // The new scene is what the build prepares against.
    m_sceneUpdate = {};
    if (scene) {
        passes::GpuScene* raw = scene.get();
        const uint32_t w = m_options.compile.outputWidth, h = m_options.compile.outputHeight;
        m_sceneUpdate = [raw, w, h](uint32_t slot) { raw->updateFrame(slot, w, h); };
    }
    if (scene || rollback.scene) {
        m_runtime.executor().setScene(scene.get(), m_sceneUpdate);
        rollback.sceneChanged = true;
    }
    m_runtime.executor().setOnceCache(m_options.onceCache);
    // The first frame's rg.frame runs now, on the new pipeline and scene, and the plan is built
    // with what it changes (frame() then takes that frame as done): passes it switches off (no
    // decals, no blended draws, no sun) are never prepared, and the transient heaps are placed
    // for the passes that run, not for everything the script declares, then kept at that size
    // by the rebuilds that follow.
    // Overrides of parameters and passes the new script no longer has are dropped (kept as they
    // are if the load fails).
    FrameChanges overrides = m_overrides;
    for (auto it = overrides.params.begin(); it != overrides.params.end();) {
        if (!pipeline->findParam(it->first)) {
            it = overrides.params.erase(it);
        } else if (auto checked = checkedParam(*pipeline, it->first, it->second); checked) {
            (it++)->second = *checked;
        } else {
            note("dropped the override of '" + it->first + "': " + checked.error().message);
            it = overrides.params.erase(it);
        }
    }
    std::erase_if(overrides.enabled,
                  [&](const auto& o) { return !pipeline->graph.findPass(o.first); });
    auto tc = Clock::now();
    std::optional<FrameContext::SceneFacts> facts;
    if (scene) facts = sceneFacts(*scene, *pipeline);
    // A new script's switches start afresh (a line removed from rg.frame takes its switch away).
    std::map<std::string, bool> switches;
    auto first = frameChanges(*host, frameContext(facts), *pipeline, overrides, switches);
    if (!first) return std::unexpected(first.error());
    const double firstCallbackMs = msSince(tc);
    applyFrameChanges(*pipeline, *first);
    const std::string firstChanges = describeStructural(*first);
    // The executor keeps its previous build when this one fails.
    auto graph = buildableGraph(*pipeline, /*keepMissingShaders=*/false);
    if (!graph) return std::unexpected(graph.error());
    if (auto r = m_runtime.executor().build(*graph, m_options.compile); !r) return r;
    rollback.committed = true;
    // The previous scene may still be in use by frames in flight: retire it through the
    // deletion queue.
    if (m_scene) {
        std::shared_ptr<passes::GpuScene> retired(std::move(m_scene));
        m_runtime.gpu().deferDestroy([retired]() mutable { retired.reset(); });
    }
    // What the scene was made from: its files' contents and the scene arguments.
    std::string sceneKey;
    if (scene) {
        for (const auto& [k, v] : m_options.sceneArgs) sceneKey += k + "=" + v + ";";
        sceneKey += "environment=" + m_options.environment + ";";
        if (m_options.sceneData)
            sceneKey +=
                "memory=" + std::to_string(reinterpret_cast<uintptr_t>(m_options.sceneData.get())) +
                ";";
        for (const auto& f : scene->scene().files) {
            std::ifstream in(f, std::ios::binary);
            std::string bytes;
            if (in) readWhole(in, bytes);
            ContentHash h;
            h.str(bytes);
            sceneKey += f + ":" + h.hex() + ";";
        }
    }
    m_scene = std::move(scene);
    m_sceneFacts = std::move(facts);
    m_sceneLoadMs = sceneMs;
    // History (exposure, previous frames, a reference accumulation) carries over a reload of the
    // same pipeline drawing the same scene, not to another pipeline or a changed scene.
    if (file != m_pipeline.file || sceneKey != m_sceneKey)
        if (auto r = m_runtime.executor().resetPersistent(); !r) return r;
    m_sceneKey = sceneKey;
    m_host = std::move(host);
    m_pipeline = std::move(*pipeline);
    m_overrides = std::move(overrides);
    m_switches = std::move(switches);
    m_rebuilds = 0;
    ++m_loads;
    m_framePrepared = m_frame;
    m_callbackMs = firstCallbackMs;
    m_loadMs = msSince(t0);
    note("loaded " + file + ": " + std::to_string(m_runtime.executor().plan().passes.size()) +
         " passes (" + m_runtime.executor().lastBuildReport().summary() + ")" +
         (firstChanges.empty()
              ? std::string()
              : "; frame " + std::to_string(m_frame) + "'s rg.frame: " + firstChanges));
    for (const auto& line : m_pipeline.notes) note(line);
    return {};
}

FrameContext Session::frameContext(const std::optional<FrameContext::SceneFacts>& facts) const {
    return FrameContext{m_frame, static_cast<double>(m_frame) / 60.0, facts,
                        m_options.compile.outputWidth, m_options.compile.outputHeight};
}

Result<FrameChanges> Session::frameChanges(LuaHost& host, const FrameContext& ctx,
                                           const PipelineDesc& pipeline,
                                           const FrameChanges& overrides,
                                           std::map<std::string, bool>& switches) {
    auto changes = host.frame(ctx, pipeline);
    if (!changes) return changes;
    if (m_options.frameHook) {
        PipelineDesc seen = pipeline;
        applyFrameChanges(seen, *changes);
        auto more = m_options.frameHook(ctx, seen);
        if (!more) return std::unexpected(more.error());
        for (const auto& [k, v] : more->params) changes->params[k] = v;
        for (const auto& [k, v] : more->enabled) changes->enabled[k] = v;
        for (const auto& [k, v] : more->automatic) changes->automatic[k] = v;
        for (const auto& [k, v] : more->shaders) changes->shaders[k] = v;
    }
    for (const auto& [k, v] : changes->enabled) switches[k] = v;
    for (const auto& [k, v] : switches) changes->enabled.emplace(k, v);  // earlier frames'
    for (const auto& [k, v] : overrides.params) changes->params[k] = v;
    for (const auto& [k, v] : overrides.enabled) changes->enabled[k] = v;
    for (const auto& [k, v] : changes->automatic) changes->enabled.emplace(k, v);
    changes->automatic.clear();
    // A pass left as it is is no change (no rebuild).
    std::erase_if(changes->enabled, [&](const auto& e) {
        const PassDesc* p = pipeline.graph.findPass(e.first);
        return p && p->enabled == e.second;
    });
    std::erase_if(changes->shaders, [&](const auto& e) {
        const PassDesc* p = pipeline.graph.findPass(e.first);
        return p && p->params["shader"].asString() == e.second;
    });
    return changes;
}

Result<void> Session::frame(VkCommandBuffer hostCmd) {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    auto t0 = Clock::now();
    Result<FrameChanges> changes = FrameChanges{};
    std::map<std::string, bool> switches = m_switches;
    if (m_framePrepared == m_frame) {
        // The load ran this frame's rg.frame already and built its plan with what it changed;
        // overrides set since were applied when they were set (setOverride, setPassOverride).
        m_framePrepared.reset();
    } else {
        changes =
            frameChanges(*m_host, frameContext(m_sceneFacts), m_pipeline, m_overrides, switches);
        m_callbackMs = msSince(t0);
    }
    // A parameter restated at the value it has (rg.frame and the overrides restate theirs every
    // frame) changes nothing: no pipeline copied and no graph resolved for it.
    if (changes)
        std::erase_if(changes->params, [&](const auto& e) {
            const ParamDesc* d = m_pipeline.findParam(e.first);
            return d && d->value == e.second;
        });

    // A callback that fails, or a change that cannot be built, is refused whole: the plan as it
    // was renders this frame, and the caller hears why.
    Result<void> applied = !changes           ? Result<void>(std::unexpected(changes.error()))
                           : changes->empty() ? Result<void>{}
                                              : apply(*changes);
    if (applied) m_switches = std::move(switches);
    if (!applied && changes) {
        Error e = applied.error();
        e.message = "frame " + std::to_string(m_frame) + ": rg.frame's changes (" +
                    describeStructural(*changes) +
                    ") cannot be built; the plan stays as it was: " + e.message;
        applied = std::unexpected(e);
    }
    // Parameters the pipeline maps onto the scene (rg.param's `scene`): fields of the scene's
    // GPU data, so switching them rebuilds nothing. Checked at load, so only a value rg.frame
    // set can fail here.
    if (m_scene)
        if (auto r = applySceneSettings(*m_scene, m_pipeline); !r && applied) applied = r;
    if (m_scene) m_scene->setTime(static_cast<double>(m_frame) / 60.0);  // its camera's path
    if (m_cutRequested || (changes && changes->cut)) {  // a camera cut: no history carries over
        m_cutRequested = false;
        if (auto r = m_runtime.executor().resetPersistent(); !r) return r;
        if (m_scene) m_scene->cut();
    }
    if (auto r = m_runtime.executor().frame(hostCmd); !r) return r;
    ++m_frame;
    return applied;
}

Result<void> Session::apply(const FrameChanges& changes) {
    PipelineDesc next = m_pipeline;
    applyFrameChanges(next, changes);
    auto built = buildableGraph(next, /*keepMissingShaders=*/true);
    if (!built) return std::unexpected(built.error());
    const GraphDesc& graph = *built;
    // A parameter some pass compiles in (switches) rebuilds that pass, as a shader swap does.
    std::vector<std::string> switched;
    for (const auto& [name, value] : changes.params)
        if (isSwitch(m_pipeline, name)) {
            const ParamDesc* before = m_pipeline.findParam(name);
            if (!before || !(before->value == value)) switched.push_back(name);
        }
    if (changes.structural() || !switched.empty()) {
        auto tb = Clock::now();
        // The executor keeps its previous build when this one fails, and m_pipeline stays.
        if (auto r = m_runtime.executor().build(graph, m_options.compile); !r) return r;
        const double buildMs = msSince(tb);
        ++m_rebuilds;
        std::string what = describeStructural(changes);
        for (const auto& name : switched) {
            const Value& v = next.findParam(name)->value;
            what += (what.empty() ? "" : ", ") + ("switch " + name + " = " +
                                                  (v.isString() ? v.asString()
                                                   : v.isBool() ? (v.asBool() ? "true" : "false")
                                                                : std::to_string(v.asNumber())));
        }
        char ms[32];
        std::snprintf(ms, sizeof ms, "%.2f ms", buildMs);
        note("frame " + std::to_string(m_frame) + ": " + what + "; recompiled in " + ms + ": " +
             m_runtime.executor().lastBuildReport().summary());
    } else {
        m_runtime.executor().updateUniforms(graph);
    }
    m_pipeline = std::move(next);
    return {};
}

Result<void> Session::setOverride(const std::string& param, const Value& value) {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    auto checked = checkedParam(m_pipeline, param, value);
    if (!checked) return std::unexpected(checked.error());
    // Applied now, through the path rg.frame's changes take: a switch whose value cannot be built
    // is refused with the build's reason, and nothing changes.
    FrameChanges change;
    change.params[param] = *checked;
    if (auto r = apply(change); !r)
        return fail(r.error().code,
                    "params." + param +
                        ": this value cannot be built, nothing changed: " + r.error().message);
    m_overrides.params[param] = *checked;
    return {};
}

Result<void> Session::setNodeTransform(const std::string& name, const glm::mat4& world) {
    if (!m_scene) return fail(ErrorCode::InvalidInput, "setTransform: no scene is loaded");
    return m_scene->setNodeTransform(name, world);
}

Result<void> Session::setPassOverride(const std::string& pass, bool enabled) {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    const PassDesc* desc = m_pipeline.graph.findPass(pass);
    if (!desc) {
        std::vector<std::string> names;
        for (const auto& d : m_pipeline.graph.passes) names.push_back(d.name);
        return fail(ErrorCode::NotFound, "passes." + pass + ": the pipeline has no pass '" + pass +
                                             "'" + suggestion(pass, names));
    }
    // Applied now: a switch that leaves the graph unbuildable (a kept pass reads what only this
    // one writes) is refused with the compiler's reason, and nothing changes.
    if (desc->enabled != enabled) {
        FrameChanges change;
        change.enabled[pass] = enabled;
        if (auto r = apply(change); !r)
            return fail(ErrorCode::InvalidInput, "passes." + pass + ": cannot be switched " +
                                                     (enabled ? "on" : "off") +
                                                     ", nothing changed: " + r.error().message);
    }
    m_overrides.enabled[pass] = enabled;
    return {};
}

void Session::carryOverrides(const FrameChanges& overrides) { m_overrides = overrides; }

Result<void> Session::addCapture(const std::string& name) {
    if (std::find(m_options.captures.begin(), m_options.captures.end(), name) !=
        m_options.captures.end())
        return {};
    m_options.captures.push_back(name);
    if (!m_host) return {};
    if (auto r = load(m_pipeline.file); !r) {
        m_options.captures.pop_back();  // the load left everything as it was; so does this
        return r;
    }
    return {};
}

std::vector<std::string> Session::files() const {
    std::vector<std::string> out = m_pipeline.files;
    if (m_scene)
        for (const auto& f : m_scene->scene().files) out.push_back(f);
    for (const auto& f : m_runtime.executor().files()) out.push_back(f);
    return out;
}

}  // namespace rg
