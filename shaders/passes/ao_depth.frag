#version 460
// The AO's half-resolution inputs (scripts/ao.lua), read once from the depth buffer: texel h gets
// the view distance of full-resolution pixel 2h (r32f, m), which gtao.frag marches — a quarter of
// the depth buffer's footprint in memory, and no reconstruction per tap — and `ao_mask` gets depth
// 0 where something was drawn there, 1 elsewhere, so that gtao and ao_blur, drawn depth-tested
// over it, never shade the blocks of sky (lavapipe's early depth test drops a block before it
// runs the shader; a branch cannot).
#include "lib/scene.glsl"

layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D depth;

void main() {
    float z = texelFetch(depth, ivec2(gl_FragCoord.xy) * 2, 0).r;
    bool geometry = z < 1.0;
    color = vec4(geometry ? rgViewDistance(z) : 0.0, 0.0, 0.0, 1.0);
    gl_FragDepth = geometry ? 0.0 : 1.0;
}
