// Screen motion since the last frame, from a pixel's depth and the two cameras (lib/scene.glsl):
// the position a pixel's surface had on screen the frame before is where the last frame's
// unjittered camera (Camera.previousViewProj) projects it. That is all the motion of a surface
// that stands still; a scene whose nodes move (Node::dynamic) has the motion target too, which
// the G-buffer and forward passes write from each draw's last world matrix (rgClipMotion). The
// sub-pixel jitter (Camera.jitter) is left out, as TAA reprojection wants it.
#ifndef RG_MOTION_GLSL
#define RG_MOTION_GLSL

#include "lib/scene.glsl"

// Where the surface point seen at uv (the pixel's centre in this frame's jittered raster) is now,
// by the unjittered camera, minus where it was on the last frame's screen: uv units (pixels /
// size); the jitter cancels out of the difference.
vec2 rgMotion(vec2 uv, float depth) {
    vec4 world = vec4(rgWorldPosition(uv, depth), 1.0);
    vec4 now = camera.unjitteredViewProj * world;
    vec4 before = camera.previousViewProj * world;
    return (now.xy / now.w - before.xy / before.w) * 0.5;
}

// The motion of a rasterised point from its clip positions by this frame's unjittered camera and
// by the last frame's camera and transform (passes/scene.vert's RG_MOTION outputs): uv units, as
// rgMotion.
vec2 rgClipMotion(vec4 now, vec4 before) {
    return (now.xy / now.w - before.xy / before.w) * 0.5;
}

// The motion of what pixel `pixel` (at uv, its depth `depth`) shows: where nodes move
// (RG_MOTION), the motion target's where something was drawn (a surface's own motion), else the
// camera's from the depth.
#ifdef RG_MOTION
vec2 rgPixelMotion(sampler2D target, ivec2 pixel, vec2 uv, float depth) {
    return depth < 1.0 ? texelFetch(target, pixel, 0).xy : rgMotion(uv, depth);
}
#endif

#endif
