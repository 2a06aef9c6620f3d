// The glTF 2.0 schema's types, checked on the file's JSON before tinygltf reads it (which takes
// a field of the wrong type as absent): a name that is not a string, `primitives` that is not an
// array, an index below 0, a transform that is not numbers, an extension that is not an object —
// each an error naming the file and the field's path, e.g. "nodes[3].scale: expected an array of
// 3 numbers, got \"big\"". Only types, counts and index signs: whether an index names something
// that exists is checked where it is used.
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_load_detail.h"

namespace rg::gltf_load {

namespace {

using json = nlohmann::json;

// A JSON value as a message shows it: short, on one line.
std::string shown(const json& v) {
    std::string s = v.dump();
    return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// The path of field `key` of the object at `where` ("" for the file's top level).
std::string at(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
}

class Schema {
public:
    std::string error;  // the first thing wrong: "PATH: expected ..., got ..."

    bool fail(const std::string& where, const std::string& expected, const json& got) {
        if (error.empty()) error = where + ": expected " + expected + ", got " + shown(got);
        return false;
    }
    // Fields of an object that every glTF object may have.
    bool common(const json& o, const std::string& where) {
        if (auto n = o.find("name"); n != o.end() && !n->is_string())
            return fail(at(where, "name"), "a string", *n);
        if (auto e = o.find("extensions"); e != o.end()) {
            if (!e->is_object()) return fail(at(where, "extensions"), "an object", *e);
            for (const auto& [key, value] : e->items())
                if (!value.is_object())
                    return fail(at(at(where, "extensions"), key), "an object", value);
        }
        return true;
    }
    bool object(const json& o, const char* key, const std::string& where, bool required = false) {
        auto v = o.find(key);
        if (v == o.end()) return required ? fail(at(where, key), "an object", json()) : true;
        return v->is_object() ? common(*v, at(where, key)) : fail(at(where, key), "an object", *v);
    }
    bool index(const json& o, const char* key, const std::string& where, bool required = false) {
        auto v = o.find(key);
        if (v == o.end())
            return required ? fail(at(where, key), "an index (a whole number >= 0)", json()) : true;
        return isIndex(*v) || fail(at(where, key), "an index (a whole number >= 0)", *v);
    }
    bool integer(const json& o, const char* key, const std::string& where) {
        auto v = o.find(key);
        return v == o.end() || v->is_number_integer() || fail(at(where, key), "a whole number", *v);
    }
    bool number(const json& o, const char* key, const std::string& where) {
        auto v = o.find(key);
        return v == o.end() || v->is_number() || fail(at(where, key), "a number", *v);
    }
    bool boolean(const json& o, const char* key, const std::string& where) {
        auto v = o.find(key);
        return v == o.end() || v->is_boolean() || fail(at(where, key), "true or false", *v);
    }
    bool string(const json& o, const char* key, const std::string& where) {
        auto v = o.find(key);
        return v == o.end() || v->is_string() || fail(at(where, key), "a string", *v);
    }
    // An array (of `count` elements; 0: any count) whose elements pass `is`: "an array of
    // <plural>", each "<one>".
    template <typename Is>
    bool arrayOf(const json& o, const char* key, const std::string& where, size_t count,
                 const std::string& plural, const char* one, Is is) {
        auto v = o.find(key);
        if (v == o.end()) return true;
        const std::string what =
            "an array of " + (count ? std::to_string(count) + " " : std::string()) + plural;
        if (!v->is_array() || (count && v->size() != count)) return fail(at(where, key), what, *v);
        for (size_t i = 0; i < v->size(); ++i)
            if (!is((*v)[i]))
                return fail(at(where, key) + "[" + std::to_string(i) + "]", one, (*v)[i]);
        return true;
    }
    bool numbers(const json& o, const char* key, size_t count, const std::string& where) {
        return arrayOf(o, key, where, count, "numbers", "a number",
                       [](const json& e) { return e.is_number(); });
    }
    bool strings(const json& o, const char* key, const std::string& where) {
        return arrayOf(o, key, where, 0, "strings", "a string",
                       [](const json& e) { return e.is_string(); });
    }
    bool indices(const json& o, const char* key, const std::string& where) {
        return arrayOf(o, key, where, 0, "indices", "an index (a whole number >= 0)", isIndex);
    }
    // A texture reference (textureInfo, normalTextureInfo, occlusionTextureInfo).
    bool textureInfo(const json& o, const char* key, const std::string& where) {
        auto v = o.find(key);
        if (v == o.end()) return true;
        const std::string here = at(where, key);
        if (!v->is_object()) return fail(here, "an object", *v);
        return common(*v, here) && index(*v, "index", here, true) && index(*v, "texCoord", here) &&
               number(*v, "scale", here) && number(*v, "strength", here);
    }
    // Each element of the top-level array `key`, an object, through `check`.
    template <typename Check>
    bool each(const json& root, const char* key, Check check) {
        auto v = root.find(key);
        if (v == root.end()) return true;
        if (!v->is_array()) return fail(key, "an array", *v);
        for (size_t i = 0; i < v->size(); ++i) {
            const std::string here = std::string(key) + "[" + std::to_string(i) + "]";
            const json& o = (*v)[i];
            if (!o.is_object()) return fail(here, "an object", o);
            if (!common(o, here) || !check(o, here)) return false;
        }
        return true;
    }

private:
    static bool isIndex(const json& v) {
        return v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
    }
};

// The fields of the material extensions rgraph reads (gltf_load_materials.cpp), by type: a number,
// an array of 3 or 4 numbers, a textureInfo. A field of the wrong type is an error here, as a
// core field's is, not the default it would otherwise silently become.
struct ExtensionField {
    const char* name;
    int kind;  // 0 a number, 3 or 4 an array of that many numbers, -1 a textureInfo
};
struct MaterialExtension {
    const char* name;
    std::vector<ExtensionField> fields;
};
const std::vector<MaterialExtension>& materialExtensions() {
    static const std::vector<MaterialExtension> table = {
        {"KHR_materials_ior", {{"ior", 0}}},
        {"KHR_materials_emissive_strength", {{"emissiveStrength", 0}}},
        {"KHR_materials_specular",
         {{"specularFactor", 0},
          {"specularColorFactor", 3},
          {"specularTexture", -1},
          {"specularColorTexture", -1}}},
        {"KHR_materials_clearcoat",
         {{"clearcoatFactor", 0},
          {"clearcoatRoughnessFactor", 0},
          {"clearcoatTexture", -1},
          {"clearcoatRoughnessTexture", -1},
          {"clearcoatNormalTexture", -1}}},
        {"KHR_materials_sheen",
         {{"sheenColorFactor", 3},
          {"sheenRoughnessFactor", 0},
          {"sheenColorTexture", -1},
          {"sheenRoughnessTexture", -1}}},
        {"KHR_materials_transmission", {{"transmissionFactor", 0}, {"transmissionTexture", -1}}},
        {"KHR_materials_volume",
         {{"thicknessFactor", 0},
          {"attenuationDistance", 0},
          {"attenuationColor", 3},
          {"thicknessTexture", -1}}},
        {"KHR_materials_pbrSpecularGlossiness",
         {{"diffuseFactor", 4},
          {"specularFactor", 3},
          {"glossinessFactor", 0},
          {"diffuseTexture", -1},
          {"specularGlossinessTexture", -1}}},
    };
    return table;
}

bool checkMaterialExtensions(Schema& s, const json& m, const std::string& at) {
    auto e = m.find("extensions");
    if (e == m.end() || !e->is_object()) return true;  // common() reports a wrong type
    for (const MaterialExtension& x : materialExtensions()) {
        auto v = e->find(x.name);
        if (v == e->end() || !v->is_object()) continue;
        const std::string here = at + ".extensions." + x.name;
        for (const ExtensionField& f : x.fields)
            if (!(f.kind == 0  ? s.number(*v, f.name, here)
                  : f.kind > 0 ? s.numbers(*v, f.name, static_cast<size_t>(f.kind), here)
                               : s.textureInfo(*v, f.name, here)))
                return false;
    }
    return true;
}

bool checkMaterial(Schema& s, const json& m, const std::string& at) {
    if (!s.object(m, "pbrMetallicRoughness", at) || !checkMaterialExtensions(s, m, at))
        return false;
    if (auto p = m.find("pbrMetallicRoughness"); p != m.end()) {
        const std::string pa = at + ".pbrMetallicRoughness";
        if (!s.numbers(*p, "baseColorFactor", 4, pa) || !s.number(*p, "metallicFactor", pa) ||
            !s.number(*p, "roughnessFactor", pa) || !s.textureInfo(*p, "baseColorTexture", pa) ||
            !s.textureInfo(*p, "metallicRoughnessTexture", pa))
            return false;
    }
    return s.textureInfo(m, "normalTexture", at) && s.textureInfo(m, "occlusionTexture", at) &&
           s.textureInfo(m, "emissiveTexture", at) && s.numbers(m, "emissiveFactor", 3, at) &&
           s.string(m, "alphaMode", at) && s.number(m, "alphaCutoff", at) &&
           s.boolean(m, "doubleSided", at);
}

bool checkMesh(Schema& s, const json& m, const std::string& at) {
    auto p = m.find("primitives");
    if (p == m.end() || !p->is_array() || p->empty())
        return s.fail(at + ".primitives", "a non-empty array of primitives",
                      p == m.end() ? json() : *p);
    for (size_t i = 0; i < p->size(); ++i) {
        const std::string pa = at + ".primitives[" + std::to_string(i) + "]";
        const json& prim = (*p)[i];
        if (!prim.is_object()) return s.fail(pa, "an object", prim);
        if (!s.common(prim, pa)) return false;
        auto a = prim.find("attributes");
        if (a == prim.end() || !a->is_object())
            return s.fail(pa + ".attributes", "an object of accessor indices",
                          a == prim.end() ? json() : *a);
        for (const auto& [name, value] : a->items())
            if (!s.index(*a, name.c_str(), pa + ".attributes")) return false;
        if (!s.index(prim, "indices", pa) || !s.index(prim, "material", pa) ||
            !s.integer(prim, "mode", pa))
            return false;
        if (auto t = prim.find("targets"); t != prim.end()) {
            if (!t->is_array()) return s.fail(pa + ".targets", "an array", *t);
            for (size_t k = 0; k < t->size(); ++k) {
                const std::string ta = pa + ".targets[" + std::to_string(k) + "]";
                if (!(*t)[k].is_object())
                    return s.fail(ta, "an object of accessor indices", (*t)[k]);
                for (const auto& [name, value] : (*t)[k].items())
                    if (!s.index((*t)[k], name.c_str(), ta)) return false;
            }
        }
    }
    return s.numbers(m, "weights", 0, at);
}

bool checkNode(Schema& s, const json& n, const std::string& at) {
    return s.index(n, "camera", at) && s.index(n, "mesh", at) && s.index(n, "skin", at) &&
           s.indices(n, "children", at) && s.numbers(n, "matrix", 16, at) &&
           s.numbers(n, "rotation", 4, at) && s.numbers(n, "scale", 3, at) &&
           s.numbers(n, "translation", 3, at) && s.numbers(n, "weights", 0, at);
}

}  // namespace

Result<void> Loader::checkSchema(const nlohmann::json& j) {
    Schema s;
    const bool ok =
        s.common(j, "") && s.index(j, "scene", "") && s.strings(j, "extensionsUsed", "") &&
        s.strings(j, "extensionsRequired", "") &&
        s.each(j, "accessors",
               [&](const json& o, const std::string& at) {
                   return s.index(o, "bufferView", at) && s.index(o, "byteOffset", at) &&
                          s.integer(o, "componentType", at) && s.boolean(o, "normalized", at) &&
                          s.index(o, "count", at) && s.string(o, "type", at) &&
                          s.numbers(o, "max", 0, at) && s.numbers(o, "min", 0, at) &&
                          s.object(o, "sparse", at);
               }) &&
        s.each(j, "bufferViews",
               [&](const json& o, const std::string& at) {
                   return s.index(o, "buffer", at, true) && s.index(o, "byteOffset", at) &&
                          s.index(o, "byteLength", at) && s.index(o, "byteStride", at) &&
                          s.integer(o, "target", at);
               }) &&
        s.each(j, "buffers",
               [&](const json& o, const std::string& at) { return s.string(o, "uri", at); }) &&
        s.each(j, "cameras",
               [&](const json& o, const std::string& at) {
                   return s.string(o, "type", at) && s.object(o, "perspective", at) &&
                          s.object(o, "orthographic", at);
               }) &&
        s.each(j, "images",
               [&](const json& o, const std::string& at) {
                   return s.string(o, "uri", at) && s.string(o, "mimeType", at) &&
                          s.index(o, "bufferView", at);
               }) &&
        s.each(j, "materials",
               [&](const json& o, const std::string& at) { return checkMaterial(s, o, at); }) &&
        s.each(j, "meshes",
               [&](const json& o, const std::string& at) { return checkMesh(s, o, at); }) &&
        s.each(j, "nodes",
               [&](const json& o, const std::string& at) { return checkNode(s, o, at); }) &&
        s.each(j, "samplers",
               [&](const json& o, const std::string& at) {
                   return s.integer(o, "magFilter", at) && s.integer(o, "minFilter", at) &&
                          s.integer(o, "wrapS", at) && s.integer(o, "wrapT", at);
               }) &&
        s.each(j, "scenes",
               [&](const json& o, const std::string& at) { return s.indices(o, "nodes", at); }) &&
        s.each(j, "skins",
               [&](const json& o, const std::string& at) {
                   return s.index(o, "inverseBindMatrices", at) && s.index(o, "skeleton", at) &&
                          s.indices(o, "joints", at);
               }) &&
        s.each(j, "textures", [&](const json& o, const std::string& at) {
            return s.index(o, "sampler", at) && s.index(o, "source", at);
        });
    if (ok) return {};
    return error(ErrorCode::InvalidInput, s.error);
}

}  // namespace rg::gltf_load
