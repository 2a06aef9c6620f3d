// rg.pass: the kind's schema and parameters, reads and writes with their usages, `after`; then
// module passes moved to their insert points and the switches checked against the parameters.
#include "declarations_detail.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace rg::declarations {

const PassKindSchema* Builder::kindSchema(const std::string& name) const {
    for (const auto& k : options.kinds)
        if (k.name == name) return &k;
    return nullptr;
}

// One entry of reads/writes: "name" or { "name", as = "...", load = true }.
Result<Access> Builder::access(const Where& w, const Declaration& d, const Value& e, bool write,
                               const PassKindSchema& kind) {
    std::string name, as, loadAfter;
    bool load = write && kind.writesLoad;
    if (e.isString())
        name = e.asString();
    else if (e.isTable()) {
        if (auto r = checkFields(w, e, {"#1", "as", "load"}); !r) return std::unexpected(r.error());
        if (!e["#1"].isString())
            return w.error(
                "expected the resource name as the first entry, e.g. { \"depth\", as = \"depth\" "
                "}");
        name = e["#1"].asString();
        if (e.has("as")) {
            if (auto r = expectType(w.at("as"), e["as"], "string"); !r)
                return std::unexpected(r.error());
            as = e["as"].asString();
        }
        if (e.has("load")) {
            if (!write) return w.at("load").error("only writes can load");
            // load = "pass": load while that pass runs (it drew first), clear otherwise.
            if (e["load"].isString()) {
                auto pass = resolvePass(w.at("load"), d.module, e["load"].asString());
                if (!pass) return std::unexpected(pass.error());
                loadAfter = *pass;
                load = true;
            } else if (auto r = expectType(w.at("load"), e["load"], "boolean"); !r) {
                return std::unexpected(
                    w.at("load")
                        .error("expected a boolean, or the name of the pass that runs first")
                        .error());
            } else {
                load = e["load"].asBool();
            }
        }
    } else
        return w.error("expected a resource name or { \"name\", as = \"...\" }, got " + typeOf(e));
    auto resolved = resolveResource(w, d.module, name);
    if (!resolved) return std::unexpected(resolved.error());
    Access a;
    a.resource = *resolved;
    a.load = load;
    a.loadAfter = loadAfter;
    a.field = w.path;
    const Declaration* rd = resources[*resolved];
    bool depthFormat = false;
    if (rd->kind == DeclKind::Texture && rd->body["format"].isString())
        if (auto f = parseFormat(rd->body["format"].asString())) depthFormat = isDepthStencil(*f);
    static const std::vector<std::pair<std::string, Usage>> readUsages = {
        {"sampled", Usage::Sampled},     {"storage", Usage::StorageRead},
        {"uniform", Usage::UniformRead}, {"depth", Usage::DepthStencilRead},
        {"copy", Usage::CopySrc},        {"indirect", Usage::IndirectRead},
        {"stencil", Usage::Sampled}};
    static const std::vector<std::pair<std::string, Usage>> writeUsages = {
        {"color", Usage::ColorAttachment},
        {"depth", Usage::DepthStencilAttachment},
        {"storage", Usage::StorageWrite},
        {"storage_rw", Usage::StorageReadWrite},
        {"copy", Usage::CopyDst}};
    const auto& table = write ? writeUsages : readUsages;
    if (as.empty()) {
        a.usage = write ? kind.defaultWrite : kind.defaultRead;
        if (write && depthFormat && a.usage == Usage::ColorAttachment)
            a.usage = Usage::DepthStencilAttachment;
        if (rd->kind == DeclKind::Buffer && (a.usage == Usage::Sampled))
            a.usage = Usage::StorageRead;
        if (rd->kind == DeclKind::Buffer && (a.usage == Usage::ColorAttachment))
            a.usage = Usage::StorageWrite;
    } else {
        auto it = std::find_if(table.begin(), table.end(), [&](auto& p) { return p.first == as; });
        if (it == table.end()) {
            std::vector<std::string> names;
            for (auto& p : table) names.push_back(p.first);
            return w.at("as").error("unknown usage '" + as + "'" + suggestion(as, names) +
                                    "; expected one of: " + joinQuoted(names));
        }
        a.usage = it->second;
        if (!write && as == "stencil") {
            // The stencil of a depth/stencil texture, sampled (a pixel's material identity).
            std::optional<Format> f;
            if (rd->kind == DeclKind::Texture && rd->body["format"].isString())
                f = parseFormat(rd->body["format"].asString());
            if (!f || !formatInfo(*f).stencil)
                return w.at("as").error(
                    "'" + a.resource + "' has no stencil" +
                    (f ? " (format " + std::string(formatName(*f)) + ")" : "") +
                    ": as = \"stencil\" reads the stencil of a depth/stencil texture (d32f_s8)");
            a.stencil = true;
        }
    }
    return a;
}

Result<void> Builder::pass(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    auto kindName = requireString(w, b, "kind");
    if (!kindName) return std::unexpected(kindName.error());
    const PassKindSchema* kind = kindSchema(*kindName);
    if (!kind) {
        std::vector<std::string> names;
        for (const auto& k : options.kinds) names.push_back(k.name);
        return w.at("kind").error("unknown pass kind '" + *kindName + "'" +
                                  suggestion(*kindName, names) +
                                  "; expected one of: " + joinQuoted(names));
    }
    std::vector<std::string> allowed = {"kind",        "reads", "writes", "after",    "enabled",
                                        "side_effect", "doc",   "insert", "only_when"};
    for (const auto& p : kind->params) allowed.push_back(p.name);
    if (auto r = checkFields(w, b, allowed); !r) return r;
    PassDesc p;
    p.name = fullName(d);
    p.kind = kind->name;
    p.type = kind->type;
    p.origin = d.origin;
    Value::Table params;
    std::vector<const ParamSpec*> written;  // checked against the writes below
    for (const auto& spec : kind->params) {
        if (!b.has(spec.name)) continue;
        const bool names = spec.type == "written";
        if (names) written.push_back(&spec);
        if (auto r = expectType(w.at(spec.name), b[spec.name], names ? "string" : spec.type); !r)
            return r;
        params[spec.name] = b[spec.name];
    }
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
    for (const ParamSpec* spec : written) {
        auto name = resolveResource(w.at(spec->name), d.module, b[spec->name].asString());
        if (!name) return std::unexpected(name.error());
        std::vector<std::string> writes;
        for (const Access& a : p.accesses)
            if (usageWrites(a.usage)) writes.push_back(a.resource);
        if (std::find(writes.begin(), writes.end(), *name) == writes.end())
            return w.at(spec->name)
                .error("'" + *name + "' is not written by the pass (it writes " +
                       joinQuoted(writes) + ")");
        params[spec->name] = Value(*name);
    }
    p.params = Value(params);
    auto after = stringList(w.at("after"), b["after"]);
    if (!after) return std::unexpected(after.error());
    for (size_t i = 0; i < after->size(); ++i) {
        auto name = resolvePass(b["after"].isList() ? w.at("after").index(i) : w.at("after"),
                                d.module, (*after)[i]);
        if (!name) return std::unexpected(name.error());
        p.after.push_back(*name);
    }
    for (const char* flag : {"enabled", "side_effect"})
        if (b.has(flag))
            if (auto e = expectType(w.at(flag), b[flag], "boolean"); !e) return e;
    p.enabled = b["enabled"].asBool(true);
    p.sideEffect = b["side_effect"].asBool();
    if (b.has("only_when")) {
        auto cond = onlyWhen(w.at("only_when"), b["only_when"], /*withDefines=*/false);
        if (!cond) return std::unexpected(cond.error());
        p.onlyWhen = *cond;
    }
    out.graph.passes.push_back(p);
    return {};
}

// `load = "pass"`: that pass runs before this one (once module passes are in place) and writes the
// resource, so that what this pass loads is what it drew.
Result<void> Builder::checkLoadAfter() {
    const auto& all = out.graph.passes;
    for (size_t i = 0; i < all.size(); ++i)
        for (const Access& a : all[i].accesses) {
            if (a.loadAfter.empty()) continue;
            const Where w = Where{*passes[all[i].name], a.field}.at("load");
            size_t j = 0;
            while (j < all.size() && all[j].name != a.loadAfter) ++j;
            if (j >= i)
                return w.error("pass '" + a.loadAfter + "' runs after this one" +
                               (j == i ? " (it is this one)" : "") + ": name the pass that drew '" +
                               a.resource + "' first");
            const bool writes = std::any_of(
                all[j].accesses.begin(), all[j].accesses.end(),
                [&](const Access& b) { return b.resource == a.resource && usageWrites(b.usage); });
            if (!writes)
                return w.error("pass '" + a.loadAfter + "' does not write '" + a.resource + "'");
        }
    return {};
}

// Module passes with `insert = { after = X }` / `{ before = X }` move next to X,
// in declaration order (so two modules after the same pass keep their load order).
Result<void> Builder::insertModulePasses() {
    std::vector<PassDesc> ordered;
    std::vector<std::pair<PassDesc, const Declaration*>> inserted;
    for (auto& p : out.graph.passes) {
        const Declaration* d = passes[p.name];
        if (d->body.has("insert"))
            inserted.emplace_back(p, d);
        else
            ordered.push_back(p);
    }
    for (auto& [p, d] : inserted) {
        Where w = where(*d).at("insert");
        const Value& ins = d->body["insert"];
        if (!ins.isTable())
            return w.error("expected { after = \"pass\" } or { before = \"pass\" }");
        if (auto r = checkFields(w, ins, {"after", "before"}); !r) return r;
        if (ins.has("after") == ins.has("before"))
            return w.error("give exactly one of after / before");
        const bool after = ins.has("after");
        const Value& anchorV = ins[after ? "after" : "before"];
        if (!anchorV.isString())
            return w.at(after ? "after" : "before").error("expected a pass name");
        auto anchor = resolvePass(w.at(after ? "after" : "before"), d->module, anchorV.asString());
        if (!anchor) return std::unexpected(anchor.error());
        auto it = std::find_if(ordered.begin(), ordered.end(),
                               [&](auto& q) { return q.name == *anchor; });
        if (it == ordered.end())
            return w.error("pass '" + *anchor +
                           "' is itself inserted later; insert after a pass of the pipeline");
        if (after) {
            ++it;
            // Skip passes inserted after the same anchor earlier.
            while (it != ordered.end() &&
                   passes[it->name]->body["insert"]["after"].asString() == anchorV.asString() &&
                   passes[it->name]->body.has("insert"))
                ++it;
        }
        ordered.insert(it, p);
    }
    out.graph.passes = ordered;
    return {};
}

// switches = { param = "DEFINE" }: parameters compiled into a pass's shaders as defines
// (graphWithParams), named by the pipeline's parameters, each a GLSL identifier given once.
Result<void> Builder::checkSwitches() {
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
                return sw.error("unknown parameter '" + param + "'" + suggestion(param, params) +
                                " (declare it with rg.param)");
            }
            if (d->type == ParamType::Vec3)
                return sw.error(
                    "parameter '" + param +
                    "' is a vec3; a switch takes a number, an integer, a boolean or a choice");
            const std::string name = define.isString() ? define.asString() : "";
            if (!isGlslIdentifier(name))
                return sw.error(
                    "expected the name of a define (a GLSL identifier), got " +
                    (define.isString() ? "'" + name + "'" : std::string(define.typeName())));
            if (std::find(defines.begin(), defines.end(), name) != defines.end())
                return sw.error("define '" + name + "' is already another parameter's switch");
            if (p.params["defines"].has(name))
                return sw.error("define '" + name + "' is also in the pass's defines");
            defines.push_back(name);
        }
    }
    return {};
}

}  // namespace rg::declarations
