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
// Linear Rec.709 RGB of a black body at `kelvin`, scaled to luminance 1 (tbl:4: 1000 K–40000 K).
std::array<double, 3> colorTemperatureToRgb(double kelvin);

}  // namespace rg::lights
