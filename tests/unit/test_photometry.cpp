// The physical camera against the seeds' numbers (seed 000 eq:11, eq:12, tbl:7; seed 002 §5.1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/light_units.h"
#include "core/photometry.h"

using namespace rg::photometry;

TEST(Photometry, Ev100FromCameraSettings) {
    EXPECT_NEAR(ev100FromCamera(16, 1.0 / 125, 100), 14.966, 0.0005);  // Sunny 16
    EXPECT_NEAR(ev100FromCamera(16, 1.0 / 100, 100), 14.644, 0.0005);
    EXPECT_NEAR(ev100FromCamera(16, 1.0 / 125, 200), 13.966, 0.0005);       // one stop more gain
    EXPECT_NEAR(ev100FromCamera(16, 1.0 / 125, 100, 1.0), 13.966, 0.0005);  // EC = +1 over-exposes
}

TEST(Photometry, ExposureIsTheInverseOfTheSaturationLuminance) {
    EXPECT_NEAR(exposureFromEv100(ev100FromCamera(16, 1.0 / 125, 100)), 2.604e-5, 0.0005e-5);
    // L_max = 78 / (S q) · N² / t with q = 0.65 (seed 002 §5.1.2).
    const double lmax = 78.0 / (100 * 0.65) * 16 * 16 * 125;
    EXPECT_NEAR(exposureFromEv100(ev100FromCamera(16, 1.0 / 125, 100)), 1.0 / lmax, 1e-12);
}

TEST(Photometry, LuminanceOfEv100MatchesTable7) {
    // seed 000 tbl:7: EV100 -4..16 and the luminance (cd/m²) the table prints, rounded by it.
    const double table[] = {0.008, 0.016, 0.031, 0.063, 0.125, 0.25, 0.5,  1,    2,    4,   8,
                            16,    32,    64,    128,   256,   512,  1024, 2048, 4096, 8192};
    for (int ev = -4; ev <= 16; ++ev) {
        const double printed = table[ev + 4];
        const double places = printed < 0.1 ? 0.0005 : 1e-9;  // the table keeps three decimals
        EXPECT_NEAR(luminanceFromEv100(ev), printed, places + printed * 1e-9) << "EV100 " << ev;
        EXPECT_NEAR(ev100FromLuminance(luminanceFromEv100(ev)), ev, 1e-12);
    }
}

TEST(Photometry, MeteringUsesK12_5) {
    // eq:11 with S = 100: a meter reading 1000 cd/m² says EV100 = log2(1000 · 100 / 12.5).
    EXPECT_NEAR(ev100FromLuminance(1000), std::log2(8000.0), 1e-12);
    EXPECT_NEAR(ev100FromLuminance(12.5 / 100 * 1024), 10.0, 1e-12);
}

TEST(Photometry, BloomLuminanceIsRelativeToTheCurrentEv) {
    // seed 002 §5.1.3: colour · 2^(EV + bloomEC − 3); at EC 0 it is the luminance of the EV.
    EXPECT_NEAR(bloomLuminance(1.0, 0.0, 10.0), luminanceFromEv100(10.0), 1e-12);
    EXPECT_NEAR(bloomLuminance(0.5, -2.0, 10.0), 0.5 * luminanceFromEv100(8.0), 1e-12);
}

// Colour temperature (seed 000 tbl:4) against the CIE's illuminants: A is a black body at 2856 K,
// D65 the daylight illuminant of CCT 6504 K (off the black body's locus: 6504 K there is 5e-3
// greener in y). xy within 1e-3; and the ranges are exactly those the fits cover.
TEST(ColourTemperature, MatchesCieIlluminantsAAndD65) {
    using namespace rg::lights;
    const auto a = colorTemperatureXy(2856.0);
    EXPECT_NEAR(a[0], 0.44757, 1e-3);
    EXPECT_NEAR(a[1], 0.40745, 1e-3);
    const auto d65 = colorTemperatureXy(6504.0, /*daylight=*/true);
    EXPECT_NEAR(d65[0], 0.31271, 1e-3);
    EXPECT_NEAR(d65[1], 0.32902, 1e-3);
    const auto planck6504 = colorTemperatureXy(6504.0);
    EXPECT_GT(std::abs(planck6504[1] - 0.32902), 3e-3);  // the black body at 6504 K is not D65
    std::printf(
        "A: xy %.5f %.5f (CIE 0.44757 0.40745); D65: %.5f %.5f (CIE 0.31271 0.32902); black body "
        "at 6504 K: %.5f %.5f\n",
        a[0], a[1], d65[0], d65[1], planck6504[0], planck6504[1]);
    EXPECT_TRUE(colorTemperatureInRange(1667.0));
    EXPECT_FALSE(colorTemperatureInRange(1000.0));  // rendered as 1667 K before: now refused
    EXPECT_FALSE(colorTemperatureInRange(40000.0));
    EXPECT_FALSE(colorTemperatureInRange(3000.0, true));  // the daylight locus starts at 4000 K
    // RGB at luminance 1: A is warm, D65 near white (Rec.709's white point is D65).
    const auto rgbA = colorTemperatureToRgb(2856.0), rgbD = colorTemperatureToRgb(6504.0, true);
    EXPECT_NEAR(0.2126 * rgbA[0] + 0.7152 * rgbA[1] + 0.0722 * rgbA[2], 1.0, 1e-9);
    EXPECT_GT(rgbA[0], rgbA[2] * 2.0);
    for (double c : rgbD) EXPECT_NEAR(c, 1.0, 0.01);
}
