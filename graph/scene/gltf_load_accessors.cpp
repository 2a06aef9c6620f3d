// glTF accessors: the bytes of a buffer view, bounds-checked against the view and its buffer
// before any read, as floats (normalised integers, sparse substitution) or as vertex indices.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg {

using namespace scene_detail;

namespace gltf_load {

namespace {

const char* componentName(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return "DOUBLE";
        default:
            return "?";
    }
}

int componentBytes(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "?";
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
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? float(p[0]) / 255.0f : float(p[0]);
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
        default:
            return 0.0f;
    }
}

uint32_t readIndex(const unsigned char* p, int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return p[0];
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

}  // namespace

// Bounds of `count` elements of `elementSize` bytes at `offset` of a buffer view, stride
// from the view; checked against the view and the view against its buffer.
Result<Loader::View> Loader::viewRange(const std::string& what, int viewIndex, size_t offset,
                                       size_t count, size_t elementSize, bool allowStride) {
    if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
        return error(ErrorCode::InvalidInput,
                     what + ": buffer view " + std::to_string(viewIndex) + " does not exist (" +
                         std::to_string(model.bufferViews.size()) + " buffer views)");
    const auto& view = model.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) +
                                                  " names buffer " + std::to_string(view.buffer) +
                                                  ", which does not exist");
    const size_t bufferSize = model.buffers[size_t(view.buffer)].data.size();
    if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset)
        return error(ErrorCode::InvalidInput,
                     what + ": buffer view " + std::to_string(viewIndex) + " (bytes " +
                         std::to_string(view.byteOffset) + ".." +
                         std::to_string(view.byteOffset + view.byteLength) +
                         ") is outside buffer " + std::to_string(view.buffer) + " (" +
                         std::to_string(bufferSize) + " bytes)");
    const size_t stride = allowStride && view.byteStride ? view.byteStride : elementSize;
    if (stride < elementSize)
        return error(ErrorCode::InvalidInput, what + ": buffer view " + std::to_string(viewIndex) +
                                                  " has byteStride " + std::to_string(stride) +
                                                  ", less than the element size " +
                                                  std::to_string(elementSize));
    if (count > 0) {
        // 128-bit: offset and count come from the file and may be anything.
        const unsigned __int128 wide =
            (unsigned __int128)offset + (unsigned __int128)stride * (count - 1) + elementSize;
        const uint64_t end = wide > UINT64_MAX ? UINT64_MAX : static_cast<uint64_t>(wide);
        if (wide > view.byteLength)
            return error(ErrorCode::InvalidInput, what + " is out of range: it reads bytes " +
                                                      std::to_string(offset) + ".." +
                                                      std::to_string(end) + " of buffer view " +
                                                      std::to_string(viewIndex) + ", which has " +
                                                      std::to_string(view.byteLength) + " bytes");
    }
    return View{model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + offset, stride};
}

Result<const tinygltf::Accessor*> Loader::accessor(const std::string& what, int index) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        return error(ErrorCode::InvalidInput,
                     what + ": accessor " + std::to_string(index) + " does not exist (" +
                         std::to_string(model.accessors.size()) + " accessors)");
    return &model.accessors[size_t(index)];
}

// The accessor's elements as floats, `components` per element (sparse substitution applied).
Result<std::vector<float>> Loader::readFloats(const std::string& where, const std::string& semantic,
                                              int index, int type) {
    const std::string what = where + ": " + semantic + ": accessor " + std::to_string(index);
    auto acc = accessor(where + ": " + semantic, index);
    if (!acc) return std::unexpected(acc.error());
    const tinygltf::Accessor& a = **acc;
    if (a.type != type)
        return error(ErrorCode::InvalidInput,
                     what + " is " + typeName(a.type) + ", expected " + typeName(type));
    const int cbytes = componentBytes(a.componentType);
    if (cbytes == 0)
        return error(ErrorCode::InvalidInput, what + " has component type " +
                                                  componentName(a.componentType) +
                                                  ", which glTF vertex data cannot have");
    const size_t comps = size_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
    // Without a buffer view the elements are zeros (then maybe sparse); cap what that allocates.
    if (a.bufferView < 0 && a.count > (size_t(1) << 24))
        return error(ErrorCode::InvalidInput,
                     what + " has " + std::to_string(a.count) +
                         " elements and no buffer view (at most 16777216)");
    std::vector<float> out;
    if (a.bufferView >= 0) {
        auto v = viewRange(what, a.bufferView, a.byteOffset, a.count, comps * size_t(cbytes),
                           /*allowStride=*/true);
        if (!v) return std::unexpected(v.error());
        out.assign(a.count * comps, 0.0f);
        for (size_t i = 0; i < a.count; ++i)
            for (size_t c = 0; c < comps; ++c)
                out[i * comps + c] = readComponent(v->data + i * v->stride + c * size_t(cbytes),
                                                   a.componentType, a.normalized);
    } else
        out.assign(a.count * comps, 0.0f);
    if (a.sparse.isSparse) {
        const auto& sp = a.sparse;
        if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0 || sp.count < 0)
            return error(ErrorCode::InvalidInput, what + ": negative sparse count or byteOffset");
        const size_t n = size_t(std::max(sp.count, 0));
        const int itype = sp.indices.componentType;
        if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            return error(ErrorCode::InvalidInput,
                         what + ": sparse indices have component type " + componentName(itype));
        auto iv = viewRange(what + " (sparse indices)", sp.indices.bufferView,
                            size_t(sp.indices.byteOffset), n, size_t(componentBytes(itype)), false);
        if (!iv) return std::unexpected(iv.error());
        auto vv = viewRange(what + " (sparse values)", sp.values.bufferView,
                            size_t(sp.values.byteOffset), n, comps * size_t(cbytes), false);
        if (!vv) return std::unexpected(vv.error());
        for (size_t k = 0; k < n; ++k) {
            const uint32_t target = readIndex(iv->data + k * iv->stride, itype);
            if (target >= a.count)
                return error(ErrorCode::InvalidInput,
                             what + ": sparse index " + std::to_string(target) +
                                 " is out of range (" + std::to_string(a.count) + " elements)");
            for (size_t c = 0; c < comps; ++c)
                out[target * comps + c] = readComponent(
                    vv->data + k * vv->stride + c * size_t(cbytes), a.componentType, a.normalized);
        }
    }
    for (float f : out)
        if (!std::isfinite(f))
            return error(ErrorCode::InvalidInput, what + " holds a NaN or infinite value");
    return out;
}

Result<std::vector<uint32_t>> Loader::readIndices(const std::string& where, int index,
                                                  size_t vertexCount) {
    const std::string what = where + ": indices: accessor " + std::to_string(index);
    auto acc = accessor(where + ": indices", index);
    if (!acc) return std::unexpected(acc.error());
    const tinygltf::Accessor& a = **acc;
    const int ct = a.componentType;
    if (a.type != TINYGLTF_TYPE_SCALAR)
        return error(ErrorCode::InvalidInput,
                     what + " is " + typeName(a.type) + ", expected SCALAR");
    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        return error(ErrorCode::InvalidInput,
                     what + " has component type " + componentName(ct) +
                         ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (a.sparse.isSparse)
        return error(ErrorCode::Unsupported, what + ": sparse index accessors are not supported");
    if (a.bufferView < 0) return error(ErrorCode::InvalidInput, what + " has no buffer view");
    auto v = viewRange(what, a.bufferView, a.byteOffset, a.count, size_t(componentBytes(ct)),
                       /*allowStride=*/false);
    if (!v) return std::unexpected(v.error());
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
        out[i] = readIndex(v->data + i * v->stride, ct);
        if (out[i] >= vertexCount)
            return error(ErrorCode::InvalidInput, what + ": index " + std::to_string(out[i]) +
                                                      " (element " + std::to_string(i) +
                                                      ") is out of range: the primitive has " +
                                                      std::to_string(vertexCount) + " vertices");
    }
    return out;
}

}  // namespace gltf_load

}  // namespace rg
