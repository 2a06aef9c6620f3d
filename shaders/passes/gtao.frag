#version 460
// Screen-space ambient occlusion (seed 002 §4.10.1, §4.10.3): ground-truth AO (Jimenez et al.
// 2016, "Practical Realtime Strategies for Accurate Indirect Occlusion") at half resolution. For
// RG_AO_SLICES screen directions per pixel the half-resolution view distances of ao_depth.frag
// (a quarter of the depth buffer's footprint, no division a tap) are marched RG_AO_STEPS times each way
// within Params.ao_radius metres, the highest horizon on each side kept, and the visible part of
// the cosine lobe between the two horizons integrated analytically around the normal projected
// into the slice:  ¼ (−cos(2h − n) + cos n + 2h sin n)  per side, weighted by the projected
// normal's length, over the same unoccluded (below). 1 = open, 0 = closed. Directions turn per pixel (a 4×4 pattern the
// ao_blur pass averages out) and, with RG_AO_TEMPORAL, per frame (ao_temporal.frag accumulates them). Written with the pixel's view distance beside it (rg16f).
#include "lib/scene.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"

// The estimate is the ratio of the slices' visible cosine-weighted arcs to what the same slices
// would see unoccluded (cos n + n sin n each, times its projected normal's length): both sums
// tend to their integrals as slices are added, and an open plane reads exactly 1 however few there
// are (the plain mean over 3 slices read 0.961 on a floor seen at a grazing angle). Against a
// 16 × 32 reference of the default frame at 1280×720 (its `ssao`, mean relative error / RMSE):
// the plain mean over 4 slices × 6 steps 0.0279 / 0.0366, the ratio 0.0260 / 0.0358 with 4
// slices and 0.0261 / 0.0361 with 3 — a quarter of the taps for the same error.
#ifndef RG_AO_SLICES
#define RG_AO_SLICES 3
#endif
#ifndef RG_AO_STEPS
#define RG_AO_STEPS 6
#endif

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_depth;  // the view distance at every half-resolution texel's pixel 2h
layout(set = 0, binding = 2) uniform Params { float ao_radius; } params;

// What rgViewPosition computes for texel h's pixel 2h, with the per-frame constants hoisted out
// of the march (its 36 taps a pixel are the pass's cost) and the view distance read as it is
// (ao_depth.frag wrote it): x, y = (ndc − offset) · scale · (perspective: the distance).
struct Reconstruction {
    ivec2 last;             // the last half-resolution texel
    vec2 ndcScale;          // texel → ndc: (2h + 0.5) · ndcScale − 1
    vec2 xyScale, xyOffset; // 1 / proj[0][0], 1 / proj[1][1]; orthographic: proj[3][0], proj[3][1]
    float perspective;      // 1 perspective, 0 orthographic
};
Reconstruction reconstruction;

vec3 viewPosition(ivec2 h) {
    ivec2 q = clamp(h, ivec2(0), reconstruction.last);
    float d = texelFetch(ao_depth, q, 0).r;
    vec2 ndc = (vec2(q * 2) + 0.5) * reconstruction.ndcScale - 1.0;
    vec2 xy = (ndc - reconstruction.xyOffset) * reconstruction.xyScale * mix(1.0, d, reconstruction.perspective);
    return vec3(xy, -d);
}

void main() {
    reconstruction.last = textureSize(ao_depth, 0) - 1;
    reconstruction.ndcScale = 2.0 / camera.viewport.xy;
    reconstruction.perspective = rgCameraOrthographic() ? 0.0 : 1.0;
    reconstruction.xyScale = 1.0 / vec2(camera.proj[0][0], camera.proj[1][1]);
    reconstruction.xyOffset = rgCameraOrthographic() ? vec2(camera.proj[3][0], camera.proj[3][1]) : vec2(0.0);
    // Texels without geometry never get here: the pass is depth-tested against ao_mask (ao.lua)
    // and they keep the clear, (1, 0): open, no distance.
    ivec2 half_ = ivec2(gl_FragCoord.xy);
    ivec2 full = half_ * 2;
    vec3 P = viewPosition(half_);
    vec3 Nw = rgGBufferNormalAt(full);
    vec3 N = normalize(mat3(camera.view) * Nw);
    vec3 V = rgCameraOrthographic() ? vec3(0.0, 0.0, 1.0) : normalize(-P);
    // The radius on screen, in full-resolution pixels (the projection's y scale).
    float radiusPx = clamp(params.ao_radius * abs(camera.proj[1][1]) * 0.5 * camera.viewport.y / (rgCameraOrthographic() ? 1.0 : max(-P.z, 1e-3)), 2.0, 96.0);
    // 4×4 interleaved rotations and step offsets; accumulated over frames (RG_AO_TEMPORAL:
    // ao_temporal.frag), both move on by a low-discrepancy fraction of the pattern's step each
    // frame (the golden ratio's additive recurrences) — counted from the first frame or the last
    // camera cut (Camera.temporal.y), which starts as without.
    int k = (half_.x & 3) + 4 * (half_.y & 3);
#ifdef RG_AO_TEMPORAL
    vec2 onward = fract(camera.temporal.y * vec2(0.6180340, 0.7548777));
#else
    vec2 onward = vec2(0.0);
#endif
    float rotation = (float(k) + onward.x) / 16.0 * 3.14159265 / float(RG_AO_SLICES);
    float jitter = (float((k * 7) & 15) + onward.y) / 16.0;
    float visibility = 0.0, unoccluded = 0.0;
    // Slice s's screen direction (y down) at angle rotation + s π / slices: the first's, turned by
    // a constant step per slice (one sine and cosine a pixel rather than one a slice).
    vec2 d = vec2(cos(rotation), sin(rotation));
    const float step = 3.14159265 / float(RG_AO_SLICES);
    const mat2 turn = mat2(cos(step), sin(step), -sin(step), cos(step));
    for (int s = 0; s < RG_AO_SLICES; ++s, d = turn * d) {
        vec3 dir = vec3(d.x, -d.y, 0.0);          // the same in view space (y up)
        vec3 axis = normalize(cross(dir, V));
        vec3 projN = N - axis * dot(N, axis);
        float projLen = length(projN);
        if (projLen < 1e-4) { visibility += 1.0; unoccluded += 1.0; continue; }
        vec3 ortho = normalize(dir - V * dot(dir, V));
        float cosN = clamp(dot(projN / projLen, V), -1.0, 1.0);
        float n = sign(dot(projN, ortho)) * acos(cosN);
        // The cosine of the highest horizon on each side: both sides in one loop, the step's
        // offset shared (an array indexed by a side loop costs a scatter on a CPU rasteriser).
        float best0 = -1.0, best1 = -1.0;
        for (int i = 0; i < RG_AO_STEPS; ++i) {
            float t = (float(i) + jitter) / float(RG_AO_STEPS);
            // In half-resolution texels: radiusPx / 2, at least a texel a step.
            vec2 offset = d * max(t * 0.5 * radiusPx, 1.0 + float(i));
            vec3 S0 = viewPosition(half_ + ivec2(round(offset))) - P;
            vec3 S1 = viewPosition(half_ + ivec2(round(-offset))) - P;
            float len0 = length(S0), len1 = length(S1);
            // Occluders within the radius, and above the tangent plane by more than the depth
            // buffer's reconstruction noise (a flat floor must not occlude itself).
            if (len0 >= 1e-4 && len0 <= params.ao_radius && dot(S0, N) >= 0.05 * len0) best0 = max(best0, dot(S0, V) / len0);
            if (len1 >= 1e-4 && len1 <= params.ao_radius && dot(S1, N) >= 0.05 * len1) best1 = max(best1, dot(S1, V) / len1);
        }
        // Side 0 is along +ortho (h2 > 0), side 1 along −ortho (h1 < 0); clamped to the hemisphere around n.
        float h2 = acos(clamp(best0, -1.0, 1.0));
        float h1 = -acos(clamp(best1, -1.0, 1.0));
        h1 = n + max(h1 - n, -1.5707963);
        h2 = n + min(h2 - n, 1.5707963);
        float sinN = sin(n);
        float arc = 0.25 * (-cos(2.0 * h1 - n) + cosN + 2.0 * h1 * sinN) + 0.25 * (-cos(2.0 * h2 - n) + cosN + 2.0 * h2 * sinN);
        visibility += projLen * arc;
        unoccluded += projLen * (cosN + n * sinN);
    }
    // r: visibility; g: the view distance the blur weighs its taps by (read with the AO, no
    // second texture and no reconstruction per tap).
    color = vec4(clamp(visibility / max(unoccluded, 1e-4), 0.0, 1.0), -P.z, 0.0, 1.0);
}
