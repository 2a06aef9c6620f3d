#include "image/image.h"

#include <cmath>

namespace rg {

Image::Image(uint32_t w, uint32_t h, uint32_t c)
    : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}

// IEC 61966-2-1 encoding; the linear segment keeps the slope finite at 0. The breakpoint is
// compared as a float so that passing the literal 0.0031308f lands on the linear side, as the
// standard's "<=" says. Evaluated in double so that encode(decode(v)) round-trips to float precision.
float srgbEncode(float linear) {
    const double x = linear;
    if (linear <= 0.0031308f) return float(12.92 * x);
    return float(1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

// Inverse of srgbEncode; 0.04045 is where the standard's two segments meet in encoded space.
float srgbDecode(float encoded) {
    const double v = encoded;
    if (encoded <= 0.04045f) return float(v / 12.92);
    return float(std::pow((v + 0.055) / 1.055, 2.4));
}

}  // namespace rg
