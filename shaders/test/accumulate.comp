#version 460
// Adds Params.step to a persistent image every frame: after N frames it holds N * step.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform image2D history;
layout(set = 0, binding = 1) uniform Params { float step; } params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(history)))) return;
    imageStore(history, p, imageLoad(history, p) + vec4(params.step));
}
