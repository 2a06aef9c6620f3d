#include "light_units.h"

#include <algorithm>
#include <cmath>

namespace rg::lights {

double pointIntensityFromLumens(double lumens) { return lumens / (4.0 * kPi); }

double spotIntensityFromLumens(double lumens, double outerAngle, bool exactCone) {
    if (!exactCone) return lumens / kPi;                         // eq:17
    return lumens / (2.0 * kPi * (1.0 - std::cos(outerAngle)));  // eq:16
}

double luminanceFromEv100(double ev100) { return std::exp2(ev100 - 3.0); }

double illuminance(double candela, double distance, double cosine) {
    return candela * cosine / (distance * distance);
}

std::array<double, 2> colorTemperatureXy(double kelvin, bool daylight) {
    const double t = std::clamp(kelvin, daylight ? kMinDaylightTemperature : kMinColorTemperature,
                                kMaxColorTemperature);
    if (daylight) {
        // CIE 15:2004 eq. 3.3, 3.4: x_D by the CCT, y_D on the daylight locus.
        const double x =
            t <= 7000.0 ? -4.6070e9 / (t * t * t) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063
                        : -2.0064e9 / (t * t * t) + 1.9018e6 / (t * t) + 0.24748e3 / t + 0.237040;
        return {x, -3.000 * x * x + 2.870 * x - 0.275};
    }
    // CIE 1931 chromaticity of the Planckian locus (the cubic-spline fit of Kang et al. 2002, 1667–25000 K).
    const double x =
        t <= 4000.0
            ? -0.2661239e9 / (t * t * t) - 0.2343589e6 / (t * t) + 0.8776956e3 / t + 0.179910
            : -3.0258469e9 / (t * t * t) + 2.1070379e6 / (t * t) + 0.2226347e3 / t + 0.240390;
    double y;
    if (t <= 2222.0)
        y = -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683;
    else if (t <= 4000.0)
        y = -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867;
    else
        y = 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    return {x, y};
}

bool colorTemperatureInRange(double kelvin, bool daylight) {
    return kelvin >= (daylight ? kMinDaylightTemperature : kMinColorTemperature) &&
           kelvin <= kMaxColorTemperature;
}

std::array<double, 3> colorTemperatureToRgb(double kelvin, bool daylight) {
    // xy, then XYZ with Y = 1, then linear Rec.709.
    const auto [x, y] = colorTemperatureXy(kelvin, daylight);
    const double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
    std::array<double, 3> rgb = {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
                                 -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                                 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
    for (auto& c : rgb) c = std::max(c, 0.0);
    // Keep luminance 1 after clipping negative components.
    const double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    for (auto& c : rgb) c /= luminance;
    return rgb;
}

}  // namespace rg::lights
