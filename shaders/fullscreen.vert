#version 460
// One triangle that covers the viewport (no vertex buffer): vertices (-1,-1), (3,-1), (-1,3).
// uv runs 0..1 across the screen with (0,0) at the top-left texel, as Vulkan's framebuffer.
// RG_FULLSCREEN_DEPTH is the triangle's depth, for passes that test against a depth buffer
// (the fullscreen kind's params.depth.value).
// RG_FULLSCREEN_CAMERA (the kind's params.camera): 1 draws only when the scene camera moved since
// the last frame, 0 only when it stood still (lib/scene.glsl Camera.temporal.x); otherwise the
// triangle lies behind the far plane and nothing is rasterised.
#ifndef RG_FULLSCREEN_DEPTH
#define RG_FULLSCREEN_DEPTH 0.0
#endif
#ifdef RG_FULLSCREEN_CAMERA
#include "lib/scene.glsl"
#endif
layout(location = 0) out vec2 uv;

void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    uv = p;
    float z = RG_FULLSCREEN_DEPTH;
#ifdef RG_FULLSCREEN_CAMERA
    if ((camera.temporal.x > 0.5) != (RG_FULLSCREEN_CAMERA == 1)) z = 2.0;
#endif
    gl_Position = vec4(p * 2.0 - 1.0, z, 1.0);
}
