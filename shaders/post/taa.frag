#version 460
// Temporal anti-aliasing (scripts/post.lua's chain): this frame's HDR (jittered by Camera.jitter, a
// Halton (2, 3) sequence over 8 frames) blended into the history reprojected by the camera's
// motion (lib/motion.glsl) — and the objects' own, from the motion target, in a scene whose nodes
// move (RG_MOTION) — after Karis, "High Quality Temporal Supersampling" (SIGGRAPH 2014):
//   - the motion of the nearest surface of the pixel and its four diagonal neighbours, so an edge's
//     pixels follow the foreground;
//   - the history read with a Catmull-Rom filter (5 bilinear taps, Jimenez 2016) — a bilinear read
//     blurs a little more every frame. That is RG_TAA_MOVING, the pass `taa_moving` that draws on
//     frames whose camera moved; on the others the pass `taa` (without it) reads the pixel's own
//     texel of the history, exactly, and neither the depth nor the motion (scripts/post.lua: a
//     branch would cost lavapipe both sides);
//   - the history clipped towards the mean of the pixel and its four edge neighbours, into their
//     box of mean ± 1.25 σ in YCoCg (Salvi 2016's variance clipping): what the pixel's
//     surroundings cannot make now is ghost. Five taps, not nine: each fetch costs lavapipe ~1 ms
//     of the pass at 1280×720 — and on a device with quad operations (RG_QUAD_OPS) two of the
//     four neighbours are the pixel's partners in its 2×2 quad, read by a swap;
//   - rejected outside the last frame's screen and where the history is empty (alpha 0: the first
//     frame, a reset of the histories);
//   - blended with weights 1 / (1 + luma) (Karis), so a single bright sample does not flicker.
// In pre-exposed space (lib/exposure.glsl): the history, pre-exposed with the last frame's
// pre-exposure, is rescaled to this frame's, so an exposure change does not smear through it.
#ifdef RG_QUAD_OPS
#extension GL_KHR_shader_subgroup_quad : require
#endif
#include "lib/scene.glsl"
#include "lib/exposure.glsl"
#include "lib/motion.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D source;
#ifdef RG_TAA_MOVING
layout(set = 0, binding = 1) uniform sampler2D depth;
#ifdef RG_MOTION
// The motion the G-buffer and forward passes wrote (scripts/render_loop.lua), while nodes move.
layout(set = 0, binding = 5) uniform sampler2D motion;
#endif
#endif
layout(set = 0, binding = 2) uniform sampler2D taa_history;
layout(set = 0, binding = 3) uniform Params {
    float taa_feedback;
    float initial_ev100;
} params;
layout(set = 0, binding = 4, std140) uniform exposure { RgExposureState state; } ex;

vec3 toYCoCg(vec3 c) {
    return vec3(dot(c, vec3(0.25, 0.5, 0.25)), dot(c, vec3(0.5, 0.0, -0.5)), dot(c, vec3(-0.25, 0.5, -0.25)));
}
vec3 fromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// The history at uv by a Catmull-Rom filter: 9 texels as 5 bilinear reads (the corners dropped).
vec4 historyCatmullRom(vec2 at) {
    vec2 size = vec2(textureSize(taa_history, 0));
    vec2 p = at * size - 0.5, t1 = floor(p) + 0.5, f = p - floor(p);
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f)), w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f)), w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2, t12 = (t1 + w2 / w12) / size;
    vec2 t0 = (t1 - 1.0) / size, t3 = (t1 + 2.0) / size;
    vec4 sum = textureLod(taa_history, vec2(t12.x, t0.y), 0.0) * (w12.x * w0.y) +
               textureLod(taa_history, vec2(t0.x, t12.y), 0.0) * (w0.x * w12.y) +
               textureLod(taa_history, t12, 0.0) * (w12.x * w12.y) +
               textureLod(taa_history, vec2(t3.x, t12.y), 0.0) * (w3.x * w12.y) +
               textureLod(taa_history, vec2(t12.x, t3.y), 0.0) * (w12.x * w3.y);
    float weight = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    return max(sum / weight, vec4(0.0));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy), last = textureSize(source, 0) - 1;
    // min: a helper invocation past the last column or row (an odd size) reads the edge's texel,
    // as the clamped fetch of its neighbour would.
    vec3 current = texelFetch(source, min(pixel, last), 0).rgb;
    // The moments of the pixel and its edge neighbours (+x, −x, +y, −y), in YCoCg.
    const vec3 c = toYCoCg(current);
#ifdef RG_QUAD_OPS
    // The neighbour inside the pixel's 2×2 quad, on each axis, is that invocation's own pixel: a
    // quad swap, not a fetch (a fetch is ~1 ms of the pass at 1280×720 on lavapipe); the one
    // outside the quad is fetched.
    const bvec2 odd = notEqual(pixel & 1, ivec2(0));
    const vec3 acrossX = subgroupQuadSwapHorizontal(c), acrossY = subgroupQuadSwapVertical(c);
    const vec3 fetchedX = toYCoCg(texelFetch(source, clamp(pixel + ivec2(odd.x ? 1 : -1, 0), ivec2(0), last), 0).rgb);
    const vec3 fetchedY = toYCoCg(texelFetch(source, clamp(pixel + ivec2(0, odd.y ? 1 : -1), ivec2(0), last), 0).rgb);
    const vec3 plus[4] = vec3[](odd.x ? fetchedX : acrossX, odd.x ? acrossX : fetchedX,
                                odd.y ? fetchedY : acrossY, odd.y ? acrossY : fetchedY);
#else
    const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    vec3 plus[4];
    for (int i = 0; i < 4; ++i) plus[i] = toYCoCg(texelFetch(source, clamp(pixel + offsets[i], ivec2(0), last), 0).rgb);
#endif
    vec3 m1 = c, m2 = c * c;
    for (int i = 0; i < 4; ++i) {
        m1 += plus[i];
        m2 += plus[i] * plus[i];
    }
#ifdef RG_TAA_MOVING
    vec2 before = uv;
    // The nearest depth of the pixel and its diagonal neighbours, and its motion.
    float nearest = texelFetch(depth, pixel, 0).r;
    ivec2 nearestPixel = pixel;
    const ivec2 diagonal[4] = ivec2[](ivec2(1, 1), ivec2(-1, 1), ivec2(1, -1), ivec2(-1, -1));
    for (int i = 0; i < 4; ++i) {
        ivec2 q = clamp(pixel + diagonal[i], ivec2(0), last);
        float d = texelFetch(depth, q, 0).r;
        if (d < nearest) nearest = d, nearestPixel = q;
    }
    vec2 nearestUv = (vec2(nearestPixel) + 0.5) / vec2(last + 1);
#ifdef RG_MOTION
    before = uv - rgPixelMotion(motion, nearestPixel, nearestUv, nearest);  // moving nodes' own
#else
    before = uv - rgMotion(nearestUv, nearest);
#endif
    vec4 history = historyCatmullRom(before);
#else
    vec4 history = texelFetch(taa_history, pixel, 0);
#endif
    // Valid: the history has something (alpha 1) and, moving, the pixel was on the last screen.
#ifdef RG_TAA_MOVING
    const bool valid = history.a > 0.5 && all(greaterThanEqual(before, vec2(0.0))) && all(lessThanEqual(before, vec2(1.0)));
#else
    const bool valid = history.a > 0.5;
#endif
    // The last frame's pre-exposure is what the exposure state recorded for it, this frame's its
    // `exposure` (lib/exposure.glsl's rgPreExposure): before the state's first update both are
    // unknown and the history is kept as it is. (rgPreExposure's initial EV100 is for that first
    // frame alone: its exp2 per pixel cost lavapipe ~1.6 ms at 1280×720.)
    vec3 past = history.rgb * (ex.state.initialized > 0.5 ? ex.state.exposure / ex.state.preExposure : 1.0);
    // Clip towards the mean (not a per-channel clamp: that shifts the hue): |d| / (1.25 σ) per
    // channel as |d| · 0.8 / √variance (σ at least 8e-7), one inverse square root for a square
    // root and a division — the pass's arithmetic costs lavapipe as much as its fetches.
    vec3 mean = m1 * 0.2, variance = max(m2 * 0.2 - mean * mean, vec3(6.4e-13));
    vec3 h = toYCoCg(past), d = h - mean;
    vec3 scaled = abs(d) * (0.8 * inversesqrt(variance));
    float outside = max(scaled.x, max(scaled.y, scaled.z));
    if (outside > 1.0) h = mean + d * (1.0 / outside);
    past = max(fromYCoCg(h), vec3(0.0));
    float feedback = params.taa_feedback;
#ifdef RG_TAA_MOVING
    // Each reprojection resamples the history between texels and softens it a little: the faster
    // the image moves, the less of it is kept (down by 0.2 at 4 pixels a frame).
    feedback -= 0.2 * clamp(length((uv - before) * vec2(last + 1)) / 4.0, 0.0, 1.0);
#endif
    // The weights (1 − feedback) / (1 + luma(current)) and feedback / (1 + luma(past)), each
    // multiplied by both denominators: one division.
    float wc = (1.0 - feedback) * (1.0 + dot(past, vec3(0.2126, 0.7152, 0.0722)));
    float wh = feedback * (1.0 + dot(current, vec3(0.2126, 0.7152, 0.0722)));
    // Without a valid history, the frame itself.
    color = vec4(valid ? (current * wc + past * wh) * (1.0 / (wc + wh)) : current, 1.0);
}
