// Lua scene scripts -> Scene. The host runs the script and hands back scene.* declarations as
// plain Values; the Builder checks each against its schema (the same wording as the pipeline's
// declarations.cpp: "file:line: scene.sphere.ball.radius: expected a number > 0, got -1") and
// builds the meshes, materials, lights, cameras and environment (scene_script_detail.h). This
// file runs the script, and the Builder's steps in order.
#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "lua/declarations.h"
#include "lua/lua_host.h"
#include "mesh_lod.h"
#include "scene.h"
#include "scene_detail.h"
#include "scene_script_detail.h"

namespace fs = std::filesystem;

namespace rg {

using namespace scene_detail;

namespace scene_script {

// ---- files and transforms ---------------------------------------------------------------------

Where Builder::where(const Declaration& d) {
    return {d, std::string(declKindName(d.kind)) + "." + d.name};
}

// Files named in a script are relative to the script's folder (or options.baseDir).
std::string Builder::resolve(const std::string& file) const {
    fs::path p(file);
    if (p.is_absolute()) return p.string();
    const fs::path base = options.baseDir.empty() ? fs::path(scriptPath).parent_path()
                                                  : fs::absolute(options.baseDir);
    return (base / p).lexically_normal().string();
}
void Builder::addFile(const std::string& p) {
    std::error_code ec;
    std::string a = fs::weakly_canonical(fs::absolute(p), ec).string();
    if (ec) a = p;
    if (std::find(scene.files.begin(), scene.files.end(), a) == scene.files.end())
        scene.files.push_back(a);
}
Result<std::string> Builder::existingFile(const Where& w, const Value& body,
                                          const std::string& field) {
    const Value& v = body[field];
    if (!v.isString() || v.asString().empty())
        return w.at(field).error("expected a file name, got " + describe(v));
    const std::string path = resolve(v.asString());
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        auto r = readFile(path);  // for the OS's reason
        return w.at(field).error(r ? "'" + path + "' is not a regular file" : r.error().message);
    }
    addFile(path);
    return path;
}

// A texture file of a material: decoded once per file and encoding, its index in scene.images.
Result<int32_t> Builder::textureFile(const Where& w, const Value& b, const std::string& field,
                                     bool srgb) {
    std::string path;
    RG_TRY(path, existingFile(w, b, field));
    auto index = scene_detail::textureFile(scene, path, srgb);
    if (!index) return w.at(field).error(index.error().message);
    return *index;
}

Result<glm::mat4> Builder::transform(const Where& w, const Value& b) {
    glm::vec3 position, rotation, scale(1.0f);
    RG_TRY(position, vec3(w, b, "position", glm::vec3(0.0f)));
    RG_TRY(rotation, vec3(w, b, "rotation", glm::vec3(0.0f), "{x, y, z} in degrees"));
    const Value& s = b["scale"];
    if (s.isNumber()) {
        if (!Range::positive().contains(s.asNumber()))
            return w.at("scale").error("expected a number > 0 or {x, y, z} of numbers > 0, got " +
                                       describe(s));
        scale = glm::vec3(static_cast<float>(s.asNumber()));
    } else if (!s.isNil()) {
        if (!s.isList())
            return w.at("scale").error("expected a number > 0 or {x, y, z} of numbers > 0, got " +
                                       describe(s));
        RG_TRY(scale, vec3(w, b, "scale", scale, "{x, y, z}", Range::positive()));
    }
    // Rotation in degrees about X, then Y, then Z (R = Rz * Ry * Rx).
    return glm::scale(placement(position, rotation * kDegrees), scale);
}

Result<void> Builder::nodePath(const Where& w, const Value& b, size_t first) {
    if (!b.has("path")) return {};
    const Value& path = b["path"];
    const char* shape = "{ time = s, position = {x, y, z}, rotation = {x, y, z} in degrees }";
    if (!path.isList() || path.asList().size() < 2)
        return w.at("path").error(std::string("expected a list of at least two keys ") + shape +
                                  ", got " + describe(path));
    glm::vec3 position, rotation;
    RG_TRY(position, vec3(w, b, "position", glm::vec3(0.0f)));
    RG_TRY(rotation, vec3(w, b, "rotation", glm::vec3(0.0f), "{x, y, z} in degrees"));
    std::vector<Node::Key> keys;
    for (size_t i = 0; i < path.asList().size(); ++i) {
        const Where wk = w.at("path").index(i);
        const Value& key = path.asList()[i];
        if (!key.isTable()) return wk.error(std::string("expected a key ") + shape);
        if (auto r = checkFields(wk, key, {"time", "position", "rotation"}); !r) return r;
        if (!key.has("time")) return wk.error("a key needs a time");
        Node::Key k;
        RG_TRY(k.time, numberF(wk, key, "time", 0.0f, Range::closed(0, 1e6)));
        RG_TRY(k.position, vec3(wk, key, "position", position));
        RG_TRY(k.rotation, vec3(wk, key, "rotation", rotation, "{x, y, z} in degrees"));
        k.rotation *= kDegrees;
        if (!keys.empty() && k.time <= keys.back().time)
            return wk.at("time").error("is " + formatNumber(k.time) +
                                       ", not after the key before (" +
                                       formatNumber(keys.back().time) + ")");
        keys.push_back(k);
    }
    // What lies below the placement: translate(position) · R cancelled from the node's world.
    const glm::mat4 unplace = glm::inverse(placement(position, rotation * kDegrees));
    for (size_t n = first; n < scene.nodes.size(); ++n) {
        Node& node = scene.nodes[n];
        node.dynamic = true;
        node.path = keys;
        // An animated glTF node keeps its animation below the placement.
        if (node.animation)
            node.animationPlacement = unplace * node.animationPlacement;
        else
            node.placed = unplace * node.world;
        node.world = node.at(0.0);  // where the first frame has it
    }
    return {};
}

// ---- declarations ---------------------------------------------------------------------------

Result<void> Builder::names(const std::vector<Declaration>& decls) {
    for (const auto& d : decls) {
        Where w = where(d);
        if (!isSceneKind(d.kind))
            return fail(ErrorCode::InvalidInput,
                        d.origin + ": rg." + declKindName(d.kind) + " \"" + d.name +
                            "\" belongs in a pipeline script, not in a scene");
        if (!d.body.isTable())
            return w.error("expected a table of fields after " + std::string(declKindName(d.kind)) +
                           " \"" + d.name + "\", got " + describe(d.body));
        // Objects (meshes) share one namespace: each becomes a node of that name.
        DeclKind slot =
            d.kind == DeclKind::Plane || d.kind == DeclKind::Box || d.kind == DeclKind::Gltf
                ? DeclKind::Sphere
                : d.kind;
        auto [it, fresh] = seen[static_cast<size_t>(slot)].emplace(d.name, &d);
        if (!fresh)
            return w.error(std::string(declKindName(it->second->kind)) + " '" + d.name +
                           "' is already declared (at " + it->second->origin + ")");
        if (d.kind == DeclKind::Lightmap) {
            if (firstLightmap)
                return w.error("a scene has one lightmap; '" + firstLightmap->name +
                               "' is declared at " + firstLightmap->origin);
            firstLightmap = &d;
        }
        if (d.kind == DeclKind::Environment) {
            if (firstEnvironment)
                return w.error("a scene has one environment; '" + firstEnvironment->name +
                               "' is declared at " + firstEnvironment->origin);
            firstEnvironment = &d;
        }
    }
    return {};
}

Result<Scene> Builder::build(const std::vector<Declaration>& decls) {
    if (auto r = names(decls); !r) return std::unexpected(r.error());
    // Materials first, so objects may name a material declared further down.
    for (const auto& d : decls)
        if (d.kind == DeclKind::SceneMaterial)
            if (auto r = material(d); !r) return std::unexpected(r.error());
    for (const auto& d : decls) {
        Result<void> r;
        switch (d.kind) {
            case DeclKind::Sphere:
            case DeclKind::Plane:
            case DeclKind::Box:
                r = object(d);
                break;
            case DeclKind::Gltf:
                r = gltf(d);
                break;
            case DeclKind::Light:
                r = light(d);
                break;
            case DeclKind::Camera:
                r = camera(d);
                break;
            case DeclKind::Decal:
                r = decal(d);
                break;
            case DeclKind::Probe:
                r = probe(d);
                break;
            case DeclKind::Lightmap:
                r = lightmap(d);
                break;
            default:
                break;
        }
        if (!r) return std::unexpected(r.error());
    }
    for (const auto& d : decls)
        if (d.kind == DeclKind::Environment)
            if (auto r = environment(d); !r) return std::unexpected(r.error());
    if (options.generateMips)
        for (auto& img : scene.images)
            if (img.mips.empty() && img.pixels.width > 0) generateMips(img);
    if (options.buildLods) buildMeshLods(scene);
    computeBounds(scene);
    if (scene.cameras.empty()) defaultCamera();
    return std::move(scene);
}

}  // namespace scene_script

namespace {

std::string defaultRoot() {
    if (const char* r = std::getenv("RG_ROOT"); r && *r) return r;
    return RG_SOURCE_ROOT;
}

}  // namespace

Result<Scene> loadSceneScript(const std::string& path, const SceneScriptOptions& options) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        auto r = readFile(path);
        return fail(ErrorCode::NotFound, r ? "'" + path + "' is not a regular file"
                                           : "scene script: " + r.error().message);
    }
    const std::string root = options.projectRoot.empty() ? defaultRoot() : options.projectRoot;
    LuaHostOptions ho;
    ho.projectRoot = root;
    ho.searchDirs = {root + "/scripts", root + "/materials"};
    ho.sceneArgs = options.args;
    LuaHost host(ho);
    std::vector<std::string> files;
    auto decls = host.loadDeclarations(path, &files);
    if (!decls) return std::unexpected(decls.error());
    scene_script::Builder b{path, options, {}, {}, {}, {}, nullptr, nullptr};
    for (const auto& f : files) b.addFile(f);
    return b.build(*decls);
}

}  // namespace rg
