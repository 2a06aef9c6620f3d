// Internal to rg_scene: what the glTF reader, the writer and the Lua scene builder share.
// Not a public header.
#pragma once

#include <string>
#include <vector>

#include "scene.h"

// `lhs = value of expr`, or return its error: several checks in a row in the loaders.
#define RG_TRY(lhs, expr)                                      \
    do {                                                       \
        auto rg_try_ = (expr);                                 \
        if (!rg_try_) return std::unexpected(rg_try_.error()); \
        lhs = std::move(*rg_try_);                             \
    } while (0)

namespace rg {
struct Scene;
}

namespace rg::scene_detail {

// Decodes a PNG or JPEG held in memory into four float channels in [0, 1] (8-bit samples / 255,
// 16-bit / 65535), no colour conversion. The error message is the decoder's reason.
Result<Image> decodeImage(const unsigned char* data, size_t size);

// Encodes 1-4 channel values in [0, 1] as an 8-bit PNG (round(clamp(v) * 255)).
Result<std::vector<unsigned char>> encodePng(const Image& image);

// "'path'", how messages of this module name a file.
inline std::string quote(const std::string& path) { return "'" + path + "'"; }

// The OS's text for errno (thread-safe).
std::string errnoText(int err);

// The whole file, or NotFound/Io "cannot open 'path': reason" (`path` as given).
Result<std::vector<unsigned char>> readFile(const std::string& path);

// A material's texture file in scene.images, decoded once per file and encoding (`path` as
// given, the image's name; mips are the caller's): its index, or readFile's error, or "cannot
// decode 'path': reason".
Result<int32_t> textureFile(Scene& scene, const std::string& path, bool srgb);

}  // namespace rg::scene_detail
