// EXT_meshopt_compression (Debian's libmeshoptimizer-dev): buffer views whose bytes are
// meshoptimizer's vertex or index codec, decoded into their fallback buffer before any accessor
// reads them. Every count, stride, mode and filter is checked first: a broken file is an error
// naming the buffer view, never a crash or an allocation the file does not pay for.
#include <cmath>
#include <cstdint>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg::gltf_load {

namespace {

constexpr const char* kExt = "EXT_meshopt_compression";
// One placeholder byte: tinygltf needs data for a buffer without a uri; the real bytes are
// decoded into it afterwards (meshopt() below).
constexpr const char* kPlaceholder = "data:application/octet-stream;base64,AA==";
// The codecs cannot expand their input more than 64× (a vertex byte group of 16 bytes costs
// at least 2 bits; an index triangle at least a byte): a view claiming more is not honest.
constexpr uint64_t kMaxExpansion = 128, kMaxDecodedBytes = uint64_t(1) << 31;

}  // namespace

// A fallback buffer (EXT_meshopt_compression.fallback, no uri) holds nothing in the file: it
// becomes one placeholder byte for tinygltf and its length is kept to size the decoded data.
bool Loader::placeholdMeshoptFallbacks(nlohmann::json& j) {
    auto buffers = j.find("buffers");
    if (buffers == j.end() || !buffers->is_array()) return false;
    bool changed = false;
    for (size_t i = 0; i < buffers->size(); ++i) {
        auto& b = (*buffers)[i];
        if (!b.is_object() || b.contains("uri") || !b.contains("extensions") ||
            !b["extensions"].is_object() || !b["extensions"].contains(kExt))
            continue;
        const auto& ext = b["extensions"][kExt];
        if (!ext.is_object() || !ext.value("fallback", false)) continue;
        const auto len = b.find("byteLength");
        meshoptFallbacks[i] =
            len != b.end() && len->is_number_unsigned() ? len->get<uint64_t>() : uint64_t(0);
        b["uri"] = kPlaceholder;
        b["byteLength"] = 1;
        changed = true;
    }
    return changed;
}

Result<void> Loader::meshopt() {
    for (size_t v = 0; v < model.bufferViews.size(); ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        auto it = view.extensions.find(kExt);
        if (it == view.extensions.end()) continue;
        const std::string what = "buffer view " + std::to_string(v) + ": " + kExt;
        const tinygltf::Value& ext = it->second;
        if (!ext.IsObject()) return error(ErrorCode::InvalidInput, what + ": expected an object");
        // A fallback with real bytes (the file ships both) is read as it is.
        if (view.buffer < 0 || !meshoptFallbacks.count(size_t(view.buffer))) continue;
        auto whole = [&](const char* key, bool required) -> Result<uint64_t> {
            const tinygltf::Value& x = ext.Get(key);
            if (!required && !x.IsNumber()) return uint64_t(0);
            const double d = number(x, -1.0);
            if (!(d >= 0.0 && d <= 9.0e15 && std::floor(d) == d))
                return error(ErrorCode::InvalidInput,
                             what + "." + key + ": expected a whole number >= 0");
            return uint64_t(d);
        };
        uint64_t count = 0, stride = 0, offset = 0, length = 0;
        RG_TRY(count, whole("count", true));
        RG_TRY(stride, whole("byteStride", true));
        RG_TRY(offset, whole("byteOffset", false));
        RG_TRY(length, whole("byteLength", true));
        const int source = indexOf(ext.Get("buffer"));
        if (source < 0 || size_t(source) >= model.buffers.size())
            return error(ErrorCode::InvalidInput,
                         what + ".buffer: expected the index of one of the " +
                             std::to_string(model.buffers.size()) + " buffers");
        if (meshoptFallbacks.count(size_t(source)))
            return error(ErrorCode::InvalidInput,
                         what + ".buffer: buffer " + std::to_string(source) +
                             " is a fallback (it holds no bytes to decode)");
        const auto& src = model.buffers[size_t(source)].data;
        if (offset > src.size() || length > src.size() - offset)
            return error(ErrorCode::InvalidInput, what + ": bytes " + std::to_string(offset) +
                                                      ".." + std::to_string(offset + length) +
                                                      " are outside buffer " +
                                                      std::to_string(source) + " (" +
                                                      std::to_string(src.size()) + " bytes)");
        const std::string mode =
            ext.Get("mode").IsString() ? ext.Get("mode").Get<std::string>() : "";
        const std::string filter =
            ext.Get("filter").IsString() ? ext.Get("filter").Get<std::string>() : "NONE";
        if (mode == "ATTRIBUTES") {
            if (stride == 0 || stride % 4 != 0 || stride > 256)
                return error(ErrorCode::InvalidInput,
                             what + ".byteStride: " + std::to_string(stride) +
                                 " (ATTRIBUTES: a multiple of 4, at most 256)");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4)
                return error(
                    ErrorCode::InvalidInput,
                    what + ".byteStride: " + std::to_string(stride) + " (" + mode + ": 2 or 4)");
            if (mode == "TRIANGLES" && count % 3 != 0)
                return error(ErrorCode::InvalidInput, what + ".count: " + std::to_string(count) +
                                                          " is not a whole number of triangles");
        } else {
            return error(ErrorCode::InvalidInput,
                         what + ".mode: '" + mode + "', expected ATTRIBUTES, TRIANGLES or INDICES");
        }
        if (filter != "NONE" && mode != "ATTRIBUTES")
            return error(ErrorCode::InvalidInput,
                         what + ".filter: " + filter + " applies to ATTRIBUTES only");
        if ((filter == "OCTAHEDRAL" && stride != 4 && stride != 8) ||
            (filter == "QUATERNION" && stride != 8))
            return error(ErrorCode::InvalidInput, what + ".filter: " + filter +
                                                      " with byteStride " + std::to_string(stride));
        if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" &&
            filter != "EXPONENTIAL")
            return error(ErrorCode::InvalidInput,
                         what + ".filter: '" + filter +
                             "', expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
        const uint64_t bytes = count * stride;  // both below 2^53 and 2^9: no overflow
        if (bytes > kMaxDecodedBytes || bytes > kMaxExpansion * length + 4096)
            return error(ErrorCode::InvalidInput, what + ": " + std::to_string(count) +
                                                      " elements of " + std::to_string(stride) +
                                                      " bytes cannot come from " +
                                                      std::to_string(length) + " compressed bytes");
        if (view.byteOffset > SIZE_MAX - bytes || bytes > view.byteLength)
            return error(ErrorCode::InvalidInput, what + ": decodes to " + std::to_string(bytes) +
                                                      " bytes, more than the view's byteLength " +
                                                      std::to_string(view.byteLength));
        // The buffer's declared length is the file's word: what is allocated stays within what a
        // view may decode.
        if (view.byteOffset + bytes > kMaxDecodedBytes)
            return error(ErrorCode::InvalidInput, what + ": the view ends at byte " +
                                                      std::to_string(view.byteOffset + bytes) +
                                                      " of its fallback buffer (at most " +
                                                      std::to_string(kMaxDecodedBytes) + ")");
        const uint64_t declared = meshoptFallbacks[size_t(view.buffer)];
        if (view.byteOffset + bytes > declared)
            return error(ErrorCode::InvalidInput, what + ": the view ends at byte " +
                                                      std::to_string(view.byteOffset + bytes) +
                                                      ", beyond its buffer's " +
                                                      std::to_string(declared) + " bytes");
        auto& dst = model.buffers[size_t(view.buffer)].data;
        if (dst.size() < view.byteOffset + bytes) dst.resize(view.byteOffset + bytes, 0);
        unsigned char* out = dst.data() + view.byteOffset;
        const unsigned char* in = src.data() + offset;
        int rc = 0;
        if (mode == "ATTRIBUTES")
            rc = meshopt_decodeVertexBuffer(out, count, stride, in, length);
        else if (mode == "TRIANGLES")
            rc = meshopt_decodeIndexBuffer(out, count, stride, in, length);
        else
            rc = meshopt_decodeIndexSequence(out, count, stride, in, length);
        if (rc != 0) {
            // The first byte names the codec's version (low 4 bits): a newer meshoptimizer may
            // have written one this library does not know.
            const bool newer = length > 0 && mode == "ATTRIBUTES" && (in[0] & 0x0f) > 0;
            return error(ErrorCode::InvalidInput,
                         what + ": the " + mode + " data does not decode (meshoptimizer " +
                             std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." +
                             std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10) + ": " +
                             (newer ? "vertex codec version " + std::to_string(in[0] & 0x0f) +
                                          " is newer than it reads"
                                    : "error " + std::to_string(rc)) +
                             ")");
        }
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out, count, stride);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(out, count, stride);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out, count, stride);
    }
    return {};
}

}  // namespace rg::gltf_load
