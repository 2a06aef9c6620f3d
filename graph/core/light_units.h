// Photometric light units (seed 000 §4.1–§4.4, tbl:8, tbl:9, eq:12–eq:17) and colour
// temperature. Vulkan-free; the GPU scene converts each light once on the CPU with these.
#pragma once

#include <array>
#include <string>

#include "result.h"

namespace rg::lights {

inline constexpr double kPi = 3.14159265358979323846;

// Luminous intensity (cd) of a point light of luminous power Φ (lm): I = Φ / 4π (tbl:9).
double pointIntensityFromLumens(double lumens);
// Spot light, lm → cd. Frostbite's default (eq:17) treats a spot as a point light whose light
// the cone masks, I = Φ / π, so changing the cone does not change the brightness; the
// physically exact alternative (eq:16) spreads Φ over the cone. `outerHalfAngle` is the cone's
// half-angle (the seed's θ_outer is the full opening angle: eq:16 reads 2π(1 − cos(θ_outer / 2))),
// so the exact form is I = Φ / (2π (1 − cos outerHalfAngle)).
double spotIntensityFromLumens(double lumens, double outerHalfAngle, bool exactCone = false);
// Luminance (cd/m²) from an EV100 value: L = 2^(EV − 3) (eq:12).
double luminanceFromEv100(double ev100);
// Illuminance (lux) at distance d (m) and incidence cosine from an intensity (cd): E = I cosθ / d².
double illuminance(double candela, double distance, double cosine = 1.0);
// Colour temperature (tbl:4; the seed takes only the hue from it, §4.1). Two loci:
// - the black body (Planckian locus), for incandescent and halogen lamps and the seed's table: CIE
//   1931 xy by the cubic-spline fit of Kang et al. 2002, defined over 1667–25000 K (CIE illuminant
//   A, 2856 K: within 5e-4 of its xy);
// - the CIE daylight locus (the D illuminants, CIE 15:2004 §3.1), for daylight and "daylight" lamps
//   — their CCT is off the black body's locus — defined over 4000–25000 K (D65 is 6504 K).
// Outside those ranges there is no conversion: callers refuse the value (no silent clamp).
inline constexpr double kMinColorTemperature = 1667.0, kMaxColorTemperature = 25000.0;
inline constexpr double kMinDaylightTemperature = 4000.0;
std::array<double, 2> colorTemperatureXy(double kelvin, bool daylight = false);
// Linear Rec.709 RGB of that chromaticity, scaled to luminance 1 (negative components clipped).
std::array<double, 3> colorTemperatureToRgb(double kelvin, bool daylight = false);
// Whether `kelvin` lies in the range the locus converts.
bool colorTemperatureInRange(double kelvin, bool daylight = false);

}  // namespace rg::lights
