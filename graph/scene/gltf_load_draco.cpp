// KHR_draco_mesh_compression (Debian's libdraco-dev): a primitive whose attributes and indices are
// one Draco-compressed buffer view, decoded here with every index and count checked (a broken
// file is an error naming the primitive, never a crash).
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include "gltf_load_detail.h"
#include "tinygltf.h"

namespace rg::gltf_load {

namespace {
constexpr uint32_t kMaxDracoPoints = 1u << 24, kMaxDracoFaces = 1u << 26;
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
    const tinygltf::Value& attributes = ext.Get("attributes");
    if (!attributes.IsObject())
        return error(ErrorCode::InvalidInput, what + ".attributes: expected an object");
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
    return std::optional<Draco>(std::move(out));
}

}  // namespace rg::gltf_load
