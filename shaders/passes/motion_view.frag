#version 460
// The `motion` debug view: each pixel's screen motion since the last frame (lib/motion.glsl; the
// motion target where nodes move, RG_MOTION), as TAA reprojects by it: hue the direction, brightness the length (1 at 8 pixels and more); black
// where nothing moved.
#include "lib/scene.glsl"
#include "lib/motion.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D depth;
#ifdef RG_MOTION
layout(set = 0, binding = 1) uniform sampler2D motion;  // while nodes move (scripts/render_loop.lua)
#endif

void main() {
    float d = texelFetch(depth, ivec2(gl_FragCoord.xy), 0).r;
#ifdef RG_MOTION
    vec2 pixels = rgPixelMotion(motion, ivec2(gl_FragCoord.xy), uv, d) * camera.viewport.xy;
#else
    vec2 pixels = rgMotion(uv, d) * camera.viewport.xy;
#endif
    float length_ = length(pixels), angle = atan(pixels.y, pixels.x);
    vec3 hue = clamp(abs(fract(angle / 6.2831853 + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    color = vec4(hue * min(length_ / 8.0, 1.0), 1.0);
}
