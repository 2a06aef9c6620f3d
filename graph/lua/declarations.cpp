#include "declarations.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace rg {

std::string nextToDeclaration(const std::string& origin, const std::string& path, const std::string& root) {
    if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
    const size_t colon = origin.rfind(':');
    if (colon == std::string::npos || colon == 0) return path;
    const std::filesystem::path script(origin.substr(0, colon));
    std::vector<std::filesystem::path> folders;
    if (script.is_absolute()) folders.push_back(script.parent_path());
    else {
        if (!root.empty()) folders.push_back((std::filesystem::path(root) / script).parent_path());
        folders.push_back(std::filesystem::absolute(script).parent_path());
    }
    for (const auto& folder : folders) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(folder / path, ec)) return std::filesystem::absolute(folder / path).lexically_normal().string();
    }
    return path;
}

const char* declKindName(DeclKind k) {
    switch (k) {
    case DeclKind::Texture: return "resource";
    case DeclKind::Buffer: return "buffer";
    case DeclKind::Pass: return "pass";
    case DeclKind::Param: return "param";
    case DeclKind::Layout: return "layout";
    case DeclKind::Stencil: return "stencil";
    case DeclKind::Path: return "path";
    case DeclKind::Material: return "material";
    case DeclKind::SceneMaterial: return "scene.material";
    case DeclKind::Sphere: return "scene.sphere";
    case DeclKind::Plane: return "scene.plane";
    case DeclKind::Box: return "scene.box";
    case DeclKind::Gltf: return "scene.gltf";
    case DeclKind::Light: return "scene.light";
    case DeclKind::Camera: return "scene.camera";
    case DeclKind::Environment: return "scene.environment";
    case DeclKind::Decal: return "scene.decal";
    case DeclKind::Probe: return "scene.probe";
    case DeclKind::Lightmap: return "scene.lightmap";
    case DeclKind::Count: break;
    }
    return "?";
}

bool isSceneKind(DeclKind k) { return k >= DeclKind::SceneMaterial && k < DeclKind::Count; }

namespace {

// A name GLSL accepts as an identifier: a letter or '_', then letters, digits and '_'.
bool isGlslIdentifier(const std::string& name) {
    return !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
           std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string typeOf(const Value& v) {
    if (v.isNumber()) return "number";
    if (v.isBool()) return "boolean";
    if (v.isString()) return "string";
    if (v.isList()) return "list";
    if (v.isTable()) return "table";
    return "nil";
}

bool isInteger(const Value& v) {
    return v.isNumber() && std::floor(v.asNumber()) == v.asNumber();
}

Result<void> expectType(const Where& w, const Value& v, const std::string& type) {
    bool ok = (type == "string" && v.isString()) || (type == "number" && v.isNumber()) ||
              (type == "boolean" && v.isBool()) || (type == "table" && (v.isTable() || (v.isList() && v.asList().empty()))) ||
              (type == "list" && v.isList()) || (type == "number|list" && (v.isNumber() || v.isList())) ||
              (type == "string|list" && (v.isString() || v.isList())) || (type == "integer" && isInteger(v));
    if (ok) return {};
    std::string want = type == "number|list" ? "a number or a list of numbers"
                       : type == "string|list" ? "a string or a list of strings"
                       : type == "integer"     ? "a whole number"
                       : type == "list"        ? "a list"
                       : type == "table"       ? "a table"
                       : type == "boolean"     ? "a boolean"
                                               : "a " + type;
    return w.error("expected " + want + ", got " + (v.isNumber() && type == "integer" ? "a fraction" : typeOf(v)));
}

Result<std::string> requireString(const Where& w, const Value& body, const std::string& field) {
    const Value& v = body[field];
    if (v.isNil()) return w.at(field).error("missing (expected a string)");
    if (auto r = expectType(w.at(field), v, "string"); !r) return std::unexpected(r.error());
    return v.asString();
}

Result<std::vector<std::string>> stringList(const Where& w, const Value& v) {
    std::vector<std::string> out;
    if (v.isNil()) return out;
    if (v.isString()) return std::vector<std::string>{v.asString()};
    if (!v.isList()) return w.error("expected a string or a list of strings, got " + typeOf(v));
    for (size_t i = 0; i < v.asList().size(); ++i) {
        const Value& e = v.asList()[i];
        if (!e.isString()) return w.index(i).error("expected a string, got " + typeOf(e));
        out.push_back(e.asString());
    }
    return out;
}

struct Builder {
    const std::vector<Declaration>& decls;
    const BuildOptions& options;
    PipelineDesc out;
    std::map<std::string, const Declaration*> resources;  // full name -> declaration
    std::map<std::string, const Declaration*> passes;
    std::vector<std::string> resourceNames, passNames;

    static std::string fullName(const Declaration& d) { return d.module.empty() ? d.name : d.module + "." + d.name; }
    static std::string section(DeclKind k) {
        switch (k) {
        case DeclKind::Texture:
        case DeclKind::Buffer: return "resources";
        case DeclKind::Pass: return "passes";
        case DeclKind::Param: return "params";
        case DeclKind::Layout: return "layouts";
        case DeclKind::Stencil: return "stencil";
        case DeclKind::Path: return "paths";
        case DeclKind::Material: return "materials";
        default: return "scene";
        }
    }
    static Where where(const Declaration& d) { return {d, section(d.kind) + "." + fullName(d)}; }

    // A resource name as a declaration in `module` means it: module-local first, then global.
    Result<std::string> resolveResource(const Where& w, const std::string& module, const std::string& name) {
        if (!module.empty() && resources.count(module + "." + name)) return module + "." + name;
        if (resources.count(name)) return name;
        return w.error("unknown resource '" + name + "'" + suggestion(name, resourceNames));
    }
    Result<std::string> resolvePass(const Where& w, const std::string& module, const std::string& name) {
        if (!module.empty() && passes.count(module + "." + name)) return module + "." + name;
        if (passes.count(name)) return name;
        return w.error("unknown pass '" + name + "'" + suggestion(name, passNames));
    }

    Result<void> collectNames() {
        std::map<std::string, const Declaration*> seen[static_cast<size_t>(DeclKind::Count)];
        for (const auto& d : decls) {
            Where w = where(d);
            if (isSceneKind(d.kind))
                return w.error(std::string(declKindName(d.kind)) + " belongs in a scene script (--scene), not in a pipeline");
            if (!d.body.isTable() && !(d.body.isList() && (d.kind == DeclKind::Layout || d.body.asList().empty())))
                return w.error("expected a table after " + std::string(declKindName(d.kind)) + " \"" + d.name + "\", got " + typeOf(d.body));
            // Textures and buffers share one namespace.
            size_t slot = d.kind == DeclKind::Buffer ? static_cast<size_t>(DeclKind::Texture) : static_cast<size_t>(d.kind);
            auto [it, fresh] = seen[slot].emplace(fullName(d), &d);
            if (!fresh)
                return w.error(std::string(declKindName(d.kind)) + " '" + fullName(d) + "' is declared twice (first at " +
                               it->second->origin + ")");
            if (d.kind == DeclKind::Texture || d.kind == DeclKind::Buffer) {
                resources[fullName(d)] = &d;
                resourceNames.push_back(fullName(d));
            } else if (d.kind == DeclKind::Pass) {
                passes[fullName(d)] = &d;
                passNames.push_back(fullName(d));
            }
        }
        return {};
    }

    Result<void> texture(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"format", "size", "scale", "mips", "layers", "scene_layers", "cube", "export", "import", "persistent", "doc"}); !r)
            return r;
        ResourceDesc r;
        r.name = fullName(d);
        r.origin = d.origin;
        auto format = requireString(w, b, "format");
        if (!format) return std::unexpected(format.error());
        auto f = parseFormat(*format);
        if (!f) return w.at("format").error("unknown format '" + *format + "'" + suggestion(*format, [] {
                                                std::vector<std::string> n;
                                                for (int i = 1; i < static_cast<int>(Format::Count); ++i) n.push_back(formatInfo(static_cast<Format>(i)).name);
                                                return n;
                                            }()) + "; expected one of: " + formatNameList());
        r.texture.format = *f;
        if (b.has("size") && b.has("scale")) return w.error("give either size (texels) or scale (fraction of the output), not both");
        if (b.has("size")) {
            const Value& s = b["size"];
            if (!s.isList() || s.asList().size() != 2 || !isInteger(s.asList()[0]) || !isInteger(s.asList()[1]) ||
                s.asList()[0].asNumber() < 1 || s.asList()[1].asNumber() < 1)
                return w.at("size").error("expected {width, height} in texels (whole numbers >= 1)");
            r.texture.sizeMode = SizeMode::Absolute;
            r.texture.width = static_cast<uint32_t>(s.asList()[0].asNumber());
            r.texture.height = static_cast<uint32_t>(s.asList()[1].asNumber());
        }
        if (b.has("scale")) {
            const Value& s = b["scale"];
            if (s.isNumber()) r.texture.scaleX = r.texture.scaleY = static_cast<float>(s.asNumber());
            else if (s.isList() && s.asList().size() == 2 && s.asList()[0].isNumber() && s.asList()[1].isNumber()) {
                r.texture.scaleX = static_cast<float>(s.asList()[0].asNumber());
                r.texture.scaleY = static_cast<float>(s.asList()[1].asNumber());
            } else
                return w.at("scale").error("expected a number or {x, y}: the fraction of the output size");
            if (r.texture.scaleX <= 0 || r.texture.scaleY <= 0 || r.texture.scaleX > 16 || r.texture.scaleY > 16)
                return w.at("scale").error("expected a value in (0, 16]");
        }
        if (b.has("mips")) {
            const Value& m = b["mips"];
            if (m.isString() && m.asString() == "full") r.texture.mips = 0;
            else if (isInteger(m) && m.asNumber() >= 1 && m.asNumber() <= 16) r.texture.mips = static_cast<uint32_t>(m.asNumber());
            else return w.at("mips").error("expected a whole number in 1..16 or \"full\"");
        }
        if (b.has("layers")) {
            if (!isInteger(b["layers"]) || b["layers"].asNumber() < 1 || b["layers"].asNumber() > 2048)
                return w.at("layers").error("expected a whole number in 1..2048");
            r.texture.layers = static_cast<uint32_t>(b["layers"].asNumber());
        }
        if (b.has("scene_layers")) {
            if (!b["scene_layers"].isString() || b["scene_layers"].asString() != "shadow_views")
                return w.at("scene_layers").error("expected \"shadow_views\" (the layers the scene's shadowed local lights need, at most `layers`)");
            if (b["cube"].asBool()) return w.at("scene_layers").error("a cube's layers are fixed; scene_layers is for arrays");
            r.texture.sceneLayers = b["scene_layers"].asString();
        }
        for (const char* flag : {"cube", "export", "import", "persistent"})
            if (b.has(flag))
                if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
        r.texture.cube = b["cube"].asBool();
        r.persistent = b["persistent"].asBool();
        if (r.texture.cube && !b.has("layers")) r.texture.layers = 6;  // one cube; `layers` = 6 × cubes for an array
        r.exported = b["export"].asBool();
        r.imported = b["import"].asBool();
        out.graph.resources.push_back(r);
        return {};
    }

    Result<void> buffer(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"size", "tile", "tile_bytes", "export", "import", "persistent", "doc"}); !r) return r;
        ResourceDesc r;
        r.name = fullName(d);
        r.origin = d.origin;
        r.kind = ResourceKind::Buffer;
        if (!isInteger(b["size"]) || b["size"].asNumber() < 4)
            return w.at("size").error(b.has("size") ? "expected a whole number of bytes >= 4" : "missing (expected the size in bytes)");
        r.buffer.size = static_cast<uint64_t>(b["size"].asNumber());
        // Screen-tiled: `tile_bytes` more for every tile x tile pixels of the output.
        if (b.has("tile") != b.has("tile_bytes"))
            return w.at(b.has("tile") ? "tile_bytes" : "tile").error("missing (a tiled buffer gives both tile, in pixels, and tile_bytes)");
        if (b.has("tile")) {
            if (!isInteger(b["tile"]) || b["tile"].asNumber() < 1 || b["tile"].asNumber() > 256)
                return w.at("tile").error("expected a tile size in pixels, 1..256");
            if (!isInteger(b["tile_bytes"]) || b["tile_bytes"].asNumber() < 4 || b["tile_bytes"].asNumber() > (1 << 20))
                return w.at("tile_bytes").error("expected a whole number of bytes per tile, 4..1048576");
            r.buffer.tileSize = static_cast<uint32_t>(b["tile"].asNumber());
            r.buffer.tileBytes = static_cast<uint64_t>(b["tile_bytes"].asNumber());
        }
        for (const char* flag : {"export", "import", "persistent"})
            if (b.has(flag))
                if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
        r.exported = b["export"].asBool();
        r.imported = b["import"].asBool();
        r.persistent = b["persistent"].asBool();
        out.graph.resources.push_back(r);
        return {};
    }

    const PassKindSchema* kindSchema(const std::string& name) const {
        for (const auto& k : options.kinds)
            if (k.name == name) return &k;
        return nullptr;
    }

    // One entry of reads/writes: "name" or { "name", as = "...", load = true }.
    Result<Access> access(const Where& w, const Declaration& d, const Value& e, bool write, const PassKindSchema& kind) {
        std::string name, as;
        bool load = write && kind.writesLoad;
        if (e.isString()) name = e.asString();
        else if (e.isTable()) {
            if (auto r = checkFields(w, e, {"#1", "as", "load"}); !r) return std::unexpected(r.error());
            if (!e["#1"].isString()) return w.error("expected the resource name as the first entry, e.g. { \"depth\", as = \"depth\" }");
            name = e["#1"].asString();
            if (e.has("as")) {
                if (auto r = expectType(w.at("as"), e["as"], "string"); !r) return std::unexpected(r.error());
                as = e["as"].asString();
            }
            if (e.has("load")) {
                if (!write) return w.at("load").error("only writes can load");
                if (auto r = expectType(w.at("load"), e["load"], "boolean"); !r) return std::unexpected(r.error());
                load = e["load"].asBool();
            }
        } else
            return w.error("expected a resource name or { \"name\", as = \"...\" }, got " + typeOf(e));
        auto resolved = resolveResource(w, d.module, name);
        if (!resolved) return std::unexpected(resolved.error());
        Access a;
        a.resource = *resolved;
        a.load = load;
        a.field = w.path;
        const Declaration* rd = resources[*resolved];
        bool depthFormat = false;
        if (rd->kind == DeclKind::Texture && rd->body["format"].isString())
            if (auto f = parseFormat(rd->body["format"].asString())) depthFormat = isDepthStencil(*f);
        static const std::vector<std::pair<std::string, Usage>> readUsages = {
            {"sampled", Usage::Sampled}, {"storage", Usage::StorageRead}, {"uniform", Usage::UniformRead},
            {"depth", Usage::DepthStencilRead}, {"copy", Usage::CopySrc}, {"indirect", Usage::IndirectRead}};
        static const std::vector<std::pair<std::string, Usage>> writeUsages = {
            {"color", Usage::ColorAttachment}, {"depth", Usage::DepthStencilAttachment}, {"storage", Usage::StorageWrite},
            {"storage_rw", Usage::StorageReadWrite}, {"copy", Usage::CopyDst}};
        const auto& table = write ? writeUsages : readUsages;
        if (as.empty()) {
            a.usage = write ? kind.defaultWrite : kind.defaultRead;
            if (write && depthFormat && a.usage == Usage::ColorAttachment) a.usage = Usage::DepthStencilAttachment;
            if (rd->kind == DeclKind::Buffer && (a.usage == Usage::Sampled)) a.usage = Usage::StorageRead;
            if (rd->kind == DeclKind::Buffer && (a.usage == Usage::ColorAttachment)) a.usage = Usage::StorageWrite;
        } else {
            auto it = std::find_if(table.begin(), table.end(), [&](auto& p) { return p.first == as; });
            if (it == table.end()) {
                std::vector<std::string> names;
                for (auto& p : table) names.push_back(p.first);
                return w.at("as").error("unknown usage '" + as + "'" + suggestion(as, names) + "; expected one of: " + joinQuoted(names));
            }
            a.usage = it->second;
        }
        return a;
    }

    Result<void> pass(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        auto kindName = requireString(w, b, "kind");
        if (!kindName) return std::unexpected(kindName.error());
        const PassKindSchema* kind = kindSchema(*kindName);
        if (!kind) {
            std::vector<std::string> names;
            for (const auto& k : options.kinds) names.push_back(k.name);
            return w.at("kind").error("unknown pass kind '" + *kindName + "'" + suggestion(*kindName, names) +
                                      "; expected one of: " + joinQuoted(names));
        }
        std::vector<std::string> allowed = {"kind", "reads", "writes", "after", "enabled", "side_effect", "doc", "insert"};
        for (const auto& p : kind->params) allowed.push_back(p.name);
        if (auto r = checkFields(w, b, allowed); !r) return r;
        PassDesc p;
        p.name = fullName(d);
        p.kind = kind->name;
        p.type = kind->type;
        p.origin = d.origin;
        Value::Table params;
        for (const auto& spec : kind->params) {
            if (!b.has(spec.name)) continue;
            if (auto r = expectType(w.at(spec.name), b[spec.name], spec.type); !r) return r;
            params[spec.name] = b[spec.name];
        }
        p.params = Value(params);
        for (const char* field : {"reads", "writes"}) {
            const bool write = std::string(field) == "writes";
            const Value& list = b[field];
            if (list.isNil()) continue;
            if (!list.isList() && !(list.isTable() && list.asTable().empty()))
                return w.at(field).error("expected a list of resource names, got " + typeOf(list));
            for (size_t i = 0; i < list.asList().size(); ++i) {
                auto a = access(w.at(field).index(i), d, list.asList()[i], write, *kind);
                if (!a) return std::unexpected(a.error());
                p.accesses.push_back(*a);
            }
        }
        auto after = stringList(w.at("after"), b["after"]);
        if (!after) return std::unexpected(after.error());
        for (size_t i = 0; i < after->size(); ++i) {
            auto name = resolvePass(b["after"].isList() ? w.at("after").index(i) : w.at("after"), d.module, (*after)[i]);
            if (!name) return std::unexpected(name.error());
            p.after.push_back(*name);
        }
        for (const char* flag : {"enabled", "side_effect"})
            if (b.has(flag))
                if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
        p.enabled = b["enabled"].asBool(true);
        p.sideEffect = b["side_effect"].asBool();
        out.graph.passes.push_back(p);
        return {};
    }

    Result<void> param(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"type", "default", "min", "max", "choices", "doc"}); !r) return r;
        ParamDesc p;
        p.name = fullName(d);
        p.origin = d.origin;
        p.doc = b["doc"].asString();
        auto type = requireString(w, b, "type");
        if (!type) return std::unexpected(type.error());
        static const std::vector<std::pair<std::string, ParamType>> types = {
            {"number", ParamType::Number}, {"integer", ParamType::Integer}, {"boolean", ParamType::Boolean},
            {"vec3", ParamType::Vec3}, {"choice", ParamType::Choice}};
        auto it = std::find_if(types.begin(), types.end(), [&](auto& t) { return t.first == *type; });
        if (it == types.end()) {
            std::vector<std::string> names;
            for (auto& t : types) names.push_back(t.first);
            return w.at("type").error("unknown type '" + *type + "'" + suggestion(*type, names) + "; expected one of: " + joinQuoted(names));
        }
        p.type = it->second;
        for (const char* bound : {"min", "max"}) {
            if (!b.has(bound)) continue;
            if (p.type != ParamType::Number && p.type != ParamType::Integer)
                return w.at(bound).error(std::string("only number and integer parameters have a ") + bound);
            if (auto r = expectType(w.at(bound), b[bound], "number"); !r) return r;
        }
        p.min = b["min"].asNumber(p.min);
        p.max = b["max"].asNumber(p.max);
        if (p.min > p.max) {
            char b[96];
            std::snprintf(b, sizeof b, "min (%g) is above max (%g)", p.min, p.max);
            return w.at("min").error(b);
        }
        if (p.type == ParamType::Choice) {
            auto choices = stringList(w.at("choices"), b["choices"]);
            if (!choices) return std::unexpected(choices.error());
            if (choices->empty()) return w.at("choices").error("missing (expected the list of allowed strings)");
            p.choices = *choices;
        } else if (b.has("choices"))
            return w.at("choices").error("only choice parameters have choices");
        if (!b.has("default")) return w.at("default").error("missing (expected the default value)");
        auto value = checkParamValue(p, b["default"]);
        if (!value) return w.at("default").error(value.error().message);
        p.value = *value;
        out.params.push_back(p);
        return {};
    }

    Result<void> layout(const Declaration& d) {
        Where w = where(d);
        LayoutDesc l;
        // Layout names become GLSL identifiers (GBuffer_<name>): modules use '_' as separator.
        l.name = d.module.empty() ? d.name : d.module + "_" + d.name;
        l.origin = d.origin;
        if (!d.body.isList()) return w.error("expected a list of targets: { { \"GB0\", \"rgb10a2\", { \"normal:oct:20\", ... } }, ... }");
        for (size_t i = 0; i < d.body.asList().size(); ++i) {
            const Value& t = d.body.asList()[i];
            Where tw = w.index(i);
            if (!t.isList() || t.asList().size() != 3 || !t.asList()[0].isString() || !t.asList()[1].isString() || !t.asList()[2].isList())
                return tw.error("expected { \"name\", \"format\", { \"channel:encoding:bits\", ... } }");
            TargetDesc target;
            target.name = t.asList()[0].asString();
            target.origin = d.origin;
            auto f = parseFormat(t.asList()[1].asString());
            if (!f) return tw.index(1).error("unknown format '" + t.asList()[1].asString() + "'; expected one of: " + formatNameList());
            target.format = *f;
            const auto& channels = t.asList()[2].asList();
            for (size_t c = 0; c < channels.size(); ++c) {
                Where cw = tw.index(2).index(c);
                if (!channels[c].isString()) return cw.error("expected \"name:encoding:bits\", got " + typeOf(channels[c]));
                std::string spec = channels[c].asString();
                std::vector<std::string> parts;
                size_t start = 0;
                for (size_t pos; (pos = spec.find(':', start)) != std::string::npos; start = pos + 1) parts.push_back(spec.substr(start, pos - start));
                parts.push_back(spec.substr(start));
                // bits: a total ("20") or per component times components ("16x3").
                uint32_t components = 0, bits = 0;
                bool ok = parts.size() == 3 && !parts[0].empty();
                if (ok) {
                    std::string b = parts[2];
                    size_t x = b.find('x');
                    std::string total = x == std::string::npos ? b : b.substr(0, x);
                    std::string count = x == std::string::npos ? "" : b.substr(x + 1);
                    ok = !total.empty() && total.size() <= 3 && total.find_first_not_of("0123456789") == std::string::npos &&
                         (x == std::string::npos || (!count.empty() && count.size() == 1 && std::isdigit(static_cast<unsigned char>(count[0]))));
                    if (ok) {
                        bits = static_cast<uint32_t>(std::stoul(total));
                        if (!count.empty()) {
                            components = static_cast<uint32_t>(count[0] - '0');
                            bits *= components;
                        }
                    }
                }
                if (!ok)
                    return cw.error("expected \"name:encoding:bits\" (e.g. \"smoothness:unorm:10\" or \"emissive:float:16x3\"), got \"" + spec + "\"");
                ChannelDesc ch;
                ch.name = parts[0];
                ch.origin = d.origin;
                auto encoding = parseEncoding(parts[1]);
                if (!encoding) {
                    std::vector<std::string> names;
                    for (auto e : {Encoding::Unorm, Encoding::Snorm, Encoding::Srgb, Encoding::Oct, Encoding::Uint, Encoding::Float})
                        names.emplace_back(encodingName(e));
                    return cw.error("unknown encoding '" + parts[1] + "'" + suggestion(parts[1], names) + "; expected one of: " + encodingNameList());
                }
                ch.encoding = *encoding;
                ch.bits = bits;
                ch.components = components;
                target.channels.push_back(ch);
            }
            l.targets.push_back(target);
        }
        auto info = analyzeLayout(l);
        if (!info) return std::unexpected(info.error());
        out.layouts.push_back(l);
        return {};
    }

    // Classes of their own take the low `stencilBits` (explicit values first, then the lowest
    // free value in declaration order); variants (`variant_of`) keep their base's low bits and
    // take the lowest free value in the high bits, so a class's value never depends on another
    // class's explicit value.
    Result<void> stencils() {
        const uint32_t bits = options.stencilBits;
        const uint32_t capacity = (1u << bits) - 1;
        const uint32_t variants = (1u << (8 - bits)) - 1;
        std::map<uint32_t, const Declaration*> taken;
        std::map<std::string, const Declaration*> byName;
        for (int pass = 0; pass < 3; ++pass) {
            for (const auto& d : decls) {
                if (d.kind != DeclKind::Stencil) continue;
                Where w = where(d);
                if (pass == 0) {
                    if (auto r = checkFields(w, d.body, {"value", "variant_of", "doc"}); !r) return r;
                    if (d.body.has("variant_of") && d.body.has("value"))
                        return w.at("value").error("a variant takes its base's value in the low bits and is allocated the high bits; give no value");
                    if (d.body.has("doc"))
                        if (auto r = expectType(w.at("doc"), d.body["doc"], "string"); !r) return r;
                }
                const bool variant = d.body.has("variant_of");
                const bool explicitValue = d.body.has("value");
                if (pass != (variant ? 2 : explicitValue ? 0 : 1)) continue;
                StencilClassDesc c{fullName(d), 0, capacity, "", d.body["doc"].asString(), d.origin};
                if (variant) {
                    if (auto r = expectType(w.at("variant_of"), d.body["variant_of"], "string"); !r) return r;
                    const std::string baseName = d.body["variant_of"].asString();
                    auto base = std::find_if(out.stencilClasses.begin(), out.stencilClasses.end(), [&](auto& s) { return s.name == baseName; });
                    if (base == out.stencilClasses.end()) {
                        std::vector<std::string> names;
                        for (const auto& s : out.stencilClasses) names.push_back(s.name);
                        return w.at("variant_of").error("unknown stencil class '" + baseName + "'" + suggestion(baseName, names) +
                                                        (names.empty() ? "" : "; expected one of: " + joinQuoted(names)));
                    }
                    if (!base->base.empty())
                        return w.at("variant_of").error("'" + baseName + "' is itself a variant of '" + base->base + "'; name a class of its own");
                    uint32_t k = 1;
                    while (k <= variants && taken.count(base->value | (k << bits))) ++k;
                    if (k > variants)
                        return w.error("no variant of '" + baseName + "' left: the high " + std::to_string(8 - bits) + " stencil bits hold " +
                                       std::to_string(variants) + " variants per class");
                    c.value = base->value | (k << bits);
                    c.mask = 0xFFu;
                    c.base = base->name;
                } else if (explicitValue) {
                    const Value& v = d.body["value"];
                    if (!isInteger(v) || v.asNumber() < 1 || v.asNumber() > capacity)
                        return w.at("value").error("expected a whole number in 1.." + std::to_string(capacity) + " (" + std::to_string(bits) +
                                                   " stencil bits for classes; a class lit as another is a variant: variant_of = \"class\")");
                    c.value = static_cast<uint32_t>(v.asNumber());
                    if (taken.count(c.value))
                        return w.at("value").error(std::to_string(c.value) + " is already the value of stencil class '" +
                                                   fullName(*taken[c.value]) + "' (" + taken[c.value]->origin + ")");
                } else {
                    for (c.value = 1; c.value <= capacity && taken.count(c.value); ++c.value) {}
                    if (c.value > capacity) {
                        std::vector<std::string> names;
                        for (auto& [_, td] : taken) names.push_back(fullName(*td));
                        return w.error("no stencil value left: " + std::to_string(bits) + " stencil bits hold " +
                                       std::to_string(capacity) + " classes, all taken by " + joinQuoted(names));
                    }
                }
                taken[c.value] = &d;
                out.stencilClasses.push_back(c);
            }
        }
        // Keep declaration order in the result.
        std::vector<StencilClassDesc> ordered;
        for (const auto& d : decls)
            for (const auto& s : out.stencilClasses)
                if (d.kind == DeclKind::Stencil && s.name == fullName(d)) ordered.push_back(s);
        out.stencilClasses = ordered;
        return {};
    }

    bool hasStencil(const std::string& n) const {
        return std::any_of(out.stencilClasses.begin(), out.stencilClasses.end(), [&](auto& s) { return s.name == n; });
    }
    std::vector<std::string> stencilNames() const {
        std::vector<std::string> v;
        for (auto& s : out.stencilClasses) v.push_back(s.name);
        return v;
    }

    Result<void> path(const Declaration& d) {
        Where w = where(d);
        if (auto r = checkFields(w, d.body, {"stencil", "shading", "doc"}); !r) return r;
        auto stencil = requireString(w, d.body, "stencil");
        if (!stencil) return std::unexpected(stencil.error());
        if (!hasStencil(*stencil))
            return w.at("stencil").error("unknown stencil class '" + *stencil + "'" + suggestion(*stencil, stencilNames()));
        std::string shading;
        if (d.body.has("shading")) {
            if (auto r = expectType(w.at("shading"), d.body["shading"], "string"); !r) return r;
            // Next to the declaring script (a game team's folder), else the shader include folders.
            shading = nextToDeclaration(d.origin, d.body["shading"].asString(), options.projectRoot);
        }
        out.lightingPaths.push_back({fullName(d), *stencil, shading, d.body["doc"].asString(), d.origin});
        return {};
    }

    // `channels = { baseColor = "diffuseColor" }`: which of the layout's channels holds each
    // standard parameter (kStandardChannels) where the name differs; the rest by their own name.
    // `decals = { "normal", ... }` (or false): the standard parameters decals blend; by default
    // the seed's common set that the layout holds (000 §3.3: Normal, BaseColor, Smoothness).
    Result<void> standardChannels(const Where& w, const Value& b, const LayoutDesc& layout, MaterialDesc& m) {
        auto channel = [&](const std::string& name) -> const ChannelDesc* {
            for (const auto& t : layout.targets)
                for (const auto& c : t.channels)
                    if (c.name == name) return &c;
            return nullptr;
        };
        // What each standard parameter needs of its channel: components, and a float encoding.
        auto fits = [&](const std::string& standard, const ChannelDesc& c) {
            const bool vec3 = standard == "normal" || standard == "baseColor" || standard == "f0" || standard == "emissive";
            if (c.encoding == Encoding::Uint) return false;
            if (standard == "normal") return c.encoding == Encoding::Oct || (c.encoding == Encoding::Snorm && valueComponents(c) == 3);
            return valueComponents(c) == (vec3 ? 3u : 1u);
        };
        std::vector<std::string> standard(std::begin(kStandardChannels), std::end(kStandardChannels));
        if (b.has("channels")) {
            if (auto r = expectType(w.at("channels"), b["channels"], "table"); !r) return r;
            for (const auto& [key, value] : b["channels"].asTable()) {
                const Where cw = w.at("channels").at(key);
                if (std::find(standard.begin(), standard.end(), key) == standard.end())
                    return cw.error("not a standard parameter" + suggestion(key, standard) + "; expected one of: " + joinQuoted(standard));
                if (!value.isString()) return cw.error("expected the name of a channel of layout '" + layout.name + "'");
                m.channels[key] = value.asString();
            }
        }
        for (const auto& s : standard) {
            const bool declared = m.channels.count(s) > 0;
            const std::string name = declared ? m.channels[s] : s;
            const ChannelDesc* c = channel(name);
            if (!c) {
                if (declared) {
                    std::vector<std::string> names;
                    for (const auto& t : layout.targets)
                        for (const auto& ch : t.channels) names.push_back(ch.name);
                    return w.at("channels").at(s).error("layout '" + layout.name + "' has no channel '" + name + "'" + suggestion(name, names));
                }
                continue;
            }
            if (!fits(s, *c)) {
                if (declared)
                    return w.at("channels").at(s).error("channel '" + name + "' (" + std::string(encodingName(c->encoding)) + ", " +
                                                        std::to_string(valueComponents(*c)) + " components) cannot hold " + s);
                continue;  // a channel of the same name but another meaning: not the standard one
            }
            m.channels[s] = name;
        }
        std::vector<std::string> allowed(std::begin(kDecalParameters), std::end(kDecalParameters));
        if (!b.has("decals")) {
            for (const char* s : {"normal", "baseColor", "smoothness"})
                if (m.channels.count(s)) m.decals.push_back(s);
            return {};
        }
        const Value& dv = b["decals"];
        if (dv.isBool() && !dv.asBool()) return {};
        auto list = stringList(w.at("decals"), dv);
        if (!list) return std::unexpected(list.error());
        for (size_t i = 0; i < list->size(); ++i) {
            const std::string& s = (*list)[i];
            if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
                return w.at("decals").index(i).error("decals blend " + joinQuoted(allowed) + suggestion(s, allowed) + "; not '" + s + "'");
            if (!m.channels.count(s))
                return w.at("decals").index(i).error("layout '" + layout.name + "' has no channel for " + s +
                                                     " (name it in channels = { " + s + " = \"...\" }), so decals cannot blend it");
            m.decals.push_back(s);
        }
        return {};
    }

    Result<void> material(const Declaration& d, std::map<uint32_t, const Declaration*>& ids) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"id", "layout", "surface", "path", "stencil", "fills", "fixup", "params", "channels", "decals", "doc"}); !r)
            return r;
        MaterialDesc m;
        m.name = fullName(d);
        m.origin = d.origin;
        if (!b.has("id")) return w.at("id").error("missing (expected the materialId, a whole number)");
        if (!isInteger(b["id"]) || b["id"].asNumber() < 0) return w.at("id").error("expected a whole number >= 0");
        m.id = static_cast<uint32_t>(b["id"].asNumber());
        auto layoutName = requireString(w, b, "layout");
        if (!layoutName) return std::unexpected(layoutName.error());
        auto lit = std::find_if(out.layouts.begin(), out.layouts.end(),
                                [&](auto& l) { return !d.module.empty() && l.name == d.module + "_" + *layoutName; });
        if (lit == out.layouts.end())
            lit = std::find_if(out.layouts.begin(), out.layouts.end(), [&](auto& l) { return l.name == *layoutName; });
        if (lit == out.layouts.end()) {
            std::vector<std::string> names;
            for (auto& l : out.layouts) names.push_back(l.name);
            return w.at("layout").error("unknown layout '" + *layoutName + "'" + suggestion(*layoutName, names));
        }
        m.layout = lit->name;
        // The id must fit the layout's materialId field.
        for (const auto& t : lit->targets)
            for (const auto& c : t.channels)
                if (c.name == "materialId" && c.encoding == Encoding::Uint && c.bits < 32 && m.id >= (1u << c.bits))
                    return w.at("id").error(std::to_string(m.id) + " does not fit layout '" + m.layout + "': its materialId has " +
                                            std::to_string(c.bits) + " bits (ids 0.." + std::to_string((1u << c.bits) - 1) + ")");
        for (const char* field : {"surface", "path", "stencil", "fixup"})
            if (b.has(field))
                if (auto r = expectType(w.at(field), b[field], "string"); !r) return r;
        m.surface = b["surface"].asString();
        // A surface file next to the declaring script (a game team's folder) is found there;
        // otherwise the shader include folders are searched (materials/, shaders/).
        if (!m.surface.empty()) m.surface = nextToDeclaration(d.origin, m.surface, options.projectRoot);
        m.path = b["path"].asString();
        if (!m.path.empty()) {
            auto pit = std::find_if(out.lightingPaths.begin(), out.lightingPaths.end(), [&](auto& p) { return p.name == m.path; });
            if (pit == out.lightingPaths.end()) {
                std::vector<std::string> names;
                for (auto& p : out.lightingPaths) names.push_back(p.name);
                return w.at("path").error("unknown lighting path '" + m.path + "'" + suggestion(m.path, names));
            }
            m.stencil = pit->stencil;
        }
        if (b.has("stencil")) {
            m.stencil = b["stencil"].asString();
            if (!hasStencil(m.stencil))
                return w.at("stencil").error("unknown stencil class '" + m.stencil + "'" + suggestion(m.stencil, stencilNames()));
        }
        auto fills = stringList(w.at("fills"), b["fills"]);
        if (!fills) return std::unexpected(fills.error());
        for (size_t i = 0; i < fills->size(); ++i) {
            std::vector<std::string> targets;
            for (auto& t : lit->targets) targets.push_back(t.name);
            if (std::find(targets.begin(), targets.end(), (*fills)[i]) == targets.end())
                return w.at("fills").index(i).error("layout '" + m.layout + "' has no target '" + (*fills)[i] + "'" +
                                                    suggestion((*fills)[i], targets));
        }
        m.fills = *fills;
        m.fixup = b["fixup"].asString();
        if (!m.fixup.empty()) {
            auto p = resolvePass(w.at("fixup"), d.module, m.fixup);
            if (!p) return std::unexpected(p.error());
            m.fixup = *p;
        }
        if (!m.fills.empty() && m.fills.size() < lit->targets.size() && m.fixup.empty())
            return w.at("fixup").error("material fills only part of layout '" + m.layout + "': name the fix-up pass that fills the rest");
        if (auto r = standardChannels(w, b, *lit, m); !r) return r;
        // A lighting path's pass and shading function decode one layout.
        if (!m.path.empty())
            for (const MaterialDesc& other : out.materials)
                if (other.path == m.path && other.layout != m.layout)
                    return w.at("path").error("lighting path '" + m.path + "' lights layout '" + other.layout + "' (material '" + other.name + "', " +
                                              other.origin + "); this material's layout is '" + m.layout +
                                              "': a path's lighting pass and shading function decode one layout, so declare a path of its own");
        // A materialId names how its pixels decode (decals, debug views): materials may share
        // one when they decode alike, as foliage shares the standard material's after its fix-up.
        if (ids.count(m.id)) {
            const MaterialDesc& first = *std::find_if(out.materials.begin(), out.materials.end(), [&](auto& x) { return x.id == m.id; });
            const std::string shared = std::to_string(m.id) + " is the id of material '" + first.name + "' (" + first.origin + ")";
            if (first.layout != m.layout)
                return w.at("id").error(shared + " of layout '" + first.layout + "': materials share an id only when their pixels decode alike (the same layout); choose a free id");
            if (!b.has("channels") && !b.has("decals")) {
                m.channels = first.channels;
                m.decals = first.decals;
            } else if (first.channels != m.channels || first.decals != m.decals)
                return w.at(b.has("decals") ? "decals" : "channels").error(shared + " with other channels or decals: materials sharing an id decode alike; match them or choose a free id");
        }
        ids.emplace(m.id, &d);
        if (b.has("params"))
            if (auto r = expectType(w.at("params"), b["params"], "table"); !r) return r;
        m.params = b["params"];
        // Numeric params become `#define NAME material.custom[i][j]` in the generated G-buffer
        // shader (passes/scene_pass.cpp): a name that is also a layout channel, a field of the
        // sampled surface or a name of the generated code would rewrite that code.
        {
            static const std::vector<std::string> reserved = {
                "position", "normal", "baseColor", "opacity", "smoothness", "metalMask", "reflectance", "ao", "emissive",
                "diffuseColor", "f0", "twoColour",  // RgSurface (shaders/lib/material.glsl)
                "material", "s", "g", "main", "worldPosition", "worldNormal", "worldTangent", "uv0", "uv1"};  // the generated code
            for (const auto& [name, value] : m.params.asTable()) {
                const Where pw = w.at("params").at(name);
                if (!isGlslIdentifier(name)) return pw.error("a material parameter's name must be a GLSL identifier (letters, digits, _)");
                if (name.rfind("rg", 0) == 0 || name.rfind("RG_", 0) == 0 || name.rfind("gl_", 0) == 0)
                    return pw.error("names starting with 'rg', 'RG_' or 'gl_' are rgraph's and GLSL's; choose another");
                for (const auto& t : lit->targets)
                    for (const auto& c : t.channels)
                        if (c.name == name)
                            return pw.error("clashes with channel '" + name + "' of layout '" + m.layout + "' (target " + t.name +
                                            "): the generated shader defines each parameter as a name; choose another");
                if (std::find(reserved.begin(), reserved.end(), name) != reserved.end())
                    return pw.error("clashes with '" + name + "' of the generated G-buffer shader (the sampled surface's fields and its variables: " +
                                    joinQuoted(reserved) + "); choose another");
            }
        }
        out.materials.push_back(m);
        return {};
    }

    // Decals and debug views find a pixel's layout from its materialId, so every layout a
    // material uses keeps materialId in the same place (000 §3.2: "MaterialId at the same place
    // for every material", to interpret MaterialData): the same target, bits and width.
    Result<void> checkMaterialIdPlacement() {
        struct Place {
            std::string target;
            uint32_t component = 0, bitOffset = 0, bits = 0;
            Encoding encoding = Encoding::Uint;
            bool operator==(const Place&) const = default;
        };
        auto describe = [](const Place& p) {
            static const char* comps = "RGBA";
            return "target " + p.target + "." + comps[p.component] + " bits " + std::to_string(p.bitOffset) + ".." +
                   std::to_string(p.bitOffset + p.bits - 1) + " (" + std::string(encodingName(p.encoding)) + ")";
        };
        std::optional<Place> first;
        const MaterialDesc* firstMaterial = nullptr;
        for (const MaterialDesc& m : out.materials) {
            const LayoutDesc& l = *std::find_if(out.layouts.begin(), out.layouts.end(), [&](auto& x) { return x.name == m.layout; });
            auto info = analyzeLayout(l);
            if (!info) return std::unexpected(info.error());
            const int c = info->find("materialId");
            const Declaration& d = *std::find_if(decls.begin(), decls.end(), [&](auto& x) { return x.kind == DeclKind::Material && fullName(x) == m.name; });
            if (c < 0)
                return where(d).at("layout").error("layout '" + l.name + "' has no materialId channel: decals and debug views tell a pixel's layout by it (declare \"materialId:uint:2\" where the other layouts keep it)");
            const ChannelPlacement& pl = info->channels[static_cast<size_t>(c)];
            Place p{l.targets[pl.target].name, pl.component, pl.bitOffset, info->channelDesc(static_cast<size_t>(c)).bits,
                    info->channelDesc(static_cast<size_t>(c)).encoding};
            if (p.encoding != Encoding::Uint)
                return where(d).at("layout").error("layout '" + l.name + "' keeps materialId as " + std::string(encodingName(p.encoding)) + "; it must be a uint field");
            if (!first) {
                first = p;
                firstMaterial = &m;
            } else if (!(p == *first))
                return where(d).at("layout").error("layout '" + l.name + "' keeps materialId in " + describe(p) + ", but layout '" + firstMaterial->layout +
                                                   "' (material '" + firstMaterial->name + "', " + firstMaterial->origin + ") keeps it in " + describe(*first) +
                                                   ": every layout of a pipeline keeps materialId in the same place");
        }
        return {};
    }

    // Module passes with `insert = { after = X }` / `{ before = X }` move next to X,
    // in declaration order (so two modules after the same pass keep their load order).
    Result<void> insertModulePasses() {
        std::vector<PassDesc> ordered;
        std::vector<std::pair<PassDesc, const Declaration*>> inserted;
        for (auto& p : out.graph.passes) {
            const Declaration* d = passes[p.name];
            if (d->body.has("insert")) inserted.emplace_back(p, d);
            else ordered.push_back(p);
        }
        for (auto& [p, d] : inserted) {
            Where w = where(*d).at("insert");
            const Value& ins = d->body["insert"];
            if (!ins.isTable()) return w.error("expected { after = \"pass\" } or { before = \"pass\" }");
            if (auto r = checkFields(w, ins, {"after", "before"}); !r) return r;
            if (ins.has("after") == ins.has("before")) return w.error("give exactly one of after / before");
            const bool after = ins.has("after");
            const Value& anchorV = ins[after ? "after" : "before"];
            if (!anchorV.isString()) return w.at(after ? "after" : "before").error("expected a pass name");
            auto anchor = resolvePass(w.at(after ? "after" : "before"), d->module, anchorV.asString());
            if (!anchor) return std::unexpected(anchor.error());
            auto it = std::find_if(ordered.begin(), ordered.end(), [&](auto& q) { return q.name == *anchor; });
            if (it == ordered.end()) return w.error("pass '" + *anchor + "' is itself inserted later; insert after a pass of the pipeline");
            if (after) {
                ++it;
                // Skip passes inserted after the same anchor earlier.
                while (it != ordered.end() && passes[it->name]->body["insert"]["after"].asString() == anchorV.asString() &&
                       passes[it->name]->body.has("insert"))
                    ++it;
            }
            ordered.insert(it, p);
        }
        out.graph.passes = ordered;
        return {};
    }

    // Passes that name stencil classes (stencil = { class = ... }) or select materials (scene
    // passes: materials = { ... }, paths = { ... }) name ones that exist, with surfaces.
    Result<void> checkMaterialReferences() {
        for (const auto& p : out.graph.passes) {
            const Declaration& d = *passes[p.name];
            Where w = where(d);
            const Value& stencil = p.params["stencil"];
            if (stencil.has("class")) {
                const std::string cls = stencil["class"].asString();
                if (!hasStencil(cls))
                    return w.at("stencil").at("class").error("unknown stencil class '" + cls + "'" + suggestion(cls, stencilNames()));
            }
            if (p.kind != "scene") continue;
            std::vector<std::string> materialNames, pathNames;
            for (const auto& m : out.materials) materialNames.push_back(m.name);
            for (const auto& lp : out.lightingPaths) pathNames.push_back(lp.name);
            auto selected = stringList(w.at("materials"), p.params["materials"]);
            if (!selected) return std::unexpected(selected.error());
            for (size_t i = 0; i < selected->size(); ++i)
                if (std::find(materialNames.begin(), materialNames.end(), (*selected)[i]) == materialNames.end())
                    return w.at("materials").index(i).error("unknown material '" + (*selected)[i] + "'" + suggestion((*selected)[i], materialNames));
            auto paths = stringList(w.at("paths"), p.params["paths"]);
            if (!paths) return std::unexpected(paths.error());
            for (size_t i = 0; i < paths->size(); ++i)
                if (std::find(pathNames.begin(), pathNames.end(), (*paths)[i]) == pathNames.end())
                    return w.at("paths").index(i).error("unknown lighting path '" + (*paths)[i] + "'" + suggestion((*paths)[i], pathNames));
            for (const auto& m : out.materials) {
                const bool chosen = (selected->empty() && paths->empty()) ||
                                    std::find(selected->begin(), selected->end(), m.name) != selected->end() ||
                                    std::find(paths->begin(), paths->end(), m.path) != paths->end();
                if (chosen && m.surface.empty())
                    return w.error("material '" + m.name + "' (" + m.origin + ") has no surface function (surface = \"file.glsl\"), so this scene pass cannot draw it");
            }
        }
        return {};
    }

    // switches = { param = "DEFINE" }: parameters compiled into a pass's shaders as defines
    // (graphWithParams), named by the pipeline's parameters, each a GLSL identifier given once.
    Result<void> checkSwitches() {
        for (const auto& p : out.graph.passes) {
            const Value& switches = p.params["switches"];
            if (switches.isNil()) continue;
            Where w = where(*passes[p.name]).at("switches");
            std::vector<std::string> defines;
            for (const auto& [param, define] : switches.asTable()) {
                const Where sw = w.at(param);
                const ParamDesc* d = out.findParam(param);
                if (!d) {
                    std::vector<std::string> params;
                    for (const auto& q : out.params) params.push_back(q.name);
                    return sw.error("unknown parameter '" + param + "'" + suggestion(param, params) + " (declare it with rg.param)");
                }
                if (d->type == ParamType::Vec3)
                    return sw.error("parameter '" + param + "' is a vec3; a switch takes a number, an integer, a boolean or a choice");
                const std::string name = define.isString() ? define.asString() : "";
                if (!isGlslIdentifier(name)) return sw.error("expected the name of a define (a GLSL identifier), got " + (define.isString() ? "'" + name + "'" : std::string(define.typeName())));
                if (std::find(defines.begin(), defines.end(), name) != defines.end()) return sw.error("define '" + name + "' is already another parameter's switch");
                if (p.params["defines"].has(name)) return sw.error("define '" + name + "' is also in the pass's defines");
                defines.push_back(name);
            }
        }
        return {};
    }

    Result<PipelineDesc> build(const OutputNames& names) {
        const std::string& output = names.display;
        if (auto r = collectNames(); !r) return std::unexpected(r.error());
        for (const auto& d : decls) {
            Result<void> r;
            switch (d.kind) {
            case DeclKind::Texture: r = texture(d); break;
            case DeclKind::Buffer: r = buffer(d); break;
            case DeclKind::Param: r = param(d); break;
            case DeclKind::Layout: r = layout(d); break;
            default: break;
            }
            if (!r) return std::unexpected(r.error());
        }
        if (auto r = stencils(); !r) return std::unexpected(r.error());
        for (const auto& d : decls)
            if (d.kind == DeclKind::Path)
                if (auto r = path(d); !r) return std::unexpected(r.error());
        for (const auto& d : decls)
            if (d.kind == DeclKind::Pass)
                if (auto r = pass(d); !r) return std::unexpected(r.error());
        std::map<uint32_t, const Declaration*> ids;
        for (const auto& d : decls)
            if (d.kind == DeclKind::Material)
                if (auto r = material(d, ids); !r) return std::unexpected(r.error());
        if (auto r = checkMaterialIdPlacement(); !r) return std::unexpected(r.error());
        if (auto r = insertModulePasses(); !r) return std::unexpected(r.error());
        if (auto r = checkMaterialReferences(); !r) return std::unexpected(r.error());
        if (auto r = checkSwitches(); !r) return std::unexpected(r.error());

        out.output = output.empty() ? "output" : output;
        auto it = std::find_if(out.graph.resources.begin(), out.graph.resources.end(), [&](auto& r) { return r.name == out.output; });
        const std::string where = names.origin.empty() ? "rg.output" : names.origin + ": rg.output";
        if (it == out.graph.resources.end())
            return fail(ErrorCode::InvalidInput, output.empty() ? "the pipeline declares no output: call rg.output \"resource\" (or name a resource 'output')"
                                                                : where + ": unknown resource '" + output + "'" + suggestion(output, resourceNames));
        if (it->kind != ResourceKind::Texture) return fail(ErrorCode::InvalidInput, where + ": '" + out.output + "' is a buffer, not a texture");
        it->exported = true;
        if (!names.hdr.empty()) {
            auto h = std::find_if(out.graph.resources.begin(), out.graph.resources.end(), [&](auto& r) { return r.name == names.hdr; });
            if (h == out.graph.resources.end() || h->kind != ResourceKind::Texture)
                return fail(ErrorCode::InvalidInput, where + ".hdr: unknown texture '" + names.hdr + "'" + suggestion(names.hdr, resourceNames));
            h->exported = true;
            out.hdr = names.hdr;
            if (names.exposure.empty())
                return fail(ErrorCode::InvalidInput, where + ".exposure: an hdr output needs the exposure state buffer that says its pre-exposure");
        }
        if (!names.exposure.empty()) {
            auto e = std::find_if(out.graph.resources.begin(), out.graph.resources.end(), [&](auto& r) { return r.name == names.exposure; });
            if (e == out.graph.resources.end() || e->kind != ResourceKind::Buffer || !e->persistent)
                return fail(ErrorCode::InvalidInput, where + ".exposure: '" + names.exposure + "' must be a persistent buffer (post.exposure_state())");
            out.exposure = names.exposure;
        }
        for (const auto& d : decls)
            if (!d.module.empty() && std::find(out.modules.begin(), out.modules.end(), d.module) == out.modules.end())
                out.modules.push_back(d.module);
        return std::move(out);
    }
};

}  // namespace

Result<void> checkFields(const Where& w, const Value& body, const std::vector<std::string>& allowed) {
    for (const auto& [key, _] : body.asTable()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        if (key[0] == '#')
            return w.error("unexpected positional value " + key.substr(1) + "; expected named fields: " + joinQuoted(allowed));
        return w.at(key).error("unknown field" + suggestion(key, allowed) + "; expected one of: " + joinQuoted(allowed));
    }
    return {};
}

Result<PipelineDesc> buildPipeline(const std::vector<Declaration>& decls, const OutputNames& output,
                                   const BuildOptions& options) {
    Builder b{decls, options, {}, {}, {}, {}, {}};
    return b.build(output);
}

}  // namespace rg
