// glTF 2.0 -> Scene. tinygltf parses; everything it does not check (accessor and buffer view
// bounds, index ranges, hierarchy cycles, array sizes) is checked here before any read, so a
// broken file is an error that names the file and the thing, never a crash.
// The steps are split over gltf_load_*.cpp (gltf_load_detail.h); this file reads the file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "gltf_load_detail.h"
#include "mesh_lod.h"
#include "scene.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace fs = std::filesystem;

namespace rg {

using namespace scene_detail;

namespace gltf_load {

namespace {

// Extensions whose meaning we implement (a file may require them).
const std::set<std::string> kSupported = {
    "KHR_texture_transform",      "KHR_materials_emissive_strength",
    "KHR_lights_punctual",        "KHR_mesh_quantization",
    "KHR_materials_ior",          "KHR_materials_specular",
    "KHR_materials_clearcoat",    "KHR_materials_sheen",
    "KHR_materials_unlit",        "KHR_materials_pbrSpecularGlossiness",
    "EXT_mesh_gpu_instancing",    "KHR_materials_variants",
    "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "KHR_materials_transmission", "KHR_materials_volume"};

std::string percentDecode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else
            out += uri[i];
    }
    return out;
}

std::string absolutePath(const std::string& p) {
    std::error_code ec;
    fs::path a = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? p : a.string();
}

// Keeps the encoded bytes of data: URI and buffer-view images for decoding later (tinygltf
// calls this while it parses; buffer views are parsed by then, so their bounds can be checked
// before the bytes are touched).
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto* state = static_cast<ImageCallbackState*>(user);
    if (image->bufferView >= 0) {
        const auto& views = state->model->bufferViews;
        const auto& view = views[size_t(image->bufferView)];  // index checked by tinygltf
        if (view.buffer < 0 || size_t(view.buffer) >= state->model->buffers.size()) {
            state->errors[index] = "buffer view " + std::to_string(image->bufferView) +
                                   " names buffer " + std::to_string(view.buffer) +
                                   ", which does not exist";
            return true;
        }
        const size_t have = state->model->buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > have || view.byteLength > have - view.byteOffset) {
            state->errors[index] = "buffer view " + std::to_string(image->bufferView) + " (bytes " +
                                   std::to_string(view.byteOffset) + ".." +
                                   std::to_string(view.byteOffset + view.byteLength) +
                                   ") is outside buffer " + std::to_string(view.buffer) + " (" +
                                   std::to_string(have) + " bytes)";
            return true;
        }
    }
    if (size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

}  // namespace

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// The top-level JSON (and the GLB's binary chunk size) as read before tinygltf runs, so the
// first errors are worded here.
struct Preflight {
    nlohmann::json json;
    bool binary = false;
    size_t jsonChunk = 0;  // a GLB's JSON chunk length (its data starts at byte 20)
};

// ---- messages and file names ----------------------------------------------------------------

std::unexpected<Error> Loader::error(ErrorCode code, const std::string& msg) const {
    return fail(code, quote(path) + ": " + msg);
}
void Loader::warn(const std::string& msg) { scene.warnings.push_back(quote(path) + ": " + msg); }
std::string Loader::named(const std::string& what, size_t index, const std::string& name) {
    return what + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}
std::string Loader::resolve(const std::string& uri) const {
    return (dir / percentDecode(uri)).string();
}
// A file rgraph's extras name (an IES profile, an environment image): relative to the glTF
// file's folder, as export-scene writes them; an absolute path is refused (a model carries no
// machine paths).
Result<std::string> Loader::extrasFile(const std::string& name, const std::string& label) const {
    if (name.empty()) return name;
    if (fs::path(name).is_absolute())
        return error(ErrorCode::InvalidInput,
                     label + ": '" + name +
                         "' is an absolute path; name the file relative to the glTF file");
    return (dir / fs::path(name)).lexically_normal().string();
}
// A file URI stays inside the glTF file's folder (a relative path that does not climb out of
// it with ".."); absolute paths and other schemes (http:, file:) are refused: a model names
// its own files, and rgraph downloads nothing.
Result<std::string> Loader::resolveInside(const std::string& uri, const std::string& label) const {
    const std::string decoded = percentDecode(uri);
    const auto colon = decoded.find(':'), slash = decoded.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
        return error(ErrorCode::InvalidInput,
                     label + ": only relative file names and data: URIs are read, not '" +
                         uri.substr(0, colon + 1) + "' URIs");
    const fs::path relative = fs::path(decoded).lexically_normal();
    if (relative.is_absolute() || (!relative.empty() && *relative.begin() == ".."))
        return error(
            ErrorCode::InvalidInput,
            label +
                ": the URI leaves the glTF file's folder; rgraph reads only files in or below it");
    return (dir / relative).string();
}
void Loader::addFile(const std::string& p) {
    std::string a = absolutePath(p);
    if (std::find(scene.files.begin(), scene.files.end(), a) == scene.files.end())
        scene.files.push_back(a);
}

// ---- reading the file ------------------------------------------------------------------------

Result<Preflight> Loader::preflight(const std::vector<unsigned char>& bytes) {
    Preflight pf;
    const unsigned char* json = bytes.data();
    size_t jsonSize = bytes.size();
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        pf.binary = true;
        auto u32 = [&](size_t at) {
            uint32_t v;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 20)
            return error(ErrorCode::InvalidInput, "truncated GLB: " + std::to_string(bytes.size()) +
                                                      " bytes, no JSON chunk");
        if (u32(4) != 2)
            return error(ErrorCode::Unsupported,
                         "GLB version " + std::to_string(u32(4)) + " is not supported (only 2)");
        if (u32(8) > bytes.size())
            return error(ErrorCode::InvalidInput,
                         "truncated GLB: the header says " + std::to_string(u32(8)) +
                             " bytes, the file has " + std::to_string(bytes.size()));
        if (u32(16) != 0x4E4F534Au)
            return error(ErrorCode::InvalidInput, "the first GLB chunk is not JSON");
        jsonSize = u32(12);
        if (jsonSize > bytes.size() - 20)
            return error(ErrorCode::InvalidInput,
                         "truncated GLB: the JSON chunk has " + std::to_string(jsonSize) +
                             " bytes, " + std::to_string(bytes.size() - 20) + " are left");
        json = bytes.data() + 20;
        pf.jsonChunk = jsonSize;
    }
    try {
        pf.json = nlohmann::json::parse(json, json + jsonSize);
    } catch (const nlohmann::json::parse_error& e) {
        // "[json.exception.parse_error.101] parse error at line 3, column 7: syntax error ..."
        std::string what = e.what();
        const std::string marker = "parse error at ";
        const size_t at = what.find(marker);
        return error(ErrorCode::InvalidInput,
                     at == std::string::npos
                         ? "invalid JSON: " + what
                         : "invalid JSON at " + what.substr(at + marker.size()));
    } catch (const nlohmann::json::exception& e) {
        // Not a syntax error but a value JSON cannot hold, e.g. out_of_range.406 "number
        // overflow parsing '1e400'" (found by tools/fuzz.sh gltf).
        std::string what = e.what();
        const size_t close = what.find("] ");
        return error(
            ErrorCode::InvalidInput,
            "invalid JSON: " + (close == std::string::npos ? what : what.substr(close + 2)));
    }
    if (!pf.json.is_object())
        return error(ErrorCode::InvalidInput, "invalid glTF: the top level is not a JSON object");
    auto asset = pf.json.find("asset");
    if (asset == pf.json.end() || !asset->is_object() || !asset->contains("version") ||
        !(*asset)["version"].is_string())
        return error(ErrorCode::InvalidInput,
                     "invalid glTF: no asset.version (is this a glTF file?)");
    const std::string version = (*asset)["version"].get<std::string>();
    if (version.rfind("2.", 0) != 0)
        return error(ErrorCode::Unsupported,
                     "glTF version " + version + " is not supported (only 2.x)");
    return pf;
}

Result<void> Loader::checkExtensions(const nlohmann::json& j) {
    std::vector<std::string> unsupported;
    if (auto it = j.find("extensionsRequired"); it != j.end() && it->is_array())
        for (const auto& e : *it)
            if (e.is_string() && !kSupported.count(e.get<std::string>()))
                unsupported.push_back(e.get<std::string>());
    if (!unsupported.empty()) {
        std::vector<std::string> reasons;
        if (unsupported.size() > 1)
            for (const auto& u : unsupported) reasons.push_back("required and not supported: " + u);
        return fail(ErrorCode::Unsupported,
                    quote(path) + " requires extension '" + unsupported[0] +
                        "', which rgraph does not support",
                    reasons);
    }
    if (auto it = j.find("extensionsUsed"); it != j.end() && it->is_array())
        for (const auto& e : *it)
            if (e.is_string() && !kSupported.count(e.get<std::string>()))
                warn("uses extension '" + e.get<std::string>() + "', which rgraph ignores");
    return {};
}

// External buffers: opened here so a missing or short .bin names itself.
Result<void> Loader::checkBuffers(const nlohmann::json& j) {
    auto it = j.find("buffers");
    if (it == j.end() || !it->is_array()) return {};
    for (size_t i = 0; i < it->size(); ++i) {
        const auto& b = (*it)[i];
        if (!b.is_object()) continue;
        if (auto len = b.find("byteLength");
            len != b.end() && !(len->is_number_unsigned() && len->get<uint64_t>() >= 1))
            return error(ErrorCode::InvalidInput, "buffer " + std::to_string(i) +
                                                      ": byteLength is " + len->dump() +
                                                      ", expected a whole number >= 1");
        auto uri = b.find("uri");
        if (uri == b.end() || !uri->is_string() || isDataUri(uri->get<std::string>())) continue;
        const std::string label =
            "buffer " + std::to_string(i) + " '" + uri->get<std::string>() + "'";
        auto inside = resolveInside(uri->get<std::string>(), label);
        if (!inside) return std::unexpected(inside.error());
        const std::string file = *inside;
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) {
            auto r = readFile(file);  // for the OS's reason
            return error(ErrorCode::InvalidInput,
                         label + ": " + (r ? "not a regular file" : r.error().message));
        }
        const uintmax_t size = fs::file_size(file, ec);
        auto len = b.find("byteLength");
        if (!ec && len != b.end() && len->is_number_unsigned() && len->get<uintmax_t>() > size)
            return error(ErrorCode::InvalidInput, label + ": the file has " + std::to_string(size) +
                                                      " bytes, byteLength says " +
                                                      std::to_string(len->get<uintmax_t>()));
        addFile(file);
    }
    return {};
}

bool Loader::dropDracoIndices(nlohmann::json& j) {
    bool changed = false;
    if (!j.contains("meshes") || !j["meshes"].is_array()) return false;
    for (auto& mesh : j["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        for (auto& prim : mesh["primitives"])
            if (prim.is_object() && prim.contains("indices") && prim.contains("extensions") &&
                prim["extensions"].is_object() &&
                prim["extensions"].contains("KHR_draco_mesh_compression")) {
                prim.erase("indices");
                changed = true;
            }
    }
    return changed;
}

Result<void> Loader::parse() {
    auto bytes = readFile(path);
    if (!bytes) return std::unexpected(bytes.error());
    addFile(path);
    dir = fs::path(path).parent_path();
    auto pf = preflight(*bytes);
    if (!pf) return std::unexpected(pf.error());
    if (auto r = checkSchema(pf->json); !r) return r;
    if (auto r = checkExtensions(pf->json); !r) return r;
    if (auto r = checkBuffers(pf->json); !r) return r;
    // A Draco primitive's index accessor has no buffer view (its indices are in the compressed
    // view), which tinygltf refuses: the JSON it reads leaves them out (gltf_load_draco.cpp decodes them).
    // A meshopt fallback buffer has no uri, which tinygltf refuses too (gltf_load_meshopt.cpp).
    const bool draco = dropDracoIndices(pf->json);
    if (placeholdMeshoptFallbacks(pf->json) || draco) {
        std::string text = pf->json.dump();
        if (!pf->binary) {
            bytes->assign(text.begin(), text.end());
        } else {
            while (text.size() % 4) text.push_back(' ');
            std::vector<unsigned char> glb(bytes->begin(), bytes->begin() + 20);
            glb.insert(glb.end(), text.begin(), text.end());
            glb.insert(glb.end(), bytes->begin() + 20 + std::ptrdiff_t(pf->jsonChunk),
                       bytes->end());
            auto put = [&](size_t at, uint32_t v) {
                for (int k = 0; k < 4; ++k) glb[at + size_t(k)] = (unsigned char)(v >> (8 * k));
            };
            put(8, uint32_t(glb.size()));
            put(12, uint32_t(text.size()));
            *bytes = std::move(glb);
        }
    }

    tinygltf::TinyGLTF gltf;
    imageState.model = &model;
    gltf.SetImageLoader(keepEncodedImage, &imageState);
    std::string err, warnings;
    const std::string base = fs::absolute(dir.empty() ? fs::path(".") : dir).string();
    bool ok = false;
    try {  // tinygltf throws on some inputs (e.g. vector::at on an empty GLB buffer)
        ok = pf->binary ? gltf.LoadBinaryFromMemory(&model, &err, &warnings, bytes->data(),
                                                    static_cast<unsigned int>(bytes->size()), base)
                        : gltf.LoadASCIIFromString(&model, &err, &warnings,
                                                   reinterpret_cast<const char*>(bytes->data()),
                                                   static_cast<unsigned int>(bytes->size()), base);
    } catch (const std::exception& e) {
        return error(ErrorCode::InvalidInput,
                     std::string("invalid glTF: tinygltf failed (") + e.what() + ")");
    }
    if (!ok) {
        std::string first = err.substr(0, err.find('\n'));
        if (first.empty()) first = "tinygltf could not read it";
        return error(ErrorCode::InvalidInput, "invalid glTF: " + first);
    }
    warnings += err;  // what tinygltf complained about but read anyway
    for (size_t from = 0; from < warnings.size();) {
        size_t to = warnings.find('\n', from);
        if (to == std::string::npos) to = warnings.size();
        if (to > from) warn(warnings.substr(from, to - from));
        from = to + 1;
    }
    return {};
}

// ---- numbers glTF gives a range ---------------------------------------------------------------

std::string Loader::fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}
// v within [lo, hi] (hi = inf: v >= lo), else an error naming `what`.
Result<float> Loader::ranged(const std::string& what, double v, double lo, double hi) const {
    if (v >= lo && v <= hi && std::isfinite(v)) return static_cast<float>(v);
    return error(ErrorCode::InvalidInput,
                 what + " is " + fmt(v) + ", expected " +
                     (std::isinf(hi) ? "a number >= " + fmt(lo)
                                     : "a number in [" + fmt(lo) + ", " + fmt(hi) + "]"));
}
Result<glm::vec3> Loader::ranged3(const std::string& what, const std::vector<double>& v,
                                  glm::vec3 def, double lo, double hi) const {
    if (v.empty()) return def;
    if (v.size() != 3)
        return error(ErrorCode::InvalidInput,
                     what + " has " + std::to_string(v.size()) + " values, expected 3");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        auto r = ranged(what + "[" + std::to_string(i) + "]", v[size_t(i)], lo, hi);
        if (!r) return std::unexpected(r.error());
        out[i] = *r;
    }
    return out;
}

double Loader::number(const tinygltf::Value& v, double def) {
    return v.IsNumber() ? v.GetNumberAsDouble() : def;
}
// A JSON number used as an index: -1 unless it is a whole number an int can hold.
int Loader::indexOf(const tinygltf::Value& v) {
    const double d = number(v, -1.0);
    return d >= 0.0 && d <= 2147483647.0 && std::floor(d) == d ? static_cast<int>(d) : -1;
}

glm::vec3 Loader::vec3Of(const std::vector<double>& v, glm::vec3 def) {
    return v.size() >= 3 ? glm::vec3(float(v[0]), float(v[1]), float(v[2])) : def;
}
glm::vec3 Loader::vec3Of(const tinygltf::Value& v, glm::vec3 def) {
    if (!v.IsArray() || v.ArrayLen() != 3) return def;
    return glm::vec3(float(number(v.Get(0), def.x)), float(number(v.Get(1), def.y)),
                     float(number(v.Get(2), def.z)));
}

Result<Scene> Loader::run() {
    if (auto r = parse(); !r) return std::unexpected(r.error());
    if (auto r = meshopt(); !r) return std::unexpected(r.error());
    convertSamplers();
    if (auto r = chooseVariant(); !r) return std::unexpected(r.error());
    if (auto r = materials(); !r) return std::unexpected(r.error());
    if (auto r = meshes(); !r) return std::unexpected(r.error());
    if (auto r = nodes(); !r) return std::unexpected(r.error());
    if (auto r = animations(); !r) return std::unexpected(r.error());
    volumeScale();
    if (options.buildLods) buildMeshLods(scene);
    computeBounds(scene);
    return std::move(scene);
}

}  // namespace gltf_load

Result<Scene> loadGltf(const std::string& path, const GltfOptions& options) {
    gltf_load::Loader loader;
    loader.path = path;
    loader.options = options;
    return loader.run();
}

}  // namespace rg
