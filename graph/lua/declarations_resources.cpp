// rg.resource and rg.buffer: textures (format, size or scale, mips, layers, cube) and buffers
// (bytes, screen tiles), each imported, exported or persistent.
#include "declarations_detail.h"

#include <algorithm>
#include <vector>

namespace rg::declarations {

namespace {

// `mips`: a whole number 1..16, or "full" (0: the whole chain).
Result<uint32_t> mipCount(const Where& w, const Value& m) {
    if (m.isString() && m.asString() == "full") return 0u;
    if (isInteger(m) && m.asNumber() >= 1 && m.asNumber() <= 16)
        return static_cast<uint32_t>(m.asNumber());
    return w.error("expected a whole number in 1..16 or \"full\"");
}

}  // namespace

// rg.resource's and rg.buffer's only_when = { scene = FEATURE or { FEATURES }, param = NAME or
// { NAMES }, defines = { ... } }; rg.pass's without defines.
Result<ResourceDesc::Condition> onlyWhen(const Where& ow, const Value& c, bool withDefines) {
    if (!c.isTable() || c.asTable().empty())
        return ow.error(std::string("expected a table { scene = FEATURE, param = NAME") +
                        (withDefines ? ", defines = { ... } }" : " }") + ", got " + typeOf(c));
    if (auto e = withDefines ? checkFields(ow, c, {"scene", "param", "defines"})
                             : checkFields(ow, c, {"scene", "param"});
        !e)
        return std::unexpected(e.error());
    ResourceDesc::Condition cond;
    // A scene feature is a name, or a name:name ("material:transmission": the scene draws that
    // pipeline material) or name:number ("draws:4096": the scene has at least that many draws).
    auto featureName = [](const std::string& s) {
        const size_t colon = s.find(':');
        if (colon == std::string::npos) return isGlslIdentifier(s);
        const std::string tail = s.substr(colon + 1);
        const bool number =
            !tail.empty() && tail.size() <= 9 &&
            std::all_of(tail.begin(), tail.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
        return isGlslIdentifier(s.substr(0, colon)) && (isGlslIdentifier(tail) || number);
    };
    // scene = FEATURE and param = NAME, or lists of them: every one of them.
    auto names = [&](const char* field, std::vector<std::string>& out) -> Result<void> {
        const Value& v = c[field];
        if (v.isString())
            out = {v.asString()};
        else if (v.isList() && !v.asList().empty())
            for (size_t i = 0; i < v.asList().size(); ++i) {
                if (!v.asList()[i].isString())
                    return ow.at(field).index(i).error("expected a name, got " +
                                                       typeOf(v.asList()[i]));
                out.push_back(v.asList()[i].asString());
            }
        else
            return ow.at(field).error("expected a name or a list of names, got " + typeOf(v));
        const bool scene = std::string(field) == "scene";
        for (size_t i = 0; i < out.size(); ++i)
            if (scene ? !featureName(out[i]) : !isGlslIdentifier(out[i]))
                return (v.isList() ? ow.at(field).index(i) : ow.at(field))
                    .error("'" + out[i] + "' is not a name" +
                           (scene ? " (or name:name, name:number)" : ""));
        return {};
    };
    if (c.has("scene"))
        if (auto r = names("scene", cond.sceneFeatures); !r) return std::unexpected(r.error());
    if (c.has("param"))
        if (auto r = names("param", cond.params); !r) return std::unexpected(r.error());
    if (cond.sceneFeatures.empty() && cond.params.empty())
        return ow.error(
            "names neither a scene feature (scene = ...) nor a parameter (param = ...)");
    if (c.has("defines")) {
        auto defines = stringList(ow.at("defines"), c["defines"]);
        if (!defines) return std::unexpected(defines.error());
        cond.defines = *defines;
    }
    return cond;
}

Result<void> Builder::texture(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"format", "size", "scale", "mips", "layers", "scene_layers", "cube",
                              "export", "import", "persistent", "only_when", "history", "doc"});
        !r)
        return r;
    ResourceDesc r;
    r.name = fullName(d);
    r.origin = d.origin;
    auto format = requireString(w, b, "format");
    if (!format) return std::unexpected(format.error());
    auto f = parseFormat(*format);
    if (!f)
        return w.at("format").error(
            "unknown format '" + *format + "'" +
            suggestion(*format,
                       [] {
                           std::vector<std::string> n;
                           for (int i = 1; i < static_cast<int>(Format::Count); ++i)
                               n.push_back(formatInfo(static_cast<Format>(i)).name);
                           return n;
                       }()) +
            "; expected one of: " + formatNameList());
    r.texture.format = *f;
    if (b.has("size") && b.has("scale"))
        return w.error("give either size (texels) or scale (fraction of the output), not both");
    if (b.has("size")) {
        const Value& s = b["size"];
        if (!s.isList() || s.asList().size() != 2 || !isInteger(s.asList()[0]) ||
            !isInteger(s.asList()[1]) || s.asList()[0].asNumber() < 1 ||
            s.asList()[1].asNumber() < 1)
            return w.at("size").error("expected {width, height} in texels (whole numbers >= 1)");
        r.texture.sizeMode = SizeMode::Absolute;
        r.texture.width = static_cast<uint32_t>(s.asList()[0].asNumber());
        r.texture.height = static_cast<uint32_t>(s.asList()[1].asNumber());
    }
    if (b.has("scale")) {
        const Value& s = b["scale"];
        if (s.isNumber())
            r.texture.scaleX = r.texture.scaleY = static_cast<float>(s.asNumber());
        else if (s.isList() && s.asList().size() == 2 && s.asList()[0].isNumber() &&
                 s.asList()[1].isNumber()) {
            r.texture.scaleX = static_cast<float>(s.asList()[0].asNumber());
            r.texture.scaleY = static_cast<float>(s.asList()[1].asNumber());
        } else
            return w.at("scale").error(
                "expected a number or {x, y}: the fraction of the output size");
        if (r.texture.scaleX <= 0 || r.texture.scaleY <= 0 || r.texture.scaleX > 16 ||
            r.texture.scaleY > 16)
            return w.at("scale").error("expected a value in (0, 16]");
    }
    if (b.has("mips")) {
        auto mips = mipCount(w.at("mips"), b["mips"]);
        if (!mips) return std::unexpected(mips.error());
        r.texture.mips = *mips;
    }
    if (b.has("layers")) {
        if (!isInteger(b["layers"]) || b["layers"].asNumber() < 1 || b["layers"].asNumber() > 2048)
            return w.at("layers").error("expected a whole number in 1..2048");
        r.texture.layers = static_cast<uint32_t>(b["layers"].asNumber());
    }
    if (b.has("scene_layers")) {
        if (!b["scene_layers"].isString() || !isGlslIdentifier(b["scene_layers"].asString()))
            return w.at("scene_layers")
                .error(
                    "expected the name of a layer extent of the scene, e.g. \"shadow_views\" (the "
                    "layers its shadowed local lights need, at most `layers`)");
        if (b["cube"].asBool())
            return w.at("scene_layers")
                .error("a cube's layers are fixed; scene_layers is for arrays");
        r.texture.sceneLayers = b["scene_layers"].asString();
    }
    for (const char* flag : {"cube", "export", "import", "persistent"})
        if (b.has(flag))
            if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
    r.texture.cube = b["cube"].asBool();
    r.persistent = b["persistent"].asBool();
    if (r.texture.cube && !b.has("layers"))
        r.texture.layers = 6;  // one cube; `layers` = 6 × cubes for an array
    r.exported = b["export"].asBool();
    r.imported = b["import"].asBool();
    if (b.has("only_when")) {
        auto cond = onlyWhen(w.at("only_when"), b["only_when"], true);
        if (!cond) return std::unexpected(cond.error());
        r.onlyWhen = *cond;
    }
    out.graph.resources.push_back(r);
    if (b.has("history")) {
        if (r.imported)
            return w.at("history").error(
                "an imported texture's contents come from outside the graph: it has no history "
                "of its own");
        auto h = std::find_if(histories.begin(), histories.end(),
                              [&](const History& x) { return x.decl == &d; });
        if (auto e = historyResource(*h, r, w.at("history")); !e) return e;
    }
    return {};
}

// The history's texture: the source's format, size and layers (its own mips when given),
// persistent, never exported.
Result<void> Builder::historyResource(const History& h, const ResourceDesc& source,
                                      const Where& w) {
    ResourceDesc past = source;
    past.name = h.name;
    past.origin = h.decl->origin;
    past.persistent = true;
    past.exported = false;
    past.historyOf = source.name;
    if (!h.mips.isNil()) {
        auto mips = mipCount(w.at("mips"), h.mips);
        if (!mips) return std::unexpected(mips.error());
        past.texture.mips = *mips;
    }
    out.graph.resources.push_back(past);
    return {};
}

// rg.history "NAME" { of = TEXTURE, mips = M }: a module's history of a texture another file
// declares (SSR's of the lit image), as rg.resource's `history` field gives one.
Result<void> Builder::historyResources() {
    for (const History& h : histories) {
        if (h.decl->kind != DeclKind::History) continue;
        const Where w = where(*h.decl);
        auto source = std::find_if(out.graph.resources.begin(), out.graph.resources.end(),
                                   [&](const ResourceDesc& r) { return r.name == h.source; });
        if (source->imported)
            return w.at("of").error("'" + h.source +
                                    "' is imported: its contents come from outside the graph");
        const ResourceDesc copy = *source;  // the push below may move the vector
        if (auto e = historyResource(h, copy, w); !e) return e;
    }
    return {};
}

// A history's names and keep passes (collectNames). rg.resource's field, `history = NAME` or
// `{ name = NAME, mips = M }`, or rg.history "NAME" { of = TEXTURE, mips = M }: NAME (in the
// declaration's module) reads the texture as the last frame left it — a persistent texture of
// its format and size (its own mips when given), zeros at first and whenever it is emptied
// (gpu::Executor: the passes writing the texture were rebuilt or switched, the texture resized,
// a camera cut). Its keep passes: NAME_keep copies the texture into it after every other pass,
// and NAME_mips fills its mips when it has more than one.
Result<void> Builder::history(const Declaration& d) {
    const bool declared = d.kind == DeclKind::History;
    Where w = declared ? where(d) : where(d).at("history");
    const Value& v = declared ? d.body : d.body["history"];
    History h;
    h.decl = &d;
    std::string name;
    if (declared) {
        if (auto r = checkFields(w, v, {"of", "mips", "doc"}); !r) return r;
        if (!v["of"].isString())
            return w.at("of").error("expected the name of the texture whose history it is, got " +
                                    typeOf(v["of"]));
        auto source = resolveResource(w.at("of"), d.module, v["of"].asString());
        if (!source) return std::unexpected(source.error());
        if (resources[*source]->kind != DeclKind::Texture)
            return w.at("of").error("'" + *source + "' is a " +
                                    declKindName(resources[*source]->kind) +
                                    "; a history is a texture's (rg.resource)");
        h.source = *source;
        h.name = fullName(d);
        h.mips = v["mips"];
    } else {
        h.source = fullName(d);
        if (v.isString()) {
            name = v.asString();
        } else if (v.isTable()) {
            if (auto r = checkFields(w, v, {"name", "mips"}); !r) return r;
            if (!v["name"].isString())
                return w.at("name").error("expected the history's name, got " + typeOf(v["name"]));
            name = v["name"].asString();
            h.mips = v["mips"];
        } else {
            return w.error("expected a name or { name = NAME, mips = M }, got " + typeOf(v));
        }
        h.name = d.module.empty() ? name : d.module + "." + name;
    }
    const std::string shortName = declared ? d.name : name;
    if (!isGlslIdentifier(shortName))
        return w.error("'" + shortName + "' is not a name a shader can bind (letters, digits, _)");
    if (!declared) {
        if (resources.count(h.name))
            return w.error("'" + h.name + "' is already declared (at " + resources[h.name]->origin +
                           ")");
        resources[h.name] = &d;
        resourceNames.push_back(h.name);
    }
    const bool mips = h.mips.isString() || h.mips.asNumber(1) > 1;
    const std::string keepName = h.name + "_keep", mipsName = h.name + "_mips";
    for (const std::string& pass : {keepName, mipsName}) {
        if (pass == mipsName && !mips) break;
        if (passes.count(pass))
            return w.error("its keep pass '" + pass + "' is already declared (at " +
                           passes[pass]->origin + ")");
        Declaration keep;
        keep.kind = DeclKind::Pass;
        keep.name = pass;
        keep.origin = d.origin;
        Value::Table body;
        if (pass == keepName) {
            body["kind"] = Value("copy");
            body["reads"] = Value(Value::List{Value(h.source)});
        } else {
            body["kind"] = Value("mips");
        }
        body["writes"] = Value(Value::List{Value(h.name)});
        keep.body = Value(std::move(body));
        synthesized.push_back(std::move(keep));
        passes[pass] = &synthesized.back();
        passNames.push_back(pass);
        h.keep.push_back(&synthesized.back());
    }
    histories.push_back(std::move(h));
    return {};
}

Result<void> Builder::historyPasses() {
    for (const History& h : histories)
        for (const Declaration* keep : h.keep)
            if (auto r = pass(*keep); !r) return r;
    return {};
}

Result<void> Builder::buffer(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"size", "tile", "tile_bytes", "scene_count", "count_bytes", "export",
                              "import", "persistent", "only_when", "doc"});
        !r)
        return r;
    ResourceDesc r;
    r.name = fullName(d);
    r.origin = d.origin;
    r.kind = ResourceKind::Buffer;
    if (!isInteger(b["size"]) || b["size"].asNumber() < 4)
        return w.at("size").error(b.has("size") ? "expected a whole number of bytes >= 4"
                                                : "missing (expected the size in bytes)");
    r.buffer.size = static_cast<uint64_t>(b["size"].asNumber());
    // Screen-tiled: `tile_bytes` more for every tile x tile pixels of the output.
    if (b.has("tile") != b.has("tile_bytes"))
        return w.at(b.has("tile") ? "tile_bytes" : "tile")
            .error("missing (a tiled buffer gives both tile, in pixels, and tile_bytes)");
    if (b.has("tile")) {
        if (!isInteger(b["tile"]) || b["tile"].asNumber() < 1 || b["tile"].asNumber() > 256)
            return w.at("tile").error("expected a tile size in pixels, 1..256");
        if (!isInteger(b["tile_bytes"]) || b["tile_bytes"].asNumber() < 4 ||
            b["tile_bytes"].asNumber() > (1 << 20))
            return w.at("tile_bytes")
                .error("expected a whole number of bytes per tile, 4..1048576");
        r.buffer.tileSize = static_cast<uint32_t>(b["tile"].asNumber());
        r.buffer.tileBytes = static_cast<uint64_t>(b["tile_bytes"].asNumber());
    }
    // Scene-sized: `count_bytes` more for every item of a count the scene has.
    if (b.has("scene_count") != b.has("count_bytes"))
        return w.at(b.has("scene_count") ? "count_bytes" : "scene_count")
            .error("missing (a scene-sized buffer gives both scene_count and count_bytes)");
    if (b.has("scene_count")) {
        if (b.has("tile"))
            return w.at("scene_count")
                .error("a buffer is sized by screen tiles or by the scene, not both");
        if (!b["scene_count"].isString() || !isGlslIdentifier(b["scene_count"].asString()))
            return w.at("scene_count")
                .error("expected the name of a count of the scene, e.g. \"shadow_casters\"");
        if (!isInteger(b["count_bytes"]) || b["count_bytes"].asNumber() < 4 ||
            b["count_bytes"].asNumber() > (1 << 20))
            return w.at("count_bytes")
                .error("expected a whole number of bytes per item, 4..1048576");
        r.buffer.sceneCount = b["scene_count"].asString();
        r.buffer.countBytes = static_cast<uint64_t>(b["count_bytes"].asNumber());
    }
    for (const char* flag : {"export", "import", "persistent"})
        if (b.has(flag))
            if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
    r.exported = b["export"].asBool();
    r.imported = b["import"].asBool();
    r.persistent = b["persistent"].asBool();
    if (b.has("only_when")) {
        auto cond = onlyWhen(w.at("only_when"), b["only_when"], true);
        if (!cond) return std::unexpected(cond.error());
        r.onlyWhen = *cond;
    }
    out.graph.resources.push_back(r);
    return {};
}

}  // namespace rg::declarations
