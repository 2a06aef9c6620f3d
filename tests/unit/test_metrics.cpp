// Golden-test machinery without a GPU: every metric on synthetic image pairs with known answers,
// the heat map, half-float rounding, golden storage round trips, golden test scripts and their
// errors (exact texts), the frame callback's ctx, and the report / JUnit writers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "golden/golden_test.h"
#include "golden/metrics.h"
#include "golden/report.h"
#include "golden/storage.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::golden;

namespace {

constexpr double kPi = 3.14159265358979323846;

Image filled(uint32_t w, uint32_t h, uint32_t c, float v) {
    Image img(w, h, c);
    std::fill(img.pixels.begin(), img.pixels.end(), v);
    return img;
}

Comparison with(Metric m, double tolerance) {
    Comparison c;
    c.metric = m;
    c.tolerance = tolerance;
    return c;
}

MetricResult run(const Image& a, const Image& e, const Comparison& c) {
    auto r = compare(a, e, c);
    EXPECT_TRUE(r.has_value()) << (r ? "" : r.error().message);
    return r ? *r : MetricResult{};
}

std::string tmpDir(const std::string& name) {
    const std::string dir = std::string(RG_TEST_TMP) + "/metrics/" + name;
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    return dir;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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

// ---- golden storage ----

// What comparisons assume: quantizeForStorage is exactly what a write and a read give back.
TEST(Storage, QuantisingMatchesTheFileRoundTrip) {
    const std::string dir = tmpDir("storage");
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.2f, 1.3f);
    struct Case {
        std::string format;
        uint32_t channels;
        float scale;
    };
    for (const Case& c : {Case{"rgba8", 4, 1.0f}, Case{"rgba8_srgb", 4, 1.0f}, Case{"r8", 1, 1.0f},
                          Case{"rgba16f", 4, 500.0f}, Case{"rg16f", 2, 1e-3f},
                          Case{"rgba32f", 4, 1e5f}, Case{"r32ui", 1, 1e4f}}) {
        Image img(13, 7, c.channels);
        for (float& v : img.pixels) v = u(rng) * c.scale;
        if (c.format == "r32ui")
            for (float& v : img.pixels) v = std::round(std::fabs(v));
        const Storage s = storageForFormat(c.format);
        const bool srgb = isSrgbFormat(c.format);
        const std::string path = dir + "/" + c.format + storageExtension(s);
        ASSERT_TRUE(writeStored(path, img, s, srgb).has_value()) << c.format;
        auto back = readStored(path, s, srgb);
        ASSERT_TRUE(back.has_value()) << back.error().message;
        const Image q = quantizeForStorage(img, s, srgb);
        ASSERT_EQ(back->channels, q.channels) << c.format;
        for (size_t i = 0; i < q.pixels.size(); ++i)
            ASSERT_EQ(back->pixels[i], q.pixels[i]) << c.format << " sample " << i;
        // Quantising twice changes nothing.
        EXPECT_EQ(quantizeForStorage(q, s, srgb).pixels, q.pixels) << c.format;
    }
    EXPECT_EQ(storageForFormat("rgba16f"), Storage::ExrHalf);
    EXPECT_EQ(storageForFormat("rgba8"), Storage::Png);
    EXPECT_EQ(storageForFormat("rgb10a2"), Storage::ExrFloat);
    EXPECT_EQ(storageForFormat("buffer:float32"), Storage::ExrFloat);
}

// ---- golden test scripts ----

std::string writeScript(const std::string& name, const std::string& text) {
    const std::string dir = std::string(RG_TEST_TMP) + "/metrics/scripts";
    fs::create_directories(dir);
    const std::string path = dir + "/" + name + ".lua";
    std::ofstream(path) << text;
    return path;
}

Result<std::unique_ptr<GoldenScript>> loadScript(const std::string& name, const std::string& text) {
    return GoldenScript::load(writeScript(name, text), name + ".lua");
}

std::string loadError(const std::string& name, const std::string& text) {
    auto s = loadScript(name, text);
    EXPECT_FALSE(s.has_value()) << name << " loaded but should not";
    if (s) return "";
    const std::string& m = s.error().message;
    return m.substr(0, m.find('\n'));  // without the traceback
}

const std::string kGood = R"(return {
    doc = "a test",
    pipeline = "scripts/pipelines/test.lua",
    size = { 64, 32 },
    frames = 3,
    params = { scale = 0.5 },
    captures = {
        output = { metric = "psnr", tolerance = 40 },
        pattern = { { metric = "max_abs", tolerance = 0 }, { metric = "flip", tolerance = 0.01, display = "srgb", channels = "rgb" } },
        ids = { metric = "exact" },
        n = { metric = "angular", encoding = "oct_unorm", channels = "rg", tolerance = 0.1 },
        o = { metric = "over_threshold", threshold = 1 / 255, tolerance = 0.001 },
    },
})";

TEST(GoldenScripts, AValidTestIsParsed) {
    auto s = loadScript("good", kGood);
    ASSERT_TRUE(s.has_value()) << s.error().message;
    const GoldenTest& t = (*s)->test();
    EXPECT_EQ(t.name, "good");
    EXPECT_EQ(t.golden, "good");
    EXPECT_EQ(t.pipeline, "scripts/pipelines/test.lua");
    EXPECT_EQ(t.width, 64u);
    EXPECT_EQ(t.height, 32u);
    EXPECT_EQ(t.frames, 3u);
    EXPECT_FALSE(t.hasFrameCallback);
    EXPECT_DOUBLE_EQ(t.params.at("scale").asNumber(), 0.5);
    ASSERT_EQ(t.captures.size(), 5u);
    std::map<std::string, CaptureSpec> byName;
    for (const auto& c : t.captures) byName[c.resource] = c;
    EXPECT_EQ(byName["output"].comparisons[0].metric, Metric::Psnr);
    EXPECT_DOUBLE_EQ(byName["output"].comparisons[0].tolerance, 40.0);
    ASSERT_EQ(byName["pattern"].comparisons.size(), 2u);
    EXPECT_EQ(byName["pattern"].comparisons[1].display, DisplayEncoding::Srgb);
    EXPECT_EQ(byName["pattern"].comparisons[1].channels, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(byName["ids"].comparisons[0].metric, Metric::Exact);
    EXPECT_DOUBLE_EQ(byName["ids"].comparisons[0].tolerance, 0.0);
    EXPECT_EQ(byName["n"].comparisons[0].normals, NormalEncoding::OctUnorm);
    EXPECT_NEAR(byName["o"].comparisons[0].threshold, 1.0 / 255.0, 1e-12);
}

TEST(GoldenScripts, EachKindOfMistakeHasItsMessage) {
    auto replace = [](std::string text, const std::string& from, const std::string& to) {
        auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    };
    EXPECT_EQ(loadError("syntax", "return { size = { 1, 2 }"),
              "syntax.lua:1: '}' expected near <eof>");
    EXPECT_EQ(loadError("not_a_table", "return 42"),
              "not_a_table.lua: a golden test script returns a table { pipeline = ..., size = ..., "
              "captures = ... }, got 42");
    EXPECT_EQ(loadError("unknown", replace(kGood, "frames = 3", "frmes = 3")),
              "unknown.lua: frmes: unknown field (did you mean 'frames'?); expected one of: 'doc', "
              "'pipeline', 'scene', "
              "'camera', 'size', 'frames', 'params', 'frame', 'golden', 'captures'");
    EXPECT_EQ(loadError("too_big", replace(kGood, "{ 64, 32 }", "{ 512, 32 }")),
              "too_big.lua: size[1]: expected a whole number in [1, 256], got 512");
    EXPECT_EQ(loadError("size_shape", replace(kGood, "{ 64, 32 }", "\"64x32\"")),
              "size_shape.lua: size: expected { width, height }, got '64x32'");
    EXPECT_EQ(loadError("frames", replace(kGood, "frames = 3", "frames = 0")),
              "frames.lua: frames: expected a whole number in [1, 1000], got 0");
    EXPECT_EQ(
        loadError("no_pipeline", replace(kGood, "pipeline = \"scripts/pipelines/test.lua\",", "")),
        "no_pipeline.lua: pipeline: missing: the pipeline script to render (e.g. "
        "'scripts/pipelines/test.lua')");
    EXPECT_EQ(
        loadError("metric", replace(kGood, "\"psnr\"", "\"psnrr\"")),
        "metric.lua: captures.output.metric: unknown metric 'psnrr' (did you mean 'psnr'?); "
        "expected one of: 'max_abs', "
        "'rmse', 'psnr', 'over_threshold', 'rel_mean', 'rel_max', 'angular', 'exact', 'flip'");
    EXPECT_EQ(loadError("tolerance",
                        replace(kGood, "metric = \"psnr\", tolerance = 40", "metric = \"psnr\"")),
              "tolerance.lua: captures.output.tolerance: missing: metric 'psnr' needs one (peak "
              "signal-to-noise ratio in dB; the "
              "tolerance is the least PSNR allowed)");
    EXPECT_EQ(loadError("negative", replace(kGood, "tolerance = 0 }", "tolerance = -1 }")),
              "negative.lua: captures.pattern[1].tolerance: must not be negative, got -1");
    EXPECT_EQ(loadError("threshold", replace(kGood, "threshold = 1 / 255, ", "")),
              "threshold.lua: captures.o.threshold: missing: over_threshold counts pixels whose "
              "difference exceeds it");
    EXPECT_EQ(loadError("misplaced",
                        replace(kGood, "metric = \"exact\"", "metric = \"exact\", threshold = 1")),
              "misplaced.lua: captures.ids.threshold: metric 'exact' does not use 'threshold'; its "
              "fields: 'metric', 'tolerance', "
              "'channels'");
    EXPECT_EQ(loadError("channels", replace(kGood, "channels = \"rgb\"", "channels = \"rgx\"")),
              "channels.lua: captures.pattern[2].channels: expected letters of 'rgba' such as "
              "'rgb', got 'rgx'");
    EXPECT_EQ(loadError("oct", replace(kGood, "channels = \"rg\"", "channels = \"rgb\"")),
              "oct.lua: captures.n.channels: an octahedral normal needs 2 channels, got 'rgb'");
    EXPECT_EQ(loadError("encoding", replace(kGood, "\"oct_unorm\"", "\"octa\"")),
              "encoding.lua: captures.n.encoding: expected one of: 'signed', 'unorm', 'oct', "
              "'oct_unorm', got 'octa'");
    EXPECT_EQ(loadError("empty", "return { pipeline = 'p.lua', size = { 8, 8 }, captures = {} }"),
              "empty.lua: captures: expected a table { resource = { metric = ..., tolerance = ... "
              "} } with at least one entry, got "
              "table");
    EXPECT_EQ(loadError("camera", replace(kGood, "frames = 3,", "frames = 3, camera = \"main\",")),
              "camera.lua: camera: names a camera of the scene: set 'scene' too");
    EXPECT_EQ(loadError("golden", replace(kGood, "frames = 3,", "frames = 3, golden = \"../x\",")),
              "golden.lua: golden: expected the name of another golden test, got '../x'");
    EXPECT_EQ(loadError("function", replace(kGood, "doc = \"a test\"", "doc = function() end")),
              "function.lua: doc: a function is not allowed here (only the top-level 'frame' is a "
              "function)");
    EXPECT_EQ(loadError("frame_type", replace(kGood, "frames = 3,", "frames = 3, frame = 5,")),
              "frame_type.lua: frame: expected a function(ctx), got number");
    EXPECT_EQ(loadError("mixed", replace(kGood, "{ 64, 32 }", "{ 64, 32, w = 1 }")),
              "mixed.lua: size: mixes list entries and named fields");
}

TEST(GoldenScripts, TheSandboxHoldsAndLimitsStopRunaways) {
    EXPECT_EQ(loadError("io", "local f = io.open('/etc/passwd') return {}"),
              "io.lua:1: attempt to index a nil value (global 'io')");
    EXPECT_EQ(loadError("load", "load('return 1') return {}"),
              "load.lua:1: load is not available to golden test scripts (sandbox)");
    EXPECT_EQ(loadError("require", "require 'rg' return {}"),
              "require.lua:1: require is not available to golden test scripts (sandbox)");
    EXPECT_EQ(loadError("os", "os.execute('touch /tmp/x') return {}"),
              "os.lua:1: attempt to index a nil value (global 'os')");
    GoldenScript::Limits small;
    small.instructions = 2'000'000;
    auto s = GoldenScript::load(writeScript("runaway", "while true do end"), "runaway.lua", small);
    ASSERT_FALSE(s.has_value());
    EXPECT_EQ(s.error().message.substr(0, s.error().message.find('\n')),
              "runaway.lua:1: golden test script stopped after 2 million instructions: a runaway "
              "loop? (limit: 2 million)");
    small.memoryBytes = 8u << 20;
    auto m = GoldenScript::load(
        writeScript("hog", "local t = {} for i = 1, 1e8 do t[i] = i end return {}"), "hog.lua",
        small);
    ASSERT_FALSE(m.has_value());
    EXPECT_NE(m.error().message.find(
                  "hog.lua:1: golden test script stopped: it used more than 8 MiB of Lua memory"),
              std::string::npos)
        << m.error().message;
    auto missing = GoldenScript::load("/nonexistent/x.lua", "x.lua");
    ASSERT_FALSE(missing.has_value());
    EXPECT_EQ(missing.error().message, "cannot open golden test script '/nonexistent/x.lua'");
}

// A pipeline as the frame callback sees it: two parameters and two passes.
PipelineDesc fakePipeline() {
    PipelineDesc p;
    ParamDesc scale;
    scale.name = "scale";
    scale.type = ParamType::Number;
    scale.value = Value(1.0);
    scale.min = 0;
    scale.max = 16;
    ParamDesc mode;
    mode.name = "mode";
    mode.type = ParamType::Choice;
    mode.value = Value("a");
    mode.choices = {"a", "b"};
    p.params = {scale, mode};
    PassDesc gen;
    gen.name = "generate";
    gen.kind = "compute";
    gen.params = Value(Value::Table{{"shader", Value("test/pattern.comp")}});
    PassDesc tint;
    tint.name = "tint";
    tint.kind = "fullscreen";
    tint.params = Value(Value::Table{{"shader", Value("test/tint.frag")}});
    p.graph.passes = {gen, tint};
    return p;
}

TEST(GoldenScripts, TheFrameCallbackChangesParametersAndPasses) {
    auto s = loadScript("frames", R"(return {
    pipeline = "p.lua", size = { 8, 8 }, frames = 4, captures = { output = { metric = "exact" } },
    frame = function(ctx)
        if ctx.frame == 1 then ctx.params.scale = ctx.params.scale * 0.5 end
        if ctx.frame == 2 then ctx.pass("tint").enabled = false; ctx.params.mode = "b" end
        if ctx.frame == 3 then ctx.pass("generate").shader = "other.comp" end
    end,
})");
    ASSERT_TRUE(s.has_value()) << s.error().message;
    EXPECT_TRUE((*s)->test().hasFrameCallback);
    const PipelineDesc p = fakePipeline();
    auto f0 = (*s)->frame({0, 0.0}, p);
    ASSERT_TRUE(f0.has_value()) << f0.error().message;
    EXPECT_TRUE(f0->empty());
    auto f1 = (*s)->frame({1, 1.0 / 60}, p);
    ASSERT_TRUE(f1.has_value()) << f1.error().message;
    EXPECT_DOUBLE_EQ(f1->params.at("scale").asNumber(), 0.5);
    EXPECT_FALSE(f1->structural());
    auto f2 = (*s)->frame({2, 2.0 / 60}, p);
    ASSERT_TRUE(f2.has_value()) << f2.error().message;
    EXPECT_EQ(f2->enabled.at("tint"), false);
    EXPECT_EQ(f2->params.at("mode").asString(), "b");
    auto f3 = (*s)->frame({3, 3.0 / 60}, p);
    ASSERT_TRUE(f3.has_value()) << f3.error().message;
    EXPECT_EQ(f3->shaders.at("generate"), "other.comp");
}

TEST(GoldenScripts, FrameCallbackErrorsNameTheLine) {
    auto frameError = [](const std::string& name, const std::string& body) {
        auto s = loadScript(name,
                            "return { pipeline = 'p.lua', size = { 8, 8 }, captures = { o = { "
                            "metric = 'exact' } },\n"
                            "frame = function(ctx)\n" +
                                body + "\nend }");
        EXPECT_TRUE(s.has_value()) << (s ? "" : s.error().message);
        if (!s) return std::string();
        auto r = (*s)->frame({0, 0.0}, fakePipeline());
        EXPECT_FALSE(r.has_value());
        return r ? std::string() : r.error().message.substr(0, r.error().message.find('\n'));
    };
    EXPECT_EQ(frameError("unknown_param", "ctx.params.scal = 1"),
              "unknown_param.lua:3: ctx.params: unknown parameter 'scal' (did you mean 'scale'?)");
    EXPECT_EQ(frameError("range", "ctx.params.scale = 20"),
              "range.lua:3: ctx.params: parameter 'scale' expects a number in [0, 16], got 20");
    EXPECT_EQ(frameError("choice", "ctx.params.mode = 'c'"),
              "choice.lua:3: ctx.params: parameter 'mode' expects one of 'a', 'b', got 'c'");
    EXPECT_EQ(frameError("unknown_pass", "ctx.pass('tnt').enabled = false"),
              "unknown_pass.lua:3: ctx.pass: unknown pass 'tnt' (did you mean 'tint'?)");
    EXPECT_EQ(frameError("enabled_type", "ctx.pass('tint').enabled = 1"),
              "enabled_type.lua:3: ctx.pass('tint').enabled: expected a boolean, got number");
    EXPECT_EQ(frameError("runtime", "local x = nil; x.y = 1"),
              "runtime.lua:3: attempt to index a nil value (local 'x')");
}

TEST(GoldenScripts, FindingTestsByPattern) {
    EXPECT_TRUE(matchesPattern("shading", ""));
    EXPECT_TRUE(matchesPattern("shading", "shading"));
    EXPECT_FALSE(matchesPattern("shading_sun", "shading"));
    EXPECT_TRUE(matchesPattern("shading_sun", "shading*"));
    EXPECT_TRUE(matchesPattern("deferred_pipeline", "*pipe*"));
    EXPECT_FALSE(matchesPattern("test_pipeline", "deferred_*"));
    const std::string dir = tmpDir("find");
    for (const char* n : {"b.lua", "a.lua", "a_two.lua", "notes.txt"})
        std::ofstream(dir + "/" + n) << "return {}";
    fs::create_directories(dir + "/sub");
    std::ofstream(dir + "/sub/c.lua") << "return {}";
    auto all = findGoldenTests(dir, "");
    ASSERT_TRUE(all.has_value());
    ASSERT_EQ(all->size(), 3u);
    EXPECT_EQ(fs::path((*all)[0]).filename(), "a.lua");
    EXPECT_EQ(fs::path((*all)[2]).filename(), "b.lua");
    auto some = findGoldenTests(dir, "a*");
    ASSERT_TRUE(some.has_value());
    EXPECT_EQ(some->size(), 2u);
    auto none = findGoldenTests(dir + "/missing", "");
    ASSERT_FALSE(none.has_value());
    EXPECT_EQ(none.error().message, "no golden test folder '" + dir + "/missing'");
}

// ---- report and JUnit ----

RunReport sampleReport() {
    RunReport run;
    run.environment.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
    run.environment.driver = "llvmpipe Mesa 22.3.6";
    run.profile = "LP_NUM_THREADS=2";
    run.seconds = 1.5;
    TestOutcome pass;
    pass.name = "good";
    pass.status = TestStatus::Passed;
    pass.width = pass.height = 4;
    pass.frames = 1;
    CaptureOutcome c;
    c.resource = "output";
    c.format = "rgba16f";
    c.actual = filled(4, 4, 4, 0.5f);
    c.expected = c.actual;
    ComparisonOutcome cmp;
    cmp.spec = with(Metric::MaxAbs, 0);
    cmp.result = *compare(c.actual, c.expected, cmp.spec);
    c.comparisons = {cmp};
    c.passed = true;
    pass.captures = {c};
    TestOutcome bad = pass;
    bad.name = "bad <one> & \"two\"";
    bad.status = TestStatus::Failed;
    bad.captures[0].actual.at(1, 1, 0) = 1.0f;
    bad.captures[0].comparisons[0].result =
        *compare(bad.captures[0].actual, bad.captures[0].expected, cmp.spec);
    bad.captures[0].passed = false;
    bad.firstDivergent = "output";
    bad.message = "first divergent resource in pipeline order: 'output'";
    TestOutcome err;
    err.name = "broken";
    err.status = TestStatus::Error;
    err.message = "broken.lua:1: unexpected symbol";
    run.tests = {pass, bad, err};
    return run;
}

TEST(Report, HtmlHasEveryTestItsMetricsAndTheViews) {
    const std::string dir = tmpDir("report");
    ASSERT_TRUE(writeHtmlReport(dir, sampleReport()).has_value());
    const std::string html = readFile(dir + "/index.html");
    EXPECT_NE(html.find("rgraph golden tests: 1 passed, 1 failed, 1 errors"), std::string::npos);
    EXPECT_NE(html.find("bad &lt;one&gt; &amp; &quot;two&quot;"), std::string::npos);  // escaped
    EXPECT_EQ(html.find("bad <one>"), std::string::npos);
    EXPECT_NE(html.find("first divergent resource in pipeline order"), std::string::npos);
    EXPECT_NE(html.find("class=\"swipebox\""), std::string::npos);
    EXPECT_NE(html.find("class=\"exposure\""), std::string::npos);
    EXPECT_NE(html.find("diff: max_abs"), std::string::npos);
    EXPECT_NE(html.find("broken.lua:1: unexpected symbol"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos);  // nothing to fetch: works offline
}

TEST(Report, JunitCountsFailuresAndErrors) {
    const std::string dir = tmpDir("junit");
    ASSERT_TRUE(writeJunit(dir + "/golden.xml", sampleReport()).has_value());
    const std::string xml = readFile(dir + "/golden.xml");
    EXPECT_NE(xml.find("<testsuite name=\"golden\" tests=\"3\" failures=\"1\" errors=\"1\""),
              std::string::npos)
        << xml;
    EXPECT_NE(
        xml.find("<testcase classname=\"golden\" name=\"bad &lt;one&gt; &amp; &quot;two&quot;\""),
        std::string::npos);
    EXPECT_NE(
        xml.find(
            "<failure message=\"first divergent resource in pipeline order: &apos;output&apos;\">"),
        std::string::npos);
    EXPECT_NE(xml.find("<error message=\"broken.lua:1: unexpected symbol\">"), std::string::npos);
    EXPECT_NE(xml.find("output: max_abs 0.5 &gt; 0 FAIL"), std::string::npos);
}

TEST(Report, Base64) {
    const uint8_t man[] = {'M', 'a', 'n'};
    EXPECT_EQ(base64Encode(man, 3), "TWFu");
    EXPECT_EQ(base64Encode(man, 2), "TWE=");
    EXPECT_EQ(base64Encode(man, 1), "TQ==");
    EXPECT_EQ(base64Encode(man, 0), "");
}

}  // namespace
