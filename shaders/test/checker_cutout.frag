#version 460
// Writes Params.tint on the even squares of a one-pixel checkerboard and discards the odd ones:
// the pass keeps its clear colour there (tests/gpu/test_gpu.cpp).
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform Params { vec4 tint; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (((p.x + p.y) & 1) == 1) discard;
    color = params.tint;
}
