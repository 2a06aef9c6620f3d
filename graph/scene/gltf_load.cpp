// glTF 2.0 -> Scene. tinygltf parses; everything it does not check (accessor and buffer view
// bounds, index ranges, hierarchy cycles, array sizes) is checked here before any read, so a
// broken file is an error that names the file and the thing, never a crash.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace fs = std::filesystem;

namespace rg {

using namespace scene_detail;

namespace {

// Extensions whose meaning we implement (a file may require them).
constexpr size_t kMaxDepth = 1000;  // node hierarchy levels (recursion depth)

const std::set<std::string> kSupported = {"KHR_texture_transform", "KHR_materials_emissive_strength",
                                          "KHR_lights_punctual", "KHR_mesh_quantization"};

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return nullptr;
    }
}

const char* componentName(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return "?";
    }
}

int componentBytes(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

const char* typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "?";
    }
}

// One component as float; normalised integers map to [0, 1] / [-1, 1] (glTF 3.11).
float readComponent(const unsigned char* p, int type, bool normalized) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<int8_t>(p[0]);
        return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
        int32_t v;
        std::memcpy(&v, p, 4);
        return float(v);
    }
    default: return 0.0f;
    }
}

uint32_t readIndex(const unsigned char* p, int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    default: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

std::string percentDecode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else
            out += uri[i];
    }
    return out;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string absolutePath(const std::string& p) {
    std::error_code ec;
    fs::path a = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? p : a.string();
}

// The top-level JSON (and the GLB's binary chunk size) as read before tinygltf runs, so the
// first errors are worded here.
struct Preflight {
    nlohmann::json json;
    bool binary = false;
};

// Keeps the encoded bytes of data: URI and buffer-view images for decoding later (tinygltf
// calls this while it parses; buffer views are parsed by then, so their bounds can be checked
// before the bytes are touched).
struct ImageCallbackState {
    const tinygltf::Model* model = nullptr;
    std::map<int, std::string> errors;  // image index -> what is wrong
};

bool keepEncodedImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto* state = static_cast<ImageCallbackState*>(user);
    if (image->bufferView >= 0) {
        const auto& views = state->model->bufferViews;
        const auto& view = views[size_t(image->bufferView)];  // index checked by tinygltf
        if (view.buffer < 0 || size_t(view.buffer) >= state->model->buffers.size()) {
            state->errors[index] = "buffer view " + std::to_string(image->bufferView) + " names buffer " +
                                   std::to_string(view.buffer) + ", which does not exist";
            return true;
        }
        const size_t have = state->model->buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > have || view.byteLength > have - view.byteOffset) {
            state->errors[index] = "buffer view " + std::to_string(image->bufferView) + " (bytes " +
                                   std::to_string(view.byteOffset) + ".." + std::to_string(view.byteOffset + view.byteLength) +
                                   ") is outside buffer " + std::to_string(view.buffer) + " (" + std::to_string(have) + " bytes)";
            return true;
        }
    }
    if (size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

struct Loader {
    std::string path;  // as given: every message starts with it
    GltfOptions options;
    fs::path dir;      // the file's folder, as given (for messages) and for resolving uris
    tinygltf::Model model;
    ImageCallbackState imageState;
    Scene scene;
    std::map<std::pair<int, bool>, int32_t> images;  // (glTF image, srgb) -> Scene image
    std::vector<int32_t> samplers;                    // glTF sampler -> Scene sampler
    int32_t defaultMaterial = -1;

    std::unexpected<Error> error(ErrorCode code, const std::string& msg) const {
        return fail(code, quote(path) + ": " + msg);
    }
    void warn(const std::string& msg) const {
        if (options.warnings) options.warnings->push_back(quote(path) + ": " + msg);
    }
    static std::string named(const std::string& what, size_t index, const std::string& name) {
        return what + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
    }
    std::string resolve(const std::string& uri) const { return (dir / percentDecode(uri)).string(); }
    // A file URI stays inside the glTF file's folder (a relative path that does not climb out of
    // it with ".."); absolute paths and other schemes (http:, file:) are refused: a model names
    // its own files, and rgraph downloads nothing.
    // A file rgraph's extras name (an IES profile, an environment image): relative to the glTF
    // file's folder, as export-scene writes them; an absolute path is refused (a model carries no
    // machine paths).
    Result<std::string> extrasFile(const std::string& name, const std::string& label) const {
        if (name.empty()) return name;
        if (fs::path(name).is_absolute())
            return error(ErrorCode::InvalidInput, label + ": '" + name + "' is an absolute path; name the file relative to the glTF file");
        return (dir / fs::path(name)).lexically_normal().string();
    }
    Result<std::string> resolveInside(const std::string& uri, const std::string& label) const {
        const std::string decoded = percentDecode(uri);
        const auto colon = decoded.find(':'), slash = decoded.find('/');
        if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
            return error(ErrorCode::InvalidInput, label + ": only relative file names and data: URIs are read, not '" + uri.substr(0, colon + 1) + "' URIs");
        const fs::path relative = fs::path(decoded).lexically_normal();
        if (relative.is_absolute() || (!relative.empty() && *relative.begin() == ".."))
            return error(ErrorCode::InvalidInput, label + ": the URI leaves the glTF file's folder; rgraph reads only files in or below it");
        return (dir / relative).string();
    }
    void addFile(const std::string& p) {
        std::string a = absolutePath(p);
        if (std::find(scene.files.begin(), scene.files.end(), a) == scene.files.end()) scene.files.push_back(a);
    }

    // ---- reading the file -------------------------------------------------------------------

    Result<Preflight> preflight(const std::vector<unsigned char>& bytes) {
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
            if (bytes.size() < 20) return error(ErrorCode::InvalidInput, "truncated GLB: " + std::to_string(bytes.size()) + " bytes, no JSON chunk");
            if (u32(4) != 2) return error(ErrorCode::Unsupported, "GLB version " + std::to_string(u32(4)) + " is not supported (only 2)");
            if (u32(8) > bytes.size())
                return error(ErrorCode::InvalidInput, "truncated GLB: the header says " + std::to_string(u32(8)) + " bytes, the file has " +
                                                          std::to_string(bytes.size()));
            if (u32(16) != 0x4E4F534Au) return error(ErrorCode::InvalidInput, "the first GLB chunk is not JSON");
            jsonSize = u32(12);
            if (jsonSize > bytes.size() - 20)
                return error(ErrorCode::InvalidInput, "truncated GLB: the JSON chunk has " + std::to_string(jsonSize) + " bytes, " +
                                                          std::to_string(bytes.size() - 20) + " are left");
            json = bytes.data() + 20;
        }
        try {
            pf.json = nlohmann::json::parse(json, json + jsonSize);
        } catch (const nlohmann::json::parse_error& e) {
            // "[json.exception.parse_error.101] parse error at line 3, column 7: syntax error ..."
            std::string what = e.what();
            const std::string marker = "parse error at ";
            const size_t at = what.find(marker);
            return error(ErrorCode::InvalidInput,
                         at == std::string::npos ? "invalid JSON: " + what : "invalid JSON at " + what.substr(at + marker.size()));
        } catch (const nlohmann::json::exception& e) {
            // Not a syntax error but a value JSON cannot hold, e.g. out_of_range.406 "number
            // overflow parsing '1e400'" (found by tools/fuzz.sh gltf).
            std::string what = e.what();
            const size_t close = what.find("] ");
            return error(ErrorCode::InvalidInput, "invalid JSON: " + (close == std::string::npos ? what : what.substr(close + 2)));
        }
        if (!pf.json.is_object()) return error(ErrorCode::InvalidInput, "invalid glTF: the top level is not a JSON object");
        auto asset = pf.json.find("asset");
        if (asset == pf.json.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
            return error(ErrorCode::InvalidInput, "invalid glTF: no asset.version (is this a glTF file?)");
        const std::string version = (*asset)["version"].get<std::string>();
        if (version.rfind("2.", 0) != 0)
            return error(ErrorCode::Unsupported, "glTF version " + version + " is not supported (only 2.x)");
        return pf;
    }

    Result<void> checkExtensions(const nlohmann::json& j) {
        std::vector<std::string> unsupported;
        if (auto it = j.find("extensionsRequired"); it != j.end() && it->is_array())
            for (const auto& e : *it)
                if (e.is_string() && !kSupported.count(e.get<std::string>())) unsupported.push_back(e.get<std::string>());
        if (!unsupported.empty()) {
            std::vector<std::string> reasons;
            if (unsupported.size() > 1)
                for (const auto& u : unsupported) reasons.push_back("required and not supported: " + u);
            return fail(ErrorCode::Unsupported, quote(path) + " requires extension '" + unsupported[0] +
                                                    "', which rgraph does not support", reasons);
        }
        if (auto it = j.find("extensionsUsed"); it != j.end() && it->is_array())
            for (const auto& e : *it)
                if (e.is_string() && !kSupported.count(e.get<std::string>()))
                    warn("uses extension '" + e.get<std::string>() + "', which rgraph ignores");
        return {};
    }

    // External buffers: opened here so a missing or short .bin names itself.
    Result<void> checkBuffers(const nlohmann::json& j) {
        auto it = j.find("buffers");
        if (it == j.end() || !it->is_array()) return {};
        for (size_t i = 0; i < it->size(); ++i) {
            const auto& b = (*it)[i];
            if (!b.is_object()) continue;
            if (auto len = b.find("byteLength"); len != b.end() && !(len->is_number_unsigned() && len->get<uint64_t>() >= 1))
                return error(ErrorCode::InvalidInput, "buffer " + std::to_string(i) + ": byteLength is " + len->dump() + ", expected a whole number >= 1");
            auto uri = b.find("uri");
            if (uri == b.end() || !uri->is_string() || isDataUri(uri->get<std::string>())) continue;
            const std::string label = "buffer " + std::to_string(i) + " '" + uri->get<std::string>() + "'";
            auto inside = resolveInside(uri->get<std::string>(), label);
            if (!inside) return std::unexpected(inside.error());
            const std::string file = *inside;
            std::error_code ec;
            if (!fs::is_regular_file(file, ec)) {
                auto r = readFile(file);  // for the OS's reason
                return error(ErrorCode::InvalidInput, label + ": " + (r ? "not a regular file" : r.error().message));
            }
            const uintmax_t size = fs::file_size(file, ec);
            auto len = b.find("byteLength");
            if (!ec && len != b.end() && len->is_number_unsigned() && len->get<uintmax_t>() > size)
                return error(ErrorCode::InvalidInput, label + ": the file has " + std::to_string(size) + " bytes, byteLength says " +
                                                          std::to_string(len->get<uintmax_t>()));
            addFile(file);
        }
        return {};
    }

    Result<void> parse() {
        auto bytes = readFile(path);
        if (!bytes) return std::unexpected(bytes.error());
        addFile(path);
        dir = fs::path(path).parent_path();
        auto pf = preflight(*bytes);
        if (!pf) return std::unexpected(pf.error());
        if (auto r = checkExtensions(pf->json); !r) return r;
        if (auto r = checkBuffers(pf->json); !r) return r;

        tinygltf::TinyGLTF gltf;
        imageState.model = &model;
        gltf.SetImageLoader(keepEncodedImage, &imageState);
        std::string err, warnings;
        const std::string base = fs::absolute(dir.empty() ? fs::path(".") : dir).string();
        bool ok = false;
        try {  // tinygltf throws on some inputs (e.g. vector::at on an empty GLB buffer)
            ok = pf->binary ? gltf.LoadBinaryFromMemory(&model, &err, &warnings, bytes->data(), static_cast<unsigned int>(bytes->size()), base)
                            : gltf.LoadASCIIFromString(&model, &err, &warnings, reinterpret_cast<const char*>(bytes->data()),
                                                       static_cast<unsigned int>(bytes->size()), base);
        } catch (const std::exception& e) {
            return error(ErrorCode::InvalidInput, std::string("invalid glTF: tinygltf failed (") + e.what() + ")");
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

    // ---- accessors --------------------------------------------------------------------------

    struct View {
        const unsigned char* data = nullptr;  // first element
        size_t stride = 0;
    };

    // Bounds of `count` elements of `elementSize` bytes at `offset` of a buffer view, stride
    // from the view; checked against the view and the view against its buffer.
    Result<View> viewRange(const std::string& what, int viewIndex, size_t offset, size_t count, size_t elementSize,
                           bool allowStride) {
        if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
            return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) + " does not exist (" +
                                                      std::to_string(model.bufferViews.size()) + " buffer views)");
        const auto& view = model.bufferViews[size_t(viewIndex)];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) + " names buffer " +
                                                      std::to_string(view.buffer) + ", which does not exist");
        const size_t bufferSize = model.buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset)
            return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) + " (bytes " +
                                                      std::to_string(view.byteOffset) + ".." + std::to_string(view.byteOffset + view.byteLength) +
                                                      ") is outside buffer " + std::to_string(view.buffer) + " (" +
                                                      std::to_string(bufferSize) + " bytes)");
        const size_t stride = allowStride && view.byteStride ? view.byteStride : elementSize;
        if (stride < elementSize)
            return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) + " has byteStride " +
                                                      std::to_string(stride) + ", less than the element size " + std::to_string(elementSize));
        if (count > 0) {
            // 128-bit: offset and count come from the file and may be anything.
            const unsigned __int128 wide = (unsigned __int128)offset + (unsigned __int128)stride * (count - 1) + elementSize;
            const uint64_t end = wide > UINT64_MAX ? UINT64_MAX : static_cast<uint64_t>(wide);
            if (wide > view.byteLength)
                return error(ErrorCode::InvalidInput, what + " is out of range: it reads bytes " + std::to_string(offset) + ".." +
                                                          std::to_string(end) + " of buffer view " + std::to_string(viewIndex) +
                                                          ", which has " + std::to_string(view.byteLength) + " bytes");
        }
        return View{model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + offset, stride};
    }

    Result<const tinygltf::Accessor*> accessor(const std::string& what, int index) {
        if (index < 0 || size_t(index) >= model.accessors.size())
            return error(ErrorCode::InvalidInput, what + ": accessor " + std::to_string(index) + " does not exist (" +
                                                      std::to_string(model.accessors.size()) + " accessors)");
        return &model.accessors[size_t(index)];
    }

    // The accessor's elements as floats, `components` per element (sparse substitution applied).
    Result<std::vector<float>> readFloats(const std::string& where, const std::string& semantic, int index, int type) {
        const std::string what = where + ": " + semantic + ": accessor " + std::to_string(index);
        auto acc = accessor(where + ": " + semantic, index);
        if (!acc) return std::unexpected(acc.error());
        const tinygltf::Accessor& a = **acc;
        if (a.type != type)
            return error(ErrorCode::InvalidInput, what + " is " + typeName(a.type) + ", expected " + typeName(type));
        const int cbytes = componentBytes(a.componentType);
        if (cbytes == 0)
            return error(ErrorCode::InvalidInput, what + " has component type " + componentName(a.componentType) +
                                                      ", which glTF vertex data cannot have");
        const size_t comps = size_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
        // Without a buffer view the elements are zeros (then maybe sparse); cap what that allocates.
        if (a.bufferView < 0 && a.count > (size_t(1) << 24))
            return error(ErrorCode::InvalidInput, what + " has " + std::to_string(a.count) + " elements and no buffer view (at most 16777216)");
        std::vector<float> out;
        if (a.bufferView >= 0) {
            auto v = viewRange(what, a.bufferView, a.byteOffset, a.count, comps * size_t(cbytes), /*allowStride=*/true);
            if (!v) return std::unexpected(v.error());
            out.assign(a.count * comps, 0.0f);
            for (size_t i = 0; i < a.count; ++i)
                for (size_t c = 0; c < comps; ++c)
                    out[i * comps + c] = readComponent(v->data + i * v->stride + c * size_t(cbytes), a.componentType, a.normalized);
        } else
            out.assign(a.count * comps, 0.0f);
        if (a.sparse.isSparse) {
            const auto& sp = a.sparse;
            if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0 || sp.count < 0)
                return error(ErrorCode::InvalidInput, what + ": negative sparse count or byteOffset");
            const size_t n = size_t(std::max(sp.count, 0));
            const int itype = sp.indices.componentType;
            if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                return error(ErrorCode::InvalidInput, what + ": sparse indices have component type " + componentName(itype));
            auto iv = viewRange(what + " (sparse indices)", sp.indices.bufferView, size_t(sp.indices.byteOffset), n,
                                size_t(componentBytes(itype)), false);
            if (!iv) return std::unexpected(iv.error());
            auto vv = viewRange(what + " (sparse values)", sp.values.bufferView, size_t(sp.values.byteOffset), n,
                                comps * size_t(cbytes), false);
            if (!vv) return std::unexpected(vv.error());
            for (size_t k = 0; k < n; ++k) {
                const uint32_t target = readIndex(iv->data + k * iv->stride, itype);
                if (target >= a.count)
                    return error(ErrorCode::InvalidInput, what + ": sparse index " + std::to_string(target) + " is out of range (" +
                                                              std::to_string(a.count) + " elements)");
                for (size_t c = 0; c < comps; ++c)
                    out[target * comps + c] = readComponent(vv->data + k * vv->stride + c * size_t(cbytes), a.componentType, a.normalized);
            }
        }
        for (float f : out)
            if (!std::isfinite(f)) return error(ErrorCode::InvalidInput, what + " holds a NaN or infinite value");
        return out;
    }

    Result<std::vector<uint32_t>> readIndices(const std::string& where, int index, size_t vertexCount) {
        const std::string what = where + ": indices: accessor " + std::to_string(index);
        auto acc = accessor(where + ": indices", index);
        if (!acc) return std::unexpected(acc.error());
        const tinygltf::Accessor& a = **acc;
        const int ct = a.componentType;
        if (a.type != TINYGLTF_TYPE_SCALAR) return error(ErrorCode::InvalidInput, what + " is " + typeName(a.type) + ", expected SCALAR");
        if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            return error(ErrorCode::InvalidInput, what + " has component type " + componentName(ct) +
                                                      ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        if (a.sparse.isSparse) return error(ErrorCode::Unsupported, what + ": sparse index accessors are not supported");
        if (a.bufferView < 0) return error(ErrorCode::InvalidInput, what + " has no buffer view");
        auto v = viewRange(what, a.bufferView, a.byteOffset, a.count, size_t(componentBytes(ct)), /*allowStride=*/false);
        if (!v) return std::unexpected(v.error());
        std::vector<uint32_t> out(a.count);
        for (size_t i = 0; i < a.count; ++i) {
            out[i] = readIndex(v->data + i * v->stride, ct);
            if (out[i] >= vertexCount)
                return error(ErrorCode::InvalidInput, what + ": index " + std::to_string(out[i]) + " (element " + std::to_string(i) +
                                                          ") is out of range: the primitive has " + std::to_string(vertexCount) + " vertices");
        }
        return out;
    }

    // ---- meshes -----------------------------------------------------------------------------

    Result<uint32_t> materialIndex(const std::string& where, int m) {
        if (m < 0) {
            if (defaultMaterial < 0) {
                // glTF 3.9: without a material, the defaults of every property (white, fully
                // metallic, fully rough).
                Material d;
                d.name = "default";
                d.baseColor = glm::vec3(1.0f);
                d.metalMask = 1.0f;
                d.smoothness = 0.0f;
                defaultMaterial = static_cast<int32_t>(scene.materials.size());
                scene.materials.push_back(d);
            }
            return static_cast<uint32_t>(defaultMaterial);
        }
        if (size_t(m) >= model.materials.size())
            return error(ErrorCode::InvalidInput, where + ": material " + std::to_string(m) + " does not exist (" +
                                                      std::to_string(model.materials.size()) + " materials)");
        return static_cast<uint32_t>(m);
    }

    Result<Primitive> primitive(size_t meshIndex, size_t primIndex) {
        const auto& mesh = model.meshes[meshIndex];
        const auto& prim = mesh.primitives[primIndex];
        const std::string where = named("mesh", meshIndex, mesh.name) + " primitive " + std::to_string(primIndex);
        const char* mode = modeName(prim.mode);
        if (!mode) return error(ErrorCode::InvalidInput, where + ": mode " + std::to_string(prim.mode) + " is not a glTF primitive mode");
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
            return error(ErrorCode::Unsupported, where + ": mode " + mode + " is not supported (only triangles)");
        auto attr = [&](const char* name) {
            auto it = prim.attributes.find(name);
            return it == prim.attributes.end() ? -1 : it->second;
        };
        if (attr("POSITION") < 0) return error(ErrorCode::InvalidInput, where + ": no POSITION attribute");
        auto pos = readFloats(where, "POSITION", attr("POSITION"), TINYGLTF_TYPE_VEC3);
        if (!pos) return std::unexpected(pos.error());
        const size_t n = pos->size() / 3;
        Primitive p;
        p.vertices.resize(n);
        for (size_t i = 0; i < n; ++i) p.vertices[i].position = glm::vec3((*pos)[3 * i], (*pos)[3 * i + 1], (*pos)[3 * i + 2]);

        // Other attributes must have as many elements as POSITION.
        auto optional = [&](const char* semantic, int type) -> Result<std::vector<float>> {
            if (attr(semantic) < 0) return std::vector<float>{};
            auto v = readFloats(where, semantic, attr(semantic), type);
            if (!v) return v;
            const size_t comps = size_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
            if (v->size() / comps != n)
                return error(ErrorCode::InvalidInput, where + ": " + semantic + ": accessor " + std::to_string(attr(semantic)) + " has " +
                                                          std::to_string(v->size() / comps) + " elements, POSITION has " + std::to_string(n));
            return v;
        };
        auto normals = optional("NORMAL", TINYGLTF_TYPE_VEC3);
        if (!normals) return std::unexpected(normals.error());
        auto tangents = optional("TANGENT", TINYGLTF_TYPE_VEC4);
        if (!tangents) return std::unexpected(tangents.error());
        auto uv0 = optional("TEXCOORD_0", TINYGLTF_TYPE_VEC2);
        if (!uv0) return std::unexpected(uv0.error());
        auto uv1 = optional("TEXCOORD_1", TINYGLTF_TYPE_VEC2);
        if (!uv1) return std::unexpected(uv1.error());
        for (size_t i = 0; i < n; ++i) {
            Vertex& v = p.vertices[i];
            if (!normals->empty()) v.normal = glm::vec3((*normals)[3 * i], (*normals)[3 * i + 1], (*normals)[3 * i + 2]);
            if (!tangents->empty())
                v.tangent = glm::vec4((*tangents)[4 * i], (*tangents)[4 * i + 1], (*tangents)[4 * i + 2], (*tangents)[4 * i + 3] < 0 ? -1.0f : 1.0f);
            if (!uv0->empty()) v.uv0 = glm::vec2((*uv0)[2 * i], (*uv0)[2 * i + 1]);
            if (!uv1->empty()) v.uv1 = glm::vec2((*uv1)[2 * i], (*uv1)[2 * i + 1]);
        }
        // TEXCOORD_1 is the lightmap parameterisation game teams author (charts in [0, 1]²).
        p.lightmapUv = !uv1->empty();

        std::vector<uint32_t> idx;
        if (prim.indices >= 0) {
            auto r = readIndices(where, prim.indices, n);
            if (!r) return std::unexpected(r.error());
            idx = std::move(*r);
        } else {
            idx.resize(n);
            for (size_t i = 0; i < n; ++i) idx[i] = static_cast<uint32_t>(i);
        }
        // Strips and fans become lists; a strip's odd triangles swap two corners to stay CCW.
        if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (size_t i = 0; i + 2 < idx.size(); ++i)
                if (i % 2 == 0) p.indices.insert(p.indices.end(), {idx[i], idx[i + 1], idx[i + 2]});
                else p.indices.insert(p.indices.end(), {idx[i + 1], idx[i], idx[i + 2]});
        } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (size_t i = 1; i + 1 < idx.size(); ++i) p.indices.insert(p.indices.end(), {idx[0], idx[i], idx[i + 1]});
        } else {
            if (idx.size() % 3 != 0) warn(where + ": " + std::to_string(idx.size()) + " indices is not a whole number of triangles; the last " +
                                          std::to_string(idx.size() % 3) + " are ignored");
            idx.resize(idx.size() - idx.size() % 3);
            p.indices = std::move(idx);
        }

        auto m = materialIndex(where, prim.material);
        if (!m) return std::unexpected(m.error());
        p.material = *m;
        // glTF 3.7.2.1: without normals, flat normals, and tangents are then ignored.
        if (normals->empty()) generateFlatNormals(p);
        else
            for (auto& v : p.vertices) {
                // Renormalise only what is not unit already, so written normals load back bit-exact.
                const float len = glm::length(v.normal);
                if (!(len > 0.0f)) v.normal = glm::vec3(0, 0, 1);
                else if (std::fabs(len - 1.0f) > 1e-6f) v.normal /= len;
            }
        if (normals->empty() || tangents->empty()) generateTangents(p);
        return p;
    }

    Result<void> meshes() {
        for (size_t m = 0; m < model.meshes.size(); ++m) {
            Mesh mesh;
            mesh.name = model.meshes[m].name.empty() ? "mesh " + std::to_string(m) : model.meshes[m].name;
            for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
                auto prim = primitive(m, p);
                if (!prim) return std::unexpected(prim.error());
                mesh.primitives.push_back(std::move(*prim));
            }
            scene.meshes.push_back(std::move(mesh));
        }
        return {};
    }

    // ---- numbers glTF gives a range -----------------------------------------------------------

    static std::string fmt(double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", v);
        return buf;
    }
    // v within [lo, hi] (hi = inf: v >= lo), else an error naming `what`.
    Result<float> ranged(const std::string& what, double v, double lo, double hi) const {
        if (v >= lo && v <= hi && std::isfinite(v)) return static_cast<float>(v);
        return error(ErrorCode::InvalidInput, what + " is " + fmt(v) + ", expected " +
                                                  (std::isinf(hi) ? "a number >= " + fmt(lo) : "a number in [" + fmt(lo) + ", " + fmt(hi) + "]"));
    }
    Result<glm::vec3> ranged3(const std::string& what, const std::vector<double>& v, glm::vec3 def, double lo, double hi) const {
        if (v.empty()) return def;
        if (v.size() != 3) return error(ErrorCode::InvalidInput, what + " has " + std::to_string(v.size()) + " values, expected 3");
        glm::vec3 out;
        for (int i = 0; i < 3; ++i) {
            auto r = ranged(what + "[" + std::to_string(i) + "]", v[size_t(i)], lo, hi);
            if (!r) return std::unexpected(r.error());
            out[i] = *r;
        }
        return out;
    }

    // ---- materials, textures, images --------------------------------------------------------

    void convertSamplers() {
        for (const auto& s : model.samplers) {
            SamplerDesc d;
            auto wrap = [](int w) {
                return w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? Wrap::ClampToEdge
                       : w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? Wrap::MirroredRepeat
                                                                    : Wrap::Repeat;
            };
            d.wrapS = wrap(s.wrapS);
            d.wrapT = wrap(s.wrapT);
            d.magFilter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
            switch (s.minFilter) {
            case TINYGLTF_TEXTURE_FILTER_NEAREST:
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
                d.minFilter = Filter::Nearest;
                d.mipmapMode = MipmapMode::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR:
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
                d.minFilter = Filter::Linear;
                d.mipmapMode = MipmapMode::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
                d.minFilter = Filter::Nearest;
                d.mipmapMode = MipmapMode::Linear;
                break;
            default:  // LINEAR_MIPMAP_LINEAR or undefined
                d.minFilter = Filter::Linear;
                d.mipmapMode = MipmapMode::Linear;
                break;
            }
            samplers.push_back(static_cast<int32_t>(scene.samplers.size()));
            scene.samplers.push_back(d);
        }
    }

    Result<int32_t> image(const std::string& where, int index, bool srgb) {
        if (auto it = images.find({index, srgb}); it != images.end()) return it->second;
        const auto& img = model.images[size_t(index)];
        const std::string label = named("image", size_t(index), !img.uri.empty() && !isDataUri(img.uri) ? img.uri : img.name);
        SceneImage out;
        out.name = !img.name.empty() ? img.name : !img.uri.empty() && !isDataUri(img.uri) ? img.uri : "image " + std::to_string(index);
        out.srgb = srgb;
        if (options.loadImages) {
            if (auto e = imageState.errors.find(index); e != imageState.errors.end())
                return error(ErrorCode::InvalidInput, label + ": " + e->second);
            std::vector<unsigned char> bytes = img.image;
            if (bytes.empty() && !img.uri.empty() && !isDataUri(img.uri)) {
                auto inside = resolveInside(img.uri, label);
                if (!inside) return std::unexpected(inside.error());
                const std::string file = *inside;
                auto r = readFile(file);
                if (!r) return error(ErrorCode::InvalidInput, label + ": " + r.error().message);
                bytes = std::move(*r);
                addFile(file);
            }
            if (bytes.empty()) return error(ErrorCode::InvalidInput, label + ": no image data");
            auto decoded = decodeImage(bytes.data(), bytes.size());
            if (!decoded) return error(ErrorCode::InvalidInput, label + ": " + decoded.error().message);
            out.pixels = std::move(*decoded);
            if (options.generateMips) generateMips(out);
        }
        (void)where;
        const auto slot = static_cast<int32_t>(scene.images.size());
        scene.images.push_back(std::move(out));
        images[{index, srgb}] = slot;
        return slot;
    }

    static glm::mat3 uvTransform(glm::vec2 offset, float rotation, glm::vec2 scale) {
        // KHR_texture_transform: T * R * S, rows of R = (cos, sin), (-sin, cos).
        const float c = std::cos(rotation), s = std::sin(rotation);
        const glm::mat3 t(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
        const glm::mat3 r(glm::vec3(c, -s, 0), glm::vec3(s, c, 0), glm::vec3(0, 0, 1));
        const glm::mat3 sc(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
        return t * r * sc;
    }

    static double number(const tinygltf::Value& v, double def) { return v.IsNumber() ? v.GetNumberAsDouble() : def; }
    // A JSON number used as an index: -1 unless it is a whole number an int can hold.
    static int indexOf(const tinygltf::Value& v) {
        const double d = number(v, -1.0);
        return d >= 0.0 && d <= 2147483647.0 && std::floor(d) == d ? static_cast<int>(d) : -1;
    }

    Result<TextureRef> texture(const std::string& where, int index, int texCoord, const tinygltf::ExtensionMap& ext, bool srgb) {
        TextureRef ref;
        if (index < 0) return ref;
        if (size_t(index) >= model.textures.size())
            return error(ErrorCode::InvalidInput, where + ": texture " + std::to_string(index) + " does not exist (" +
                                                      std::to_string(model.textures.size()) + " textures)");
        const auto& tex = model.textures[size_t(index)];
        if (tex.source < 0) {
            warn(where + ": texture " + std::to_string(index) + " has no PNG/JPEG source; ignored");
            return ref;
        }
        if (size_t(tex.source) >= model.images.size())
            return error(ErrorCode::InvalidInput, where + ": texture " + std::to_string(index) + " names image " +
                                                      std::to_string(tex.source) + ", which does not exist");
        if (tex.sampler >= 0 && size_t(tex.sampler) >= samplers.size())
            return error(ErrorCode::InvalidInput, where + ": texture " + std::to_string(index) + " names sampler " +
                                                      std::to_string(tex.sampler) + ", which does not exist");
        auto img = image(where, tex.source, srgb);
        if (!img) return std::unexpected(img.error());
        ref.image = *img;
        ref.sampler = tex.sampler >= 0 ? samplers[size_t(tex.sampler)] : -1;
        int coord = texCoord;
        if (auto it = ext.find("KHR_texture_transform"); it != ext.end() && it->second.IsObject()) {
            const auto& t = it->second;
            glm::vec2 offset(0.0f), scale(1.0f);
            if (t.Has("offset") && t.Get("offset").IsArray() && t.Get("offset").ArrayLen() == 2)
                offset = glm::vec2(float(number(t.Get("offset").Get(0), 0)), float(number(t.Get("offset").Get(1), 0)));
            if (t.Has("scale") && t.Get("scale").IsArray() && t.Get("scale").ArrayLen() == 2)
                scale = glm::vec2(float(number(t.Get("scale").Get(0), 1)), float(number(t.Get("scale").Get(1), 1)));
            const float rotation = float(number(t.Get("rotation"), 0.0));
            ref.transform = uvTransform(offset, rotation, scale);
            if (t.Has("texCoord")) coord = indexOf(t.Get("texCoord"));
        }
        if (coord < 0 || coord > 1) {
            warn(where + ": texCoord " + std::to_string(coord) + " is not supported (TEXCOORD_0 and _1 only); using TEXCOORD_0");
            coord = 0;
        }
        ref.texCoord = static_cast<uint32_t>(coord);
        return ref;
    }

    static glm::vec3 vec3Of(const std::vector<double>& v, glm::vec3 def) {
        return v.size() >= 3 ? glm::vec3(float(v[0]), float(v[1]), float(v[2])) : def;
    }
    static glm::vec3 vec3Of(const tinygltf::Value& v, glm::vec3 def) {
        if (!v.IsArray() || v.ArrayLen() != 3) return def;
        return glm::vec3(float(number(v.Get(0), def.x)), float(number(v.Get(1), def.y)), float(number(v.Get(2), def.z)));
    }

    // A tinygltf JSON value -> Value (for material params written by exportGlb).
    static Value toValue(const tinygltf::Value& v) {
        if (v.IsBool()) return Value(v.Get<bool>());
        if (v.IsNumber()) return Value(v.GetNumberAsDouble());
        if (v.IsString()) return Value(v.Get<std::string>());
        if (v.IsArray()) {
            Value::List l;
            for (size_t i = 0; i < v.ArrayLen(); ++i) l.push_back(toValue(v.Get(int(i))));
            return Value(l);
        }
        if (v.IsObject()) {
            Value::Table t;
            for (const auto& k : v.Keys()) t[k] = toValue(v.Get(k));
            return Value(t);
        }
        return Value();
    }

    Result<void> materials() {
        for (size_t i = 0; i < model.materials.size(); ++i) {
            const auto& src = model.materials[i];
            const std::string where = named("material", i, src.name);
            Material m;
            m.name = src.name.empty() ? "material " + std::to_string(i) : src.name;
            const auto& pbr = src.pbrMetallicRoughness;
            if (pbr.baseColorFactor.size() != 4)
                return error(ErrorCode::InvalidInput, where + ": baseColorFactor has " + std::to_string(pbr.baseColorFactor.size()) +
                                                          " values, expected 4");
            glm::vec4 base;
            for (int k = 0; k < 4; ++k) {
                auto r = ranged(where + ": baseColorFactor[" + std::to_string(k) + "]", pbr.baseColorFactor[size_t(k)], 0, 1);
                if (!r) return std::unexpected(r.error());
                base[k] = *r;
            }
            m.baseColor = glm::vec3(base);
            m.opacity = base.a;
            float roughness = 1.0f, strength = 1.0f;
            RG_TRY(m.metalMask, ranged(where + ": metallicFactor", pbr.metallicFactor, 0, 1));
            RG_TRY(roughness, ranged(where + ": roughnessFactor", pbr.roughnessFactor, 0, 1));
            m.smoothness = 1.0f - roughness;  // glTF roughness is perceptual (DESIGN.md §5)
            m.reflectance = 0.5f;             // f0 = 4 %; KHR_materials_specular / _ior are ignored
            if (auto it = src.extensions.find("KHR_materials_emissive_strength"); it != src.extensions.end())
                RG_TRY(strength, ranged(where + ": emissiveStrength", number(it->second.Get("emissiveStrength"), 1.0), 0, HUGE_VAL));
            glm::vec3 emissive;
            RG_TRY(emissive, ranged3(where + ": emissiveFactor", src.emissiveFactor, glm::vec3(0.0f), 0, 1));
            // Read as nits (see Material::emissive).
            m.emissive = emissive * strength;
            auto tex = [&](const char* what, int index, int texCoord, const tinygltf::ExtensionMap& ext, bool srgb,
                           TextureRef& out) -> Result<void> {
                auto r = texture(where + " " + what, index, texCoord, ext, srgb);
                if (!r) return std::unexpected(r.error());
                out = *r;
                return {};
            };
            if (auto r = tex("baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                             pbr.baseColorTexture.extensions, true, m.baseColorTex); !r)
                return r;
            if (auto r = tex("metallicRoughnessTexture", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                             pbr.metallicRoughnessTexture.extensions, false, m.metallicRoughnessTex); !r)
                return r;
            if (auto r = tex("normalTexture", src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions, false,
                             m.normalTex); !r)
                return r;
            if (auto r = tex("occlusionTexture", src.occlusionTexture.index, src.occlusionTexture.texCoord,
                             src.occlusionTexture.extensions, false, m.occlusionTex); !r)
                return r;
            if (auto r = tex("emissiveTexture", src.emissiveTexture.index, src.emissiveTexture.texCoord, src.emissiveTexture.extensions,
                             true, m.emissiveTex); !r)
                return r;
            RG_TRY(m.normalScale, ranged(where + ": normalTexture.scale", src.normalTexture.scale, -1e6, 1e6));
            RG_TRY(m.occlusionStrength, ranged(where + ": occlusionTexture.strength", src.occlusionTexture.strength, 0, 1));
            if (src.alphaMode == "OPAQUE" || src.alphaMode.empty()) m.alphaMode = AlphaMode::Opaque;
            else if (src.alphaMode == "MASK") m.alphaMode = AlphaMode::Mask;
            else if (src.alphaMode == "BLEND") m.alphaMode = AlphaMode::Blend;
            else
                return error(ErrorCode::InvalidInput, where + ": alphaMode '" + src.alphaMode + "', expected OPAQUE, MASK or BLEND");
            RG_TRY(m.alphaCutoff, ranged(where + ": alphaCutoff", src.alphaCutoff, 0, HUGE_VAL));
            m.doubleSided = src.doubleSided;
            // What glTF cannot say, as exportGlb wrote it.
            if (src.extras.IsObject() && src.extras.Has("rgraph") && src.extras.Get("rgraph").IsObject()) {
                const auto& x = src.extras.Get("rgraph");
                if (x.Get("model").IsString()) m.model = x.Get("model").Get<std::string>();
                m.reflectance = float(number(x.Get("reflectance"), m.reflectance));
                m.ao = float(number(x.Get("ao"), m.ao));
                m.diffuseColor = vec3Of(x.Get("diffuse_color"), m.diffuseColor);
                m.f0 = vec3Of(x.Get("f0"), m.f0);
                if (x.Has("params")) m.extra = toValue(x.Get("params"));
            }
            scene.materials.push_back(std::move(m));
        }
        return {};
    }

    // ---- nodes, cameras, lights -------------------------------------------------------------

    Result<glm::mat4> localTransform(size_t index) {
        const auto& n = model.nodes[index];
        const std::string where = named("node", index, n.name);
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16)
                return error(ErrorCode::InvalidInput, where + ": matrix has " + std::to_string(n.matrix.size()) + " values, expected 16");
            glm::mat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) {
                    auto v = ranged(where + ": matrix[" + std::to_string(c * 4 + r) + "]", n.matrix[size_t(c * 4 + r)], -1e30, 1e30);
                    if (!v) return std::unexpected(v.error());
                    m[c][r] = *v;  // column-major, as glm
                }
            return m;
        }
        auto sized = [&](const std::vector<double>& v, size_t want, const char* what) -> Result<void> {
            if (!v.empty() && v.size() != want)
                return error(ErrorCode::InvalidInput, where + ": " + what + " has " + std::to_string(v.size()) + " values, expected " +
                                                          std::to_string(want));
            return {};
        };
        if (auto r = sized(n.translation, 3, "translation"); !r) return std::unexpected(r.error());
        if (auto r = sized(n.rotation, 4, "rotation"); !r) return std::unexpected(r.error());
        if (auto r = sized(n.scale, 3, "scale"); !r) return std::unexpected(r.error());
        glm::vec3 t, s;
        RG_TRY(t, ranged3(where + ": translation", n.translation, glm::vec3(0.0f), -1e30, 1e30));
        RG_TRY(s, ranged3(where + ": scale", n.scale, glm::vec3(1.0f), -1e30, 1e30));
        glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);  // glm::quat(w, x, y, z); glTF stores x, y, z, w
        if (n.rotation.size() == 4) {
            glm::vec4 r;
            for (int k = 0; k < 4; ++k) RG_TRY(r[k], ranged(where + ": rotation[" + std::to_string(k) + "]", n.rotation[size_t(k)], -1, 1));
            if (glm::length(r) < 1e-6f) return error(ErrorCode::InvalidInput, where + ": rotation is not a unit quaternion (it is zero)");
            q = glm::normalize(glm::quat(r.w, r.x, r.y, r.z));
        }
        return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(q) * glm::scale(glm::mat4(1.0f), s);
    }

    Result<void> camera(size_t nodeIndex, const glm::mat4& world) {
        const auto& n = model.nodes[nodeIndex];
        if (size_t(n.camera) >= model.cameras.size())
            return error(ErrorCode::InvalidInput, named("node", nodeIndex, n.name) + ": camera " + std::to_string(n.camera) + " does not exist");
        const auto& c = model.cameras[size_t(n.camera)];
        Camera cam;
        cam.name = !c.name.empty() ? c.name : !n.name.empty() ? n.name : "camera " + std::to_string(n.camera);
        const std::string where = named("camera", size_t(n.camera), c.name);
        if (c.type == "orthographic") {
            // glTF: xmag, ymag are half the view's width and height in metres; rgraph keeps the
            // height and takes the width from the image's aspect.
            float ymag = 1.0f;
            RG_TRY(ymag, ranged(where + ": ymag", c.orthographic.ymag, 1e-9, 1e30));
            cam.orthographic = true;
            cam.orthoHeight = 2.0f * ymag;
            RG_TRY(cam.nearPlane, ranged(where + ": znear", c.orthographic.znear, 0, 1e30));
            cam.nearPlane = std::max(cam.nearPlane, 1e-4f);
            RG_TRY(cam.farPlane, ranged(where + ": zfar", c.orthographic.zfar, c.orthographic.znear, 1e30));
            if (cam.farPlane <= cam.nearPlane) return error(ErrorCode::InvalidInput, where + ": zfar must lie beyond znear");
        } else if (c.type == "perspective") {
            RG_TRY(cam.verticalFov, ranged(where + ": yfov", c.perspective.yfov, 1e-6, 3.14159));
            RG_TRY(cam.nearPlane, ranged(where + ": znear", c.perspective.znear, 1e-9, 1e30));
            // glTF: no zfar means an infinite projection; we keep the finite default.
            if (c.perspective.zfar > 0) RG_TRY(cam.farPlane, ranged(where + ": zfar", c.perspective.zfar, c.perspective.znear, 1e30));
        } else {
            return error(ErrorCode::InvalidInput, where + ": unknown camera type '" + c.type + "' (glTF has 'perspective' and 'orthographic')");
        }
        cam.position = glm::vec3(world[3]);
        cam.target = cam.position + glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
        cam.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
        if (c.extras.IsObject() && c.extras.Get("rgraph").IsObject()) {
            const auto& x = c.extras.Get("rgraph");
            cam.aperture = float(number(x.Get("aperture"), cam.aperture));
            cam.shutter = float(number(x.Get("shutter"), cam.shutter));
            cam.iso = float(number(x.Get("iso"), cam.iso));
            cam.exposureCompensation = float(number(x.Get("ec"), cam.exposureCompensation));
            cam.focalLength = float(number(x.Get("focal_length"), cam.focalLength));
            cam.sensorHeight = float(number(x.Get("sensor_height"), cam.sensorHeight));
            // The exact target and up the scene had (the node only gives a direction).
            cam.target = vec3Of(x.Get("target"), cam.target);
            cam.up = vec3Of(x.Get("up"), cam.up);
        }
        scene.cameras.push_back(cam);
        return {};
    }

    Result<void> light(size_t nodeIndex, const glm::mat4& world) {
        const auto& n = model.nodes[nodeIndex];
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext == n.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light")) return {};
        const int li = indexOf(ext->second.Get("light"));
        if (li < 0 || size_t(li) >= model.lights.size())
            return error(ErrorCode::InvalidInput, named("node", nodeIndex, n.name) + ": KHR_lights_punctual light " +
                                                      (li < 0 ? "index is not a whole number >= 0" : std::to_string(li) + " does not exist (" +
                                                      std::to_string(model.lights.size()) + " lights)"));
        const auto& l = model.lights[size_t(li)];
        Light out;
        out.name = !l.name.empty() ? l.name : !n.name.empty() ? n.name : "light " + std::to_string(li);
        // KHR_lights_punctual: point and spot in candela, directional in lux.
        if (l.type == "point") out.type = LightType::Point, out.unit = "cd";
        else if (l.type == "spot") out.type = LightType::Spot, out.unit = "cd";
        else if (l.type == "directional") out.type = LightType::Directional, out.unit = "lux";
        else
            return error(ErrorCode::InvalidInput, named("light", size_t(li), l.name) + ": type '" + l.type +
                                                      "', expected point, spot or directional");
        const std::string where = named("light", size_t(li), l.name);
        RG_TRY(out.color, ranged3(where + ": color", l.color, glm::vec3(1.0f), 0, 1));
        RG_TRY(out.intensity, ranged(where + ": intensity", l.intensity, 0, HUGE_VAL));
        RG_TRY(out.range, ranged(where + ": range", l.range, 0, HUGE_VAL));
        if (out.type == LightType::Spot) {
            RG_TRY(out.outerAngle, ranged(where + ": spot.outerConeAngle", l.spot.outerConeAngle, 0, 1.5707964));
            RG_TRY(out.innerAngle, ranged(where + ": spot.innerConeAngle", l.spot.innerConeAngle, 0, l.spot.outerConeAngle));
        }
        out.position = glm::vec3(world[3]);
        out.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
        if (l.extras.IsObject() && l.extras.Get("rgraph").IsObject()) {
            const auto& x = l.extras.Get("rgraph");
            out.temperatureK = float(number(x.Get("temperature"), 0.0));
            if (x.Get("ies").IsString()) {
                auto file = extrasFile(x.Get("ies").Get<std::string>(), where + ": extras.rgraph.ies");
                if (!file) return std::unexpected(file.error());
                out.ies = *file;
            }
            if (x.Get("ies_mode").IsString()) {
                out.iesMode = x.Get("ies_mode").Get<std::string>();
                if (out.iesMode != "mask" && out.iesMode != "intensity")
                    return fail(ErrorCode::InvalidInput, where + ": extras.rgraph.ies_mode '" + out.iesMode + "' is not 'mask' or 'intensity'");
            }
            if (x.Get("exact_cone").IsBool()) out.exactCone = x.Get("exact_cone").Get<bool>();
            if (x.Get("shadow").IsBool()) out.castShadows = x.Get("shadow").Get<bool>() && out.type != LightType::Directional;
            out.sunAngularRadius = float(number(x.Get("angular_radius"), out.sunAngularRadius));
            // Written by exportGlb for a light declared in lumens (its cd is what rgraph renders).
            if (x.Get("lumens").IsNumber() && (out.type == LightType::Point || out.type == LightType::Spot)) {
                RG_TRY(out.intensity, ranged(where + ": extras.rgraph.lumens", number(x.Get("lumens"), 0.0), 0, HUGE_VAL));
                out.unit = "lm";
            }
        }
        scene.lights.push_back(out);
        return {};
    }

    // Each node once: glTF nodes have at most one parent, and a node reached twice (a shared
    // child, a cycle) would repeat or never end. Depth first with a stack of its own (not the
    // call stack: a hostile hierarchy thousands deep must not overflow it).
    Result<void> enter(size_t index, const glm::mat4& parent, std::vector<bool>& onPath, std::vector<bool>& seen, size_t depth, glm::mat4& world) {
        if (onPath[index]) return error(ErrorCode::InvalidInput, named("node", index, model.nodes[index].name) + " is its own ancestor (the node hierarchy has a cycle)");
        if (seen[index])
            return error(ErrorCode::InvalidInput, named("node", index, model.nodes[index].name) +
                                                      " appears twice in the hierarchy (a glTF node has one parent)");
        if (depth > kMaxDepth)
            return error(ErrorCode::InvalidInput, "the node hierarchy is deeper than " + std::to_string(kMaxDepth) + " levels");
        onPath[index] = seen[index] = true;
        const auto& n = model.nodes[index];
        auto local = localTransform(index);
        if (!local) return std::unexpected(local.error());
        world = parent * *local;
        if (n.mesh >= 0) {
            if (size_t(n.mesh) >= scene.meshes.size())
                return error(ErrorCode::InvalidInput, named("node", index, n.name) + ": mesh " + std::to_string(n.mesh) + " does not exist (" +
                                                          std::to_string(model.meshes.size()) + " meshes)");
            scene.nodes.push_back({n.name.empty() ? scene.meshes[size_t(n.mesh)].name : n.name, world, n.mesh});
        }
        if (n.camera >= 0)
            if (auto r = camera(index, world); !r) return r;
        return light(index, world);
    }
    Result<void> visit(size_t root, const glm::mat4& parent, std::vector<bool>& onPath, std::vector<bool>& seen, size_t depth) {
        struct Frame { size_t index; glm::mat4 world; size_t next; };
        std::vector<Frame> stack;
        glm::mat4 world;
        if (auto r = enter(root, parent, onPath, seen, depth, world); !r) return r;
        stack.push_back({root, world, 0});
        while (!stack.empty()) {
            Frame& f = stack.back();
            const auto& n = model.nodes[f.index];
            if (f.next == n.children.size()) {
                onPath[f.index] = false;
                stack.pop_back();
                continue;
            }
            const int child = n.children[f.next++];
            if (child < 0 || size_t(child) >= model.nodes.size())
                return error(ErrorCode::InvalidInput, named("node", f.index, n.name) + ": child " + std::to_string(child) + " does not exist (" +
                                                          std::to_string(model.nodes.size()) + " nodes)");
            const glm::mat4 parentWorld = f.world;
            if (auto r = enter(size_t(child), parentWorld, onPath, seen, depth + stack.size(), world); !r) return r;
            stack.push_back({size_t(child), world, 0});
        }
        return {};
    }

    // exportGlb keeps a scene's environment in the glTF scene's extras.
    Result<void> environment(const tinygltf::Value& extras) {
        if (!extras.IsObject() || !extras.Get("rgraph").IsObject() || !extras.Get("rgraph").Get("environment").IsObject()) return {};
        const auto& x = extras.Get("rgraph").Get("environment");
        Environment e;
        auto str = [&](const char* k, const std::string& def) { return x.Get(k).IsString() ? x.Get(k).Get<std::string>() : def; };
        e.name = str("name", e.name);
        e.kind = str("kind", e.kind);
        if (x.Get("file").IsString()) {
            auto file = extrasFile(x.Get("file").Get<std::string>(), "scene extras.rgraph.environment.file");
            if (!file) return std::unexpected(file.error());
            e.file = *file;
        }
        e.unit = str("unit", e.unit);
        e.color = vec3Of(x.Get("color"), e.color);
        e.intensity = float(number(x.Get("intensity"), e.intensity));
        e.rotation = float(number(x.Get("rotation"), e.rotation));
        e.turbidity = std::clamp(float(number(x.Get("turbidity"), e.turbidity)), 1.7f, 10.0f);
        scene.environment = e;
        return {};
    }

    Result<void> nodes() {
        std::vector<int> roots;
        if (!model.scenes.empty()) {
            const size_t s = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? size_t(model.defaultScene) : 0;
            roots = model.scenes[s].nodes;
            if (auto r = environment(model.scenes[s].extras); !r) return r;
        } else {
            std::vector<bool> child(model.nodes.size(), false);
            for (const auto& n : model.nodes)
                for (int c : n.children)
                    if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
            for (size_t i = 0; i < model.nodes.size(); ++i)
                if (!child[i]) roots.push_back(int(i));
        }
        std::vector<bool> onPath(model.nodes.size(), false), seen(model.nodes.size(), false);
        for (int r : roots) {
            if (r < 0 || size_t(r) >= model.nodes.size())
                return error(ErrorCode::InvalidInput, "scene root node " + std::to_string(r) + " does not exist (" +
                                                          std::to_string(model.nodes.size()) + " nodes)");
            if (auto v = visit(size_t(r), glm::mat4(1.0f), onPath, seen, 0); !v) return v;
        }
        return {};
    }

    Result<Scene> run() {
        if (auto r = parse(); !r) return std::unexpected(r.error());
        convertSamplers();
        if (auto r = materials(); !r) return std::unexpected(r.error());
        if (auto r = meshes(); !r) return std::unexpected(r.error());
        if (auto r = nodes(); !r) return std::unexpected(r.error());
        computeBounds(scene);
        return std::move(scene);
    }
};

}  // namespace

Result<Scene> loadGltf(const std::string& path, const GltfOptions& options) {
    Loader loader;
    loader.path = path;
    loader.options = options;
    return loader.run();
}

}  // namespace rg
