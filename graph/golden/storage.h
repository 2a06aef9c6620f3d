// Golden image files: which storage a resource's format gets, how an image is quantised to it,
// and reading and writing it. Lossless for every format: the file holds exactly what the
// resource held, so a comparison only ever sees rendering differences.
#pragma once

#include <map>
#include <string>

#include "core/result.h"
#include "golden/report.h"
#include "image/image.h"

namespace rg::golden {

// The storage of a resource's format (script name, e.g. "rgba16f"; "buffer:float32" for buffers).
Storage storageForFormat(const std::string& format);
// True for "rgba8_srgb": its values are read back decoded and stored sRGB-encoded in the PNG.
bool isSrgbFormat(const std::string& format);

// The image as its golden stores it: 8-bit rounding for PNG (through the sRGB encoding when
// `srgb`), binary16 rounding for half EXR, unchanged for float EXR. What readStored returns after
// writeStored, bit for bit; comparisons run on quantised actual images.
Image quantizeForStorage(const Image& image, Storage storage, bool srgb);

// Writes an image (already quantised or not) as its storage says, creating the folder; EXR
// files are ZIP-compressed, with `meta` as header attributes (PNG: text chunks).
Result<void> writeStored(const std::string& path, const Image& image, Storage storage, bool srgb,
                         const std::map<std::string, std::string>& meta = {});
Result<Image> readStored(const std::string& path, Storage storage, bool srgb);

// A PNG-ready preview: RGB display values (linear images clamped and sRGB-encoded; grey for
// one channel, blue 0 for two).
Image previewImage(const Image& image, bool display);

}  // namespace rg::golden
