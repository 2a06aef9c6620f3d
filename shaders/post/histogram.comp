#version 460
// Auto-exposure, step 1: the log2-luminance histogram of the HDR target in absolute cd/m²
// (the pre-exposure divided out). Shared-memory bins per work group, then one atomic per bin.
#include "lib/exposure.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 2, std430) buffer histogram { uint counts[RG_HISTOGRAM_BINS]; uint fractions[RG_HISTOGRAM_BINS]; } hist;
layout(set = 0, binding = 3) uniform Params { float initial_ev100; } params;

shared uint sCounts[RG_HISTOGRAM_BINS];
shared uint sFractions[RG_HISTOGRAM_BINS];

void main() {
    sCounts[gl_LocalInvocationIndex] = 0u;
    sFractions[gl_LocalInvocationIndex] = 0u;
    barrier();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(hdr, 0);
    if (all(lessThan(p, size))) {
        float pre = rgPreExposure(ex.state, params.initial_ev100);
        float L = rgLuminance(texelFetch(hdr, p, 0).rgb) / pre;
        // Black pixels (and anything below the range) land in bin 0.
        const float binWidth = (RG_HISTOGRAM_MAX - RG_HISTOGRAM_MIN) / float(RG_HISTOGRAM_BINS);
        // NaN or negative luminance (a broken HDR pass) must not index outside the bins.
        if (!(L >= 0.0)) L = 0.0;
        float x = (clamp(log2(max(L, 1e-30)), RG_HISTOGRAM_MIN, RG_HISTOGRAM_MAX - 1e-4) - RG_HISTOGRAM_MIN) / binWidth;
        uint bin = min(uint(max(x, 0.0)), uint(RG_HISTOGRAM_BINS - 1));
        atomicAdd(sCounts[bin], 1u);
        atomicAdd(sFractions[bin], uint(fract(x) * RG_HISTOGRAM_FRACTION + 0.5));
    }
    barrier();
    uint c = sCounts[gl_LocalInvocationIndex];
    if (c > 0u) {
        atomicAdd(hist.counts[gl_LocalInvocationIndex], c);
        atomicAdd(hist.fractions[gl_LocalInvocationIndex], sFractions[gl_LocalInvocationIndex]);
    }
}
