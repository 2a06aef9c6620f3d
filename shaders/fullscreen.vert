#version 460
// One triangle that covers the viewport (no vertex buffer): vertices (-1,-1), (3,-1), (-1,3).
// uv runs 0..1 across the screen with (0,0) at the top-left texel, as Vulkan's framebuffer.
// RG_FULLSCREEN_DEPTH is the triangle's depth, for passes that test against a depth buffer
// (the fullscreen kind's params.depth.value).
#ifndef RG_FULLSCREEN_DEPTH
#define RG_FULLSCREEN_DEPTH 0.0
#endif
layout(location = 0) out vec2 uv;

void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    uv = p;
    gl_Position = vec4(p * 2.0 - 1.0, RG_FULLSCREEN_DEPTH, 1.0);
}
