#version 460
// Exposure, bloom, tone curve and the exact sRGB transfer function: HDR (luminance × this
// frame's pre-exposure) to an 8-bit display image.
//  - exposure: the HDR is divided by its pre-exposure and multiplied by the current exposure
//    (1 / (1.2 · 2^EV100), seed 002 §5.1.2);
//  - bloom: mixed in as (1 − w)·image + w·blur, w = 2^bloom_mix_stops, so the mix keeps the
//    energy (seed 002 §5.1.3's EV-relative luminance is for emission: lib/exposure.glsl's
//    rgEmissiveScale);
//  - curves: 0 ACES (Narkowicz's fit of the ACES RRT+ODT), 1 Khronos PBR Neutral (keeps base
//    colours up to its compression start), 2 linear (clamped);
//  - sRGB: exact piecewise function (seed 002 §5.1.5), then triangular dither when `dither`.
// The curve and the dither are compiled in when the pass declares them as switches
// (RG_TONEMAP_CURVE, RG_DITHER: scripts/post.lua) — a CPU rasteriser runs every side of a branch,
// so the curves not chosen cost ~1 ms at 1280×720 on lavapipe — and read from Params otherwise.
// Stages: 0 the HDR, 1 exposed (with bloom), 2 tone-mapped (display-referred linear), 3 encoded.
// A pass runs RG_POST_FROM to RG_POST_TO (default 0 to 3, the whole); from a later stage it reads
// the image of that stage as `source`, to an earlier one it writes it linear (post.chain splits
// the pass where a team's pass is put: post.at "exposed", "display_linear").
#include "lib/exposure.glsl"

#ifndef RG_POST_FROM
#define RG_POST_FROM 0
#endif
#ifndef RG_POST_TO
#define RG_POST_TO 3
#endif

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
// RG_TONEMAP_COPY (post.chain with FXAA): the same display image to a second target, the one FXAA
// then filters in place on its edge blocks only (fxaa_edges.frag).
#ifdef RG_TONEMAP_COPY
layout(location = 1) out vec4 copy;
#endif
#if RG_POST_FROM == 0
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1) uniform sampler2D bloom;
layout(set = 0, binding = 2, std140) uniform exposure { RgExposureState state; } ex;  // a uniform block: read once per block of pixels
#else
layout(set = 0, binding = 0) uniform sampler2D source;
#endif
layout(set = 0, binding = 3) uniform Params {
    float tonemap;
    float dither;
#if RG_POST_FROM == 0
    float bloom_mix_stops;
    float bloom_levels;
    float initial_ev100;
#endif
} params;
layout(push_constant) uniform Constants { float rg_frame; } pc;

vec3 acesFit(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 pbrNeutral(vec3 c) {
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < startCompression) return c;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    c *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(c, vec3(newPeak), g);
}

float hash(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    return float(v.x) / 4294967296.0;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
#if RG_POST_FROM == 0
    float pre = ex.state.preExposure > 0.0 ? ex.state.preExposure : rgPreExposure(ex.state, params.initial_ev100);
    float exposure = ex.state.initialized > 0.5 ? ex.state.exposure : pre;
    vec3 image = texelFetch(hdr, p, 0).rgb / pre * exposure;
    if (params.bloom_levels > 0.0) {
        vec3 blur = texture(bloom, uv).rgb / params.bloom_levels / pre * exposure;
        float w = exp2(params.bloom_mix_stops);
        image = mix(image, blur, w);
    }
#else
    vec3 image = texelFetch(source, p, 0).rgb;
#endif
#if RG_POST_TO == 1
    color = vec4(image, 1.0);
#else
#if RG_POST_FROM >= 2
    vec3 mapped = image;
#elif defined(RG_TONEMAP_CURVE) && RG_TONEMAP_CURVE == 0
    vec3 mapped = acesFit(image);
#elif defined(RG_TONEMAP_CURVE) && RG_TONEMAP_CURVE == 1
    vec3 mapped = pbrNeutral(image);
#elif defined(RG_TONEMAP_CURVE)
    vec3 mapped = clamp(image, 0.0, 1.0);
#else
    vec3 mapped = params.tonemap < 0.5 ? acesFit(image) : params.tonemap < 1.5 ? pbrNeutral(image) : clamp(image, 0.0, 1.0);
#endif
#if RG_POST_TO == 2
    color = vec4(mapped, 1.0);
#else
    vec3 display = rgLinearToSrgb(mapped);
#ifdef RG_DITHER
    if (RG_DITHER != 0) {
#else
    if (params.dither > 0.5) {
#endif
        uvec3 seed = uvec3(uvec2(p), uint(pc.rg_frame));
        display += (hash(seed) + hash(seed + 7919u) - 1.0) / 255.0;
    }
    color = vec4(clamp(display, 0.0, 1.0), 1.0);
#endif
#endif
#ifdef RG_TONEMAP_COPY
    copy = color;
#endif
}
