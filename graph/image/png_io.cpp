// PNG through libpng. libpng reports errors by longjmp back to a setjmp; that is only defined in
// C++ when no frame in between has objects with destructors. So every libpng call sits in a small
// function (runPng*) whose only state is a context struct owned by the caller, the callbacks have
// no such objects either, and all allocation happens outside those functions.
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>

#include "image/file_io.h"
#include "image/image.h"

namespace rg {

using image_detail::quoted;

namespace {

// State shared by libpng's callbacks and the caller; lives in the caller's frame.
struct PngContext {
    png_structp png = nullptr;
    png_infop info = nullptr;
    char message[256] = {};  // libpng's error text
    bool truncated = false;  // the read callback ran out of data

    // Reading.
    const std::vector<char>* data = nullptr;
    size_t pos = 0;
    png_uint_32 width = 0, height = 0;
    int fileBitDepth = 0, fileColorType = 0;
    size_t fileRowBytes = 0;  // before transforms: what the compressed stream must inflate to
    int channels = 0, bitDepth = 0;
    size_t rowBytes = 0;
    std::vector<png_bytep> rows;

    // Writing.
    std::FILE* file = nullptr;
    int writeErrno = 0;
    int colorType = 0;
    std::vector<png_text> texts;
};

void onError(png_structp png, png_const_charp message) {
    auto* ctx = static_cast<PngContext*>(png_get_error_ptr(png));
    std::snprintf(ctx->message, sizeof(ctx->message), "%s", message);
    png_longjmp(png, 1);
}

// Warnings are about ancillary chunks (bad gamma, unknown profile) that are not used here.
void onWarning(png_structp, png_const_charp) {}

void readFromMemory(png_structp png, png_bytep out, size_t n) {
    auto* ctx = static_cast<PngContext*>(png_get_io_ptr(png));
    if (n > ctx->data->size() - ctx->pos) {
        ctx->truncated = true;
        png_error(png, "unexpected end of file");
    }
    std::memcpy(out, ctx->data->data() + ctx->pos, n);
    ctx->pos += n;
}

void writeToFile(png_structp png, png_bytep bytes, size_t n) {
    auto* ctx = static_cast<PngContext*>(png_get_io_ptr(png));
    if (std::fwrite(bytes, 1, n, ctx->file) != n) {
        ctx->writeErrno = errno != 0 ? errno : EIO;
        png_error(png, "write failed");
    }
}

void flushFile(png_structp png) {
    auto* ctx = static_cast<PngContext*>(png_get_io_ptr(png));
    if (std::fflush(ctx->file) != 0) {
        ctx->writeErrno = errno != 0 ? errno : EIO;
        png_error(png, "write failed");
    }
}

// Phase 1 of reading: header and the transforms that make every PNG 8 or 16 bits per sample
// with 1-4 channels.
bool runPngReadHeader(PngContext& ctx) {
    if (setjmp(png_jmpbuf(ctx.png))) return false;
    png_set_read_fn(ctx.png, &ctx, readFromMemory);
    png_read_info(ctx.png, ctx.info);
    ctx.width = png_get_image_width(ctx.png, ctx.info);
    ctx.height = png_get_image_height(ctx.png, ctx.info);
    ctx.fileBitDepth = png_get_bit_depth(ctx.png, ctx.info);
    ctx.fileColorType = png_get_color_type(ctx.png, ctx.info);
    ctx.fileRowBytes = png_get_rowbytes(ctx.png, ctx.info);
    png_set_expand(ctx.png);  // palette -> RGB, gray 1/2/4 bits -> 8, tRNS -> alpha channel
    png_set_interlace_handling(ctx.png);
    png_read_update_info(ctx.png, ctx.info);
    ctx.channels = png_get_channels(ctx.png, ctx.info);
    ctx.bitDepth = png_get_bit_depth(ctx.png, ctx.info);
    ctx.rowBytes = png_get_rowbytes(ctx.png, ctx.info);
    return true;
}

// Phase 2: pixels into ctx.rows (allocated by the caller), then the chunks after the image.
bool runPngReadPixels(PngContext& ctx) {
    if (setjmp(png_jmpbuf(ctx.png))) return false;
    png_read_image(ctx.png, ctx.rows.data());
    png_read_end(ctx.png, ctx.info);
    return true;
}

bool runPngWrite(PngContext& ctx) {
    if (setjmp(png_jmpbuf(ctx.png))) return false;
    png_set_write_fn(ctx.png, &ctx, writeToFile, flushFile);
    png_set_IHDR(ctx.png, ctx.info, ctx.width, ctx.height, 8, ctx.colorType, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!ctx.texts.empty())
        png_set_text(ctx.png, ctx.info, ctx.texts.data(), int(ctx.texts.size()));
    // zlib's fastest level with the Sub filter alone: the default frame at 1280x720 writes in
    // ~55 ms rather than ~260 with libpng's defaults (level 6, every filter tried per row), a file
    // ~18 % larger; the pixels are the same (PNG is lossless).
    png_set_compression_level(ctx.png, 1);
    png_set_filter(ctx.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_write_info(ctx.png, ctx.info);
    png_write_image(ctx.png, ctx.rows.data());
    png_write_end(ctx.png, ctx.info);
    return true;
}

// tEXt keyword rules (PNG spec 11.3.4.3): 1-79 Latin-1 printable characters, no leading,
// trailing or consecutive spaces. libpng would silently drop a bad one; here it is an error.
bool isValidKeyword(const std::string& key) {
    if (key.empty() || key.size() > 79 || key.front() == ' ' || key.back() == ' ') return false;
    if (key.find("  ") != std::string::npos) return false;
    return std::all_of(key.begin(), key.end(), [](char ch) {
        const auto c = static_cast<unsigned char>(ch);
        return (c >= 32 && c <= 126) || c >= 161;
    });
}

uint8_t toByte(float v) {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    return uint8_t(std::lround(v * 255.0f));
}

}  // namespace

Result<void> writePng(const std::string& path, const Image& img,
                      const std::map<std::string, std::string>& text) {
    const std::string file = quoted(path);
    if (img.channels < 1 || img.channels > 4)
        return fail(ErrorCode::InvalidInput, file + ": PNG takes 1-4 channels, the image has " +
                                                 std::to_string(img.channels));
    if (img.width == 0 || img.height == 0 || img.width > PNG_UINT_31_MAX ||
        img.height > PNG_UINT_31_MAX)
        return fail(ErrorCode::InvalidInput, file + ": cannot write a " +
                                                 std::to_string(img.width) + "x" +
                                                 std::to_string(img.height) + " PNG");
    if (img.pixels.size() != size_t(img.width) * img.height * img.channels)
        return fail(ErrorCode::InvalidInput,
                    file + ": image has " + std::to_string(img.pixels.size()) +
                        " samples, expected " + std::to_string(img.width) + "x" +
                        std::to_string(img.height) + "x" + std::to_string(img.channels));

    // png_text wants mutable strings, so the text lives in copies owned here.
    std::vector<std::string> keys, values;
    for (const auto& [key, value] : text) {
        if (!isValidKeyword(key))
            return fail(ErrorCode::InvalidInput,
                        file + ": invalid PNG text key '" + key +
                            "' (1-79 printable Latin-1 characters, no leading, trailing or "
                            "double spaces)");
        if (value.find('\0') != std::string::npos)
            return fail(ErrorCode::InvalidInput,
                        file + ": PNG text '" + key + "' contains a NUL character");
        keys.push_back(key);
        values.push_back(value);
    }

    std::vector<uint8_t> bytes(img.pixels.size());
    std::transform(img.pixels.begin(), img.pixels.end(), bytes.begin(), toByte);

    PngContext ctx;
    ctx.width = img.width;
    ctx.height = img.height;
    static constexpr int colorTypes[4] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                          PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    ctx.colorType = colorTypes[img.channels - 1];
    const size_t rowBytes = size_t(img.width) * img.channels;
    ctx.rows.resize(img.height);
    for (uint32_t y = 0; y < img.height; ++y) ctx.rows[y] = bytes.data() + y * rowBytes;
    for (size_t i = 0; i < keys.size(); ++i) {
        png_text t{};
        t.compression = PNG_TEXT_COMPRESSION_NONE;
        t.key = keys[i].data();
        t.text = values[i].data();
        t.text_length = values[i].size();
        ctx.texts.push_back(t);
    }

    auto writer = image_detail::AtomicFileWriter::open(path);
    if (!writer) return std::unexpected(writer.error());
    ctx.file = writer->file();
    ctx.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
    if (ctx.png) ctx.info = png_create_info_struct(ctx.png);
    if (!ctx.info) {
        png_destroy_write_struct(&ctx.png, nullptr);
        return fail(ErrorCode::Io, "cannot write " + file + ": out of memory in libpng");
    }
    const bool ok = runPngWrite(ctx);
    png_destroy_write_struct(&ctx.png, &ctx.info);
    if (!ok) {
        if (ctx.writeErrno != 0) return std::unexpected(writer->writeError(ctx.writeErrno));
        return fail(ErrorCode::InvalidInput, file + ": libpng: " + ctx.message);
    }
    return writer->commit();
}

Result<Image> readPng(const std::string& path, std::map<std::string, std::string>* text) {
    auto data = image_detail::readWholeFile(path);
    if (!data) return std::unexpected(data.error());
    const std::string file = quoted(path);
    if (data->size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data->data()), 0, 8) != 0)
        return fail(ErrorCode::InvalidInput, file + ": not a PNG file");

    PngContext ctx;
    ctx.data = &*data;
    ctx.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
    if (ctx.png) ctx.info = png_create_info_struct(ctx.png);
    // Frees libpng's state on every return below.
    struct Guard {
        PngContext& ctx;
        ~Guard() { png_destroy_read_struct(&ctx.png, ctx.info ? &ctx.info : nullptr, nullptr); }
    } guard{ctx};
    if (!ctx.info) return fail(ErrorCode::Io, "cannot read " + file + ": out of memory in libpng");

    auto corrupt = [&]() {
        if (ctx.truncated) return fail(ErrorCode::InvalidInput, file + ": truncated PNG file");
        return fail(ErrorCode::InvalidInput, file + ": corrupt PNG file: " + ctx.message);
    };
    if (!runPngReadHeader(ctx)) return corrupt();

    // zlib cannot inflate more than 1032 bytes per input byte, so a header that claims more
    // pixel data than that is garbage; refusing it avoids allocating for a lie.
    const uint64_t inflated = uint64_t(ctx.height) * (ctx.fileRowBytes + 1);
    if (inflated / 1032 > data->size())
        return fail(ErrorCode::InvalidInput,
                    file + ": header claims " + std::to_string(ctx.width) + "x" +
                        std::to_string(ctx.height) + " pixels, more than a " +
                        std::to_string(data->size()) + "-byte file can hold");
    if ((ctx.bitDepth != 8 && ctx.bitDepth != 16) || ctx.channels < 1 || ctx.channels > 4 ||
        ctx.rowBytes != size_t(ctx.width) * size_t(ctx.channels) * size_t(ctx.bitDepth / 8))
        return fail(ErrorCode::Unsupported, file + ": unsupported PNG layout (bit depth " +
                                                std::to_string(ctx.fileBitDepth) + ", color type " +
                                                std::to_string(ctx.fileColorType) + ")");

    std::vector<png_byte> bytes(size_t(ctx.height) * ctx.rowBytes);
    ctx.rows.resize(ctx.height);
    for (png_uint_32 y = 0; y < ctx.height; ++y) ctx.rows[y] = bytes.data() + y * ctx.rowBytes;
    if (!runPngReadPixels(ctx)) return corrupt();

    Image img(ctx.width, ctx.height, uint32_t(ctx.channels));
    if (ctx.bitDepth == 8) {
        for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(bytes[i]) / 255.0f;
    } else {
        // 16-bit samples are big-endian in the file and libpng leaves them so.
        for (size_t i = 0; i < img.pixels.size(); ++i)
            img.pixels[i] = float((unsigned(bytes[2 * i]) << 8) | bytes[2 * i + 1]) / 65535.0f;
    }

    if (text) {
        text->clear();
        png_textp entries = nullptr;
        const int count = png_get_text(ctx.png, ctx.info, &entries, nullptr);
        for (int i = 0; i < count; ++i) {
            // libpng NUL-terminates every kind of text (tEXt, zTXt, iTXt), and none may hold a NUL.
            (*text)[entries[i].key] = entries[i].text ? entries[i].text : "";
        }
    }
    return img;
}

}  // namespace rg
