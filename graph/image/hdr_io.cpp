// Radiance RGBE through stb_image. Only its HDR decoder is compiled in, reading from memory, so
// the file is opened (and its OS errors reported) by readWholeFile like every other format.
//
// stb_image 2.27 trusts the pixel stream: a run-length count of 0 (in garbage, or the 0 it reads
// past the end of a truncated file) makes it loop forever, and a truncated flat file decodes with
// black pixels. So checkPixelStream walks the stream first, exactly as stb will, and only a
// stream that is complete and terminates is handed to stb.
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

// Offset of the first pixel byte: after the signature line, the header lines up to the first
// empty one, and the resolution line ("-Y <height> +X <width>"), as stbi__hdr_load reads them
// (a line ends at '\n'; a line whose first byte is NUL counts as empty, as in stb's C strings).
size_t pixelDataOffset(const std::vector<char>& data) {
    size_t pos = 0;
    auto nextLine = [&]() {
        const size_t start = pos;
        while (pos < data.size() && data[pos] != '\n') ++pos;
        const bool empty = pos == start || data[start] == '\0';
        if (pos < data.size()) ++pos;  // the '\n'
        return empty;
    };
    nextLine();  // "#?RADIANCE" / "#?RGBE"
    while (pos < data.size() && !nextLine()) {
    }
    nextLine();  // resolution
    return pos;
}

// Walks the pixel stream the way stbi__hdr_load does (flat RGBE, or per-scanline "new" RLE:
// 2, 2, width as 16 bits, then each of the 4 components as runs/dumps), without decoding.
// The header (and so width and height) has already been accepted by stbi_info.
Result<void> checkPixelStream(const std::string& file, const std::vector<char>& data, int width,
                              int height) {
    const auto truncated = [&]() {
        return fail(ErrorCode::InvalidInput, file + ": truncated Radiance HDR file");
    };
    const auto corrupt = [&](int row, const std::string& what) {
        return fail(ErrorCode::InvalidInput, file + ": corrupt Radiance HDR file: scanline " +
                                                 std::to_string(row) + ": " + what);
    };
    size_t pos = pixelDataOffset(data);
    const size_t size = data.size();
    const auto byteAt = [&](size_t i) { return static_cast<unsigned char>(data[i]); };
    const uint64_t flatBytes = uint64_t(width) * uint64_t(height) * 4;

    // stb reads files outside this width range as flat RGBE, as Radiance writers do.
    if (width < 8 || width >= 32768) return size - pos >= flatBytes ? Result<void>{} : truncated();
    for (int row = 0; row < height; ++row) {
        if (size - pos < 4) return truncated();
        const unsigned c1 = byteAt(pos), c2 = byteAt(pos + 1), hi = byteAt(pos + 2);
        if (c1 != 2 || c2 != 2 || (hi & 0x80) != 0) {
            // No RLE marker on the first scanline: a flat file.
            if (row == 0) return size - pos >= flatBytes ? Result<void>{} : truncated();
            // stb would restart the whole image as flat data here, which decodes as garbage.
            return fail(ErrorCode::Unsupported,
                        file + ": scanline " + std::to_string(row) +
                            " is not run-length encoded although earlier ones are");
        }
        const int length = int((hi << 8) | byteAt(pos + 3));
        pos += 4;
        if (length != width)
            return corrupt(
                row, "length " + std::to_string(length) + ", expected " + std::to_string(width));
        for (int component = 0; component < 4; ++component) {
            int x = 0;
            while (x < width) {
                if (pos >= size) return truncated();
                int count = byteAt(pos++);
                const bool run = count > 128;  // a run repeats one value; a dump lists values
                if (run) count -= 128;
                if (count == 0) return corrupt(row, "zero-length run");
                if (count > width - x) return corrupt(row, "run-length data overruns the line");
                const size_t need = run ? 1 : size_t(count);
                if (size - pos < need) return truncated();
                pos += need;
                x += count;
            }
        }
    }
    return {};
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
    if (!stbi_info_from_memory(bytes, size, &width, &height, &fileChannels) || width <= 0 ||
        height <= 0)
        return fail(ErrorCode::InvalidInput,
                    file +
                        ": invalid Radiance HDR file: bad header (expected "
                        "FORMAT=32-bit_rle_rgbe and a '-Y <height> +X <width>' line)");
    // Radiance run-length encoding packs at most 127 values of one component into 2 bytes, i.e.
    // under 16 pixels per byte; a header claiming far more than that is garbage, and refusing it
    // avoids allocating for a lie.
    if (int64_t(width) * height > 32 * int64_t(size))
        return fail(ErrorCode::InvalidInput, file + ": header claims " + std::to_string(width) +
                                                 "x" + std::to_string(height) +
                                                 " pixels, more than a " + std::to_string(size) +
                                                 "-byte file can hold");
    if (auto ok = checkPixelStream(file, *data, width, height); !ok)
        return std::unexpected(ok.error());

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
