// Golden-test metrics without a GPU: every metric and FLIP on synthetic image pairs with known
// answers, the heat map, half-float rounding and number formatting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "golden/golden_test.h"
#include "golden/metrics.h"
#include "metrics_test_util.h"

using namespace rg;
using namespace rg::golden;
using namespace rg::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

MetricResult run(const Image& a, const Image& e, const Comparison& c) {
    auto r = compare(a, e, c);
    EXPECT_TRUE(r.has_value()) << (r ? "" : r.error().message);
    return r ? *r : MetricResult{};
}

// ---- metrics on known pairs ----

TEST(Metrics, MaxAbsFindsTheLargestDifferenceAndWhere) {
    Image e(8, 4, 3), a(8, 4, 3);
    a.at(3, 2, 1) = 0.25f;
    a.at(5, 1, 0) = -0.125f;
    auto r = run(a, e, with(Metric::MaxAbs, 0.25));
    EXPECT_DOUBLE_EQ(r.value, 0.25);
    EXPECT_TRUE(r.passed);
    EXPECT_EQ(r.worstX, 3);
    EXPECT_EQ(r.worstY, 2);
    EXPECT_FLOAT_EQ(r.error.at(5, 1, 0), 0.125f);
    EXPECT_FALSE(run(a, e, with(Metric::MaxAbs, 0.2)).passed);
    EXPECT_EQ(run(a, e, with(Metric::MaxAbs, 0.2)).verdict(), "max_abs 0.25 > 0.2");
}

TEST(Metrics, RmseOfOneDifferingSample) {
    Image e(4, 4, 1), a(4, 4, 1);
    a.at(1, 1, 0) = 1.0f;
    EXPECT_DOUBLE_EQ(run(a, e, with(Metric::Rmse, 1)).value, 0.25);  // sqrt(1 / 16)
    // Over 3 channels: sqrt(1 / 48).
    Image e3(4, 4, 3), a3(4, 4, 3);
    a3.at(2, 3, 2) = 1.0f;
    EXPECT_NEAR(run(a3, e3, with(Metric::Rmse, 1)).value, std::sqrt(1.0 / 48.0), 1e-12);
}

TEST(Metrics, PsnrOfAUniformOffset) {
    Image e = filled(16, 16, 3, 0.5f), a = filled(16, 16, 3, 0.6f);
    auto r = run(a, e, with(Metric::Psnr, 19));
    EXPECT_NEAR(r.value, 20.0, 1e-5);  // MSE = 0.01
    EXPECT_TRUE(r.passed);
    EXPECT_FALSE(run(a, e, with(Metric::Psnr, 21)).passed);  // higher is better
    Comparison c = with(Metric::Psnr, 0);
    c.peak = 2.0;
    EXPECT_NEAR(run(a, e, c).value, 20.0 + 20.0 * std::log10(2.0), 1e-5);
    auto same = run(e, e, with(Metric::Psnr, 1000));
    EXPECT_TRUE(std::isinf(same.value));
    EXPECT_TRUE(same.passed);
    EXPECT_EQ(same.verdict(), "psnr inf >= 1000 dB");
}

TEST(Metrics, OverThresholdCountsPixelsStrictlyAbove) {
    Image e(10, 10, 4), a(10, 10, 4);
    for (uint32_t i = 0; i < 7; ++i) a.at(i, i, i % 4) = 0.02f;
    a.at(9, 0, 0) = 0.01f;  // exactly at the threshold: not over
    Comparison c = with(Metric::OverThreshold, 0.07);
    c.threshold = 0.01;
    auto r = run(a, e, c);
    EXPECT_DOUBLE_EQ(r.value, 0.07);
    EXPECT_TRUE(r.passed);
    c.tolerance = 0.05;
    EXPECT_FALSE(run(a, e, c).passed);
    EXPECT_EQ(c.describe(), "over_threshold(0.01) <= 0.05");
}

TEST(Metrics, RelativeErrorForHdr) {
    Image e = filled(4, 4, 3, 100.0f), a = filled(4, 4, 3, 100.0f);
    a.at(0, 0, 0) = 101.0f;
    EXPECT_NEAR(run(a, e, with(Metric::RelMax, 1)).value, 0.01, 1e-9);
    EXPECT_NEAR(run(a, e, with(Metric::RelMean, 1)).value, 0.01 / 48.0, 1e-9);
    // Near zero the floor epsilon takes over: 1e-4 / max(0, 1e-3) = 0.1.
    Image z(2, 2, 1), zz(2, 2, 1);
    zz.at(1, 1, 0) = 1e-4f;
    EXPECT_NEAR(run(zz, z, with(Metric::RelMax, 1)).value, 0.1, 1e-6);
    Comparison c = with(Metric::RelMax, 1);
    c.epsilon = 1e-2;
    EXPECT_NEAR(run(zz, z, c).value, 0.01, 1e-6);
}

TEST(Metrics, AngularErrorInDegrees) {
    const double t = 10.0 * kPi / 180.0;
    Image e(2, 1, 3), a(2, 1, 3);
    for (uint32_t x = 0; x < 2; ++x) {
        e.at(x, 0, 2) = 1.0f;
        a.at(x, 0, 1) = static_cast<float>(std::sin(x == 0 ? t : t / 2));
        a.at(x, 0, 2) = static_cast<float>(std::cos(x == 0 ? t : t / 2));
    }
    auto r = run(a, e, with(Metric::Angular, 10.001));
    EXPECT_NEAR(r.value, 10.0, 1e-4);
    EXPECT_EQ(r.worstX, 0);
    EXPECT_NE(r.detail.find("mean 7.5"), std::string::npos) << r.detail;
    // Lengths do not matter; the unorm encoding is n * 0.5 + 0.5.
    Image e2(1, 1, 3), a2(1, 1, 3);
    e2.at(0, 0, 0) = 2.0f;  // +x, not normalised
    a2.at(0, 0, 1) = 1.0f;  // +y
    EXPECT_NEAR(run(a2, e2, with(Metric::Angular, 90)).value, 90.0, 1e-9);
    Image eu(1, 1, 3), au(1, 1, 3);
    eu.at(0, 0, 0) = 0.5f, eu.at(0, 0, 1) = 0.5f, eu.at(0, 0, 2) = 1.0f;  // +z
    au.at(0, 0, 0) = 0.5f, au.at(0, 0, 1) = 0.5f, au.at(0, 0, 2) = 0.0f;  // -z
    Comparison cu = with(Metric::Angular, 180);
    cu.normals = NormalEncoding::Unorm;
    EXPECT_NEAR(run(au, eu, cu).value, 180.0, 1e-9);
    // Zero vectors: two agree, one against a normal is 180 degrees off.
    Image z(1, 1, 3);
    EXPECT_DOUBLE_EQ(run(z, z, with(Metric::Angular, 0)).value, 0.0);
    EXPECT_DOUBLE_EQ(run(z, eu, with(Metric::Angular, 0)).value, 180.0);
}

TEST(Metrics, AngularErrorOfOctahedralNormals) {
    // The octahedral map of graph/layout (p = n / |n|_1, folded below the equator), * 0.5 + 0.5.
    auto encode = [](double x, double y, double z, float out[2]) {
        const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
        x /= l1, y /= l1, z /= l1;
        double px = x, py = y;
        if (z < 0)
            px = (1 - std::fabs(y)) * (x >= 0 ? 1 : -1),
            py = (1 - std::fabs(x)) * (y >= 0 ? 1 : -1);
        out[0] = static_cast<float>(px * 0.5 + 0.5);
        out[1] = static_cast<float>(py * 0.5 + 0.5);
    };
    // Two normals in the lower hemisphere (z < 0, where the map folds), 20 degrees apart about y.
    const double t = 20.0 * kPi / 180.0, z0 = -std::sqrt(1 - 0.09);
    Image e(1, 1, 2), a(1, 1, 2);
    float o[2];
    encode(0.3, 0.0, z0, o);
    e.at(0, 0, 0) = o[0], e.at(0, 0, 1) = o[1];
    encode(0.3 * std::cos(t) + z0 * std::sin(t), 0.0, -0.3 * std::sin(t) + z0 * std::cos(t), o);
    a.at(0, 0, 0) = o[0], a.at(0, 0, 1) = o[1];
    Comparison c = with(Metric::Angular, 20.01);
    c.normals = NormalEncoding::OctUnorm;
    EXPECT_NEAR(run(a, e, c).value, 20.0, 1e-4);
    // Three channels are not an octahedral normal.
    c.channels = {0, 1, 2};
    Image e3(1, 1, 3);
    auto bad = compare(e3, e3, c);
    ASSERT_FALSE(bad.has_value());
    EXPECT_EQ(bad.error().message,
              "angular: an octahedral normal needs 2 channels, got 3 (set channels, e.g. 'rg')");
}

TEST(Metrics, ExactCountsDifferingPixels) {
    Image e(5, 5, 1), a(5, 5, 1);
    a.at(1, 2, 0) = 3.0f;
    a.at(4, 4, 0) = 1.0f;
    auto r = run(a, e, with(Metric::Exact, 0));
    EXPECT_DOUBLE_EQ(r.value, 2.0);
    EXPECT_FALSE(r.passed);
    EXPECT_EQ(r.detail, "2 of 25 pixels differ; first at pixel (1, 2): (3) instead of (0)");
    EXPECT_TRUE(run(a, e, with(Metric::Exact, 2)).passed);
    EXPECT_TRUE(run(e, e, with(Metric::Exact, 0)).passed);
}

TEST(Metrics, ChannelsSelectWhatIsCompared) {
    Image e = filled(4, 4, 4, 0.5f), a = e;
    a.at(2, 2, 3) = 0.0f;  // alpha only
    Comparison c = with(Metric::MaxAbs, 0);
    EXPECT_FALSE(run(a, e, c).passed);
    c.channels = *parseChannels("rgb");
    EXPECT_TRUE(run(a, e, c).passed);
    c.channels = *parseChannels("a");
    EXPECT_DOUBLE_EQ(run(a, e, c).value, 0.5);
    Image rg(4, 4, 2);
    c.channels = *parseChannels("rgb");
    auto bad = compare(rg, rg, c);
    ASSERT_FALSE(bad.has_value());
    EXPECT_EQ(bad.error().message, "max_abs: channel B does not exist in a 2-channel image");
}

TEST(Metrics, NanAndInfinityRules) {
    const float nan = std::numeric_limits<float>::quiet_NaN(),
                inf = std::numeric_limits<float>::infinity();
    Image e(3, 1, 1), a(3, 1, 1);
    e.at(0, 0, 0) = nan, a.at(0, 0, 0) = nan;  // NaN = NaN
    e.at(1, 0, 0) = inf, a.at(1, 0, 0) = inf;  // same infinity
    EXPECT_DOUBLE_EQ(run(a, e, with(Metric::MaxAbs, 0)).value, 0.0);
    EXPECT_TRUE(run(a, e, with(Metric::Exact, 0)).passed);
    a.at(2, 0, 0) = nan;  // NaN where a number was expected
    auto r = run(a, e, with(Metric::MaxAbs, 1e30));
    EXPECT_TRUE(std::isinf(r.value));
    EXPECT_FALSE(r.passed);
    EXPECT_EQ(r.worstX, 2);
    a.at(2, 0, 0) = 0.0f;
    a.at(1, 0, 0) = -inf;
    EXPECT_FALSE(run(a, e, with(Metric::RelMax, 1e30)).passed);
}

TEST(Metrics, ImagesOfDifferentShapesAreAnError) {
    auto r = compare(Image(4, 4, 3), Image(4, 2, 3), with(Metric::Rmse, 0));
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message, "rmse: the images differ in shape: actual 4x4x3, expected 4x2x3");
}

// ---- FLIP ----

// CIELAB L* of a linear luminance (Y / Yn), the textbook formula.
double lstar(double y) {
    const double d = 6.0 / 29.0;
    const double f = y > d * d * d ? std::cbrt(y) : y / (3 * d * d) + 4.0 / 29.0;
    return 116.0 * f - 16.0;
}

// FLIP of two uniform grey images from the paper's closed form: no features, so FLIP is the
// colour term: HyAB = |dL*| (greys have a* = b* = 0), compressed with 0.7 and redistributed
// against cmax, the Hunt-adjusted HyAB distance from pure green to pure blue (CIELAB of the
// sRGB primaries: green L 87.737 a -86.185 b 83.181, blue L 32.303 a 79.197 b -107.864).
double flipOfGreys(double linearA, double linearB) {
    const double gL = 87.737, ga = -86.185, gb = 83.181, bL = 32.303, ba = 79.197, bb = -107.864;
    const double hyabGB = std::fabs(gL - bL) + std::hypot(0.01 * gL * ga - 0.01 * bL * ba,
                                                          0.01 * gL * gb - 0.01 * bL * bb);
    const double cmax = std::pow(hyabGB, 0.7);
    const double de = std::pow(std::fabs(lstar(linearA) - lstar(linearB)), 0.7);
    return de < 0.4 * cmax ? 0.95 / (0.4 * cmax) * de
                           : 0.95 + (de - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
}

TEST(Flip, IdenticalImagesScoreZero) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image img(32, 24, 3);
    for (float& v : img.pixels) v = u(rng);
    auto r = run(img, img, with(Metric::Flip, 0));
    EXPECT_DOUBLE_EQ(r.value, 0.0);
    EXPECT_TRUE(r.passed);
}

TEST(Flip, UniformBlackAgainstWhiteMatchesTheClosedForm) {
    auto r = run(filled(24, 24, 3, 1.0f), filled(24, 24, 3, 0.0f), with(Metric::Flip, 1));
    EXPECT_NEAR(r.value, flipOfGreys(1.0, 0.0), 2e-3);
    EXPECT_NEAR(r.value, 0.9674, 2e-3);
    EXPECT_NEAR(r.error.at(0, 0, 0), r.error.at(12, 12, 0), 1e-6);  // uniform: borders replicate
}

TEST(Flip, UniformGreysMatchTheClosedForm) {
    for (auto [a, b] : {std::pair{0.5, 0.45}, std::pair{0.2, 0.21}, std::pair{0.05, 0.5}}) {
        Comparison c = with(Metric::Flip, 1);
        auto r = run(filled(20, 20, 1, float(a)), filled(20, 20, 1, float(b)), c);
        EXPECT_NEAR(r.value, flipOfGreys(a, b), 2e-3) << a << " vs " << b;
    }
    // The same greys given sRGB-encoded read the same.
    Comparison c = with(Metric::Flip, 1);
    c.display = DisplayEncoding::Srgb;
    auto r = run(filled(20, 20, 1, srgbEncode(0.5f)), filled(20, 20, 1, srgbEncode(0.45f)), c);
    EXPECT_NEAR(r.value, flipOfGreys(0.5, 0.45), 2e-3);
}

TEST(Flip, SymmetricAndGrowsWithTheError) {
    std::mt19937 rng(11);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    Image ref(48, 48, 3);
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 48; ++x)
            for (uint32_t k = 0; k < 3; ++k)
                ref.at(x, y, k) = 0.2f + 0.6f * float(x + k * 5) / 60.0f;
    double last = 0.0;
    for (float sigma : {1.0f / 255.0f, 0.02f, 0.08f}) {
        Image test = ref;
        for (float& v : test.pixels) v = std::clamp(v + sigma * noise(rng), 0.0f, 1.0f);
        const double fwd = run(test, ref, with(Metric::Flip, 1)).value,
                     back = run(ref, test, with(Metric::Flip, 1)).value;
        EXPECT_NEAR(fwd, back, 1e-9);
        EXPECT_GT(fwd, last);
        last = fwd;
    }
    EXPECT_GT(last, 0.1);
}

TEST(Flip, OneAndTwoLsbCheckerboardsOnAGradient) {
    // A checkerboard of +1 (+2) 8-bit steps over a ramp: visible to FLIP's feature term, but small.
    auto lsb = [](int k) {
        Image ref(64, 16, 3), test(64, 16, 3);
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                for (uint32_t c = 0; c < 3; ++c) {
                    ref.at(x, y, c) = float(x * 3) / 255.0f;
                    test.at(x, y, c) = float(x * 3 + k * ((x + y) % 2)) / 255.0f;
                }
        Comparison cmp = with(Metric::Flip, 1);
        cmp.display = DisplayEncoding::Srgb;
        return run(test, ref, cmp).value;
    };
    const double one = lsb(1), two = lsb(2);
    EXPECT_GT(one, 0.005);
    EXPECT_LT(one, 0.05);
    EXPECT_GT(two, one);
}

// The pair below was also run through a direct, non-separable transcription of the reference
// LDR-FLIP equations (2D kernels, no shortcuts), which gave mean 0.132605406 and the three
// pixels checked here: the separable filters of flip.cpp compute the same thing.
TEST(Flip, MatchesADirectTranscriptionOfTheEquations) {
    const uint32_t w = 24, h = 20;
    Image a(w, h, 3), b(w, h, 3);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (uint32_t c = 0; c < 3; ++c) {
                const float v = float((x * 7 + y * 13 + c * 5) % 17) / 16.0f;
                a.at(x, y, c) = v;
                double t = v;
                if (x >= 5 && x < 12 && y >= 4 && y < 9) t = std::min(1.0, t + 0.2);
                if ((x + y) % 5 == 0) t *= 0.9;
                b.at(x, y, c) = float(t);
            }
    Comparison c = with(Metric::Flip, 1);
    c.display = DisplayEncoding::Srgb;
    auto r = run(b, a, c);
    EXPECT_NEAR(r.value, 0.132605406, 1e-6);
    EXPECT_NEAR(r.error.at(0, 0, 0), 0.125838819, 1e-6);
    EXPECT_NEAR(r.error.at(7, 5, 0), 0.467730016, 1e-6);
    EXPECT_NEAR(r.error.at(20, 15, 0), 0.100541833, 1e-6);
}

TEST(Flip, AShiftedEdgeIsSeenByTheFeatureTerm) {
    // A black/white edge moved by one pixel: the colour term alone sees a 1-pixel column; the
    // feature term spreads the error around the edge, so FLIP is larger than that column's share.
    Image a(32, 8, 1), b(32, 8, 1);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            a.at(x, y, 0) = x >= 16 ? 1.0f : 0.0f;
            b.at(x, y, 0) = x >= 17 ? 1.0f : 0.0f;
        }
    auto r = run(a, b, with(Metric::Flip, 1));
    int flagged = 0;
    for (uint32_t x = 0; x < 32; ++x) flagged += r.error.at(x, 4, 0) > 0.05f;
    EXPECT_GT(flagged, 1);
    EXPECT_GT(r.error.at(16, 4, 0), 0.5f);
}

TEST(Flip, RejectsWhatItCannotRead) {
    auto r = flipErrorMap(Image(4, 4, 2), Image(4, 4, 2), DisplayEncoding::Linear);
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().message, "flip: compares 1 (grey) or 3 (colour) channels, got 2");
    auto p = flipErrorMap(Image(4, 4, 3), Image(4, 4, 3), DisplayEncoding::Linear, 0.0);
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(p.error().message, "flip: pixels per degree must be in (0, 1000], got 0");
}

// ---- heat map, half floats, numbers ----

TEST(HeatMap, BlackAtZeroLightYellowAtTheScale) {
    Image err(3, 1, 1);
    err.at(1, 0, 0) = 0.5f;
    err.at(2, 0, 0) = 2.0f;  // beyond the scale: clamped
    Image h = heatMap(err, 1.0f);
    ASSERT_EQ(h.channels, 3u);
    EXPECT_NEAR(h.at(0, 0, 0), 0.0f, 1e-6);
    EXPECT_NEAR(h.at(0, 0, 2), 4.0f / 255.0f, 1e-6);
    EXPECT_NEAR(h.at(2, 0, 0), 252.0f / 255.0f, 1e-6);
    EXPECT_NEAR(h.at(2, 0, 1), 253.0f / 255.0f, 1e-6);
    EXPECT_NEAR(h.at(2, 0, 2), 191.0f / 255.0f, 1e-6);
    EXPECT_NEAR(h.at(1, 0, 0), 181.0f / 255.0f, 1e-6);  // magma's midpoint
    // Brightness grows with the error.
    float prev = -1.0f;
    for (int i = 0; i <= 16; ++i) {
        float rgb[3];
        magma(float(i) / 16.0f, rgb);
        const float luma = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
        EXPECT_GT(luma, prev);
        prev = luma;
    }
}

TEST(Half, RoundsToNearestEven) {
    EXPECT_EQ(roundToHalf(1.0f), 1.0f);
    EXPECT_EQ(roundToHalf(1.0f + 1.0f / 2048.0f), 1.0f);  // halfway: to even (1.0)
    EXPECT_EQ(roundToHalf(1.0f + 3.0f / 2048.0f),
              1.0f + 2.0f / 1024.0f);  // halfway: to even (1 + 2^-9)
    EXPECT_EQ(roundToHalf(1.0f + 1.0f / 1500.0f), 1.0f + 1.0f / 1024.0f);
    EXPECT_EQ(roundToHalf(65504.0f), 65504.0f);
    EXPECT_EQ(roundToHalf(65519.0f), 65504.0f);
    EXPECT_TRUE(std::isinf(roundToHalf(65520.0f)));
    EXPECT_EQ(roundToHalf(-2.5f), -2.5f);
    EXPECT_EQ(roundToHalf(std::ldexp(1.0f, -24)), std::ldexp(1.0f, -24));  // smallest subnormal
    EXPECT_EQ(roundToHalf(std::ldexp(1.0f, -25)), 0.0f);                   // halfway to 0: even
    EXPECT_EQ(roundToHalf(std::ldexp(1.5f, -25)), std::ldexp(1.0f, -24));
    EXPECT_EQ(roundToHalf(std::ldexp(3.0f, -24)), std::ldexp(3.0f, -24));
    EXPECT_TRUE(std::isnan(roundToHalf(std::numeric_limits<float>::quiet_NaN())));
    EXPECT_EQ(floatToHalfBits(1.0f), 0x3c00);
    EXPECT_EQ(floatToHalfBits(-0.0f), 0x8000);
    EXPECT_EQ(halfBitsToFloat(0x7bff), 65504.0f);
    for (uint32_t h = 0; h < 0x7c00; ++h)  // every finite half round-trips
        ASSERT_EQ(floatToHalfBits(halfBitsToFloat(static_cast<uint16_t>(h))), h);
}

TEST(Numbers, FormatNumber) {
    EXPECT_EQ(formatNumber(0.00390625), "0.00390625");
    EXPECT_EQ(formatNumber(1.0 / 3.0), "0.333333");
    EXPECT_EQ(formatNumber(1e-7), "1e-07");
    EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "inf");
}

}  // namespace
