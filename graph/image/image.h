// Image I/O: float images in memory; OpenEXR (layers, metadata), PNG (8-bit display values) and
// Radiance .hdr (read only) on disk.
//
// Contract shared by every function here:
// - Pixels are 32-bit floats, interleaved per pixel, rows stored top row first.
// - Nothing is ever colour-managed on the way in or out: EXR and HDR hold linear values, PNG holds
//   whatever display encoding the caller chose (use srgbEncode/srgbDecode explicitly).
// - Failures caused by the file or the arguments come back as an Error whose message starts with
//   the quoted file name ("'out.exr': ..." or "cannot open 'out.exr': ..."). No function throws and
//   none crashes on a truncated or garbage file.
// - Writers write "<path>.tmp-<pid>-<n>" and rename it to `path`, so a failed write leaves an
//   existing file at `path` untouched (and removes the temp file).
// - Every function is safe to call from several threads at once on different files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/result.h"

namespace rg {

// A width x height image with `channels` floats per pixel.
struct Image {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<float> pixels;  // width * height * channels, interleaved, row-major, top row first

    Image() = default;
    // A zero-filled image.
    Image(uint32_t w, uint32_t h, uint32_t c);

    // Index of sample (x, y, c) in pixels; x < width, y < height, c < channels (a bug otherwise,
    // checked in every build).
    size_t index(uint32_t x, uint32_t y, uint32_t c) const {
        RG_CHECK(x < width && y < height && c < channels)
            << "pixel (" << x << ", " << y << ", " << c << ") outside a " << width << "x" << height
            << "x" << channels << " image";
        return (size_t(y) * width + x) * channels + c;
    }
    float& at(uint32_t x, uint32_t y, uint32_t c) { return pixels[index(x, y, c)]; }
    float at(uint32_t x, uint32_t y, uint32_t c) const { return pixels[index(x, y, c)]; }
};

// One EXR layer. In the file its channels are named name + "." + channelNames[i] (just
// channelNames[i] when name is empty), which is how EXR viewers recognise layers.
struct ImageLayer {
    std::string name;                       // "" or e.g. "hdr", "gbuffer.normal"
    std::vector<std::string> channelNames;  // one per image channel, e.g. {"R","G","B","A"}; no '.'
    Image image;
};

enum class ExrPixelType { Half, Float };

struct ExrWriteOptions {
    ExrPixelType pixelType = ExrPixelType::Half;  // Half: values beyond ±65504 become ±inf
    bool compress = true;                         // lossless ZIP when true, else uncompressed
    std::map<std::string, std::string> metadata;  // written as string attributes of the header
    std::map<std::string, float> floats;          // written as float attributes
    std::map<std::string, int> ints;              // written as int attributes
};

// Writes a single-part scanline EXR. All layers must have the same size (at least 1x1), channel
// names must be unique within the file, and metadata keys must not be standard EXR attribute names.
Result<void> writeExr(const std::string& path, const std::vector<ImageLayer>& layers,
                      const ExrWriteOptions& opts = {});

struct ExrFile {
    std::vector<ImageLayer> layers;               // ordered by name ("" first)
    std::map<std::string, std::string> metadata;  // every string attribute of the header
    std::map<std::string, double> floats;         // every float and double attribute
    std::map<std::string, int> ints;              // every int attribute
};

// Reads the data window of the first part of an EXR (scanline or tiled; not deep). Channels are
// grouped into layers by the text before their last '.'; within a layer R, G, B, A come first (in
// that order, when present), then the rest alphabetically. Every pixel type is converted to float.
Result<ExrFile> readExr(const std::string& path);

// Writes an 8-bit PNG: 1-4 channels = gray, gray+alpha, RGB, RGBA. Values are display values in
// [0, 1], already encoded (e.g. by srgbEncode); each is stored as round(clamp(v, 0, 1) * 255)
// (NaN as 0). `text` becomes tEXt chunks: keys 1-79 printable Latin-1 characters without
// leading, trailing or double spaces; values without NUL characters.
Result<void> writePng(const std::string& path, const Image& img,
                      const std::map<std::string, std::string>& text = {});

// Reads any PNG (palette, gray, 1-16 bits, interlaced, transparency key) as 1-4 channels with
// values in [0, 1]: 8-bit samples divided by 255, 16-bit by 65535. No gamma is applied. When
// `text` is not null it receives the file's text chunks (tEXt, zTXt, iTXt).
Result<Image> readPng(const std::string& path, std::map<std::string, std::string>* text = nullptr);

// Reads a Radiance RGBE (.hdr) file, flat or run-length encoded, as 3-channel linear float
// (decoded by stb_image after the pixel stream is checked: truncated and corrupt files fail).
Result<Image> readHdr(const std::string& path);

// The sRGB transfer function of IEC 61966-2-1, for one colour value (never apply it to alpha).
// srgbEncode: linear -> encoded; srgbDecode: encoded -> linear. Values outside [0, 1] follow the
// same formulas (negative values stay on the linear segment).
float srgbEncode(float linear);
float srgbDecode(float encoded);

}  // namespace rg
