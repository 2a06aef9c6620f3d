#include "session.h"

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

Result<AbsoluteHdr> readAbsoluteHdr(gpu::Executor& executor, const PipelineDesc& pipeline) {
    auto hdr = executor.readback(pipeline.hdr);
    if (!hdr) return std::unexpected(hdr.error());
    auto state = executor.readbackBuffer(pipeline.exposure);
    if (!state) return std::unexpected(state.error());
    float s[4] = {};
    std::memcpy(s, state->data(), std::min<size_t>(sizeof s, state->size()));
    AbsoluteHdr out;
    out.ev100 = s[0];
    out.exposure = s[1];
    out.preExposure = s[2] > 0 ? s[2] : 1.0f;
    out.image = std::move(*hdr);
    for (size_t i = 0; i < out.image.pixels.size(); ++i)
        if (i % out.image.channels < 3) out.image.pixels[i] /= out.preExposure;
    return out;
}

LuaHostOptions luaHostOptions(const Runtime& runtime) { return hostOptions(runtime.kinds().schemas()); }

LuaHostOptions luaHostOptionsWithoutDevice() {
    gpu::PassRegistry registry;
    passes::registerBuiltinPassKinds(registry);
    return hostOptions(registry.schemas());
}

Session::Session(Runtime& runtime, SessionOptions options) : m_runtime(runtime), m_options(std::move(options)) {}
Session::~Session() {
    // The executor must not keep drawing (or calling back into) a scene that goes away with us,
    // and the frames still in flight draw with its buffers: they finish first.
    // (Also when another session's scene has replaced ours: frames recorded before that drew ours.)
    if (m_scene) {
        if (auto r = m_runtime.executor().finish(); !r) std::fprintf(stderr, "rgraph: %s\n", r.error().describe().c_str());
        if (m_runtime.executor().scene() == m_scene.get()) m_runtime.executor().setScene(nullptr, 0, {});
    }
}

void Session::note(const std::string& line) {
    m_log.push_back(line);
    if (m_options.verbose) std::fprintf(stderr, "rgraph: %s\n", line.c_str());
}

namespace {

const std::vector<std::string> kViews = {"normals", "basecolor", "smoothness", "metalmask", "materialid",
                                         "reflectance", "ao", "emissive"};

// The debug view's fullscreen pass: `reads`, then the view target it writes; `params` its shader
// and uniforms.
void addViewPass(GraphDesc& g, std::vector<Access> reads, Value::Table params) {
    PassDesc pass;
    pass.name = "debug_view";
    pass.kind = "fullscreen";
    pass.accesses = std::move(reads);
    pass.accesses.push_back({"debug_view", Usage::ColorAttachment});
    pass.params = Value(std::move(params));
    g.passes.push_back(std::move(pass));
}

// A view that needs `resource`: an error naming what provides it when the pipeline lacks it.
Result<void> needs(const GraphDesc& g, const std::string& view, const std::string& resource, const std::string& hint) {
    if (g.findResource(resource)) return {};
    return fail(ErrorCode::InvalidInput, "--view " + view + ": the pipeline has no '" + resource + "' (" + hint + ")");
}

// Appends the debug view's passes: a fullscreen decode of the disney G-buffer, or for the
// stencil one colour per stencil class drawn with that class's stencil test.
Result<void> addDebugView(GraphDesc& g, const PipelineDesc& p, const std::string& view, const Scene* scene) {
    for (const char* r : {"GB0", "GB1", "GB2", "GB3", "depth"})
        if (!g.findResource(r))
            return fail(ErrorCode::InvalidInput, "--view " + view + ": the pipeline has no '" + r +
                                                     "' (views read the disney G-buffer GB0..GB3 and depth)");
    ResourceDesc out;
    out.name = "debug_view";
    out.texture.format = Format::RGBA8Unorm;
    out.exported = true;
    g.resources.push_back(out);
    // shadow:LIGHT — that local light's shadow maps this frame (a spot's one, a cube's six).
    if (view.starts_with("shadow:")) {
        const std::string name = view.substr(7);
        if (auto r = needs(g, view, "local_shadow", "require \"shadows\""); !r) return r;
        std::string shadowed;
        int index = -1;
        for (size_t i = 0; scene && i < scene->lights.size(); ++i) {
            const Light& l = scene->lights[i];
            if (!l.castShadows) continue;
            shadowed += (shadowed.empty() ? "'" : ", '") + l.name + "'";
            if (l.name == name) index = static_cast<int>(i);
        }
        if (index < 0)
            return fail(ErrorCode::InvalidInput, "--view " + view + ": the scene has no light '" + name + "' that casts shadows (" +
                                                     (shadowed.empty() ? std::string("none does: give a local light shadow = true") : "those that do: " + shadowed) + ")");
        addViewPass(g, {{"local_shadow", Usage::Sampled}},
                    {{"shader", Value("passes/local_shadow_view.frag")},
                     {"uniforms", Value(Value::Table{{"light", Value(static_cast<double>(index))}})}});
        return {};
    }
    if (view == "stencil") {
        PassDesc clear;
        clear.name = "debug_view_clear";
        clear.kind = "clear";
        clear.type = PassType::Transfer;
        clear.accesses = {{"debug_view", Usage::CopyDst}};
        clear.params = Value(Value::Table{{"value", Value(Value::List{0.0, 0.0, 0.0, 1.0})}});
        g.passes.push_back(clear);
        static const double colors[][3] = {{0.9, 0.2, 0.2}, {0.2, 0.8, 0.2}, {0.2, 0.4, 0.9}, {0.9, 0.8, 0.2},
                                           {0.8, 0.3, 0.9}, {0.2, 0.9, 0.9}, {0.9, 0.5, 0.1}, {0.6, 0.6, 0.6}};
        for (size_t i = 0; i < p.stencilClasses.size(); ++i) {
            const auto& c = p.stencilClasses[i];
            PassDesc pass;
            pass.name = "debug_view_" + c.name;
            pass.kind = "fullscreen";
            pass.accesses = {{"depth", Usage::DepthStencilRead}, {"debug_view", Usage::ColorAttachment, /*load=*/true}};
            const double* rgb = colors[i % 8];
            pass.params = Value(Value::Table{
                {"shader", Value("passes/stencil_view.frag")},
                {"stencil", Value(Value::Table{{"ref", Value(static_cast<double>(c.value))}, {"mask", Value(255.0)}, {"compare", Value("equal")}})},
                {"uniforms", Value(Value::Table{{"class_color", Value(Value::List{rgb[0], rgb[1], rgb[2], 1.0})}})}});
            g.passes.push_back(pass);
        }
        return {};
    }
    if (view == "lights") {
        if (auto r = needs(g, view, "light_tiles", "require \"lighting\" and light its passes with lighting.tiled"); !r) return r;
        addViewPass(g, {{"light_tiles", Usage::StorageRead}, {"depth", Usage::Sampled}},
                    {{"shader", Value("passes/light_count_view.frag")}, {"defines", Value(Value::Table{{"RG_LIGHT_TILES", Value(true)}})}});
        return {};
    }
    if (view == "ssr" || view == "ssr_confidence") {
        if (auto r = needs(g, view, "ssr", "require \"ssr\""); !r) return r;
        if (auto r = needs(g, view, "exposure", "post.exposure_state(): the reflection is in nits"); !r) return r;
        addViewPass(g, {{"ssr", Usage::Sampled}, {"exposure", Usage::StorageRead}},
                    {{"shader", Value("passes/ssr_view.frag")}, {"uniforms", Value(Value::Table{{"view", Value(view == "ssr" ? 0.0 : 1.0)}})}});
        return {};
    }
    if (view == "reflection") {
        if (auto r = needs(g, view, "reflection", "require \"reflections\""); !r) return r;
        if (auto r = needs(g, view, "exposure", "post.exposure_state(): the reflection is in nits"); !r) return r;
        addViewPass(g, {{"reflection", Usage::Sampled}, {"exposure", Usage::StorageRead}},
                    {{"shader", Value("passes/ssr_view.frag")}, {"bind", Value(Value::Table{{"ssr", Value("reflection")}})},
                     {"uniforms", Value(Value::Table{{"view", Value(2.0)}})}});
        return {};
    }
    if (view == "probes") {
        addViewPass(g, {{"depth", Usage::Sampled}}, {{"shader", Value("passes/probe_view.frag")}});
        return {};
    }
    if (view == "ssao") {
        if (auto r = needs(g, view, "ssao", "require \"ao\""); !r) return r;
        addViewPass(g, {{"ssao", Usage::Sampled}}, {{"shader", Value("passes/ssao_view.frag")}});
        return {};
    }
    if (view == "cascades" || view == "shadow") {
        for (const char* r : {"sun_shadow0", "sun_cascades"})
            if (auto n = needs(g, view, r, "require \"shadows\""); !n) return n;
        // The maps, one per cascade (scripts/shadows.lua): sun_shadow0 ..
        std::vector<Access> maps;
        while (maps.size() < 4 && g.findResource("sun_shadow" + std::to_string(maps.size())))
            maps.push_back({"sun_shadow" + std::to_string(maps.size()), Usage::Sampled});
        Value::Table defines{{"RG_SUN_CASCADES", Value(static_cast<double>(maps.size()))}};
        if (view == "shadow") {
            addViewPass(g, maps, {{"shader", Value("passes/shadow_map_view.frag")}, {"defines", Value(defines)}});
        } else {
            std::vector<Access> reads{{"GB0", Usage::Sampled}, {"depth", Usage::Sampled}, {"sun_cascades", Usage::UniformRead}};
            reads.insert(reads.end(), maps.begin(), maps.end());
            addViewPass(g, reads, {{"shader", Value("passes/cascade_view.frag")}, {"defines", Value(defines)}});
        }
        return {};
    }
    // lightmap / sgN: the G-buffer pass writes the baked lightmap — the irradiance at the shaded
    // normal, or lobe N's amplitude — as the emission (RG_LIGHTMAP_VIEW), shown in colour.
    if (view == "lightmap" || (view.size() > 2 && view.starts_with("sg") && view.find_first_not_of("0123456789", 2) == std::string::npos)) {
        const Lightmap* lm = scene ? scene->bakedLightmap.get() : nullptr;
        if (!lm)
            return fail(ErrorCode::InvalidInput, "--view " + view + ": the scene has no baked lightmap (declare scene.lightmap; the pipeline's "
                                                                     "lightmap parameter must be on)");
        int what = 0;
        if (view != "lightmap") {
            const int lobe = std::atoi(view.c_str() + 2);
            if (lobe < 0 || size_t(lobe) >= lm->axes.size())
                return fail(ErrorCode::InvalidInput, "--view " + view + ": the lightmap has lobes sg0 .. sg" + std::to_string(lm->axes.size() - 1));
            what = lobe + 1;
        }
        bool found = false;
        for (PassDesc& pass : g.passes)
            if (pass.name == "gbuffer") {
                Value::Table params = pass.params.isTable() ? pass.params.asTable() : Value::Table{};
                Value::Table defines = params["defines"].isTable() ? params["defines"].asTable() : Value::Table{};
                defines["RG_LIGHTMAP_VIEW"] = Value(static_cast<double>(what + 1));
                params["defines"] = Value(defines);
                pass.params = Value(params);
                found = true;
            }
        if (!found) return fail(ErrorCode::InvalidInput, "--view " + view + ": the pipeline has no 'gbuffer' scene pass");
        addViewPass(g, {{"GB0", Usage::Sampled}, {"GB1", Usage::Sampled}, {"GB2", Usage::Sampled}, {"GB3", Usage::Sampled}, {"depth", Usage::Sampled}},
                    {{"shader", Value("passes/debug_view.frag")}, {"uniforms", Value(Value::Table{{"view", Value(8.0)}})}});
        return {};
    }
    auto it = std::find(kViews.begin(), kViews.end(), view);
    if (it == kViews.end()) {
        std::string all = "'stencil', 'lights', 'ssao', 'ssr', 'ssr_confidence', 'reflection', 'probes', 'cascades', 'shadow', 'shadow:LIGHT', "
                          "'lightmap', 'sgN'";
        for (const auto& v : kViews) all += ", '" + v + "'";
        return fail(ErrorCode::InvalidInput, "--view: unknown view '" + view + "'; expected one of: " + all);
    }
    Value::Table params{{"shader", Value("passes/debug_view.frag")},
                        {"uniforms", Value(Value::Table{{"view", Value(static_cast<double>(it - kViews.begin()))}})}};
    addViewPass(g, {{"GB0", Usage::Sampled}, {"GB1", Usage::Sampled}, {"GB2", Usage::Sampled}, {"GB3", Usage::Sampled}, {"depth", Usage::Sampled}},
                std::move(params));
    return {};
}

}  // namespace

// The pipeline's graph with parameters as uniforms, captures exported, and shader paths that
// exist next to the pipeline script made absolute (shaders/ and the root are searched anyway).
GraphDesc Session::buildableGraph(const PipelineDesc& p, bool keepMissingShaders) {
    GraphDesc g = graphWithParams(p);
    // The lightmap's specular target (render_loop.lua's `lightmap_specular`, which the G-buffer's
    // generated shaders know by name) exists only while the scene has a baked lightmap: without
    // one, the target and every access to it leave the graph, so it costs no attachment traffic
    // (~10 ms of a 1280×720 G-buffer on lavapipe).
    // The same when the pipeline's lightmap_specular parameter is off: then the passes that read it
    // lose its define (RG_LIGHTMAP_SPECULAR) too and reflect the distant probe.
    const passes::GpuScene* gpuScene = m_runtime.executor().scene();
    const ParamDesc* specular = p.findParam("lightmap_specular");
    const bool specularOff = specular && specular->value.isBool() && !specular->value.asBool();
    if (!gpuScene || !gpuScene->hasLightmap() || specularOff) {
        const std::string target = "lightmap_specular";
        std::erase_if(g.resources, [&](const ResourceDesc& r) { return r.name == target; });
        for (auto& pass : g.passes) {
            const size_t before = pass.accesses.size();
            std::erase_if(pass.accesses, [&](const Access& a) { return a.resource == target; });
            if (pass.accesses.size() != before && pass.params.isTable() && pass.params["defines"].isTable()) {
                Value::Table defines = pass.params["defines"].asTable();
                defines.erase("RG_LIGHTMAP_SPECULAR");
                pass.params.table()["defines"] = Value(defines);
            }
        }
    }
    if (!m_options.view.empty()) {  // checked in load()
        const passes::GpuScene* scene = m_runtime.executor().scene();
        (void)addDebugView(g, p, m_options.view, scene ? &scene->scene() : nullptr);
    }
    for (auto& r : g.resources) {
        for (const auto& c : m_options.captures)
            if (r.name == c) r.exported = true;
        for (const auto& ch : m_channels)
            for (const auto& t : ch.layout.targets)
                if (r.name == t.name) r.exported = true;
    }
    std::vector<std::string> declared;  // each pass's shader as the script names it
    for (const auto& pass : g.passes) declared.push_back(pass.params["shader"].isString() ? pass.params["shader"].asString() : "");
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
        if (fs::path(now).is_absolute()) m_shaderPaths[key] = now;
        else if (auto it = m_shaderPaths.find(key); keepMissingShaders && it != m_shaderPaths.end())
            pass.params.table()["shader"] = Value(it->second);
    }
    return g;
}

Result<std::string> writeLayoutHeaders(const PipelineDesc& pipeline) {
    std::vector<std::pair<std::string, std::string>> headers;  // file name, text
    uint64_t hash = 1469598103934665603ull;  // FNV-1a over every header: the folder's name
    for (const auto& layout : pipeline.layouts) {
        auto info = analyzeLayout(layout);
        if (!info) return std::unexpected(info.error());
        const std::string glsl = "// Generated by rgraph from layout '" + layout.name + "'. Do not edit: change the layout in Lua.\n" +
                                 generateGlsl(*info);
        headers.emplace_back("gbuffer_" + layout.name + ".glsl", glsl);
        for (const std::string* part : {&headers.back().first, &headers.back().second})
            for (unsigned char c : *part) hash = (hash ^ c) * 1099511628211ull;
    }
    // Every material's pixels decoded by materialId (decals, debug views, the reference).
    auto dispatch = generatePipelineGlsl(pipeline);
    if (!dispatch) return std::unexpected(dispatch.error());
    headers.emplace_back("gbuffer_pipeline.glsl", *dispatch);
    for (unsigned char c : *dispatch) hash = (hash ^ c) * 1099511628211ull;
    char name[17];
    std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(hash));
    const fs::path dir = fs::path(generatedShaderDir()) / name;
    std::error_code ec;
    fs::create_directories(dir, ec);
    for (const auto& [fileName, glsl] : headers) {
        const fs::path file = dir / fileName;
        // Rewrite only when it changed, so file times (and hot reload) stay quiet.
        std::ifstream in(file);
        std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (old == glsl) continue;
        const fs::path tmp = file.string() + ".tmp" + std::to_string(::getpid());
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

// One `--capture gbuffer.X` / `LAYOUT.X` as an image: each pixel decoded on the CPU with its
// material's layout (by its materialId), NaN where that material has no such channel.
Result<Image> Session::channelImage(const ChannelCapture& ch) const {
    auto info = analyzeLayout(ch.layout);
    if (!info) return std::unexpected(info.error());
    std::vector<Image> targets;
    for (const auto& t : ch.layout.targets) {
        auto img = m_runtime.executor().readback(t.name);
        if (!img) return std::unexpected(img.error());
        targets.push_back(std::move(*img));
    }
    // Each pixel decoded with its material's layout (by materialId), else with ch.layout.
    struct Decoder {
        LayoutInfo info;
        std::vector<Image*> targets;
        int index = -1;
    };
    std::map<std::string, Image> extra;  // targets the id layout does not have
    auto decoderFor = [&](const LayoutDesc& l, const std::string& channel) -> Result<Decoder> {
        auto li = analyzeLayout(l);
        if (!li) return std::unexpected(li.error());
        Decoder d{*li, {}, li->find(channel)};
        for (const auto& t : l.targets) {
            auto it = std::find_if(ch.layout.targets.begin(), ch.layout.targets.end(), [&](auto& x) { return x.name == t.name; });
            if (it != ch.layout.targets.end()) {
                d.targets.push_back(&targets[static_cast<size_t>(it - ch.layout.targets.begin())]);
                continue;
            }
            if (!extra.count(t.name)) {
                auto img = m_runtime.executor().readback(t.name);
                if (!img) return std::unexpected(img.error());
                extra[t.name] = std::move(*img);
            }
            d.targets.push_back(&extra[t.name]);
        }
        return d;
    };
    auto main = decoderFor(ch.layout, ch.channel);
    if (!main) return std::unexpected(main.error());
    std::map<uint32_t, Decoder> byId;
    for (const auto& [id, lc] : ch.byId) {
        auto d = decoderFor(lc.first, lc.second);
        if (!d) return std::unexpected(d.error());
        byId.emplace(id, std::move(*d));
    }
    const int idIndex = main->info.find("materialId");
    const ChannelDesc& desc = main->index >= 0 ? main->info.channelDesc(static_cast<size_t>(main->index))
                                               : byId.begin()->second.info.channelDesc(static_cast<size_t>(byId.begin()->second.index));
    const bool integer = desc.encoding == Encoding::Uint;
    const uint32_t comps = valueComponents(desc);
    Image out(targets[0].width, targets[0].height, comps);
    auto decode = [&](const Decoder& d, uint32_t x, uint32_t y) {
        std::vector<TexelValue> texels(d.targets.size());
        for (size_t t = 0; t < d.targets.size(); ++t)
            texels[t] = texelFromFloats(d.info.desc.targets[t].format, &d.targets[t]->pixels[(size_t(y) * out.width + x) * d.targets[t]->channels],
                                        d.targets[t]->channels);
        return unpackTexel(d.info, texels);
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const Decoder* d = &*main;
            if (!byId.empty() && idIndex >= 0) {
                auto it = byId.find(decode(*main, x, y)[static_cast<size_t>(idIndex)].u[0]);
                d = it == byId.end() ? nullptr : &it->second;
            }
            if (!d || d->index < 0) {
                for (uint32_t c = 0; c < comps; ++c) out.at(x, y, c) = nan;  // its material has no such channel
                continue;
            }
            auto values = decode(*d, x, y);
            const ChannelValue& v = values[static_cast<size_t>(d->index)];
            for (uint32_t c = 0; c < comps; ++c) out.at(x, y, c) = integer ? static_cast<float>(v.u[c]) : v.v[c];
        }
    return out;
}

const Scene* Session::scene() const { return m_scene ? &m_scene->scene() : nullptr; }

namespace {

// A value for parameter `name` of `pipeline`, checked against its type and range: what --set,
// the golden tests' params and `rgraph serve`'s controls all go through.
Result<Value> checkedParam(const PipelineDesc& pipeline, const std::string& name, const Value& value) {
    const ParamDesc* p = pipeline.findParam(name);
    if (!p) {
        std::vector<std::string> names;
        for (const auto& d : pipeline.params) names.push_back(d.name);
        return fail(ErrorCode::NotFound, "params." + name + ": the pipeline has no parameter '" + name + "'" + suggestion(name, names));
    }
    auto checked = checkParamValue(*p, value);
    if (!checked) return fail(ErrorCode::InvalidInput, "params." + name + ": " + checked.error().message);
    return *checked;
}

std::string defaultScene() { return projectRoot() + "/scripts/scenes/default.lua"; }

bool hasScenePass(const PipelineDesc& p) {
    return std::any_of(p.graph.passes.begin(), p.graph.passes.end(), [](const PassDesc& d) { return d.kind == "scene"; });
}

Result<Scene> readScene(const std::string& file, const std::map<std::string, std::string>& args) {
    const std::string ext = fs::path(file).extension().string();
    if (ext == ".lua") {
        SceneScriptOptions o;
        o.args = args;
        o.projectRoot = projectRoot();
        return loadSceneScript(file, o);
    }
    if (ext == ".gltf" || ext == ".glb") {
        auto scene = loadGltf(file);
        if (!scene) return scene;
        if (scene->cameras.empty()) {
            // Frame the bounds from the front, slightly above.
            Camera c;
            c.name = "default";
            const glm::vec3 centre = 0.5f * (scene->boundsMin + scene->boundsMax);
            const float radius = std::max(0.5f * glm::length(scene->boundsMax - scene->boundsMin), 0.01f);
            c.target = centre;
            c.position = centre + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * radius / std::sin(c.verticalFov * 0.5f);
            c.nearPlane = radius * 0.01f;
            c.farPlane = radius * 100.0f;
            scene->cameras.push_back(c);
        }
        return scene;
    }
    return fail(ErrorCode::InvalidInput, "--scene '" + file + "': expected a .lua scene script, a .gltf or a .glb file");
}

}  // namespace

// Loads the scene the pipeline's scene passes draw, matches its materials to the pipeline's, and
// takes the camera's exposure settings into the camera parameters.
Result<std::unique_ptr<passes::GpuScene>> Session::loadScene(PipelineDesc& pipeline) {
    // A scene built in code (the library's setScene) or read from its file.
    const std::string file = m_options.sceneData ? std::string("the host's scene") : m_options.scene.empty() ? defaultScene() : m_options.scene;
    auto scene = m_options.sceneData ? Result<Scene>(*m_options.sceneData) : readScene(file, m_options.sceneArgs);
    if (!scene) return std::unexpected(scene.error());
    const std::string ext = m_options.sceneData ? std::string() : fs::path(file).extension().string();
    if (auto r = chooseEnvironment(*scene, m_options.environment, /*litByDefault=*/ext == ".gltf" || ext == ".glb"); !r)
        return std::unexpected(r.error());
    for (Material& m : scene->materials) {
        auto pm = std::find_if(pipeline.materials.begin(), pipeline.materials.end(), [&](auto& x) { return x.name == m.model; });
        if (pm == pipeline.materials.end()) {
            std::string names;
            for (const auto& x : pipeline.materials) names += (names.empty() ? "'" : ", '") + x.name + "'";
            return fail(ErrorCode::InvalidInput, file + ": material '" + m.name + "' uses model '" + m.model +
                                                     "', which the pipeline does not declare (materials: " + names + ")");
        }
        // Game-team parameters by name, in the order the shaders read them (the pipeline
        // material's), each checked: a key the model does not have, or a value of another type,
        // is an error naming where the scene declared it.
        const std::string where = (m.origin.empty() ? file + ": material '" + m.name + "'" : m.origin) + ".params.";
        std::vector<std::string> known;
        for (const auto& [key, def] : pm->params.asTable()) known.push_back(key);
        for (const auto& [key, value] : m.extra.asTable()) {
            const Value& def = pm->params[key];
            if (def.isNil())
                return fail(ErrorCode::InvalidInput, where + key + ": model '" + m.model + "' has no parameter '" + key + "'" +
                                                         suggestion(key, known) +
                                                         (known.empty() ? " (it takes none)" : "; its parameters: " + joinQuoted(known)));
            if (def.isNumber() && !value.isNumber())
                return fail(ErrorCode::InvalidInput, where + key + ": expected a number (as model '" + m.model + "' declares it), got " +
                                                         value.typeName());
        }
        Value::Table custom;
        for (const auto& [key, def] : pm->params.asTable())
            if (def.isNumber()) custom[key] = m.extra[key].isNumber() ? m.extra[key] : def;
        m.extra = Value(custom);
    }
    // Baked GI (scene.lightmap): from the cache, or baked now; the pipeline's `lightmap` parameter
    // (scripts/lightmap.lua) turns it off.
    if (scene->lightmap) {
        const ParamDesc* use = pipeline.findParam("lightmap");
        Value on = use ? use->value : Value(true);
        if (auto set = m_options.params.find("lightmap"); use && set != m_options.params.end()) {  // --set lightmap=...
            auto checked = checkedParam(pipeline, "lightmap", set->second);
            if (!checked) return std::unexpected(checked.error());
            on = *checked;
        }
        if (!on.isBool() || on.asBool()) {
            bake::PrepareOptions po;
            po.cacheDir = cacheDir() + "/lightmaps";
            if (auto r = bake::prepareLightmap(*scene, po); !r)
                return fail(r.error().code, scene->lightmap->origin + ": scene.lightmap." + scene->lightmap->name + ": " + r.error().message);
        }
    }
    passes::GpuSceneOptions sceneOptions;
    sceneOptions.levelsOfDetail = m_options.levelsOfDetail;
    auto gpuScene = passes::GpuScene::create(m_runtime.gpu(), std::move(*scene), sceneOptions);
    if (!gpuScene) return std::unexpected(gpuScene.error());
    if (!m_options.camera.empty())
        if (auto r = (*gpuScene)->selectCamera(m_options.camera); !r) return std::unexpected(r.error());
    const Camera& cam = (*gpuScene)->camera();
    auto set = [&](const char* name, double v) {
        if (ParamDesc* p = pipeline.findParam(name))
            if (auto ok = checkParamValue(*p, Value(v))) p->value = *ok;
    };
    set("aperture", cam.aperture);
    set("shutter", cam.shutter);
    set("iso", cam.iso);
    set("ec", cam.exposureCompensation);
    set("initial_ev100", std::log2(cam.aperture * cam.aperture / cam.shutter * 100.0 / cam.iso) - cam.exposureCompensation);
    m_sceneFile = file;
    return std::move(*gpuScene);
}

namespace {

// The scene's draws per stencil class of the pipeline's materials (ctx.scene.classes): fixed
// while the two stay loaded, so counted once per load.
std::map<std::string, uint32_t> drawsPerClass(const passes::GpuScene& scene, const PipelineDesc& pipeline) {
    std::map<std::string, std::string> classOf;  // material name -> its stencil class
    for (const auto& m : pipeline.materials)
        if (!m.stencil.empty()) classOf[m.name] = m.stencil;
    std::map<std::string, uint32_t> classes;
    for (const auto& d : scene.draws())
        if (auto it = classOf.find(scene.scene().materials[d.material].model); it != classOf.end()) ++classes[it->second];
    return classes;
}

// What a frame's changes do to the graph, for the log: "disabled 'decals', 'sky' uses X.frag".
std::string describeStructural(const FrameChanges& changes) {
    std::string what;
    for (const auto& [pass, on] : changes.enabled) what += (what.empty() ? "" : ", ") + std::string(on ? "enabled '" : "disabled '") + pass + "'";
    for (const auto& [pass, shader] : changes.shaders) what += (what.empty() ? "" : ", ") + ("'" + pass + "' uses " + shader);
    return what;
}

}  // namespace

// `--capture` names (and the library's keep, serve's image requests) checked against a pipeline:
// a resource of its graph, or "gbuffer.<channel>" / "<layout>.<channel>", decoded per materialId.
static Result<std::vector<Session::ChannelCapture>> channelCapturesOf(const PipelineDesc& pipeline, const std::vector<std::string>& captures) {
    using ChannelCapture = Session::ChannelCapture;
    std::vector<ChannelCapture> channels;
    for (const auto& c : captures) {
        if (pipeline.graph.findResource(c)) continue;
        // "gbuffer.smoothness" or "disney.smoothness": a channel of a layout.
        const size_t dot = c.find('.');
        bool found = false;
        if (dot != std::string::npos) {
            const std::string prefix = c.substr(0, dot), channel = c.substr(dot + 1);
            auto has = [](const LayoutDesc& l, const std::string& name) {
                for (const auto& t : l.targets)
                    for (const auto& ch : t.channels)
                        if (ch.name == name) return true;
                return false;
            };
            for (const auto& l : pipeline.layouts) {
                if (prefix != "gbuffer" && prefix != l.name) continue;
                if (has(l, channel) && !found) {
                    channels.push_back({c, l, channel, {}});
                    found = true;
                }
            }
            // Per materialId: the material's own layout, and its channel for a standard name.
            for (const MaterialDesc& m : pipeline.materials) {
                const LayoutDesc& l = *std::find_if(pipeline.layouts.begin(), pipeline.layouts.end(), [&](auto& x) { return x.name == m.layout; });
                if (prefix != "gbuffer" && prefix != l.name) continue;
                const auto mapped = m.channels.find(channel);
                const std::string name = prefix == "gbuffer" && mapped != m.channels.end() ? mapped->second : channel;
                if (!has(l, name)) continue;
                if (!found) {
                    channels.push_back({c, l, name, {}});
                    found = true;
                }
                // Only channels of the same shape as the first (components, integer or not); the
                // others' pixels stay NaN.
                auto shape = [](const LayoutDesc& ld, const std::string& ch) {
                    for (const auto& t : ld.targets)
                        for (const auto& cd : t.channels)
                            if (cd.name == ch) {
                                return std::make_pair(valueComponents(cd), cd.encoding == Encoding::Uint);
                            }
                    return std::make_pair(0u, false);
                };
                const auto& first = channels.back().byId.empty() ? std::make_pair(channels.back().layout, channels.back().channel)
                                                                 : channels.back().byId.begin()->second;
                if (shape(l, name) == shape(first.first, first.second)) channels.back().byId.emplace(m.id, std::make_pair(l, name));
            }
            if (found && !channels.back().byId.empty()) {
                // The layout that tells the id: the first material's (every one keeps materialId alike).
                const MaterialDesc& first = pipeline.materials.front();
                channels.back().layout = *std::find_if(pipeline.layouts.begin(), pipeline.layouts.end(), [&](auto& x) { return x.name == first.layout; });
            }
        }
        if (!found)
            return fail(ErrorCode::NotFound, "capture '" + c + "': the pipeline has no resource named '" + c +
                                                 "' (nor a G-buffer channel: use gbuffer.<channel>)");
    }
    return channels;
}

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
        return fail(ErrorCode::InvalidInput, "--scene: pipeline '" + file + "' has no scene pass to draw it");
    }
    for (const auto& [name, value] : m_options.params) {
        auto checked = checkedParam(*pipeline, name, value);
        if (!checked) return std::unexpected(checked.error());
        pipeline->findParam(name)->value = *checked;
    }
    if (!m_options.view.empty()) {
        GraphDesc probe = graphWithParams(*pipeline);
        if (auto r = addDebugView(probe, *pipeline, m_options.view, scene ? &scene->scene() : nullptr); !r) return r;
    }
    auto channels = channelCapturesOf(*pipeline, m_options.captures);
    if (!channels) return std::unexpected(channels.error());

    // From here the runtime is pointed at the new pipeline; until commit, leaving this function
    // points it back at the previous one, which keeps rendering.
    struct Rollback {
        Session& s;
        std::string headers = s.m_runtime.shaders().options().generatedDir;
        const passes::GpuScene* scene = s.m_runtime.executor().scene();
        std::function<void(uint32_t)> hook = s.m_frameHook;
        std::vector<ChannelCapture> channels = s.m_channels;
        bool sceneChanged = false, committed = false;
        ~Rollback() {
            if (committed) return;
            useLayoutHeaders(s.m_runtime, headers);
            s.m_frameHook = hook;
            s.m_channels = channels;
            if (sceneChanged)
                s.m_runtime.executor().setScene(scene, scene ? scene->id() : 0, hook, scene ? passes::shadowViewCapacity(scene->scene()) : 0);
        }
    } rollback{*this};
    useLayoutHeaders(m_runtime, *headers);
    m_channels = std::move(*channels);
    // The new scene is what the build prepares against.
    m_frameHook = {};
    if (scene) {
        passes::GpuScene* raw = scene.get();
        const uint32_t w = m_options.compile.outputWidth, h = m_options.compile.outputHeight;
        m_frameHook = [raw, w, h](uint32_t slot) { raw->updateFrame(slot, w, h); };
    }
    if (scene || rollback.scene) {
        m_runtime.executor().setScene(scene.get(), scene ? scene->id() : 0, m_frameHook, scene ? passes::shadowViewCapacity(scene->scene()) : 0);
        rollback.sceneChanged = true;
    }
    {
        gpu::Executor& executor = m_runtime.executor();
        executor.setOnceCache(m_options.onceCache,
                              [&executor](uint32_t slot) { return executor.scene() ? executor.scene()->contentHash(slot) : 0; });
    }
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
    std::erase_if(overrides.enabled, [&](const auto& o) { return !pipeline->graph.findPass(o.first); });
    auto tc = Clock::now();
    std::map<std::string, uint32_t> classes = scene ? drawsPerClass(*scene, *pipeline) : std::map<std::string, uint32_t>{};
    auto first = frameChanges(*host, frameContext(scene ? scene.get() : nullptr, classes), *pipeline, overrides);
    if (!first) return std::unexpected(first.error());
    const double firstCallbackMs = msSince(tc);
    applyFrameChanges(*pipeline, *first);
    const std::string firstChanges = describeStructural(*first);
    // The executor keeps its previous build when this one fails.
    if (auto r = m_runtime.executor().build(buildableGraph(*pipeline, /*keepMissingShaders=*/false), m_options.compile); !r) return r;
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
        if (m_options.sceneData) sceneKey += "memory=" + std::to_string(reinterpret_cast<uintptr_t>(m_options.sceneData.get())) + ";";
        for (const auto& f : scene->scene().files) {
            std::ifstream in(f, std::ios::binary);
            sceneKey += f + ":" + std::to_string(std::hash<std::string>{}(std::string((std::istreambuf_iterator<char>(in)), {}))) + ";";
        }
    }
    m_scene = std::move(scene);
    m_classes = std::move(classes);
    m_sceneLoadMs = sceneMs;
    // History (exposure, previous frames, a reference accumulation) carries over a reload of the
    // same pipeline drawing the same scene, not to another pipeline or a changed scene.
    if (file != m_pipeline.file || sceneKey != m_sceneKey)
        if (auto r = m_runtime.executor().resetPersistent(); !r) return r;
    m_sceneKey = sceneKey;
    m_host = std::move(host);
    m_pipeline = std::move(*pipeline);
    m_overrides = std::move(overrides);
    m_rebuilds = 0;
    ++m_loads;
    m_framePrepared = m_frame;
    m_callbackMs = firstCallbackMs;
    m_loadMs = msSince(t0);
    note("loaded " + file + ": " + std::to_string(m_runtime.executor().plan().passes.size()) + " passes (" +
         m_runtime.executor().lastBuildReport().summary() + ")" +
         (firstChanges.empty() ? std::string() : "; frame " + std::to_string(m_frame) + "'s rg.frame: " + firstChanges));
    return {};
}

FrameContext Session::frameContext(const passes::GpuScene* scene, const std::map<std::string, uint32_t>& classes) const {
    FrameContext ctx{m_frame, static_cast<double>(m_frame) / 60.0, std::nullopt, m_options.compile.outputWidth, m_options.compile.outputHeight};
    if (scene)
        ctx.scene = FrameContext::SceneFacts{
            static_cast<uint32_t>(scene->draws().size()), scene->lightCount(), static_cast<uint32_t>(scene->scene().decals.size()),
            static_cast<uint32_t>(std::count_if(scene->scene().lights.begin(), scene->scene().lights.end(),
                                                [](const Light& l) { return l.type == LightType::Directional; })),
            static_cast<uint32_t>(scene->scene().probes.size()),
            static_cast<uint32_t>(std::count_if(scene->draws().begin(), scene->draws().end(), [&](const passes::DrawItem& d) {
                return scene->scene().materials[d.material].alphaMode == AlphaMode::Blend;
            }))};
    if (scene) ctx.scene->classes = classes;
    return ctx;
}

Result<FrameChanges> Session::frameChanges(LuaHost& host, const FrameContext& ctx, const PipelineDesc& pipeline, const FrameChanges& overrides) {
    auto changes = host.frame(ctx, pipeline);
    if (changes && (m_options.frameHook || !overrides.empty())) {
        PipelineDesc seen = pipeline;
        applyFrameChanges(seen, *changes);
        auto more = m_options.frameHook ? m_options.frameHook(ctx, seen) : Result<FrameChanges>(FrameChanges{});
        if (!more) return std::unexpected(more.error());
        for (const auto& [k, v] : overrides.params) more->params[k] = v;
        for (const auto& [k, v] : overrides.enabled) more->enabled[k] = v;
        for (const auto& [k, v] : more->params) changes->params[k] = v;
        for (const auto& [k, v] : more->enabled) changes->enabled[k] = v;
        for (const auto& [k, v] : more->shaders) changes->shaders[k] = v;
        // A pass the two callbacks leave as it was is no change (no rebuild).
        std::erase_if(changes->enabled, [&](const auto& e) {
            const PassDesc* p = pipeline.graph.findPass(e.first);
            return p && p->enabled == e.second;
        });
        std::erase_if(changes->shaders, [&](const auto& e) {
            const PassDesc* p = pipeline.graph.findPass(e.first);
            return p && p->params["shader"].asString() == e.second;
        });
    }
    return changes;
}

Result<void> Session::frame(VkCommandBuffer hostCmd) {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    auto t0 = Clock::now();
    Result<FrameChanges> changes = FrameChanges{};
    if (m_framePrepared == m_frame) {
        // The load ran this frame's rg.frame already and built its plan with what it changed;
        // overrides set since were applied when they were set (setOverride, setPassOverride).
        m_framePrepared.reset();
    } else {
        changes = frameChanges(*m_host, frameContext(m_scene.get(), m_classes), m_pipeline, m_overrides);
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
    Result<void> applied = !changes ? Result<void>(std::unexpected(changes.error())) : changes->empty() ? Result<void>{} : apply(*changes);
    if (!applied && changes) {
        Error e = applied.error();
        e.message = "frame " + std::to_string(m_frame) + ": rg.frame's changes (" + describeStructural(*changes) +
                    ") cannot be built; the plan stays as it was: " + e.message;
        applied = std::unexpected(e);
    }
    // The area-light model of the light loop (scripts/lighting.lua's area_lights): a field of the
    // scene's Lights block, so switching it rebuilds nothing.
    if (m_scene) {
        const ParamDesc* model = m_pipeline.findParam("area_lights");
        m_scene->setAreaLightModel(model && model->value.isString() && model->value.asString() == "ltc" ? 1u : 0u);
    }
    if (auto r = m_runtime.executor().frame(hostCmd); !r) return r;
    ++m_frame;
    return applied;
}

Result<void> Session::apply(const FrameChanges& changes) {
    PipelineDesc next = m_pipeline;
    applyFrameChanges(next, changes);
    GraphDesc graph = buildableGraph(next, /*keepMissingShaders=*/true);
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
            what += (what.empty() ? "" : ", ") + ("switch " + name + " = " + (v.isString() ? v.asString() : v.isBool() ? (v.asBool() ? "true" : "false") : std::to_string(v.asNumber())));
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
        return fail(r.error().code, "params." + param + ": this value cannot be built, nothing changed: " + r.error().message);
    m_overrides.params[param] = *checked;
    return {};
}

Result<void> Session::setPassOverride(const std::string& pass, bool enabled) {
    if (!m_host) return fail(ErrorCode::InvalidInput, "no pipeline loaded");
    const PassDesc* desc = m_pipeline.graph.findPass(pass);
    if (!desc) {
        std::vector<std::string> names;
        for (const auto& d : m_pipeline.graph.passes) names.push_back(d.name);
        return fail(ErrorCode::NotFound, "passes." + pass + ": the pipeline has no pass '" + pass + "'" + suggestion(pass, names));
    }
    // Applied now: a switch that leaves the graph unbuildable (a kept pass reads what only this
    // one writes) is refused with the compiler's reason, and nothing changes.
    if (desc->enabled != enabled) {
        FrameChanges change;
        change.enabled[pass] = enabled;
        if (auto r = apply(change); !r)
            return fail(ErrorCode::InvalidInput, "passes." + pass + ": cannot be switched " + (enabled ? "on" : "off") +
                                                     ", nothing changed: " + r.error().message);
    }
    m_overrides.enabled[pass] = enabled;
    return {};
}

void Session::carryOverrides(const FrameChanges& overrides) { m_overrides = overrides; }

Result<void> Session::addCapture(const std::string& name) {
    if (std::find(m_options.captures.begin(), m_options.captures.end(), name) != m_options.captures.end()) return {};
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
