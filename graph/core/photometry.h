// The physical camera and photometric conversions (Frostbite, seed 000 §4.3 and seed 002 §5.1).
// The same functions exist in GLSL (shaders/lib/photometry.glsl); tests hold both to the seeds'
// numbers. Units: luminance in cd/m² (nits), aperture in f-stops, shutter time in seconds.
#pragma once

namespace rg::photometry {

// Reflected-light meter calibration constant K (seed 000 eq:11: Canon, Nikon, Sekonic).
inline constexpr double kMeterCalibration = 12.5;
// Lens and vignetting attenuation q and the saturation-based sensitivity constant
// (seed 002 §5.1.2): L_max = 78 / (S q) · N² / t = 1.2 · 2^EV100 at S = 100.
inline constexpr double kLensAttenuation = 0.65;
inline constexpr double kSaturationConstant = 78.0;

// EV100 = log2(N² / t · 100 / S) − EC (seed 002 §5.1.1; EC is exposure compensation in stops).
double ev100FromCamera(double aperture, double shutterSeconds, double iso,
                       double compensation = 0.0);
// EV100 metering an average luminance: log2(L_avg · 100 / K) (seed 000 eq:11 with S = 100).
double ev100FromLuminance(double averageLuminance);
// Luminance an EV100 stands for: 2^EV · K / 100 = 2^(EV − 3) (seed 000 eq:12, tbl:7).
double luminanceFromEv100(double ev100);
// Exposure scale: 1 / L_max with L_max = 78 / (100 · q) · 2^EV100 ≈ 1.2 · 2^EV100
// (seed 002 §5.1.2, convertEV100ToExposure).
double exposureFromEv100(double ev100);
// Bloom (or emissive) luminance given in EV relative to the current exposure:
// colour · 2^(EV + bloomEC − 3) (seed 002 §5.1.3, computeBloomLuminance).
double bloomLuminance(double color, double bloomCompensation, double currentEv100);

}  // namespace rg::photometry
