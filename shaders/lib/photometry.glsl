// Physical camera and photometric conversions in GLSL: the twins of graph/core/photometry.h
// (seed 000 eq:11, eq:12, tbl:7; seed 002 §5.1.1–§5.1.3, §5.1.5).
#ifndef RG_PHOTOMETRY_GLSL
#define RG_PHOTOMETRY_GLSL

// EV100 = log2(N² / t · 100 / S) − EC (seed 002 §5.1.1).
float rgEv100FromCamera(float aperture, float shutter, float iso, float compensation) {
    return log2(aperture * aperture / shutter * 100.0 / iso) - compensation;
}

// Metering: EV100 = log2(L_avg · 100 / K), K = 12.5 (seed 000 eq:11).
float rgEv100FromLuminance(float averageLuminance) { return log2(averageLuminance * 100.0 / 12.5); }

// L = 2^(EV100 − 3) cd/m² (seed 000 eq:12).
float rgLuminanceFromEv100(float ev100) { return exp2(ev100 - 3.0); }

// 1 / L_max, L_max = 78 / (100 · 0.65) · 2^EV100 (seed 002 §5.1.2, saturation-based sensitivity).
float rgExposureFromEv100(float ev100) { return 1.0 / (78.0 / (100.0 * 0.65) * exp2(ev100)); }

// Relative luminance of linear Rec.709 RGB.
float rgLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The exact sRGB transfer functions (seed 002 §5.1.5, IEC 61966-2-1).
vec3 rgLinearToSrgb(vec3 c) {
    vec3 lo = c * 12.92;
    vec3 hi = pow(abs(c), vec3(1.0 / 2.4)) * 1.055 - 0.055;
    return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}
vec3 rgSrgbToLinear(vec3 c) {
    vec3 lo = c / 12.92;
    vec3 hi = pow((c + 0.055) / 1.055, vec3(2.4));
    return mix(hi, lo, lessThanEqual(c, vec3(0.04045)));
}

#endif
