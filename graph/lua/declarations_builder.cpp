// The Builder's frame: names collected and resolved (module-local first), each kind's
// builder run in declaration order, the checks across kinds, and the output rg.output names.
#include "declarations_detail.h"

#include <algorithm>
#include <map>

namespace rg::declarations {

// A resource name as a declaration in `module` means it: module-local first, then global.
Result<std::string> Builder::resolveResource(const Where& w, const std::string& module,
                                             const std::string& name) {
    if (!module.empty() && resources.count(module + "." + name)) return module + "." + name;
    if (resources.count(name)) return name;
    return w.error("unknown resource '" + name + "'" + suggestion(name, resourceNames));
}
Result<std::string> Builder::resolvePass(const Where& w, const std::string& module,
                                         const std::string& name) {
    if (!module.empty() && passes.count(module + "." + name)) return module + "." + name;
    if (passes.count(name)) return name;
    return w.error("unknown pass '" + name + "'" + suggestion(name, passNames));
}

Result<void> Builder::collectNames() {
    std::map<std::string, const Declaration*> seen[static_cast<size_t>(DeclKind::Count)];
    for (const auto& d : decls) {
        Where w = where(d);
        if (isSceneKind(d.kind))
            return w.error(std::string(declKindName(d.kind)) +
                           " belongs in a scene script (--scene), not in a pipeline");
        if (!d.body.isTable() &&
            !(d.body.isList() && (d.kind == DeclKind::Layout || d.body.asList().empty())))
            return w.error("expected a table after " + std::string(declKindName(d.kind)) + " \"" +
                           d.name + "\", got " + typeOf(d.body));
        // Textures and buffers share one namespace.
        size_t slot = d.kind == DeclKind::Buffer || d.kind == DeclKind::History
                          ? static_cast<size_t>(DeclKind::Texture)
                          : static_cast<size_t>(d.kind);
        auto [it, fresh] = seen[slot].emplace(fullName(d), &d);
        if (!fresh)
            return w.error(std::string(declKindName(d.kind)) + " '" + fullName(d) +
                           "' is declared twice (first at " + it->second->origin + ")");
        if (d.kind == DeclKind::Texture || d.kind == DeclKind::Buffer ||
            d.kind == DeclKind::History) {
            if (resources.count(fullName(d)))  // a history's name (rg.resource's `history`)
                return w.error("'" + fullName(d) + "' is declared twice (first as the history of " +
                               fullName(*resources[fullName(d)]) + " at " +
                               resources[fullName(d)]->origin + ")");
            resources[fullName(d)] = &d;
            resourceNames.push_back(fullName(d));
            if (d.kind == DeclKind::Texture && d.body.isTable() && d.body.has("history"))
                if (auto r = history(d); !r) return r;
        } else if (d.kind == DeclKind::Pass) {
            if (passes.count(fullName(d)))  // a history's keep pass
                return w.error("pass '" + fullName(d) +
                               "' is declared twice (first as a keep pass of the "
                               "history at " +
                               passes[fullName(d)]->origin + ")");
            passes[fullName(d)] = &d;
            passNames.push_back(fullName(d));
        }
    }
    // rg.history names its source, which may be declared after it.
    for (const auto& d : decls)
        if (d.kind == DeclKind::History)
            if (auto r = history(d); !r) return r;
    return {};
}

Result<PipelineDesc> Builder::build(const OutputNames& names) {
    const std::string& output = names.display;
    if (auto r = collectNames(); !r) return std::unexpected(r.error());
    for (const auto& d : decls) {
        Result<void> r;
        switch (d.kind) {
            case DeclKind::Texture:
                r = texture(d);
                break;
            case DeclKind::Buffer:
                r = buffer(d);
                break;
            case DeclKind::Param:
                r = param(d);
                break;
            case DeclKind::Layout:
                r = layout(d);
                break;
            default:
                break;
        }
        if (!r) return std::unexpected(r.error());
    }
    if (auto r = historyResources(); !r) return std::unexpected(r.error());
    if (auto r = stencils(); !r) return std::unexpected(r.error());
    for (const auto& d : decls)
        if (d.kind == DeclKind::Path)
            if (auto r = path(d); !r) return std::unexpected(r.error());
    for (const auto& d : decls)
        if (d.kind == DeclKind::Pass)
            if (auto r = pass(d); !r) return std::unexpected(r.error());
    for (const auto& d : decls)
        if (d.kind == DeclKind::Material)
            if (auto r = material(d); !r) return std::unexpected(r.error());
    if (auto r = materialIdentities(); !r) return std::unexpected(r.error());
    if (auto r = insertModulePasses(); !r) return std::unexpected(r.error());
    if (auto r = checkLoadAfter(); !r) return std::unexpected(r.error());
    if (auto r = historyPasses(); !r) return std::unexpected(r.error());  // after every other pass
    if (auto r = checkMaterialReferences(); !r) return std::unexpected(r.error());
    if (auto r = checkSwitches(); !r) return std::unexpected(r.error());
    // only_when's parameters: boolean ones the pipeline declares.
    auto checkCondition = [&](const std::optional<ResourceDesc::Condition>& c,
                              const Declaration& d) -> Result<void> {
        if (!c) return {};
        for (size_t i = 0; i < c->params.size(); ++i) {
            const std::string& name = c->params[i];
            const ParamDesc* p = out.findParam(name);
            if (p && p->type == ParamType::Boolean) continue;
            std::vector<std::string> params;
            for (const auto& q : out.params) params.push_back(q.name);
            const Where param = where(d).at("only_when").at("param");
            const Where w = d.body["only_when"]["param"].isList() ? param.index(i) : param;
            return p ? w.error("parameter '" + name + "' is a " + paramTypeName(p->type) +
                               "; only_when takes a boolean one")
                     : w.error("unknown parameter '" + name + "'" + suggestion(name, params) +
                               " (declare it with rg.param)");
        }
        return {};
    };
    for (const ResourceDesc& res : out.graph.resources)
        if (auto r = checkCondition(res.onlyWhen, *resources[res.name]); !r)
            return std::unexpected(r.error());
    for (const PassDesc& pass : out.graph.passes)
        if (auto r = checkCondition(pass.onlyWhen, *passes[pass.name]); !r)
            return std::unexpected(r.error());

    out.output = output.empty() ? "output" : output;
    if (!names.replaced.empty()) out.notes.push_back(names.replaced);
    auto it = std::find_if(out.graph.resources.begin(), out.graph.resources.end(),
                           [&](auto& r) { return r.name == out.output; });
    const std::string where = names.origin.empty() ? "rg.output" : names.origin + ": rg.output";
    if (it == out.graph.resources.end())
        return fail(ErrorCode::InvalidInput,
                    output.empty() ? "the pipeline declares no output: call rg.output \"resource\" "
                                     "(or name a resource 'output')"
                                   : where + ": unknown resource '" + output + "'" +
                                         suggestion(output, resourceNames));
    if (it->kind != ResourceKind::Texture)
        return fail(ErrorCode::InvalidInput,
                    where + ": '" + out.output + "' is a buffer, not a texture");
    it->exported = true;
    if (!names.hdr.empty()) {
        auto h = std::find_if(out.graph.resources.begin(), out.graph.resources.end(),
                              [&](auto& r) { return r.name == names.hdr; });
        if (h == out.graph.resources.end() || h->kind != ResourceKind::Texture)
            return fail(ErrorCode::InvalidInput, where + ".hdr: unknown texture '" + names.hdr +
                                                     "'" + suggestion(names.hdr, resourceNames));
        h->exported = true;
        out.hdr = names.hdr;
        if (names.exposure.empty())
            return fail(ErrorCode::InvalidInput, where +
                                                     ".exposure: an hdr output needs the exposure "
                                                     "state buffer that says its pre-exposure");
    }
    if (!names.exposure.empty()) {
        auto e = std::find_if(out.graph.resources.begin(), out.graph.resources.end(),
                              [&](auto& r) { return r.name == names.exposure; });
        if (e == out.graph.resources.end() || e->kind != ResourceKind::Buffer || !e->persistent)
            return fail(ErrorCode::InvalidInput,
                        where + ".exposure: '" + names.exposure +
                            "' must be a persistent buffer (post.exposure_state())");
        out.exposure = names.exposure;
    }
    for (const auto& d : decls)
        if (!d.module.empty() &&
            std::find(out.modules.begin(), out.modules.end(), d.module) == out.modules.end())
            out.modules.push_back(d.module);
    return std::move(out);
}

}  // namespace rg::declarations

namespace rg {

Result<PipelineDesc> buildPipeline(const std::vector<Declaration>& decls, const OutputNames& output,
                                   const BuildOptions& options) {
    declarations::Builder b{decls, options, {}, {}, {}, {}, {}};
    return b.build(output);
}

}  // namespace rg
