#version 460
// Auto-exposure, step 2 (one invocation): the mean log2-luminance over a percentile window of
// the histogram, EV100 from it with K = 12.5 (seed 000 eq:11) minus exposure compensation,
// temporal adaptation with separate up/down speeds, min/max EV limits. Manual mode takes EV100
// from the camera (seed 002 §5.1.1). Writes the exposure the next frame renders with.
#include "lib/exposure.glsl"

layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) readonly buffer histogram { uint counts[RG_HISTOGRAM_BINS]; uint fractions[RG_HISTOGRAM_BINS]; } hist;
layout(set = 0, binding = 1, std430) buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 2) uniform Params {
    float exposure_mode;   // 0 auto, 1 manual
    float aperture, shutter, iso, ec;
    float auto_low, auto_high;      // percentile window, 0..100
    float speed_up, speed_down;     // adaptation speed, 1/s (towards brighter / darker EV)
    float min_ev100, max_ev100;
    float frame_time;               // s
    float initial_ev100;
} params;

void main() {
    RgExposureState s = ex.state;
    float preExposure = rgPreExposure(s, params.initial_ev100);
    float target;
    if (params.exposure_mode > 0.5) {
        target = rgEv100FromCamera(params.aperture, params.shutter, params.iso, params.ec);
    } else {
        uint total = 0u;
        for (int i = 0; i < RG_HISTOGRAM_BINS; ++i) total += hist.counts[i];
        // Samples ranked in [low, high) of the total take part, partial bins pro rata.
        float low = float(total) * clamp(params.auto_low, 0.0, 100.0) / 100.0;
        float high = float(total) * clamp(params.auto_high, 0.0, 100.0) / 100.0;
        const float binWidth = (RG_HISTOGRAM_MAX - RG_HISTOGRAM_MIN) / float(RG_HISTOGRAM_BINS);
        float below = 0.0, weight = 0.0, sum = 0.0;
        for (int i = 0; i < RG_HISTOGRAM_BINS; ++i) {
            float c = float(hist.counts[i]);
            if (c == 0.0) continue;
            float take = max(0.0, min(below + c, high) - max(below, low));
            if (take > 0.0) {
                float meanInBin = RG_HISTOGRAM_MIN + binWidth * (float(i) + float(hist.fractions[i]) / (RG_HISTOGRAM_FRACTION * c));
                sum += take * meanInBin;
                weight += take;
            }
            below += c;
        }
        float meanLog2 = weight > 0.0 ? sum / weight : log2(rgLuminanceFromEv100(params.initial_ev100));
        target = log2(exp2(meanLog2) * 100.0 / 12.5) - params.ec;  // eq:11 on the geometric mean
    }
    target = clamp(target, params.min_ev100, params.max_ev100);
    float ev = target;
    if (s.initialized > 0.5 && params.exposure_mode < 0.5) {
        float speed = target > s.ev100 ? params.speed_up : params.speed_down;
        ev = s.ev100 + (target - s.ev100) * (1.0 - exp(-params.frame_time * speed));
    }
    ex.state = RgExposureState(ev, rgExposureFromEv100(ev), preExposure, 1.0);
}
