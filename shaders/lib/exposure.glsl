// The exposure state shared by the post chain and every pass that renders HDR. It lives in a
// persistent buffer named `exposure` that post/exposure_update.comp rewrites at the end of each
// frame, so a frame renders its HDR with the exposure metered on the frame before
// ("pre-exposure", seed 002 §5.2): RGBA16F targets hold luminance × preExposure and never
// overflow, even under a 100 000 lux sun.
#ifndef RG_EXPOSURE_GLSL
#define RG_EXPOSURE_GLSL

#include "lib/photometry.glsl"

#include "lib/exposure_state.h"  // struct RgExposureState, shared with the C++ core

// The pre-exposure to render this frame's HDR with; before the first update, that of the
// pipeline's initial EV100 (the camera's settings).
float rgPreExposure(RgExposureState s, float initialEv100) {
    return s.initialized > 0.5 ? s.exposure : rgExposureFromEv100(initialEv100);
}

// The EV100 this frame is pre-exposed with: the last frame's, or the pipeline's initial one.
float rgFrameEv100(RgExposureState s, float initialEv100) {
    return mix(initialEv100, s.ev100, step(0.5, s.initialized));
}

// Emission given relative to the exposure (seed 002 §5.1.3's computeBloomLuminance: luminance =
// colour · 2^(EV + EC − 3), EV the one metered on the frame before): the factor 2^(EV100 − 3) a
// colour with its EC folded in is multiplied by — the average luminance EV100 meters (seed 000
// eq:12, K = 12.5). A material's MaterialData.emissive.w says whether its emission is given so.
float rgEmissiveScale(RgExposureState s, float initialEv100) {
    return exp2(rgFrameEv100(s, initialEv100) - 3.0);
}

// Log-luminance histogram used by auto-exposure: RG_HISTOGRAM_BINS bins over
// log2(L) in [RG_HISTOGRAM_MIN, RG_HISTOGRAM_MAX); each bin has a count and the sum of the
// samples' offsets inside the bin (fixed point, RG_HISTOGRAM_FRACTION per bin width), so the
// mean log-luminance is exact, not rounded to bin centres.
#define RG_HISTOGRAM_BINS 256
#define RG_HISTOGRAM_MIN (-12.0)
#define RG_HISTOGRAM_MAX 20.0
#define RG_HISTOGRAM_FRACTION 256.0

#endif
