// Declarations as a script made them, before validation: what kind, the name, the module it
// came from, the body converted to a Value, and where (file:line). buildPipeline() checks each
// against its schema and produces the PipelineDesc. No Lua here, so it is tested directly.
#pragma once

#include <string>
#include <vector>

#include "core/kind_schema.h"
#include "core/names.h"  // closestName, suggestion, joinQuoted for the scripts' messages
#include "pipeline.h"

namespace rg {

enum class DeclKind : uint8_t {
    // Pipelines (rg.*)
    Texture,
    Buffer,
    Pass,
    Param,
    Layout,
    Stencil,
    Path,
    Material,
    History,  // rg.history: a texture's last frame, kept by the graph
    // Scenes (scene.*): graph/scene builds a Scene from these
    SceneMaterial,
    Sphere,
    Plane,
    Box,
    Gltf,
    Light,
    Camera,
    Environment,
    Decal,
    Probe,
    Lightmap,
    Count
};
const char* declKindName(DeclKind k);  // "resource", "buffer", "pass", ..., "scene.sphere", ...
bool isSceneKind(DeclKind k);

// `path` made absolute when a file of that name sits next to the script of `origin`
// ("file:line", a declaration's origin, its file relative to `root` — the chunk names of the Lua
// host — or to the working folder); unchanged otherwise (absolute, or to be searched for).
std::string nextToDeclaration(const std::string& origin, const std::string& path,
                              const std::string& root = "");

struct Declaration {
    DeclKind kind = DeclKind::Pass;
    std::string name;    // as declared (without the module prefix)
    std::string module;  // "" for the pipeline itself
    Value body;          // tables: string keys -> Table; 1..n -> List; positional entries of
                         // mixed tables appear as "#1", "#2", ... keys
    std::string origin;  // "scripts/pipelines/deferred.lua:12"
};

// Everything a check of a declaration's fields needs to word an error: the declaration and the
// field path so far ("file:line: passes.lighting.reads[3]: ..."). Shared by the pipeline schemas
// (declarations.cpp) and the scene scripts (graph/scene).
struct Where {
    const Declaration& decl;
    std::string path;
    Where at(const std::string& field) const { return {decl, path + "." + field}; }
    Where index(size_t i) const { return {decl, path + "[" + std::to_string(i + 1) + "]"}; }
    std::unexpected<Error> error(const std::string& msg) const {
        return fail(ErrorCode::InvalidInput, decl.origin + ": " + path + ": " + msg);
    }
};

// Refuses a field of `body` not in `allowed` (with the closest allowed name) and positional values.
Result<void> checkFields(const Where& w, const Value& body,
                         const std::vector<std::string>& allowed);

struct BuildOptions {
    std::vector<PassKindSchema> kinds;
    uint32_t stencilBits = 4;  // low stencil bits the framework allocates classes from
    std::string
        projectRoot;  // what origins' file names are relative to (LuaHostOptions::projectRoot)
};

// Validates every declaration and assembles the pipeline: names resolved (module-local first),
// module passes inserted at their `insert = { after = ... }` / `{ before = ... }` points,
// stencil values allocated, material ids checked. Errors: "file:line: field.path: what was
// expected" with a suggestion when a name is close to a known one.
// What rg.output named: `rg.output "name"` or `rg.output { display = , hdr = , exposure = }`.
struct OutputNames {
    std::string display, hdr, exposure;
    std::string origin;
    // Set when a script declared rg.output more than once: the last declaration holds, whole
    // (fields it leaves out are not kept from the earlier one), and this says which it replaced.
    std::string replaced;
};

Result<PipelineDesc> buildPipeline(const std::vector<Declaration>& decls, const OutputNames& output,
                                   const BuildOptions& options);

}  // namespace rg
