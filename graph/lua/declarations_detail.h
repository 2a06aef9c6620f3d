// Inside buildPipeline(): the Builder that checks declarations and assembles the PipelineDesc,
// one file per declaration kind (declarations_<kind>.cpp), and the field checks they share
// (declarations.cpp). Internal to graph/lua.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "declarations.h"

namespace rg::declarations {

// Field checks (declarations.cpp).
bool isGlslIdentifier(const std::string& name);
std::string typeOf(const Value& v);
bool isInteger(const Value& v);
Result<void> expectType(const Where& w, const Value& v, const std::string& type);
Result<std::string> requireString(const Where& w, const Value& body, const std::string& field);
Result<std::vector<std::string>> stringList(const Where& w, const Value& v);

struct Builder {
    const std::vector<Declaration>& decls;
    const BuildOptions& options;
    PipelineDesc out;
    std::map<std::string, const Declaration*> resources;  // full name -> declaration
    std::map<std::string, const Declaration*> passes;
    std::vector<std::string> resourceNames, passNames;
    // A texture's history (rg.resource's `history`): the persistent copy of its last frame and
    // the passes that keep it, declared by the Builder at the source's line.
    struct History {
        std::string source, name;  // full names
        Value mips;                // the history's own `mips`, when given
        const Declaration* decl = nullptr;
        std::vector<const Declaration*> keep;  // the copy (and the mips chain) after the frame
    };
    std::vector<History> histories;
    std::deque<Declaration> synthesized;  // the keep passes' declarations (stable addresses)

    static std::string fullName(const Declaration& d) {
        return d.module.empty() ? d.name : d.module + "." + d.name;
    }
    static std::string section(DeclKind k) {
        switch (k) {
            case DeclKind::Texture:
            case DeclKind::Buffer:
            case DeclKind::History:
                return "resources";
            case DeclKind::Pass:
                return "passes";
            case DeclKind::Param:
                return "params";
            case DeclKind::Layout:
                return "layouts";
            case DeclKind::Stencil:
                return "stencil";
            case DeclKind::Path:
                return "paths";
            case DeclKind::Material:
                return "materials";
            default:
                return "scene";
        }
    }
    static Where where(const Declaration& d) { return {d, section(d.kind) + "." + fullName(d)}; }

    // Names, the order of the steps and the output (declarations_builder.cpp).
    Result<std::string> resolveResource(const Where& w, const std::string& module,
                                        const std::string& name);
    Result<std::string> resolvePass(const Where& w, const std::string& module,
                                    const std::string& name);
    Result<void> collectNames();
    Result<PipelineDesc> build(const OutputNames& names);

    // rg.resource, rg.buffer (declarations_resources.cpp).
    Result<void> texture(const Declaration& d);
    Result<void> history(const Declaration& d);  // collectNames: the names a history adds
    Result<void> historyResources();             // rg.history's textures, once all are built
    Result<void> historyResource(const History& h, const ResourceDesc& source, const Where& w);
    Result<void> historyPasses();  // after every pass: the keep passes
    Result<void> buffer(const Declaration& d);

    // rg.pass (declarations_passes.cpp).
    const PassKindSchema* kindSchema(const std::string& name) const;
    Result<Access> access(const Where& w, const Declaration& d, const Value& e, bool write,
                          const PassKindSchema& kind);
    Result<void> pass(const Declaration& d);
    Result<void> insertModulePasses();
    Result<void> checkLoadAfter();
    Result<void> checkSwitches();

    // rg.param (declarations_params.cpp).
    Result<void> param(const Declaration& d);

    // rg.layout (declarations_layouts.cpp).
    Result<void> layout(const Declaration& d);

    // rg.stencil, rg.path (declarations_lighting.cpp).
    Result<void> stencils();
    bool hasStencil(const std::string& n) const;
    std::vector<std::string> stencilNames() const;
    Result<void> path(const Declaration& d);

    // rg.material (declarations_materials.cpp).
    Result<void> standardChannels(const Where& w, const Value& b, const LayoutDesc& layout,
                                  MaterialDesc& m);
    Result<void> material(const Declaration& d);
    Result<void> materialIdentities();
    Result<void> checkMaterialReferences();
};

// only_when = { scene = FEATURE, param = NAME or { NAMES }, defines = { ... } } (declarations_resources.cpp);
// a pass's takes no defines.
Result<ResourceDesc::Condition> onlyWhen(const Where& ow, const Value& c, bool withDefines);

}  // namespace rg::declarations
