#version 460
// A compute pass whose time is its own arithmetic, `iterations` steps a texel (tests/gpu/test_gpu.cpp:
// a compute pass's timestamps must hold its work).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D busy;
layout(set = 0, binding = 1) uniform Params { float iterations; } params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(busy);
    if (p.x >= size.x || p.y >= size.y) return;
    float x = float(p.x) / float(size.x), y = float(p.y) / float(size.y);
    for (int i = 0; i < int(params.iterations); ++i) {
        x = fract(x * 1.618034 + y);
        y = fract(y * 0.618034 + x);
    }
    imageStore(busy, p, vec4(x, y, 0.0, 1.0));
}
