#include "pipeline.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "lua_host.h"

namespace rg {

const char* paramTypeName(ParamType t) {
    switch (t) {
        case ParamType::Number:
            return "number";
        case ParamType::Integer:
            return "integer";
        case ParamType::Boolean:
            return "boolean";
        case ParamType::Vec3:
            return "vec3";
        case ParamType::Choice:
            return "choice";
    }
    return "?";
}

const ParamDesc* PipelineDesc::findParam(const std::string& name) const {
    for (const auto& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

ParamDesc* PipelineDesc::findParam(const std::string& name) {
    for (auto& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

namespace {
std::string num(double d) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", d);
    return b;
}
}  // namespace

Result<Value> checkParamValue(const ParamDesc& p, const Value& v) {
    auto bad = [&](const std::string& want) {
        return fail(ErrorCode::InvalidInput, "parameter '" + p.name + "' expects " + want +
                                                 ", got " +
                                                 (v.isNil()      ? "nil"
                                                  : v.isNumber() ? num(v.asNumber())
                                                  : v.isString() ? "'" + v.asString() + "'"
                                                                 : v.typeName()));
    };
    auto range = [&]() {
        return "a " + std::string(p.type == ParamType::Integer ? "whole number" : "number") +
               " in [" + (p.min < -1e299 ? "-inf" : num(p.min)) + ", " +
               (p.max > 1e299 ? "inf" : num(p.max)) + "]";
    };
    switch (p.type) {
        case ParamType::Number:
            if (!v.isNumber() || v.asNumber() < p.min || v.asNumber() > p.max ||
                std::isnan(v.asNumber()))
                return bad(range());
            return v;
        case ParamType::Integer:
            if (!v.isNumber() || std::floor(v.asNumber()) != v.asNumber() || v.asNumber() < p.min ||
                v.asNumber() > p.max)
                return bad(range());
            return v;
        case ParamType::Boolean:
            if (!v.isBool()) return bad("a boolean");
            return v;
        case ParamType::Vec3:
            if (!v.isList() || v.asList().size() != 3 || !v.asList()[0].isNumber() ||
                !v.asList()[1].isNumber() || !v.asList()[2].isNumber())
                return bad("{x, y, z}");
            return v;
        case ParamType::Choice:
            for (const auto& c : p.choices)
                if (v.isString() && v.asString() == c) return v;
            {
                std::string list;
                for (const auto& c : p.choices) list += (list.empty() ? "'" : ", '") + c + "'";
                return bad("one of " + list);
            }
    }
    return v;
}

void applyFrameChanges(PipelineDesc& pipeline, const FrameChanges& changes) {
    for (const auto& [name, value] : changes.params)
        if (ParamDesc* p = pipeline.findParam(name)) p->value = value;
    for (auto& pass : pipeline.graph.passes) {
        if (auto it = changes.enabled.find(pass.name); it != changes.enabled.end())
            pass.enabled = it->second;
        if (auto it = changes.shaders.find(pass.name); it != changes.shaders.end())
            pass.params.table()["shader"] = Value(it->second);
    }
}

namespace {
// A parameter as a Params-block float: booleans as 0/1, choices as their index.
Value paramAsNumber(const ParamDesc& p) {
    if (p.type == ParamType::Boolean) return Value(p.value.asBool() ? 1.0 : 0.0);
    if (p.type == ParamType::Choice) {
        double index = 0;
        for (size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == p.value.asString()) index = static_cast<double>(i);
        return Value(index);
    }
    return p.value;
}
}  // namespace

bool isSwitch(const PipelineDesc& pipeline, const std::string& param) {
    // A parameter an only_when names changes which resources and passes the graph has.
    auto names = [&](const std::optional<ResourceDesc::Condition>& c) {
        return c && std::find(c->params.begin(), c->params.end(), param) != c->params.end();
    };
    for (const auto& pass : pipeline.graph.passes)
        if (pass.params["switches"].has(param) || names(pass.onlyWhen)) return true;
    for (const auto& r : pipeline.graph.resources)
        if (names(r.onlyWhen)) return true;
    return false;
}

GraphDesc graphWithParams(const PipelineDesc& pipeline) {
    GraphDesc g = pipeline.graph;
    for (auto& pass : g.passes) {
        if (!pass.params.isTable()) pass.params = Value(Value::Table{});
        Value::Table uniforms;
        for (const auto& p : pipeline.params) uniforms[p.name] = paramAsNumber(p);
        for (const auto& [k, v] : pass.params["uniforms"].asTable()) uniforms[k] = v;
        pass.params.table()["uniforms"] = Value(uniforms);
        // switches = { param = "DEFINE" }: the parameter's value compiled in (the pass is rebuilt
        // when it changes: Session::frame).
        if (pass.params["switches"].isTable()) {
            Value::Table defines = pass.params["defines"].isTable()
                                       ? pass.params["defines"].asTable()
                                       : Value::Table{};
            for (const auto& [param, define] : pass.params["switches"].asTable())
                if (const ParamDesc* p = pipeline.findParam(param); p && define.isString())
                    defines[define.asString()] = paramAsNumber(*p);
            pass.params.table()["defines"] = Value(defines);
        }
    }
    for (auto& r : g.resources)
        if (r.name == pipeline.output) r.exported = true;
    for (auto& pass : g.passes) {
        // stencil = { class = "lit_standard" } -> the class's value and mask.
        const Value& stencil = pass.params["stencil"];
        if (stencil.has("class")) {
            Value::Table t = stencil.asTable();
            for (const auto& c : pipeline.stencilClasses)
                if (c.name == stencil["class"].asString()) {
                    t["ref"] = Value(static_cast<double>(c.value));
                    // A narrower mask lets a path light several classes (e.g. foliage = standard | 8).
                    if (!t.count("mask")) t["mask"] = Value(static_cast<double>(c.mask));
                }
            if (!t.count("compare")) t["compare"] = Value("equal");
            t.erase("class");
            pass.params.table()["stencil"] = Value(t);
        }
        if (pass.kind == "scene") pass.materials = sceneMaterials(pipeline, pass.params);
    }
    return g;
}

void resolveShaderPaths(GraphDesc& graph, const std::string& pipelineFile,
                        const std::string& projectRoot) {
    const std::filesystem::path dir = std::filesystem::absolute(pipelineFile).parent_path();
    for (auto& pass : graph.passes) {
        const Value& s = pass.params["shader"];
        if (!s.isString() || s.asString().empty() ||
            std::filesystem::path(s.asString()).is_absolute())
            continue;
        // Next to the script that declared the pass (a module of its own folder), then next to
        // the pipeline script; else the include folders.
        std::string resolved = nextToDeclaration(pass.origin, s.asString(), projectRoot);
        std::error_code ec;
        if (resolved == s.asString() && std::filesystem::is_regular_file(dir / s.asString(), ec))
            resolved = (dir / s.asString()).string();
        pass.params.table()["shader"] = Value(resolved);
    }
}

std::vector<std::pair<std::string, std::string>> generateLightingShaders(
    const PipelineDesc& pipeline) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const LightingPathDesc& path : pipeline.lightingPaths) {
        if (path.shading.empty() || path.stencil.empty())
            continue;  // forward only: no deferred pass
        // The layout its materials have (one per path: buildPipeline checks it).
        auto m = std::find_if(pipeline.materials.begin(), pipeline.materials.end(),
                              [&](const MaterialDesc& x) { return x.path == path.name; });
        if (m == pipeline.materials.end()) continue;
        auto layout = std::find_if(pipeline.layouts.begin(), pipeline.layouts.end(),
                                   [&](const LayoutDesc& l) { return l.name == m->layout; });
        if (layout == pipeline.layouts.end()) continue;
        const std::string& l = layout->name;
        std::ostringstream o;
        o << "#version 460\n// Generated by rgraph: the deferred lighting of path '" << path.name
          << "' (" << path.origin << "), its layout '" << l
          << "' unpacked and shaded by its rgShade. Do not edit: change the path in Lua.\n"
          << "#include \"lib/lighting.glsl\"\n#include \"lib/exposure.glsl\"\n"
          << "#include \"lib/ibl.glsl\"\n#include \"gbuffer_" << l << ".glsl\"\n#include \""
          << path.shading << "\"\n\n"
          << "layout(location = 0) in vec2 uv;\nlayout(location = 0) out vec4 color;\n";
        uint32_t binding = 0;
        std::string texels;
        for (const TargetDesc& t : layout->targets) {
            o << "layout(set = 0, binding = " << binding++ << ") uniform "
              << (formatInfo(t.format).integer ? "usampler2D " : "sampler2D ") << t.name << ";\n";
            texels += (texels.empty() ? "texelFetch(" : ", texelFetch(") + t.name + ", p, 0)";
        }
        o << "layout(set = 0, binding = " << binding << ") uniform sampler2D depth;\n"
          << "layout(set = 0, binding = " << binding + 1
          << ", std430) readonly buffer exposure { RgExposureState state; } ex;\n"
          << "layout(set = 0, binding = " << binding + 2
          << ") uniform Params { float initial_ev100; } params;\n\n"
          << "void main() {\n    ivec2 p = ivec2(gl_FragCoord.xy);\n"
          << "    GBuffer_" << l << " g = unpackGBuffer_" << l << "(" << texels << ");\n"
          << "    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);\n"
          << "    color = vec4(rgShade(g, position, rgViewDirection(position), p) * "
             "rgPreExposure(ex.state, params.initial_ev100), 1.0);\n}\n";
        out.emplace_back("lighting_path_" + path.name + ".frag", o.str());
    }
    return out;
}

Result<std::string> generatePipelineGlsl(const PipelineDesc& pipeline) {
    std::ostringstream o;
    o << "// Generated by rgraph from the pipeline's materials ("
      << pipeline.file.substr(pipeline.file.find_last_of('/') + 1)
      << "). Do not edit: declare materials in Lua.\n"
      << "#ifndef RG_GBUFFER_PIPELINE_GLSL\n#define RG_GBUFFER_PIPELINE_GLSL\n";
    // The standard parameters and their bits.
    static const char* const kBits[] = {"NORMAL",      "BASE_COLOR", "SMOOTHNESS", "METAL_MASK",
                                        "REFLECTANCE", "F0",         "AO",         "EMISSIVE"};
    const std::vector<std::string> standard(std::begin(kStandardChannels),
                                            std::end(kStandardChannels));
    auto bit = [&](const std::string& s) {
        return 1u << (std::find(standard.begin(), standard.end(), s) - standard.begin());
    };
    for (size_t i = 0; i < standard.size(); ++i)
        o << "#define RG_VIEW_" << kBits[i] << " " << (1u << i) << "u\n";
    std::vector<const LayoutDesc*> layouts;
    std::map<std::string, const MaterialDesc*> defines;
    for (const MaterialDesc& m : pipeline.materials) {
        auto l = std::find_if(pipeline.layouts.begin(), pipeline.layouts.end(),
                              [&](auto& x) { return x.name == m.layout; });
        if (l != pipeline.layouts.end() &&
            std::find(layouts.begin(), layouts.end(), &*l) == layouts.end())
            layouts.push_back(&*l);
        std::string id;
        for (char c : m.name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
        if (defines.count(id))
            return fail(ErrorCode::InvalidInput, m.origin + ": material '" + m.name +
                                                     "' and material '" + defines[id]->name +
                                                     "' (" + defines[id]->origin +
                                                     ") both become RG_MATERIAL_IDENTITY_" + id +
                                                     " in the generated GLSL; rename one");
        defines[id] = &m;
        o << "#define RG_MATERIAL_IDENTITY_" << id << " " << m.identity << "u\n";
    }
    for (const LayoutDesc* l : layouts) o << "#include \"gbuffer_" << l->name << ".glsl\"\n";
    o << "struct RgGBufferView {\n    uint identity;  // the pixel's stencil value: its material\n "
         "   uint has;     // RG_VIEW_* of the "
         "parameters its layout holds\n"
         "    uint decals;  // RG_VIEW_* of the parameters decals blend on it\n"
         "    vec3 normal;\n    vec3 baseColor;\n    float smoothness;\n    float metalMask;\n    "
         "float reflectance;\n"
         "    vec3 f0;\n    float ao;\n    vec3 emissive;\n};\n";
    // The targets: every material layout's, by name (so declaration order does not matter),
    // passed as four floats texels (t0..t3, vec4(0) beyond them) as the decal pass, the debug
    // views and the reference read GB0..GB3. A target name keeps one format in every layout.
    std::map<std::string, std::pair<Format, const LayoutDesc*>> byName;
    for (const LayoutDesc* l : layouts)
        for (const TargetDesc& t : l->targets) {
            auto [it, added] = byName.emplace(t.name, std::make_pair(t.format, l));
            if (!added && it->second.first != t.format)
                return fail(ErrorCode::InvalidInput,
                            (l->origin.empty() ? "" : l->origin + ": ") + "layout '" + l->name +
                                "' makes target '" + t.name + "' " +
                                std::string(formatName(t.format)) + ", layout '" +
                                it->second.second->name + "' " +
                                std::string(formatName(it->second.first)) +
                                ": a target has one format in every layout");
            if (formatInfo(t.format).integer)
                return fail(ErrorCode::InvalidInput,
                            (l->origin.empty() ? "" : l->origin + ": ") + "layout '" + l->name +
                                "' target '" + t.name +
                                "' is an integer format: decals, debug views and the reference "
                                "read a material's targets as float texels");
        }
    std::vector<std::string> targets;
    for (const auto& [name, _] : byName) targets.push_back(name);
    if (targets.size() > 4)
        return fail(ErrorCode::InvalidInput, "the pipeline's material layouts use " +
                                                 std::to_string(targets.size()) + " targets (" +
                                                 joinQuoted(targets) +
                                                 "): decals, debug views and the reference read at "
                                                 "most four (GB0..GB3 in the default loop)");
    const std::string params4 = "vec4 t0, vec4 t1, vec4 t2, vec4 t3";
    if (layouts.empty()) {
        o << "RgGBufferView rgDecodeGBuffer(uint identity, " << params4
          << ") {\n    RgGBufferView v;\n    v.identity = identity; v.has = 0u; v.decals = 0u;\n"
             "    v.normal = vec3(0.0, 0.0, 1.0); v.baseColor = vec3(0.0); v.smoothness = 0.0; "
             "v.metalMask = 0.0;\n"
             "    v.reflectance = 0.0; v.f0 = vec3(0.0); v.ao = 1.0; v.emissive = vec3(0.0);\n    "
             "return v;\n}\n"
             "void rgEncodeDecals(RgGBufferView v, "
          << params4
          << ", out vec4 o0, out vec4 o1, out vec4 o2, out vec4 o3) {\n"
             "    o0 = t0; o1 = t1; o2 = t2; o3 = t3;\n}\n"
             "#define rgGBufferAt(p) rgDecodeGBuffer(0u, vec4(0.0), vec4(0.0), vec4(0.0), "
             "vec4(0.0))\n#define rgGBufferNormalAt(p) vec3(0.0, 0.0, 1.0)\n"
             "#define rgGBufferSmoothnessAt(p) 0.0\n#define RG_DECAL_TARGETS 0\n#endif\n";
        return o.str();
    }
    auto params = [&](const std::string& prefix, bool out) {
        std::string s;
        for (size_t i = 0; i < 4; ++i)
            s += std::string(i ? ", " : "") + (out ? "out " : "") + "vec4 " + prefix +
                 std::to_string(i);
        return s;
    };
    // A material's layout (every material's is in `layouts`).
    auto layoutOf = [&](const MaterialDesc& m) -> const LayoutDesc& {
        return **std::find_if(layouts.begin(), layouts.end(),
                              [&](auto* x) { return x->name == m.layout; });
    };
    // Arguments of one layout's unpack/pack, by target name.
    auto args = [&](const LayoutDesc& l, const std::string& prefix) {
        std::string s;
        for (size_t i = 0; i < l.targets.size(); ++i) {
            const size_t k = static_cast<size_t>(
                std::find(targets.begin(), targets.end(), l.targets[i].name) - targets.begin());
            s += ", " + prefix + std::to_string(k);
        }
        return s;
    };
    // By identity (materials sharing one decode alike: Builder::materialIdentities).
    std::map<uint32_t, const MaterialDesc*> byId;
    for (const MaterialDesc& m : pipeline.materials) byId.emplace(m.identity, &m);
    o << "RgGBufferView rgDecodeGBuffer(uint identity, " << params("t", false) << ") {\n"
      << "    RgGBufferView v;\n"
      << "    v.identity = identity; v.has = 0u; v.decals = 0u;\n"
      << "    v.normal = vec3(0.0, 0.0, 1.0); v.baseColor = vec3(0.0); v.smoothness = 0.0; "
         "v.metalMask = 0.0;\n"
      << "    v.reflectance = 0.0; v.f0 = vec3(0.0); v.ao = 1.0; v.emissive = vec3(0.0);\n";
    const char* sep = "    ";
    for (const auto& [id, m] : byId) {
        uint32_t has = 0, decals = 0;
        for (const auto& [s, _] : m->channels) has |= bit(s);
        for (const auto& s : m->decals) decals |= bit(s);
        const LayoutDesc& l = layoutOf(*m);
        o << sep << "if (v.identity == " << id << "u) {  // " << m->name << "\n"
          << "        GBuffer_" << l.name << " g = unpackGBuffer_" << l.name << "("
          << args(l, "t").substr(2) << ");\n"
          << "        v.has = " << has << "u; v.decals = " << decals << "u;\n";
        for (const auto& [s, channel] : m->channels)
            o << "        v." << s << " = g." << channel << ";\n";
        o << "    }";
        sep = " else ";
    }
    o << "\n    return v;\n}\n";
    o << "void rgEncodeDecals(RgGBufferView v, " << params("t", false) << ", " << params("o", true)
      << ") {\n";
    for (size_t i = 0; i < 4; ++i) o << "    o" << i << " = t" << i << ";\n";
    sep = "    ";
    for (const auto& [id, m] : byId) {
        if (m->decals.empty()) continue;
        const LayoutDesc& l = layoutOf(*m);
        o << sep << "if (v.identity == " << id << "u) {  // " << m->name << "\n"
          << "        GBuffer_" << l.name << " g = unpackGBuffer_" << l.name << "("
          << args(l, "t").substr(2) << ");\n";
        for (const auto& s : m->decals)
            o << "        g." << m->channels.at(s) << " = v." << s << ";\n";
        o << "        packGBuffer_" << l.name << "(g" << args(l, "o") << ");\n    }";
        sep = " else ";
    }
    o << "\n}\n";
    // Which of t0..t3 hold a channel decals blend (the decal pass writes the ones it binds).
    uint32_t decalTargets = 0;
    const bool decalPass = std::any_of(
        pipeline.graph.passes.begin(), pipeline.graph.passes.end(), [](const PassDesc& p) {
            return p.params["shader"].isString() &&
                   p.params["shader"].asString() == "passes/decals.frag";
        });
    for (const MaterialDesc& m : pipeline.materials) {
        const LayoutDesc& l = layoutOf(m);
        for (const auto& d : m.decals)
            for (const TargetDesc& t : l.targets)
                for (const ChannelDesc& c : t.channels)
                    if (c.name == m.channels.at(d)) {
                        const size_t k = static_cast<size_t>(
                            std::find(targets.begin(), targets.end(), t.name) - targets.begin());
                        // The decal pass writes the first three targets (passes/decals.frag): said
                        // at the load, whether or not the scene has decals for it to run.
                        if (k >= 3 && decalPass)
                            return fail(ErrorCode::InvalidInput,
                                        m.origin + ": material '" + m.name + "': decals blend " +
                                            d + ", which layout '" + l.name + "' keeps in '" +
                                            t.name + "' (channel '" + c.name +
                                            "'), the pipeline's fourth target; the decal pass "
                                            "writes the first three (" +
                                            targets[0] + ", " + targets[1] + ", " + targets[2] +
                                            "): keep decal channels in those, or leave " + d +
                                            " out of the material's decals");
                        decalTargets |= 1u << k;
                    }
    }
    // Per standard channel, its decode alone, one branch per place materials keep it: a reader
    // that wants the normal (the sun's mask, AO) or the smoothness (SSR) decodes just that, with
    // no test at all when every material keeps it in the same place (the stencil then goes
    // unread: the default loop's normal and smoothness are GB0's for every material). Pixels of
    // a material without it get the neutral value.
    std::map<const LayoutDesc*, LayoutInfo> infos;  // each layout's channel places, once
    for (const LayoutDesc* l : layouts) {
        auto info = analyzeLayout(*l);
        if (!info) return std::unexpected(info.error());
        infos.emplace(l, std::move(*info));
    }
    for (const auto& [name, type, neutral] : {std::tuple<std::string, std::string, std::string>{
                                                  "normal", "vec3", "vec3(0.0, 0.0, 1.0)"},
                                              {"smoothness", "float", "0.0"}}) {
        std::vector<std::pair<std::string, std::vector<const MaterialDesc*>>> places;
        for (const auto& [id, m] : byId) {
            auto c = m->channels.find(name);
            if (c == m->channels.end()) continue;
            const LayoutDesc& l = layoutOf(*m);
            const LayoutInfo& info = infos.at(&l);
            const size_t index = static_cast<size_t>(info.find(c->second));
            const ChannelPlacement& pl = info.channels[index];
            const ChannelDesc& cd = info.channelDesc(index);
            std::string place = l.targets[pl.target].name + ":" +
                                std::string(formatName(l.targets[pl.target].format)) + ":" +
                                std::string(encodingName(cd.encoding)) + ":" +
                                std::to_string(cd.bits);
            for (uint32_t k = 0; k < pl.components; ++k)
                place += ":" + std::to_string(pl.slots[k].component) + "." +
                         std::to_string(pl.slots[k].bitOffset);
            auto it = std::find_if(places.begin(), places.end(),
                                   [&](auto& x) { return x.first == place; });
            if (it == places.end()) it = places.insert(places.end(), {place, {}});
            it->second.push_back(m);
        }
        std::string fn =
            "rgDecode" + std::string(1, static_cast<char>(std::toupper(name[0]))) + name.substr(1);
        o << type << " " << fn << "(uint identity, " << params("t", false) << ") {\n";
        bool unconditional = false;
        for (const auto& [place, ms] : places) {
            const MaterialDesc& m = *ms.front();
            const LayoutDesc& l = layoutOf(m);
            std::string test;
            for (const MaterialDesc* x : ms)
                test += (test.empty() ? "" : " || ") + std::string("identity == ") +
                        std::to_string(x->identity) + "u";
            const bool all = places.size() == 1 && ms.size() == byId.size();
            unconditional = unconditional || all;
            o << "    " << (all ? "" : "if (" + test + ") ") << "return unpackGBuffer_" << l.name
              << "(" << args(l, "t").substr(2) << ")." << m.channels.at(name) << ";  // " << place
              << "\n";
        }
        if (!unconditional) o << "    return " << neutral << ";\n";
        o << "}\n";
    }
    // rgGBufferAt(p): what a G-buffer reader calls, with samplers named after the targets and
    // `depth_stencil` (its reads: the targets and { "depth", as = "stencil" }), which the header
    // declares from binding RG_GBUFFER_BINDING on when a shader defines it.
    o << "#ifdef RG_GBUFFER_BINDING\n";
    for (size_t i = 0; i < targets.size(); ++i)
        o << "layout(set = 0, binding = RG_GBUFFER_BINDING + " << i << ") uniform sampler2D "
          << targets[i] << ";\n";
    o << "layout(set = 0, binding = RG_GBUFFER_BINDING + 4) uniform usampler2D depth_stencil;\n"
      << "#endif\n";
    std::string fetch = "(texelFetch(depth_stencil, p, 0).r";
    for (size_t i = 0; i < 4; ++i)
        fetch += ", " + (i < targets.size() ? "texelFetch(" + targets[i] + ", p, 0)" : "vec4(0.0)");
    fetch += ")";
    o << "#define rgGBufferAt(p) rgDecodeGBuffer" << fetch << "\n"
      << "#define rgGBufferNormalAt(p) rgDecodeNormal" << fetch << "\n"
      << "#define rgGBufferSmoothnessAt(p) rgDecodeSmoothness" << fetch << "\n"
      << "#define RG_DECAL_TARGETS " << decalTargets << "\n#endif\n";
    return o.str();
}

std::string describeMaterialSystem(const PipelineDesc& p) {
    std::ostringstream o;
    char line[512];
    // Identities: the stencil values 1..255 (0 is no material); one held by a material, or the
    // value of a declared stencil class, is taken.
    constexpr uint32_t kIdentities = 255;
    o << "material identities (a pixel's stencil value names its material: every pass that\n"
      << "decodes the G-buffer reads it; materials of one layout, channels and decals may share "
         "one):\n";
    std::map<uint32_t, std::vector<const MaterialDesc*>> byIdentity;
    for (const MaterialDesc& m : p.materials) byIdentity[m.identity].push_back(&m);
    std::set<uint32_t> taken;
    for (const StencilClassDesc& c : p.stencilClasses) taken.insert(c.value);
    for (const auto& [identity, ms] : byIdentity) {
        taken.insert(identity);
        std::string names, decals;
        for (const MaterialDesc* m : ms) names += (names.empty() ? "" : ", ") + m->name;
        for (const std::string& d : ms.front()->decals) decals += (decals.empty() ? "" : " ") + d;
        std::snprintf(
            line, sizeof line, "  0x%02X %-16s layout %-12s decals %-40s materials %s\n", identity,
            ms.front()->stencil.empty() ? "(no class)" : ms.front()->stencil.c_str(),
            ms.front()->layout.c_str(), decals.empty() ? "(none)" : decals.c_str(), names.c_str());
        o << line;
    }
    o << "  free: " << (kIdentities - static_cast<uint32_t>(taken.size())) << " of " << kIdentities
      << " (a material takes its class's value, else a free variant of it)\n\n";
    o << "stencil classes (8 bits: a class takes 1..15 in the low 4 bits and its pass tests them, "
         "so it lights\n"
      << "its variants too; a variant keeps its base's low bits and takes 1..15 in the high 4):\n";
    uint32_t classes = 0;
    for (const StencilClassDesc& c : p.stencilClasses) {
        std::string paths, materials;
        for (const LightingPathDesc& lp : p.lightingPaths)
            if (lp.stencil == c.name || (!c.base.empty() && lp.stencil == c.base))
                paths += (paths.empty() ? "" : ", ") + lp.name;
        for (const MaterialDesc& m : p.materials)
            if (m.stencil == c.name) materials += (materials.empty() ? "" : ", ") + m.name;
        std::snprintf(
            line, sizeof line, "  0x%02X mask 0x%02X  %-16s %-24s lit by %-12s materials %s\n",
            c.value, c.mask, c.name.c_str(), c.base.empty() ? "" : ("variant of " + c.base).c_str(),
            paths.empty() ? "-" : paths.c_str(), materials.empty() ? "-" : materials.c_str());
        o << line;
        if (c.base.empty()) ++classes;
    }
    o << "  free: " << ((1u << kStencilPathBits) - 1 - classes) << " of "
      << ((1u << kStencilPathBits) - 1) << " classes, each with up to "
      << ((1u << kStencilVariantBits) - 1) << " variants\n";
    return o.str();
}

std::vector<PassMaterial> sceneMaterials(const PipelineDesc& pipeline, const Value& params) {
    std::vector<std::string> selected, paths;
    auto names = [](const Value& v, std::vector<std::string>& out) {
        if (v.isString()) out.push_back(v.asString());
        for (const auto& e : v.asList()) out.push_back(e.asString());
    };
    names(params["materials"], selected);
    names(params["paths"], paths);
    std::vector<PassMaterial> out;
    for (const MaterialDesc& m : pipeline.materials) {
        const bool chosen = (selected.empty() && paths.empty()) ||
                            std::find(selected.begin(), selected.end(), m.name) != selected.end() ||
                            std::find(paths.begin(), paths.end(), m.path) != paths.end();
        if (!chosen || m.surface.empty()) continue;
        PassMaterial t;
        t.name = m.name;
        t.id = m.id;
        t.layout = m.layout;
        t.surface = m.surface;
        t.origin = m.origin;
        for (const LightingPathDesc& lp : pipeline.lightingPaths)
            if (lp.name == m.path) t.shading = lp.shading;
        t.fixup = m.fixup;
        t.forward = m.forward;
        t.channels = m.channels;
        for (const LayoutDesc& l : pipeline.layouts)
            if (l.name == m.layout)
                for (const TargetDesc& target : l.targets) {
                    t.targets.push_back(target.name);
                    t.targetInteger.push_back(formatInfo(target.format).integer);
                }
        t.fills = m.fills;
        for (const auto& [key, value] : m.params.asTable())
            if (value.isNumber()) t.custom.push_back(key);
        t.textures = m.textures;
        // Its identity, the whole byte: it replaces whatever was under it.
        t.stencilValue = m.identity;
        t.stencilMask = 255;
        out.push_back(std::move(t));
    }
    return out;
}

}  // namespace rg
