// Image metrics for golden tests: pure C++ over rg::Image pairs (no Vulkan, no files).
//
// Every comparison takes the image a test produced (`actual`) and the golden (`expected`), of the
// same width, height and channel count, and gives one number, the metric's tolerance and a
// verdict, plus a per-pixel error map (what the diff heat map shows). Lower is better for every
// metric except PSNR.
//
// | metric           | value                                                        | passes when   |
// | ---------------- | ------------------------------------------------------------ | ------------- |
// | `max_abs`        | max |a - e| over compared samples                            | value <= tol  |
// | `rmse`           | sqrt(mean (a - e)^2) over compared samples                   | value <= tol  |
// | `psnr`           | 10 log10(peak^2 / MSE) in dB (inf when identical)            | value >= tol  |
// | `over_threshold` | fraction of pixels whose max |a - e| exceeds `threshold`     | value <= tol  |
// | `rel_mean`       | mean |a - e| / max(|e|, epsilon): relative error for HDR      | value <= tol  |
// | `rel_max`        | max  |a - e| / max(|e|, epsilon)                             | value <= tol  |
// | `angular`        | max angle between normals in degrees (mean in the detail)    | value <= tol  |
// | `exact`          | number of pixels with any sample different (integer data)    | value <= tol  |
// | `flip`           | mean LDR-FLIP (Andersson et al. 2020), a perceptual metric   | value <= tol  |
//
// NaN equals NaN and an infinity equals the same infinity; any other pairing with a NaN or an
// infinity is an infinite error. Threading: every function is pure and thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "image/image.h"

namespace rg::golden {

enum class Metric : uint8_t {
    MaxAbs,
    Rmse,
    Psnr,
    OverThreshold,
    RelMean,
    RelMax,
    Angular,
    Exact,
    Flip
};

struct MetricInfo {
    Metric metric;
    const char* name;     // as golden test scripts write it
    bool higherIsBetter;  // only psnr
    const char* meaning;  // one line: what the value and the tolerance mean
};
const std::vector<MetricInfo>& metricInfos();
const char* metricName(Metric m);
std::optional<Metric> parseMetric(std::string_view name);
std::vector<std::string> metricNames();

// How `angular` reads a normal from the compared channels.
enum class NormalEncoding : uint8_t {
    Signed,    // 3 channels, xyz in [-1, 1]
    Unorm,     // 3 channels, xyz * 0.5 + 0.5
    Oct,       // 2 channels, octahedral in [-1, 1]
    OctUnorm,  // 2 channels, octahedral * 0.5 + 0.5 (as a G-buffer stores it)
};
// How `flip` reads colour: linear values (clamped to [0, 1], then seen through the sRGB display
// transfer) or values already sRGB-encoded.
enum class DisplayEncoding : uint8_t { Linear, Srgb };

// FLIP's default observer: a 0.7 m wide 4K monitor seen from 0.7 m, 67 pixels per degree.
inline constexpr double kFlipDefaultPixelsPerDegree =
    0.7 * 3840.0 / 0.7 * 3.14159265358979323846 / 180.0;

// One comparison a golden test states for a capture: the metric, its tolerance and the
// metric's own settings (each used only by the metrics named beside it).
struct Comparison {
    Metric metric = Metric::MaxAbs;
    double tolerance = 0.0;
    std::vector<uint32_t> channels;  // compared channels, e.g. {0, 1, 2}; empty = all of them
    double threshold = 0.0;          // over_threshold: per-pixel max |a - e| that counts as "over"
    double epsilon = 1e-3;           // rel_mean, rel_max: floor of |e| in the denominator
    double peak = 1.0;               // psnr: the peak signal value
    NormalEncoding normals = NormalEncoding::Signed;       // angular
    DisplayEncoding display = DisplayEncoding::Linear;     // flip
    double pixelsPerDegree = kFlipDefaultPixelsPerDegree;  // flip

    // "max_abs <= 0.002", "psnr >= 40 dB", "over_threshold(0.01) <= 0.001"
    std::string describe() const;
};

struct MetricResult {
    std::string metric;  // metric name
    double value = 0.0;
    double tolerance = 0.0;
    bool passed = false;
    std::string detail;  // where it is worst and secondary numbers, e.g. "worst pixel (3, 7): 0.25"
    int32_t worstX = -1, worstY = -1;  // the pixel with the largest error; -1 when all are equal
    Image error;                       // per-pixel error, 1 channel, same size as the images
    float heatScale = 1.0f;  // the error shown at the top of the heat map (flip, exact: 1)

    // "max_abs 0.25 > 0.002" / "psnr inf >= 40 dB"
    std::string verdict() const;
};

// Compares `actual` with `expected`. Errors (InvalidInput) when the sizes or channel counts
// differ, a compared channel does not exist, or the metric cannot read the channels
// (angular: 3 channels, or 2 for octahedral; flip: 1 or 3).
Result<MetricResult> compare(const Image& actual, const Image& expected, const Comparison& c);

// The per-pixel FLIP map (values in [0, 1]) of `test` against `reference`: 1 channel (grey) or
// 3 channels (colour), decoded as `display` says. The pipeline of LDR-FLIP (HPG 2020): CSF
// filtering in YCxCz, Hunt-adjusted L*a*b*, HyAB distance, edge and point features.
Result<Image> flipErrorMap(const Image& reference, const Image& test, DisplayEncoding display,
                           double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

// A heat map of a 1-channel error map: 3 channels in [0, 1] (display values, ready for a PNG)
// through the magma colour map, 0 -> black-violet, `scale` and above -> light yellow.
Image heatMap(const Image& error, float scale);
// The magma colour map at t in [0, 1] (clamped), as display RGB in [0, 1].
void magma(float t, float rgb[3]);

// Rounds to the nearest IEEE 754 binary16 value (ties to even), as a float: what a half-float
// EXR stores. Beyond ±65504 the result is ±inf; NaN stays NaN.
float roundToHalf(float v);
// The binary16 bits of roundToHalf(v), and back.
uint16_t floatToHalfBits(float v);
float halfBitsToFloat(uint16_t h);

// "0.00390625", "inf", "1.2e-07": numbers as reports print them (6 significant digits).
std::string formatNumber(double v);

}  // namespace rg::golden
