#include "golden/metrics.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace rg::golden {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

const std::vector<MetricInfo> kMetrics = {
    {Metric::MaxAbs, "max_abs", false, "largest absolute difference of any compared sample"},
    {Metric::Rmse, "rmse", false, "root mean square difference over the compared samples"},
    {Metric::Psnr, "psnr", true,
     "peak signal-to-noise ratio in dB; the tolerance is the least PSNR allowed"},
    {Metric::OverThreshold, "over_threshold", false,
     "fraction of pixels whose largest difference exceeds `threshold`"},
    {Metric::RelMean, "rel_mean", false,
     "mean relative difference |a - e| / max(|e|, epsilon) (HDR)"},
    {Metric::RelMax, "rel_max", false,
     "largest relative difference |a - e| / max(|e|, epsilon) (HDR)"},
    {Metric::Angular, "angular", false, "largest angle between normals, in degrees"},
    {Metric::Exact, "exact", false,
     "number of pixels with any compared sample different (integer data)"},
    {Metric::Flip, "flip", false, "mean FLIP error in [0, 1] (perceptual, display images)"},
};

// Absolute difference with the NaN/inf rules of the header: equal specials are no error.
double sampleDiff(float a, float e) {
    if (std::isnan(a) || std::isnan(e)) return std::isnan(a) && std::isnan(e) ? 0.0 : kInf;
    if (std::isinf(a) || std::isinf(e)) return a == e ? 0.0 : kInf;
    return std::fabs(double(a) - double(e));
}

bool sameSample(float a, float e) { return a == e || (std::isnan(a) && std::isnan(e)); }

Result<std::vector<uint32_t>> comparedChannels(const Image& img, const Comparison& c) {
    std::vector<uint32_t> ch = c.channels;
    if (ch.empty())
        for (uint32_t i = 0; i < img.channels; ++i) ch.push_back(i);
    for (uint32_t i : ch)
        if (i >= img.channels)
            return fail(ErrorCode::InvalidInput,
                        std::string(metricName(c.metric)) + ": channel " + "RGBA"[std::min(i, 3u)] +
                            " does not exist in a " + std::to_string(img.channels) +
                            "-channel image");
    return ch;
}

void decodeNormal(const Image& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& ch,
                  NormalEncoding enc, double n[3]) {
    auto at = [&](size_t k) { return double(img.at(x, y, ch[k])); };
    switch (enc) {
        case NormalEncoding::Signed:
        case NormalEncoding::Unorm:
            for (size_t k = 0; k < 3; ++k)
                n[k] = enc == NormalEncoding::Unorm ? at(k) * 2.0 - 1.0 : at(k);
            return;
        case NormalEncoding::Oct:
        case NormalEncoding::OctUnorm: {
            // The octahedral map of graph/layout: fold the lower hemisphere back over the diagonals.
            double px = at(0), py = at(1);
            if (enc == NormalEncoding::OctUnorm) px = px * 2.0 - 1.0, py = py * 2.0 - 1.0;
            double nz = 1.0 - std::fabs(px) - std::fabs(py);
            double t = std::max(-nz, 0.0);
            n[0] = px + (px >= 0.0 ? -t : t);
            n[1] = py + (py >= 0.0 ? -t : t);
            n[2] = nz;
            return;
        }
    }
}

// Angle between two vectors in degrees; two zero vectors agree, one zero vector is 180 off.
double angleDegrees(const double a[3], const double b[3]) {
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (std::isnan(la) || std::isnan(lb)) return kInf;
    if (la < 1e-12 || lb < 1e-12) return la < 1e-12 && lb < 1e-12 ? 0.0 : 180.0;
    // atan2 of |a x b| and a.b keeps precision for tiny angles, where acos does not.
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
                 cz = a[0] * b[1] - a[1] * b[0];
    const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return std::atan2(cross, dot) * 180.0 / kPi;
}

std::string pixelName(int32_t x, int32_t y) {
    return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

// Picks the worst pixel of an error map and fills worstX/Y and heatScale (max error, or 1).
void findWorst(MetricResult& r) {
    float worst = 0.0f;
    for (uint32_t y = 0; y < r.error.height; ++y)
        for (uint32_t x = 0; x < r.error.width; ++x) {
            float e = r.error.at(x, y, 0);
            if (e > worst || (std::isnan(e) && !std::isnan(worst))) {
                worst = e;
                r.worstX = static_cast<int32_t>(x);
                r.worstY = static_cast<int32_t>(y);
            }
        }
    r.heatScale = worst > 0.0f && std::isfinite(worst) ? worst : 1.0f;
}

}  // namespace

const std::vector<MetricInfo>& metricInfos() { return kMetrics; }

const char* metricName(Metric m) {
    for (const auto& i : kMetrics)
        if (i.metric == m) return i.name;
    return "?";
}

std::optional<Metric> parseMetric(std::string_view name) {
    for (const auto& i : kMetrics)
        if (name == i.name) return i.metric;
    return std::nullopt;
}

std::vector<std::string> metricNames() {
    std::vector<std::string> out;
    for (const auto& i : kMetrics) out.push_back(i.name);
    return out;
}

std::string formatNumber(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string Comparison::describe() const {
    std::string name = metricName(metric);
    if (metric == Metric::OverThreshold) name += "(" + formatNumber(threshold) + ")";
    const bool higher = metric == Metric::Psnr;
    return name + (higher ? " >= " : " <= ") + formatNumber(tolerance) +
           (metric == Metric::Psnr ? " dB" : "") + (metric == Metric::Angular ? " deg" : "");
}

std::string MetricResult::verdict() const {
    const bool higher = metric == "psnr";
    const char* op = passed ? (higher ? " >= " : " <= ") : (higher ? " < " : " > ");
    return metric + " " + formatNumber(value) + op + formatNumber(tolerance) +
           (higher ? " dB" : "") + (metric == "angular" ? " deg" : "");
}

Result<MetricResult> compare(const Image& actual, const Image& expected, const Comparison& c) {
    const std::string name = metricName(c.metric);
    if (actual.width != expected.width || actual.height != expected.height ||
        actual.channels != expected.channels)
        return fail(ErrorCode::InvalidInput,
                    name + ": the images differ in shape: actual " + std::to_string(actual.width) +
                        "x" + std::to_string(actual.height) + "x" +
                        std::to_string(actual.channels) + ", expected " +
                        std::to_string(expected.width) + "x" + std::to_string(expected.height) +
                        "x" + std::to_string(expected.channels));
    auto channels = comparedChannels(actual, c);
    if (!channels) return std::unexpected(channels.error());
    const std::vector<uint32_t>& ch = *channels;

    MetricResult r;
    r.metric = name;
    r.tolerance = c.tolerance;
    r.error = Image(actual.width, actual.height, 1);
    const size_t pixels = size_t(actual.width) * actual.height;
    const double samples = double(pixels) * double(ch.size());

    switch (c.metric) {
        case Metric::MaxAbs:
        case Metric::Rmse:
        case Metric::Psnr:
        case Metric::OverThreshold: {
            double sumSq = 0.0, maxDiff = 0.0;
            size_t over = 0;
            for (uint32_t y = 0; y < actual.height; ++y)
                for (uint32_t x = 0; x < actual.width; ++x) {
                    double px = 0.0;
                    for (uint32_t k : ch) {
                        double d = sampleDiff(actual.at(x, y, k), expected.at(x, y, k));
                        sumSq += d * d;
                        px = std::max(px, d);
                    }
                    r.error.at(x, y, 0) = static_cast<float>(px);
                    maxDiff = std::max(maxDiff, px);
                    if (px > c.threshold) ++over;
                }
            const double mse = samples > 0 ? sumSq / samples : 0.0;
            if (c.metric == Metric::MaxAbs) r.value = maxDiff;
            if (c.metric == Metric::Rmse) r.value = std::sqrt(mse);
            if (c.metric == Metric::Psnr)
                r.value = mse == 0.0 ? kInf : 10.0 * std::log10(c.peak * c.peak / mse);
            if (c.metric == Metric::OverThreshold) {
                r.value = pixels ? double(over) / double(pixels) : 0.0;
                r.detail = std::to_string(over) + " of " + std::to_string(pixels) +
                           " pixels over " + formatNumber(c.threshold);
            }
            findWorst(r);
            if (r.worstX >= 0)
                r.detail += std::string(r.detail.empty() ? "" : "; ") + "max |a - e| " +
                            formatNumber(maxDiff) + " at pixel " + pixelName(r.worstX, r.worstY) +
                            "; rmse " + formatNumber(std::sqrt(mse));
            break;
        }
        case Metric::RelMean:
        case Metric::RelMax: {
            double sum = 0.0, maxRel = 0.0;
            for (uint32_t y = 0; y < actual.height; ++y)
                for (uint32_t x = 0; x < actual.width; ++x) {
                    double px = 0.0;
                    for (uint32_t k : ch) {
                        const float e = expected.at(x, y, k);
                        double d = sampleDiff(actual.at(x, y, k), e);
                        double rel = d == 0.0 ? 0.0 : d / std::max(std::fabs(double(e)), c.epsilon);
                        if (std::isnan(rel)) rel = kInf;
                        sum += rel;
                        px = std::max(px, rel);
                    }
                    r.error.at(x, y, 0) = static_cast<float>(px);
                    maxRel = std::max(maxRel, px);
                }
            const double mean = samples > 0 ? sum / samples : 0.0;
            r.value = c.metric == Metric::RelMean ? mean : maxRel;
            findWorst(r);
            r.detail = "mean " + formatNumber(mean) + ", max " + formatNumber(maxRel) +
                       (r.worstX >= 0 ? " at pixel " + pixelName(r.worstX, r.worstY) : "") +
                       " (epsilon " + formatNumber(c.epsilon) + ")";
            break;
        }
        case Metric::Angular: {
            const bool oct =
                c.normals == NormalEncoding::Oct || c.normals == NormalEncoding::OctUnorm;
            const size_t need = oct ? 2 : 3;
            if (ch.size() != need)
                return fail(ErrorCode::InvalidInput,
                            "angular: " + std::string(oct ? "an octahedral normal" : "a normal") +
                                " needs " + std::to_string(need) + " channels, got " +
                                std::to_string(ch.size()) + " (set channels, e.g. '" +
                                (oct ? "rg" : "rgb") + "')");
            double sum = 0.0, maxAngle = 0.0;
            for (uint32_t y = 0; y < actual.height; ++y)
                for (uint32_t x = 0; x < actual.width; ++x) {
                    double a[3], e[3];
                    decodeNormal(actual, x, y, ch, c.normals, a);
                    decodeNormal(expected, x, y, ch, c.normals, e);
                    double angle = angleDegrees(a, e);
                    r.error.at(x, y, 0) = static_cast<float>(angle);
                    sum += angle;
                    maxAngle = std::max(maxAngle, angle);
                }
            r.value = maxAngle;
            findWorst(r);
            r.detail = "mean " + formatNumber(pixels ? sum / double(pixels) : 0.0) + " deg" +
                       (r.worstX >= 0 ? ", max at pixel " + pixelName(r.worstX, r.worstY) : "");
            break;
        }
        case Metric::Exact: {
            size_t differing = 0;
            for (uint32_t y = 0; y < actual.height; ++y)
                for (uint32_t x = 0; x < actual.width; ++x) {
                    bool same = true;
                    for (uint32_t k : ch)
                        same = same && sameSample(actual.at(x, y, k), expected.at(x, y, k));
                    r.error.at(x, y, 0) = same ? 0.0f : 1.0f;
                    if (!same) ++differing;
                }
            r.value = double(differing);
            findWorst(r);
            r.heatScale = 1.0f;
            r.detail =
                std::to_string(differing) + " of " + std::to_string(pixels) + " pixels differ";
            if (r.worstX >= 0) {
                const uint32_t x = static_cast<uint32_t>(r.worstX),
                               y = static_cast<uint32_t>(r.worstY);
                std::string a, e;
                for (uint32_t k : ch) {
                    a += (a.empty() ? "" : ", ") + formatNumber(actual.at(x, y, k));
                    e += (e.empty() ? "" : ", ") + formatNumber(expected.at(x, y, k));
                }
                r.detail += "; first at pixel " + pixelName(r.worstX, r.worstY) + ": (" + a +
                            ") instead of (" + e + ")";
            }
            break;
        }
        case Metric::Flip: {
            if (ch.size() != 1 && ch.size() != 3)
                return fail(ErrorCode::InvalidInput,
                            "flip: compares 1 (grey) or 3 (colour) channels, got " +
                                std::to_string(ch.size()) + " (set channels, e.g. 'rgb')");
            Image ref(expected.width, expected.height, static_cast<uint32_t>(ch.size()));
            Image test(actual.width, actual.height, static_cast<uint32_t>(ch.size()));
            for (uint32_t y = 0; y < actual.height; ++y)
                for (uint32_t x = 0; x < actual.width; ++x)
                    for (uint32_t k = 0; k < ch.size(); ++k) {
                        ref.at(x, y, k) = expected.at(x, y, ch[k]);
                        test.at(x, y, k) = actual.at(x, y, ch[k]);
                    }
            auto map = flipErrorMap(ref, test, c.display, c.pixelsPerDegree);
            if (!map) return std::unexpected(map.error());
            r.error = std::move(*map);
            double sum = 0.0, maxFlip = 0.0;
            for (float v : r.error.pixels) {
                sum += v;
                maxFlip = std::max(maxFlip, double(v));
            }
            r.value = pixels ? sum / double(pixels) : 0.0;
            findWorst(r);
            r.heatScale = 1.0f;  // FLIP is in [0, 1]: its maps are always shown on the same scale
            r.detail = "max " + formatNumber(maxFlip) +
                       (r.worstX >= 0 ? " at pixel " + pixelName(r.worstX, r.worstY) : "") + " (" +
                       formatNumber(c.pixelsPerDegree) + " pixels per degree)";
            break;
        }
    }
    r.passed = c.metric == Metric::Psnr ? r.value >= c.tolerance : r.value <= c.tolerance;
    if (std::isnan(r.value)) r.passed = false;
    return r;
}

// Magma (matplotlib, van der Walt & Smith), sampled at 9 points and interpolated linearly: dark
// where the error is small so that a clean diff reads as black.
void magma(float t, float rgb[3]) {
    static const float kStops[9][3] = {
        {0, 0, 4},      {28, 16, 68},   {79, 18, 123},   {129, 37, 129},  {181, 54, 122},
        {229, 80, 100}, {251, 135, 97}, {254, 194, 135}, {252, 253, 191},
    };
    if (!(t > 0.0f)) t = 0.0f;  // NaN too
    t = std::min(t, 1.0f) * 8.0f;
    const int i = std::min(static_cast<int>(t), 7);
    const float f = t - static_cast<float>(i);
    for (int k = 0; k < 3; ++k)
        rgb[k] = (kStops[i][k] * (1.0f - f) + kStops[i + 1][k] * f) / 255.0f;
}

Image heatMap(const Image& error, float scale) {
    RG_CHECK(error.channels == 1) << "heatMap takes a 1-channel error map, got " << error.channels
                                  << " channels";
    Image out(error.width, error.height, 3);
    const float s = scale > 0.0f ? scale : 1.0f;
    for (uint32_t y = 0; y < error.height; ++y)
        for (uint32_t x = 0; x < error.width; ++x) {
            float e = error.at(x, y, 0);
            float rgb[3];
            magma(std::isnan(e) || std::isinf(e) ? 1.0f : e / s, rgb);
            for (uint32_t k = 0; k < 3; ++k) out.at(x, y, k) = rgb[k];
        }
    return out;
}

uint16_t floatToHalfBits(float v) {
    const uint32_t f = std::bit_cast<uint32_t>(v);
    const uint16_t sign = static_cast<uint16_t>((f >> 16) & 0x8000u);
    const uint32_t exp = (f >> 23) & 0xffu;
    uint32_t mant = f & 0x7fffffu;
    if (exp == 0xff)
        return static_cast<uint16_t>(sign | 0x7c00u | (mant ? 0x200u : 0u));  // inf, NaN
    const int e = static_cast<int>(exp) - 127;
    if (e > 15) return static_cast<uint16_t>(sign | 0x7c00u);
    if (e < -25) return sign;  // below half the smallest subnormal: rounds to zero
    if (exp != 0) mant |= 0x800000u;
    uint32_t result;
    if (e >= -14) {
        // Normal half: 10 mantissa bits; drop 13 bits of the float mantissa.
        const uint32_t halfExp = static_cast<uint32_t>(e + 15);
        uint32_t m = mant >> 13;
        const uint32_t rest = mant & 0x1fffu;
        result = (halfExp << 10) | (m & 0x3ffu);
        if (rest > 0x1000u || (rest == 0x1000u && (m & 1u)))
            ++result;  // may carry into the exponent: correct
    } else {
        // Subnormal half: the value in units of 2^-24 (the smallest subnormal) is
        // mant * 2^(e - 23) / 2^-24 = mant >> (-e - 1), rounded to nearest even.
        const int shift = -e - 1;  // 14..24
        const uint64_t full = uint64_t(mant);
        const uint64_t q = full >> shift;
        const uint64_t rem = full & ((uint64_t(1) << shift) - 1);
        const uint64_t half = uint64_t(1) << (shift - 1);
        uint64_t r = q;
        if (rem > half || (rem == half && (q & 1u))) ++r;
        result = static_cast<uint32_t>(r);
    }
    if (result >= 0x7c00u) return static_cast<uint16_t>(sign | 0x7c00u);
    return static_cast<uint16_t>(sign | result);
}

float halfBitsToFloat(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t exp = (h >> 10) & 0x1fu;
    const uint32_t mant = h & 0x3ffu;
    if (exp == 0x1f) return std::bit_cast<float>(sign | 0x7f800000u | (mant << 13));
    if (exp == 0) {
        const float v = std::ldexp(static_cast<float>(mant), -24);
        return sign ? -v : v;
    }
    return std::bit_cast<float>(sign | ((exp + 112u) << 23) | (mant << 13));
}

float roundToHalf(float v) { return halfBitsToFloat(floatToHalfBits(v)); }

}  // namespace rg::golden
