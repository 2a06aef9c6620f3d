// The exposure state's layout, shared by the shaders (lib/exposure.glsl) and the C++ core
// (graph/runtime's readAbsoluteHdr reads it back): this file is valid GLSL and C++ both, so the
// layout is written once. Four floats, the same offsets under std430, std140 and C++.
#ifndef RG_EXPOSURE_STATE_H
#define RG_EXPOSURE_STATE_H

struct RgExposureState {
    float ev100;        // EV100 metered (auto) or set (manual) at the end of the last frame
    float exposure;     // rgExposureFromEv100(ev100): the next frame's pre-exposure
    float preExposure;  // the pre-exposure this frame's HDR was rendered with
    float initialized;  // 0 until the first update
};

#endif
