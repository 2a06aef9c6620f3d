// Radiance RGBE through stb_image. Only its HDR decoder is compiled in, reading from memory, so
// the file is opened (and its OS errors reported) by readWholeFile like every other format.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

#include <algorithm>
#include <climits>
#include <memory>

#include "image/file_io.h"
#include "image/image.h"

namespace rg {

using image_detail::quoted;

namespace {

// stb's reason for the last failure on this thread (thread-local in stb_image >= 2.26).
std::string failureReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown error";
}

}  // namespace

Result<Image> readHdr(const std::string& path) {
    auto data = image_detail::readWholeFile(path);
    if (!data) return std::unexpected(data.error());
    const std::string file = quoted(path);
    if (data->size() > size_t(INT_MAX))
        return fail(ErrorCode::Unsupported, file + ": file is larger than 2 GiB");
    const auto* bytes = reinterpret_cast<const stbi_uc*>(data->data());
    const int size = int(data->size());
    if (!stbi_is_hdr_from_memory(bytes, size))
        return fail(ErrorCode::InvalidInput, file + ": not a Radiance HDR file");

    int width = 0, height = 0, fileChannels = 0;
    // stb's header check gives no reason of its own, so the message says what a header needs.
    if (!stbi_info_from_memory(bytes, size, &width, &height, &fileChannels))
        return fail(ErrorCode::InvalidInput,
                    file + ": invalid Radiance HDR file: bad header (expected "
                           "FORMAT=32-bit_rle_rgbe and a '-Y <height> +X <width>' line)");
    // Radiance run-length encoding packs at most 127 values of one component into 2 bytes, i.e.
    // under 16 pixels per byte; a header claiming far more than that is garbage, and refusing it
    // avoids allocating for a lie.
    if (int64_t(width) * height > 32 * int64_t(size))
        return fail(ErrorCode::InvalidInput,
                    file + ": header claims " + std::to_string(width) + "x" +
                        std::to_string(height) + " pixels, more than a " + std::to_string(size) +
                        "-byte file can hold");

    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(bytes, size, &width, &height, &fileChannels, 3), stbi_image_free);
    if (!pixels)
        return fail(ErrorCode::InvalidInput,
                    file + ": invalid Radiance HDR file: " + failureReason());
    Image img(uint32_t(width), uint32_t(height), 3);
    std::copy_n(pixels.get(), img.pixels.size(), img.pixels.begin());
    return img;
}

}  // namespace rg
