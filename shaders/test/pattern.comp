#version 460
// Test pattern for the built-in test graph: a colour ramp with a checker, exact in RGBA16F
// (every value is a multiple of 1/64), so GPU tests can compare pixel for pixel.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D pattern;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(pattern);
    if (p.x >= size.x || p.y >= size.y) return;
    float checker = float(((p.x >> 3) + (p.y >> 3)) & 1);
    vec4 c = vec4(float(p.x & 63) / 64.0, float(p.y & 63) / 64.0, checker, 1.0);
    imageStore(pattern, p, c);
}
