// KHR_draco_mesh_compression (Debian's libdraco-dev): a primitive whose attributes and indices are
// one Draco-compressed buffer view, decoded here with every index and count checked (a broken
// file is an error naming the primitive, never a crash). Decoding costs ~6× reading what it
// decodes to (a 1 M-triangle mesh: ~130 ms against ~20 ms for its 22 MB), so the decoded
// primitive is kept in a file by the content hash of what was decoded (setGltfDecodeCacheDir).
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "core/hash.h"
#include "core/temp_path.h"
#include "gltf_load_detail.h"
#include "tinygltf.h"

namespace rg {

namespace {

struct DecodeCacheDir {
    std::mutex mutex;
    std::string dir;
};
DecodeCacheDir& decodeCacheDir() {
    static DecodeCacheDir d;
    return d;
}

}  // namespace

void setGltfDecodeCacheDir(std::string dir) {
    std::lock_guard lock(decodeCacheDir().mutex);
    decodeCacheDir().dir = std::move(dir);
}

namespace gltf_load {

namespace {

constexpr uint32_t kMaxDracoPoints = 1u << 24, kMaxDracoFaces = 1u << 26;

// A decoded primitive's file: "RGDRC1", points, index count, the indices, attribute count, then
// per attribute its name's length and name, components and values. Read back only when every
// count is within the decoder's bounds and the file holds exactly that much.
constexpr char kDecodedMagic[6] = {'R', 'G', 'D', 'R', 'C', '1'};

bool readDecoded(const std::string& file, Loader::Draco& out) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    auto u32 = [&](uint32_t& v) { return bool(in.read(reinterpret_cast<char*>(&v), 4)); };
    char magic[6] = {};
    uint32_t points = 0, count = 0, attributes = 0;
    if (!in.read(magic, 6) || std::memcmp(magic, kDecodedMagic, 6) != 0 || !u32(points) ||
        !u32(count) || points > kMaxDracoPoints || count > 3ull * kMaxDracoFaces || count % 3)
        return false;
    Loader::Draco d;
    d.points = points;
    d.indices.resize(count);
    if (!in.read(reinterpret_cast<char*>(d.indices.data()), std::streamsize(count) * 4) ||
        !u32(attributes) || attributes > 64)
        return false;
    for (uint32_t i : d.indices)
        if (i >= points) return false;
    for (uint32_t a = 0; a < attributes; ++a) {
        uint32_t length = 0, components = 0;
        if (!u32(length) || length > 256) return false;
        std::string name(length, '\0');
        if (!in.read(name.data(), length) || !u32(components) || components < 1 || components > 4)
            return false;
        std::vector<float>& values = d.attributes[name];
        values.resize(size_t(points) * components);
        if (!in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size()) * 4))
            return false;
        d.components[name] = int(components);
    }
    if (in.peek() != std::char_traits<char>::eof()) return false;  // more than it says: not ours
    out = std::move(d);
    return true;
}

// Written to a temporary file and renamed, so a reader never sees half of one; a failure leaves
// no file (the next load decodes again).
void writeDecoded(const std::string& file, const Loader::Draco& d) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
    const std::string tmp = tempPathBeside(file);
    {
        std::ofstream out(tmp, std::ios::binary);
        auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
        out.write(kDecodedMagic, 6);
        u32(d.points);
        u32(uint32_t(d.indices.size()));
        out.write(reinterpret_cast<const char*>(d.indices.data()),
                  std::streamsize(d.indices.size()) * 4);
        u32(uint32_t(d.attributes.size()));
        for (const auto& [name, values] : d.attributes) {
            u32(uint32_t(name.size()));
            out.write(name.data(), std::streamsize(name.size()));
            u32(uint32_t(d.components.at(name)));
            out.write(reinterpret_cast<const char*>(values.data()),
                      std::streamsize(values.size()) * 4);
        }
        if (!out) {
            std::filesystem::remove(tmp, ec);
            return;
        }
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace

Result<std::optional<Loader::Draco>> Loader::draco(const std::string& where,
                                                   const tinygltf::Primitive& prim) {
    auto it = prim.extensions.find("KHR_draco_mesh_compression");
    if (it == prim.extensions.end()) return std::optional<Draco>();
    const std::string what = where + ": KHR_draco_mesh_compression";
    const tinygltf::Value& ext = it->second;
    if (prim.mode != TINYGLTF_MODE_TRIANGLES)
        return error(ErrorCode::InvalidInput, what + ": compresses triangle lists only (mode " +
                                                  std::to_string(prim.mode) + ")");
    const int view = indexOf(ext.Get("bufferView"));
    if (view < 0 || size_t(view) >= model.bufferViews.size())
        return error(ErrorCode::InvalidInput,
                     what + ".bufferView: expected the index of one of the " +
                         std::to_string(model.bufferViews.size()) + " buffer views");
    const size_t bytes = model.bufferViews[size_t(view)].byteLength;
    auto data = viewRange(what, view, 0, bytes, 1, /*allowStride=*/false);
    if (!data) return std::unexpected(data.error());
    const tinygltf::Value& attributes = ext.Get("attributes");
    if (!attributes.IsObject())
        return error(ErrorCode::InvalidInput, what + ".attributes: expected an object");
    // The cache's key: the compressed bytes and the attributes asked for by id.
    std::string file;
    {
        std::lock_guard lock(decodeCacheDir().mutex);
        file = decodeCacheDir().dir;
    }
    if (!file.empty()) {
        ContentHash key;
        key.str("KHR_draco_mesh_compression 1");
        key.bytes(data->data, bytes);
        for (const std::string& semantic : attributes.Keys()) {
            key.str(semantic);
            key.u64(static_cast<uint64_t>(static_cast<int64_t>(indexOf(attributes.Get(semantic)))));
        }
        file += "/" + key.hex() + ".draco";
        Draco cached;
        if (readDecoded(file, cached)) return std::optional<Draco>(std::move(cached));
    }
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data->data), bytes);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        return error(ErrorCode::InvalidInput, what + ": the buffer view does not decode (" +
                                                  decoded.status().error_msg_string() + ")");
    const draco::Mesh& mesh = *decoded.value();
    if (mesh.num_points() > kMaxDracoPoints || mesh.num_faces() > kMaxDracoFaces)
        return error(ErrorCode::InvalidInput, what + ": " + std::to_string(mesh.num_points()) +
                                                  " points, " + std::to_string(mesh.num_faces()) +
                                                  " faces");
    Draco out;
    for (const std::string& semantic : attributes.Keys()) {
        const int id = indexOf(attributes.Get(semantic));
        const draco::PointAttribute* a = id < 0 ? nullptr : mesh.GetAttributeByUniqueId(id);
        if (!a)
            return error(ErrorCode::InvalidInput, what + ".attributes." + semantic +
                                                      ": no attribute of that id in the mesh");
        const int components = a->num_components();
        if (components < 1 || components > 4)
            return error(ErrorCode::InvalidInput, what + ".attributes." + semantic + ": " +
                                                      std::to_string(components) + " components");
        std::vector<float> values(size_t(mesh.num_points()) * size_t(components));
        for (draco::PointIndex i(0); i < mesh.num_points(); ++i)
            if (!a->ConvertValue<float>(a->mapped_index(i), static_cast<int8_t>(components),
                                        &values[size_t(i.value()) * size_t(components)]))
                return error(ErrorCode::InvalidInput,
                             what + ".attributes." + semantic + ": a value does not convert");
        out.components[semantic] = components;
        out.attributes[semantic] = std::move(values);
    }
    out.indices.reserve(size_t(mesh.num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) out.indices.push_back(mesh.face(f)[k].value());
    out.points = mesh.num_points();
    if (!file.empty()) writeDecoded(file, out);
    return std::optional<Draco>(std::move(out));
}

}  // namespace gltf_load

}  // namespace rg
