// The golden report in a real browser: headless Chromium loads a report with one HDR comparison
// (expected all red, actual all blue), the page's own script moves the swipe slider (?swipe=) and
// the exposure slider (?exposure=), and Chromium takes a screenshot. In the screenshot, the swipe
// view must show red left of the split and blue right of it, the split where the slider put it,
// and colours at the exposure asked for. Skipped, with a message, where Chromium is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "golden/metrics.h"
#include "golden/report.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::golden;

namespace {

// RG_CHROMIUM, else the first of the usual names on PATH.
std::string findChromium() {
    if (const char* c = std::getenv("RG_CHROMIUM"); c && *c) return c;
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
        const char* path = std::getenv("PATH");
        std::string dirs = path ? path : "/usr/bin:/bin";
        size_t start = 0;
        while (start <= dirs.size()) {
            const size_t end = dirs.find(':', start);
            const std::string dir =
                dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
            const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
            std::error_code ec;
            if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
                return candidate.string();
            if (end == std::string::npos) break;
            start = end + 1;
        }
    }
    return "";
}

const std::string kTmp = std::string(RG_TEST_TMP) + "/report";

// One report: test "swipe", capture "hdr" (linear, 64 x 48): expected red 1.0, actual blue 1.0.
std::string writeReport() {
    RunReport run;
    run.environment.device = "test device";
    run.profile = "none";
    TestOutcome t;
    t.name = "swipe";
    t.status = TestStatus::Failed;
    t.width = 64;
    t.height = 48;
    t.frames = 1;
    t.firstDivergent = "hdr";
    t.message = "first divergent resource in pipeline order: 'hdr'";
    CaptureOutcome c;
    c.resource = "hdr";
    c.format = "rgba16f";
    c.storage = Storage::ExrHalf;
    c.expected = Image(64, 48, 4);
    c.actual = Image(64, 48, 4);
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            c.expected.at(x, y, 0) = 1.0f;
            c.actual.at(x, y, 2) = 1.0f;
            c.expected.at(x, y, 3) = c.actual.at(x, y, 3) = 1.0f;
        }
    ComparisonOutcome cmp;
    cmp.spec.metric = Metric::MaxAbs;
    cmp.result = *compare(c.actual, c.expected, cmp.spec);
    c.comparisons = {cmp};
    t.captures = {c};
    TestOutcome other = t;  // a second test, hidden by ?test=swipe
    other.name = "other";
    run.tests = {t, other};
    const std::string dir = kTmp + "/site";
    fs::remove_all(dir);
    auto r = writeHtmlReport(dir, run);
    EXPECT_TRUE(r.has_value()) << (r ? "" : r.error().message);
    return dir + "/index.html";
}

// Screenshots `page?query` with a fresh profile; the flags keep Chromium off the network.
std::optional<Image> screenshot(const std::string& chromium, const std::string& page,
                                const std::string& query, const std::string& name) {
    const std::string shot = kTmp + "/" + name + ".png", profile = kTmp + "/profile-" + name;
    fs::remove_all(profile);
    fs::remove(shot);
    const std::string cmd =
        "timeout 120 '" + chromium +
        "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
        "--disable-background-networking --disable-component-update --disable-sync "
        "--hide-scrollbars --force-device-scale-factor=1 --window-size=1400,1000 "
        "--user-data-dir='" +
        profile + "' --screenshot='" + shot + "' 'file://" + page + "?" + query + "' >'" + kTmp +
        "/" + name + ".log' 2>&1";
    const int rc = std::system(cmd.c_str());
    EXPECT_EQ(rc, 0) << cmd;
    auto img = readPng(shot);
    EXPECT_TRUE(img.has_value()) << (img ? "" : img.error().message) << " (see " << kTmp << "/"
                                 << name << ".log)";
    if (!img) return std::nullopt;
    return *img;
}

struct Split {
    int left = -1, split = -1,
        right = -1;  // the swipe view's left edge, the split, its right edge (pixels)
    int rows = 0;    // rows that show it
    double fraction() const { return double(split - left) / double(right - left); }
};

// Finds the swipe view: rows where a run of `isLeft` pixels ends within 3 pixels of a run of
// `isRight` pixels (the divider line sits between them; the expected and actual figures beside
// the swipe view are 24 pixels apart, so they never match). The right run may be crossed by the
// divider (2 pixels at most).
template <class L, class R>
Split findSplit(const Image& img, L isLeft, R isRight) {
    Split s;
    for (uint32_t y = 0; y < img.height; ++y) {
        int runStart = -1;
        for (uint32_t x = 0; x <= img.width; ++x) {
            if (x < img.width && isLeft(img, x, y)) {
                if (runStart < 0) runStart = static_cast<int>(x);
                continue;
            }
            if (runStart >= 0 && static_cast<int>(x) - runStart >= 8) {
                uint32_t g = x;
                while (g < std::min<uint32_t>(x + 4, img.width) && !isRight(img, g, y)) ++g;
                uint32_t e = g, gap = 0;
                for (uint32_t k = g; k < img.width; ++k) {
                    if (isRight(img, k, y))
                        e = k + 1, gap = 0;
                    else if (++gap > 2)
                        break;
                }
                if (g < img.width && isRight(img, g, y) && e - g >= 8) {
                    s.left = runStart;
                    s.split = static_cast<int>(x);
                    s.right = static_cast<int>(e);
                    ++s.rows;
                }
            }
            runStart = -1;
        }
    }
    return s;
}

int byte(const Image& img, uint32_t x, uint32_t y, uint32_t c) {
    return static_cast<int>(std::lround(img.at(x, y, c) * 255.0f));
}

TEST(GoldenReport, SwipeAndExposureSlidersInChromium) {
    const std::string chromium = findChromium();
    if (chromium.empty())
        GTEST_SKIP()
            << "Chromium not found (install the Debian package 'chromium', or set RG_CHROMIUM)";
    fs::create_directories(kTmp);
    const std::string page = writeReport();

    auto red = [](const Image& i, uint32_t x, uint32_t y) {
        return byte(i, x, y, 0) > 240 && byte(i, x, y, 1) < 20 && byte(i, x, y, 2) < 20;
    };
    auto blue = [](const Image& i, uint32_t x, uint32_t y) {
        return byte(i, x, y, 2) > 240 && byte(i, x, y, 0) < 20 && byte(i, x, y, 1) < 20;
    };
    // 64 x 48 at 4x: the swipe view is 256 x 192 pixels.
    for (double t : {0.3, 0.7}) {
        auto img = screenshot(chromium, page, "test=swipe&swipe=" + std::to_string(t),
                              "swipe-" + std::to_string(int(t * 10)));
        ASSERT_TRUE(img.has_value());
        const Split s = findSplit(*img, red, blue);
        ASSERT_GT(s.rows, 150) << "no swipe view with red left and blue right at swipe=" << t;
        EXPECT_NEAR(s.right - s.left, 256, 2);
        EXPECT_NEAR(s.fraction(), t, 0.01)
            << "split at " << s.split << " in [" << s.left << ", " << s.right << ")";
    }

    // Exposure -2 EV: 1.0 shows as 0.25 linear, sRGB 137.
    auto dim = screenshot(chromium, page, "test=swipe&swipe=0.5&exposure=-2", "exposure");
    ASSERT_TRUE(dim.has_value());
    auto dimRed = [](const Image& i, uint32_t x, uint32_t y) {
        return std::abs(byte(i, x, y, 0) - 137) <= 2 && byte(i, x, y, 1) < 10 &&
               byte(i, x, y, 2) < 10;
    };
    auto dimBlue = [](const Image& i, uint32_t x, uint32_t y) {
        return std::abs(byte(i, x, y, 2) - 137) <= 2 && byte(i, x, y, 0) < 10 &&
               byte(i, x, y, 1) < 10;
    };
    const Split s = findSplit(*dim, dimRed, dimBlue);
    ASSERT_GT(s.rows, 150) << "no swipe view at -2 EV (expected sRGB 137 red | blue)";
    EXPECT_NEAR(s.fraction(), 0.5, 0.01);
    // And the full-brightness colours are gone from the swipe view.
    EXPECT_EQ(findSplit(*dim, red, blue).rows, 0);
}

}  // namespace
