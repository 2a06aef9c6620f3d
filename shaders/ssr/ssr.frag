#version 460
// Screen-space reflections (seed 002 §4.9.4): the view ray reflected about the G-buffer normal
// (the specular dominant direction of lib/ibl.glsl), marched through the Hi-Z pyramid from the
// pixel to where it leaves the view or Params.ssr_distance: the step grows a level each time the
// ray stays in front of a cell's nearest depth and shrinks when it does not, a hit at level 0.
// Output: rgb the previous frame's lit image (`hdr_history`, pre-exposed) at the hit, reprojected
// by the previous frame's camera (Camera.previousViewProj; where nodes move, RG_MOTION, by the
// motion target at the hit), blurred by
// roughness through its mips, in nits (divided by this frame's pre-exposure, as the probes the
// lighting passes blend it with: lib/ibl.glsl, RG_SSR); a the confidence: 0 on a miss, fading at the screen's edges, for
// rays turned towards the camera, for hits far behind the surface, for hits the march found late
// in its step budget (Params.ssr_steps), and with roughness (past
// Params.ssr_max_roughness the probes alone reflect); 0 where the previous camera did not see the
// hit. Where the history holds nothing yet (its alpha: the first frame, a cut) the reflection is
// unknown rather than absent: −1 with RG_SSR_TEMPORAL (`ssr_temporal` then starts afresh), else 0. The pixel traced turns through its 2×2 block with RG_SSR_TEMPORAL (ssr_pixel.glsl).
#include "lib/scene.glsl"
#include "lib/ibl.glsl"
#include "lib/exposure.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"
#include "ssr_pixel.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2) uniform sampler2D hiz;
layout(set = 0, binding = 3) uniform sampler2D hdr_history;
layout(set = 0, binding = 4) uniform Params {
    float ssr_steps;
    float ssr_distance;
    float ssr_thickness;
    float ssr_max_roughness;
    float initial_ev100;
} params;
layout(set = 0, binding = 5, std140) uniform exposure { RgExposureState state; } ex;  // a uniform block: read once per block of pixels
#ifdef RG_MOTION
layout(set = 0, binding = 6) uniform sampler2D motion;  // while nodes move (scripts/motion.lua)
#endif

// View position → (screen uv, depth) by the projection.
vec3 project(vec3 v) {
    vec4 clip = camera.proj * vec4(v, 1.0);
    return vec3(clip.xy / clip.w * 0.5 + 0.5, clip.z / clip.w);
}

void main() {
    // Half resolution: one ray for each 2×2 block of pixels, from one pixel's surface.
    ivec2 p = rgSsrTracedPixel(ivec2(gl_FragCoord.xy), textureSize(depth, 0));
    float z = texelFetch(depth, p, 0).r;
    color = vec4(0.0);
    if (z >= 1.0) return;
    float linearRoughness = 1.0 - rgGBufferSmoothnessAt(p);
    if (linearRoughness > params.ssr_max_roughness) return;
    vec2 size = vec2(textureSize(depth, 0));
    vec3 P = rgViewPosition((vec2(p) + 0.5) / size, z);
    vec3 N = normalize(mat3(camera.view) * rgGBufferNormalAt(p));
    vec3 V = rgCameraOrthographic() ? vec3(0.0, 0.0, 1.0) : normalize(-P);
    float alpha = linearRoughness * linearRoughness;
    vec3 R = normalize(rgSpecularDominantDir(N, reflect(-V, N), alpha));
    // The ray's end: ssr_distance away, or where it meets the near plane.
    float near = camera.proj[3][2] / camera.proj[2][2];
    float len = params.ssr_distance;
    if (P.z + R.z * len > -near) len = (-near - P.z) / R.z * 0.99;
    vec3 s0 = vec3((vec2(p) + 0.5) / size, z);
    vec3 s1 = project(P + R * len);
    vec2 deltaPx = (s1.xy - s0.xy) * size;
    float lengthPx = max(length(deltaPx), 1.0);
    int maxLevel = textureQueryLevels(hiz) - 1;
    int level = 0;
    float t = 1.5 / lengthPx;  // start a pixel and a half out (no self-hit)
    bool hit = false;
    vec3 at = s0;
    int steps = int(params.ssr_steps + 0.5);
    int used = 0;  // iterations the march took
    for (int i = 0; i < steps && t <= 1.0; ++i) {
        used = i + 1;
        float tNext = t + exp2(float(level)) / lengthPx;
        vec3 q = mix(s0, s1, min(tNext, 1.0));
        if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThanEqual(q.xy, vec2(1.0)))) break;
        ivec2 cell = ivec2(q.xy * size) >> level;
        float surface = texelFetch(hiz, cell, level).r;
        if (q.z < surface) {  // in front of everything in this cell: skip it, then take bigger steps
            t = tNext;
            level = min(level + 1, maxLevel);
        } else if (level > 0) {
            --level;  // something in the cell may be in the way: look closer
        } else {
            at = q;
            hit = true;
            break;
        }
    }
    if (!hit) return;
    // A hit far behind the surface it passed (thin objects seen from behind) is no hit.
    float hitDepth = texelFetch(depth, ivec2(at.xy * size), 0).r;
    vec3 surfaceView = rgViewPosition(at.xy, hitDepth);
    vec3 rayView = rgViewPosition(at.xy, at.z);
    if (surfaceView.z - rayView.z > params.ssr_thickness) return;
    vec2 edge = smoothstep(vec2(0.0), vec2(0.06), at.xy) * (1.0 - smoothstep(vec2(0.94), vec2(1.0), at.xy));
    float confidence = edge.x * edge.y;
    // A hit found near the end of the step budget stands beside neighbours whose march ran out
    // first: alone it is a speck (the default scene's steel pillar, marching over the floor at a
    // grazing angle, hit in scattered rays at 32 steps and in all of them at 128). Such hits fade
    // out over the budget's second half, to the probes' reflection that the misses beside them show
    // (a budget under 8 steps keeps every hit: there every hit is late).
    if (steps >= 8) confidence *= 1.0 - smoothstep(0.5, 1.0, float(used) / float(steps));
    confidence *= 1.0 - smoothstep(0.2, 0.6, R.z);  // towards the camera: what it would see is off screen
    confidence *= 1.0 - smoothstep(0.6 * params.ssr_max_roughness, params.ssr_max_roughness, linearRoughness);
    // Roughness widens the reflected cone: its footprint at the hit, in pixels, picks the mip.
    float footprint = alpha * length((at.xy - s0.xy) * size);
    float lod = clamp(log2(max(footprint, 1.0)), 0.0, float(textureQueryLevels(hdr_history) - 1));
    // The history is the frame before's image: the hit's surface where that frame's camera saw
    // it. Off its screen, or where it holds nothing yet (alpha 0: the first frame), no reflection.
    vec4 before = camera.previousViewProj * vec4(rgWorldPosition(at.xy, hitDepth), 1.0);
    vec2 uvBefore = before.xy / before.w * 0.5 + 0.5;
#ifdef RG_MOTION
    // Where nodes move, where the hit's own surface was (the motion target at the hit).
    uvBefore = at.xy - texelFetch(motion, clamp(ivec2(at.xy * size), ivec2(0), ivec2(size) - 1), 0).xy;
#endif
    if (before.w <= 0.0 || any(lessThan(uvBefore, vec2(0.0))) || any(greaterThan(uvBefore, vec2(1.0)))) return;
    vec4 history = textureLod(hdr_history, uvBefore, lod);
#ifdef RG_SSR_TEMPORAL
    if (history.a == 0.0) {  // an empty history (all of it: the first frame, a cut)
        color = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
#endif
    color = vec4(history.rgb / rgPreExposure(ex.state, params.initial_ev100), confidence * clamp(history.a, 0.0, 1.0));
}
