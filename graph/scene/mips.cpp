// CPU mip chains: an area-weighted box filter, in linear space for sRGB-encoded colour.
#include <algorithm>
#include <cmath>

#include "scene.h"

namespace rg {

namespace {

struct Tap {
    uint32_t index;
    float weight;
};

// For each of `dst` output texels along one axis, the source texels its footprint
// [i * src / dst, (i + 1) * src / dst) covers and by how much (weights sum to 1).
std::vector<std::vector<Tap>> footprints(uint32_t src, uint32_t dst) {
    std::vector<std::vector<Tap>> out(dst);
    const double scale = double(src) / double(dst);
    for (uint32_t i = 0; i < dst; ++i) {
        const double lo = i * scale, hi = (i + 1) * scale;
        for (uint32_t s = static_cast<uint32_t>(std::floor(lo)); s < src && double(s) < hi; ++s) {
            const double overlap = std::min(hi, double(s) + 1.0) - std::max(lo, double(s));
            if (overlap > 1e-9) out[i].push_back({s, static_cast<float>(overlap / scale)});
        }
    }
    return out;
}

Image downsample(const Image& src, bool srgb) {
    const uint32_t w = std::max(1u, src.width / 2), h = std::max(1u, src.height / 2),
                   c = src.channels;
    // Decode once: colour channels of sRGB images are averaged as linear light.
    std::vector<float> lin(src.pixels);
    if (srgb)
        for (size_t i = 0; i < lin.size(); ++i)
            if (c < 4 || i % c != 3) lin[i] = srgbDecode(lin[i]);
    const auto fx = footprints(src.width, w), fy = footprints(src.height, h);
    Image dst(w, h, c);
    std::vector<float> acc(c);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            std::fill(acc.begin(), acc.end(), 0.0f);
            for (const Tap& ty : fy[y])
                for (const Tap& tx : fx[x]) {
                    const float wgt = tx.weight * ty.weight;
                    const size_t base = (size_t(ty.index) * src.width + tx.index) * c;
                    for (uint32_t k = 0; k < c; ++k) acc[k] += wgt * lin[base + k];
                }
            for (uint32_t k = 0; k < c; ++k)
                dst.at(x, y, k) = srgb && (c < 4 || k != 3) ? srgbEncode(acc[k]) : acc[k];
        }
    return dst;
}

}  // namespace

void generateMips(SceneImage& image) {
    image.mips.clear();
    image.mipLevels = 1;
    if (image.pixels.width == 0 || image.pixels.height == 0) return;
    const uint32_t largest = std::max(image.pixels.width, image.pixels.height);
    uint32_t levels = 1;
    while ((largest >> levels) > 0) ++levels;
    for (uint32_t l = 1; l < levels; ++l)
        image.mips.push_back(downsample(image.level(l - 1), image.srgb));
    image.mipLevels = levels;
}

}  // namespace rg
