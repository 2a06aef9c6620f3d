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

// Log-luminance histogram used by auto-exposure: RG_HISTOGRAM_BINS bins over
// log2(L) in [RG_HISTOGRAM_MIN, RG_HISTOGRAM_MAX); each bin has a count and the sum of the
// samples' offsets inside the bin (fixed point, RG_HISTOGRAM_FRACTION per bin width), so the
// mean log-luminance is exact, not rounded to bin centres.
#define RG_HISTOGRAM_BINS 256
#define RG_HISTOGRAM_MIN (-12.0)
#define RG_HISTOGRAM_MAX 20.0
#define RG_HISTOGRAM_FRACTION 256.0

#endif
