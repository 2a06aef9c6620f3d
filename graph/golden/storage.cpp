#include "golden/storage.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace rg::golden {

namespace {

std::vector<std::string> channelNames(uint32_t n) {
    static const char* rgba[] = {"R", "G", "B", "A"};
    std::vector<std::string> names;
    for (uint32_t i = 0; i < n && i < 4; ++i) names.push_back(rgba[i]);
    return names;
}

// The colour channels of a decoded sRGB-format image encoded back to what its bytes held.
Image srgbEncoded(const Image& img) {
    Image out = img;
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
            for (uint32_t k = 0; k < std::min(img.channels, 3u); ++k)
                out.at(x, y, k) = srgbEncode(img.at(x, y, k));
    return out;
}

}  // namespace

Storage storageForFormat(const std::string& format) {
    if (format == "r8" || format == "rg8" || format == "rgba8" || format == "rgba8_srgb")
        return Storage::Png;
    if (format == "r16f" || format == "rg16f" || format == "rgba16f" || format == "r11g11b10f")
        return Storage::ExrHalf;
    return Storage::ExrFloat;
}

bool isSrgbFormat(const std::string& format) { return format == "rgba8_srgb"; }

Image quantizeForStorage(const Image& image, Storage storage, bool srgb) {
    Image out = image;
    switch (storage) {
        case Storage::Png:
            for (uint32_t y = 0; y < image.height; ++y)
                for (uint32_t x = 0; x < image.width; ++x)
                    for (uint32_t k = 0; k < image.channels; ++k) {
                        const bool colour = srgb && k < 3;
                        float v = image.at(x, y, k);
                        if (colour) v = srgbEncode(v);
                        v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
                        v = static_cast<float>(std::lround(v * 255.0f)) /
                            255.0f;  // what writePng then readPng do
                        out.at(x, y, k) = colour ? srgbDecode(v) : v;
                    }
            break;
        case Storage::ExrHalf:
            for (float& v : out.pixels) v = roundToHalf(v);
            break;
        case Storage::ExrFloat:
            break;
    }
    return out;
}

Result<void> writeStored(const std::string& path, const Image& image, Storage storage, bool srgb,
                         const std::map<std::string, std::string>& meta) {
    std::error_code ec;
    if (auto parent = fs::path(path).parent_path(); !parent.empty())
        fs::create_directories(parent, ec);
    if (storage == Storage::Png) return writePng(path, srgb ? srgbEncoded(image) : image, meta);
    ExrWriteOptions o;
    o.pixelType = storage == Storage::ExrHalf ? ExrPixelType::Half : ExrPixelType::Float;
    o.compress = true;
    o.metadata = meta;
    return writeExr(path, {{"", channelNames(image.channels), image}}, o);
}

Result<Image> readStored(const std::string& path, Storage storage, bool srgb) {
    if (storage == Storage::Png) {
        auto img = readPng(path);
        if (!img) return img;
        if (srgb)
            for (uint32_t y = 0; y < img->height; ++y)
                for (uint32_t x = 0; x < img->width; ++x)
                    for (uint32_t k = 0; k < std::min(img->channels, 3u); ++k)
                        img->at(x, y, k) = srgbDecode(img->at(x, y, k));
        return img;
    }
    auto exr = readExr(path);
    if (!exr) return std::unexpected(exr.error());
    if (exr->layers.empty())
        return fail(ErrorCode::InvalidInput, "'" + path + "': no image layers");
    return exr->layers[0].image;
}

Image previewImage(const Image& img, bool display) {
    Image out(img.width, img.height, 3);
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
            for (uint32_t k = 0; k < 3; ++k) {
                float v = img.channels == 1  ? img.at(x, y, 0)
                          : k < img.channels ? img.at(x, y, k)
                                             : 0.0f;
                v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
                out.at(x, y, k) = display ? v : srgbEncode(v);
            }
    return out;
}

}  // namespace rg::golden
