#version 460
// SSR accumulated over frames (scripts/ssr.lua, `ssr_temporal`): ssr.frag traces one pixel of each
// 2×2 block a frame, a different corner every frame (ssr_pixel.glsl), into `ssr_trace`; here each
// half-resolution texel blends that frame's ray into the reflection its block had on the last frame
// — `ssr_history`, the history of `ssr` — so over four frames the texel holds its whole block, not
// one pixel of it (the edges of reflected objects stop stepping by two pixels), and a hit found
// late in the march (ssr.frag's fading speck) is averaged with its neighbours' misses.
//   - Reprojected by the camera's motion: the block's nearest surface point (Hi-Z level 1) projected
//     by the last frame's camera, as ao_temporal.frag does (where nodes move, RG_MOTION, by the
//     motion target's); the history's view distance
//     (`ssr_distance_history`) must be the one the point had then, else it is a disocclusion and the
//     history is dropped; dropped too off the last frame's screen and where it is empty (distance 0:
//     the first frame, a cut, a rebuilt pass).
//   - Clamped into the box of this frame's rays at the texel and its four edge neighbours
//     (premultiplied by their confidence), so what the surroundings cannot make now — a reflection
//     moved away, a light switched off — does not linger.
//   - Blended premultiplied (rgb × confidence, confidence): a corner that missed darkens the
//     block's reflection by its share instead of averaging a colour with nothing.
// A ray that could not know its answer (ssr.frag's −1: the lit image's history emptied) empties the
// texel, so no reflection of a lighting that is gone carries over.
#include "lib/scene.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;      // `ssr`: rgb nits, a the confidence (as ssr.frag's)
layout(location = 1) out float viewDistance;  // `ssr_distance`: the texel's view distance (m); 0 empty
layout(set = 0, binding = 0) uniform sampler2D ssr_trace;
layout(set = 0, binding = 1) uniform sampler2D ssr_history;
layout(set = 0, binding = 2) uniform sampler2D ssr_distance_history;
layout(set = 0, binding = 3) uniform sampler2D hiz;  // ssr.lua's nearest-depth pyramid
layout(set = 0, binding = 4) uniform Params { float ssr_feedback; } params;
#ifdef RG_MOTION
layout(set = 0, binding = 5) uniform sampler2D motion;  // while nodes move (scripts/motion.lua)
#endif

// A trace texel premultiplied by its confidence; an unknown one (−1) as `fallback`.
vec4 premultiplied(vec4 t, vec4 fallback) { return t.a < 0.0 ? fallback : vec4(t.rgb * t.a, t.a); }

void main() {
    ivec2 h = ivec2(gl_FragCoord.xy), last = textureSize(ssr_trace, 0) - 1;
    color = vec4(0.0);
    viewDistance = 0.0;
    // The block's nearest depth (the Hi-Z pyramid's level 1) at its centre.
    float z = texelFetch(hiz, min(h, textureSize(hiz, 1) - 1), 1).r;
    if (z >= 1.0) return;  // no geometry: no reflection
    vec2 at = (vec2(h) + 0.5) / vec2(last + 1);
    float d = rgViewDistance(z);
    // The point on the last frame's screen, and the view distance it had there (a perspective clip
    // w; an orthographic camera that moved is not followed, one standing still keeps the distance).
    // Read at the nearest texel: a bilinear read costs four, and the clamp below bounds what a
    // texel's shift can bring.
    vec4 clip = camera.previousViewProj * vec4(rgWorldPosition(at, z), 1.0);
    vec2 uvBefore = clip.xy / clip.w * 0.5 + 0.5;
#ifdef RG_MOTION
    // Where nodes move, the surface's own motion: the motion target at the block's first pixel
    // when something was drawn there (its depth, Hi-Z level 0), the camera's otherwise.
    ivec2 first = min(2 * h, textureSize(hiz, 0) - 1);
    if (texelFetch(hiz, first, 0).r < 1.0) uvBefore = at - texelFetch(motion, first, 0).xy;
#endif
    ivec2 before = ivec2(floor(uvBefore * vec2(last + 1)));
    bool ortho = rgCameraOrthographic();
    float expected = ortho ? (camera.temporal.z > 0.5 ? -1.0 : d) : clip.w;
    bool onScreen = all(greaterThanEqual(before, ivec2(0))) && all(lessThanEqual(before, last)) && expected > 0.0;
    float pastDistance = onScreen ? texelFetch(ssr_distance_history, before, 0).r : 0.0;
    bool kept = pastDistance > 0.0 && abs(pastDistance - expected) <= 0.03 * expected + 0.02;
    vec4 past = texelFetch(ssr_history, clamp(before, ivec2(0), last), 0);
    past = vec4(past.rgb * past.a, past.a);

    vec4 current = texelFetch(ssr_trace, h, 0);
    // Unknown this frame: the lit image's history was emptied — the first frame, a cut, a lighting
    // pass switched or reloaded — so what was accumulated reflects a lighting that is gone; the
    // texel empties and the next frame starts afresh.
    if (current.a < 0.0) return;
    vec4 result = premultiplied(current, vec4(0.0));
    if (kept) {
        vec4 lo = result, hi = result;
        const ivec2 plus[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int i = 0; i < 4; ++i) {
            vec4 n = premultiplied(texelFetch(ssr_trace, clamp(h + plus[i], ivec2(0), last), 0), result);
            lo = min(lo, n);
            hi = max(hi, n);
        }
        result = mix(result, clamp(past, lo, hi), params.ssr_feedback);
    }
    color = result.a > 0.0 ? vec4(result.rgb / result.a, result.a) : vec4(0.0);
    viewDistance = d;
}
