// The declarations' common ground: kind names, files next to a declaration, and the field
// checks every kind's builder uses (declarations_detail.h). buildPipeline() is in
// declarations_builder.cpp.
#include "declarations.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "declarations_detail.h"

namespace rg {

std::string nextToDeclaration(const std::string& origin, const std::string& path,
                              const std::string& root) {
    if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
    const size_t colon = origin.rfind(':');
    if (colon == std::string::npos || colon == 0) return path;
    const std::filesystem::path script(origin.substr(0, colon));
    std::vector<std::filesystem::path> folders;
    if (script.is_absolute())
        folders.push_back(script.parent_path());
    else {
        if (!root.empty()) folders.push_back((std::filesystem::path(root) / script).parent_path());
        folders.push_back(std::filesystem::absolute(script).parent_path());
    }
    for (const auto& folder : folders) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(folder / path, ec))
            return std::filesystem::absolute(folder / path).lexically_normal().string();
    }
    return path;
}

const char* declKindName(DeclKind k) {
    switch (k) {
        case DeclKind::Texture:
            return "resource";
        case DeclKind::Buffer:
            return "buffer";
        case DeclKind::Pass:
            return "pass";
        case DeclKind::Param:
            return "param";
        case DeclKind::Layout:
            return "layout";
        case DeclKind::Stencil:
            return "stencil";
        case DeclKind::Path:
            return "path";
        case DeclKind::Material:
            return "material";
        case DeclKind::History:
            return "history";
        case DeclKind::SceneMaterial:
            return "scene.material";
        case DeclKind::Sphere:
            return "scene.sphere";
        case DeclKind::Plane:
            return "scene.plane";
        case DeclKind::Box:
            return "scene.box";
        case DeclKind::Gltf:
            return "scene.gltf";
        case DeclKind::Light:
            return "scene.light";
        case DeclKind::Camera:
            return "scene.camera";
        case DeclKind::Environment:
            return "scene.environment";
        case DeclKind::Decal:
            return "scene.decal";
        case DeclKind::Probe:
            return "scene.probe";
        case DeclKind::Lightmap:
            return "scene.lightmap";
        case DeclKind::Count:
            break;
    }
    return "?";
}

bool isSceneKind(DeclKind k) { return k >= DeclKind::SceneMaterial && k < DeclKind::Count; }

namespace declarations {

// A name GLSL accepts as an identifier: a letter or '_', then letters, digits and '_'.
bool isGlslIdentifier(const std::string& name) {
    return !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
           std::all_of(name.begin(), name.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
           });
}

std::string typeOf(const Value& v) {
    if (v.isNumber()) return "number";
    if (v.isBool()) return "boolean";
    if (v.isString()) return "string";
    if (v.isList()) return "list";
    if (v.isTable()) return "table";
    return "nil";
}

bool isInteger(const Value& v) { return v.isNumber() && std::floor(v.asNumber()) == v.asNumber(); }

Result<void> expectType(const Where& w, const Value& v, const std::string& type) {
    bool ok = (type == "string" && v.isString()) || (type == "number" && v.isNumber()) ||
              (type == "boolean" && v.isBool()) ||
              (type == "table" && (v.isTable() || (v.isList() && v.asList().empty()))) ||
              (type == "list" && v.isList()) ||
              (type == "number|list" && (v.isNumber() || v.isList())) ||
              (type == "string|list" && (v.isString() || v.isList())) ||
              (type == "integer" && isInteger(v));
    if (ok) return {};
    std::string want = type == "number|list"   ? "a number or a list of numbers"
                       : type == "string|list" ? "a string or a list of strings"
                       : type == "integer"     ? "a whole number"
                       : type == "list"        ? "a list"
                       : type == "table"       ? "a table"
                       : type == "boolean"     ? "a boolean"
                                               : "a " + type;
    return w.error("expected " + want + ", got " +
                   (v.isNumber() && type == "integer" ? "a fraction" : typeOf(v)));
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

}  // namespace declarations

Result<void> checkFields(const Where& w, const Value& body,
                         const std::vector<std::string>& allowed) {
    for (const auto& [key, _] : body.asTable()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        if (key[0] == '#')
            return w.error("unexpected positional value " + key.substr(1) +
                           "; expected named fields: " + joinQuoted(allowed));
        return w.at(key).error("unknown field" + suggestion(key, allowed) +
                               "; expected one of: " + joinQuoted(allowed));
    }
    return {};
}

}  // namespace rg
