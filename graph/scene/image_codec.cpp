// PNG/JPEG decoding from memory and PNG encoding for glTF images, with stb_image and
// stb_image_write compiled *static* into this file only: graph/image/hdr_io.cpp already has a
// global stb_image (HDR decoder only), and static copies cannot clash with it.
#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/read_whole.h"
#include "scene.h"
#include "scene_detail.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace rg::scene_detail {

std::string errnoText(int err) {
    char buf[256];
    // GNU strerror_r returns the message (maybe not in buf).
    return strerror_r(err, buf, sizeof buf);
}

Result<std::vector<unsigned char>> readFile(const std::string& path) {
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int err = errno ? errno : ENOENT;
        return fail(err == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                    "cannot open " + quote(path) + ": " + errnoText(err));
    }
    std::vector<unsigned char> bytes;
    if (!readWhole(in, bytes))
        return fail(ErrorCode::Io,
                    "cannot read " + quote(path) + ": " + errnoText(errno ? errno : EIO));
    return bytes;
}

Result<Image> decodeImage(const unsigned char* data, size_t size) {
    if (size > size_t(INT32_MAX)) return fail(ErrorCode::InvalidInput, "image too large");
    const int len = static_cast<int>(size);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, len, &w, &h, &comp))
        return fail(ErrorCode::InvalidInput,
                    std::string("not a PNG or JPEG image (") + stbi_failure_reason() + ")");
    // Refuse decompression bombs before allocating: 16384 x 16384 is the largest 2D image a
    // Vulkan implementation must support.
    if (w > 16384 || h > 16384)
        return fail(ErrorCode::Unsupported, "image is " + std::to_string(w) + "x" +
                                                std::to_string(h) + ", larger than 16384x16384");
    const bool sixteen = stbi_is_16_bit_from_memory(data, len) != 0;
    void* pixels = sixteen
                       ? static_cast<void*>(stbi_load_16_from_memory(data, len, &w, &h, &comp, 4))
                       : static_cast<void*>(stbi_load_from_memory(data, len, &w, &h, &comp, 4));
    if (!pixels)
        return fail(ErrorCode::InvalidInput,
                    std::string("cannot decode (") + stbi_failure_reason() + ")");
    Image img(static_cast<uint32_t>(w), static_cast<uint32_t>(h), 4);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = sixteen ? float(static_cast<const uint16_t*>(pixels)[i]) / 65535.0f
                                : float(static_cast<const uint8_t*>(pixels)[i]) / 255.0f;
    stbi_image_free(pixels);
    return img;
}

Result<std::vector<unsigned char>> encodePng(const Image& image) {
    if (image.width == 0 || image.height == 0 || image.channels < 1 || image.channels > 4)
        return fail(ErrorCode::InvalidInput, "cannot encode a " + std::to_string(image.width) +
                                                 "x" + std::to_string(image.height) + "x" +
                                                 std::to_string(image.channels) + " image as PNG");
    std::vector<unsigned char> bytes(image.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        const float v = image.pixels[i];
        bytes[i] = static_cast<unsigned char>(
            std::lround((v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f) * 255.0f));
    }
    std::vector<unsigned char> out;
    auto sink = [](void* ctx, void* data, int size) {
        auto* o = static_cast<std::vector<unsigned char>*>(ctx);
        o->insert(o->end(), static_cast<unsigned char*>(data),
                  static_cast<unsigned char*>(data) + size);
    };
    const int ok =
        stbi_write_png_to_func(sink, &out, static_cast<int>(image.width),
                               static_cast<int>(image.height), static_cast<int>(image.channels),
                               bytes.data(), static_cast<int>(image.width * image.channels));
    if (!ok) return fail(ErrorCode::Io, "PNG encoding failed");
    return out;
}

Result<int32_t> textureFile(Scene& scene, const std::string& path, bool srgb) {
    for (size_t i = 0; i < scene.images.size(); ++i)
        if (scene.images[i].name == path && scene.images[i].srgb == srgb)
            return static_cast<int32_t>(i);
    auto bytes = readFile(path);
    if (!bytes) return std::unexpected(bytes.error());
    auto image = decodeImage(bytes->data(), bytes->size());
    if (!image)
        return fail(ErrorCode::InvalidInput,
                    "cannot decode " + quote(path) + ": " + image.error().message);
    SceneImage si;
    si.name = path;
    si.pixels = std::move(*image);
    si.srgb = srgb;
    scene.images.push_back(std::move(si));
    return static_cast<int32_t>(scene.images.size() - 1);
}

}  // namespace rg::scene_detail
