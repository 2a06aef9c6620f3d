#version 460
// The half-resolution AO accumulated over frames (scripts/ao.lua, `ao_temporal`): gtao.frag turns
// its 4×4 pattern of slice directions and step offsets a little further every frame
// (RG_AO_TEMPORAL), so successive frames sample directions the others did not; here each texel's
// filtered AO (ao_blur.frag) is blended into the AO its surface had on the last frame — the
// history `ao_history` (rg.resource's `history` of `ao_resolved`), reprojected by the camera's
// motion (the surface point from its view distance, projected by the last frame's camera) — where
// nodes move (RG_MOTION), by the motion target's.
// The history is rejected where its view distance is not the one the point had on the last
// frame (a disocclusion: a surface that was hidden, or a silhouette's other side), where it is
// empty (0: the first frame, a camera cut, a rebuilt gtao) and off the last frame's screen.
// Only the AO is accumulated: the view distance and the sun's visibility (b) are this frame's.
#include "lib/scene.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_blurred;  // AO, view distance (m)[, sun]: ao_blur.frag's
layout(set = 0, binding = 1) uniform sampler2D ao_history;   // the last frame's ao_resolved
layout(set = 0, binding = 2) uniform Params { float ao_feedback; } params;
#ifdef RG_MOTION
layout(set = 0, binding = 3) uniform sampler2D motion;  // while nodes move (scripts/motion.lua)
#endif

void main() {
    ivec2 h = ivec2(gl_FragCoord.xy);
    vec4 current = texelFetch(ao_blurred, h, 0);
    color = current;
    float d = current.g;
    if (d <= 0.0) return;  // no geometry (the clear)
    // The texel's surface point (view space as gtao.frag reconstructs pixel 2h), then in the
    // world: the view matrix is rigid, so its inverse is the transposed rotation.
    vec2 ndc = (vec2(h * 2) + 0.5) * (2.0 / camera.viewport.xy) - 1.0;
    bool ortho = rgCameraOrthographic();
    vec2 xyOffset = ortho ? vec2(camera.proj[3][0], camera.proj[3][1]) : vec2(0.0);
    vec3 P = vec3((ndc - xyOffset) / vec2(camera.proj[0][0], camera.proj[1][1]) * (ortho ? 1.0 : d), -d);
    vec3 world = transpose(mat3(camera.view)) * (P - camera.view[3].xyz);
    vec4 clip = camera.previousViewProj * vec4(world, 1.0);
#ifdef RG_MOTION
    // Where nodes move, the surface's own motion (the motion target at the texel's pixel 2h).
    vec2 before = (vec2(h * 2) + 0.5) / camera.viewport.xy - texelFetch(motion, h * 2, 0).xy;
#else
    vec2 before = clip.xy / clip.w * 0.5 + 0.5;
#endif
    // A perspective clip w is the view distance; an orthographic camera that moved is not
    // followed (its history is dropped), one standing still keeps the distance.
    float expected = ortho ? (camera.temporal.z > 0.5 ? -1.0 : d) : clip.w;
    if (any(lessThan(before, vec2(0.0))) || any(greaterThan(before, vec2(1.0))) || expected <= 0.0) return;
    vec2 past = textureLod(ao_history, before, 0.0).rg;  // bilinear: a mixed distance at edges is rejected below
    if (past.g <= 0.0 || abs(past.g - expected) > 0.03 * expected + 0.02) return;
    color.r = mix(current.r, past.r, params.ao_feedback);
}
